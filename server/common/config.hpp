#pragma once
// rupture-server configuration: every option is a flag and an environment variable (RUPTURE_*),
// flags win over the environment, and `--help` lists them all from the same table.
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "rupture/run.hpp"

namespace rupture::server {

struct ServerConfig {
  int port = 8080;                        ///< TCP port; 0 picks a free one (printed on start)
  std::string bind = "127.0.0.1";         ///< address to listen on
  std::string dataDir = "data";           ///< holds rupture.sqlite and jobs/<id>/run-<k>.h5
  int workers = 0;                        ///< concurrent runs; 0 = cores / threads-per-run
  int threadsPerRun = 1;                  ///< OpenMP threads given to each run
  int maxRuns = 1000;                     ///< most runs one sweep may expand to
  std::size_t maxRequestBytes = 1 << 20;  ///< largest request body accepted (413 above)
  long long maxElements = 5'000'000;      ///< most elements/particles one run may hold (400 above)
  long long minFreeBytes = 256LL << 20;   ///< free disk in the data directory below which no run starts
  double statusInterval = 10;             ///< s between a running run's status lines in the log
  long long maxRunMemory = 0;             ///< B one run may need (spec estimate; 400 above); 0 = defaultRunMemory()
  long long maxRunSteps = static_cast<long long>(rupture::kDefaultMaxRunSteps);  ///< time steps one run may take (spec estimate; 400 above)
  int maxQueuedRuns = 10'000;             ///< accepted runs waiting in the whole server (503 above)
  long long maxQueuedBytes = 1LL << 30;   ///< stored inputs of unfinished jobs in the whole server (503 above)
  int maxRenders = 2;                     ///< renders at once; http-threads - 2 - this may wait, the rest get 503
  long long maxRenderPixels = 8'000'000;  ///< largest PNG, thumbnails and series too (width x height x scale^2 px; 400 above)
  std::string token;                      ///< when set, POST and DELETE need "Authorization: Bearer <token>"
  int httpThreads = 8;                    ///< threads answering HTTP requests
  bool logRequests = false;               ///< one line per request on stderr

  // Where runs execute (server/executor.hpp).
  std::string executor = "local";         ///< "local" (worker threads) or "slurm"
  std::string sharedDir;                  ///< slurm: holds jobs/ and cache/, visible to the compute nodes
  std::string slurmPartition, slurmAccount, slurmTime;  ///< sbatch --partition/--account/--time when set
  int slurmCheckpointLead = 120;  ///< s before the time limit at which a run is told to checkpoint and stop
  int slurmCpusPerRun = 1;                ///< sbatch --cpus-per-task, and rupture run --threads
  int slurmMaxRanks = 64;                 ///< most MPI ranks one run may ask for (run.ranks)
  std::string slurmMpi = "pmix";          ///< srun --mpi for runs of several ranks
  std::vector<std::string> slurmOptions;  ///< extra "#SBATCH" lines, e.g. "--qos=short"
  std::string ruptureCli;                 ///< the `rupture` binary the batch script runs (default: beside the server)
  // HTTP boundary (docs/server.md, "Security and limits")
  double requestTimeout = 10;             ///< s from a request's first byte to its last (408 after)
  int maxConnections = 512;               ///< open connections in all (503 above)
  int maxConnectionsPerClient = 64;       ///< open connections from one address (503 above)
  int listenBacklog = 0;                  ///< connections the kernel queues before accept; 0 = net.core.somaxconn
  std::vector<std::string> allowOrigins;  ///< Origins (scheme://host[:port]) allowed to POST and DELETE
  std::vector<std::string> publicHosts;   ///< host names clients may use besides the bound address
  std::string readToken;                  ///< when set, every route but /health needs a bearer token
};

/// Worker threads actually started: `workers` when set, otherwise max(1, cores / threadsPerRun).
int effectiveWorkers(const ServerConfig& config);

/// The memory one run may need: `maxRunMemory` when set, otherwise 3/4 of the machine's memory
/// (MemTotal, or the cgroup's memory.max when lower) shared by the workers, since they may all run
/// at once.
long long effectiveRunMemory(const ServerConfig& config);

struct ConfigResult {
  ServerConfig config;
  bool showHelp = false;
  bool showVersion = false;
  std::string error;  ///< non-empty: the first bad flag or variable, with what is allowed
};

using EnvLookup = std::function<std::optional<std::string>(const std::string& name)>;

/// The process environment (std::getenv).
EnvLookup processEnvironment();

/// Parses `args` (without argv[0]) over the defaults, after applying the RUPTURE_* variables.
ConfigResult parseConfig(const std::vector<std::string>& args, const EnvLookup& env);

/// The `--help` text: usage, every option with its variable and default.
std::string helpText();

}  // namespace rupture::server
