#pragma once
// Checks every request passes before routing (the pre-routing handler), in this order:
//   1. the path and the query are valid UTF-8 (400 naming the parameter);
//   2. Host names this server (421): an IP address, localhost, the --bind name or a --public-host,
//      so a DNS-rebinding page (evil.example resolving to 127.0.0.1) is refused;
//   3. with --read-token, a bearer token on every route but /health (401);
//   4. on mutating methods, Origin is this server's own or listed in --allow-origin (403), and a
//      POST body is application/json (415): together they stop a web page from submitting jobs.
#include <optional>
#include <string>

#include <httplib.h>

#include "common/config.hpp"
#include "common/problem.hpp"

namespace rupture::server {

/// The first check `req` fails, as the error to answer with; nullopt when it passes all.
std::optional<ApiError> checkRequest(const httplib::Request& req, const ServerConfig& config);

/// "Authorization: Bearer <token>" against `token`, in time independent of where they differ.
bool bearerMatches(const std::string& authorization, const std::string& token);

}  // namespace rupture::server
