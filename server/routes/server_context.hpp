#pragma once
// What the request handlers share: the options, the store, the scheduler and the render gate,
// owned by RuptureServer.
#include <atomic>
#include <chrono>
#include <filesystem>
#include <memory>

#include "common/config.hpp"
#include "execution/executor.hpp"
#include "jobs/job_store.hpp"
#include "jobs/preview_store.hpp"

namespace rupture::server {

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
  /// The dry runs' preview pictures, fetched by the form (GET /processes/{id}/previews/{name}).
  std::shared_ptr<PreviewStore> previews = std::make_shared<PreviewStore>();
  std::chrono::steady_clock::time_point startedAt = std::chrono::steady_clock::now();
};

}  // namespace rupture::server
