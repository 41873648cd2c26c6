#pragma once
// The HTTP API (OGC API - Processes, Part 1 shape, extended for sweeps): the route table, the
// 405/OPTIONS answers it implies, and the boundary that turns every failure into a problem
// document. See api/openapi.yaml for the contract.
#include <string>

#include "http/http_frontend.hpp"
#include "routes/server_context.hpp"

namespace rupture::server {

/// Registers every route, the 405 answers, and the pre-routing / error / exception handlers.
void registerRoutes(HttpFrontend& http, ServerContext& context);

/// The OpenAPI document served at /openapi.yaml (api/openapi.yaml, compiled in).
const std::string& openApiYaml();

}  // namespace rupture::server
