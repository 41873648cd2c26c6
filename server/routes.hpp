#pragma once
// The HTTP API (OGC API - Processes, Part 1 shape, extended for sweeps): routes, problem+json
// errors, authentication, downloads. See api/openapi.yaml for the contract.
#include <atomic>
#include <chrono>
#include <filesystem>
#include <memory>
#include <string>

#include "config.hpp"
#include "http_frontend.hpp"
#include "job_store.hpp"
#include "executor.hpp"

namespace rupture::server {

/// What the handlers need; owned by RuptureServer.
class RenderGate;

struct ServerContext {
  ServerConfig config;
  std::filesystem::path dataDir;     ///< the database (rupture.sqlite) and, locally, the run files
  std::filesystem::path resultsDir;  ///< holds jobs/<id>/run-<k>.h5: dataDir, or --shared-dir with Slurm
  JobStore* store = nullptr;
  Executor* scheduler = nullptr;
  std::atomic<bool> stopping{false};
  double maxRunMemory = 0;  ///< B one run may need (config.maxRunMemory or this machine's share; inf with Slurm)
  std::shared_ptr<RenderGate> renders;  ///< bounds the PNG renders running and waiting
  std::chrono::steady_clock::time_point startedAt = std::chrono::steady_clock::now();
};

/// Registers every route, the 405 answers, and the pre-routing / error / exception handlers.
void registerRoutes(HttpFrontend& http, ServerContext& context);

/// The OpenAPI document served at /openapi.yaml (api/openapi.yaml, compiled in).
const std::string& openApiYaml();

}  // namespace rupture::server
