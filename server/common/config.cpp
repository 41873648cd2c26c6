#include "common/config.hpp"

#include <algorithm>
#include <charconv>
#include <fstream>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <thread>

namespace rupture::server {
namespace {

/// One configurable option: its flag, its environment variable and how to store a value.
struct Option {
  const char* flag;      // without the leading "--"
  const char* env;       // RUPTURE_*
  const char* metavar;   // shown in --help; empty for switches
  const char* help;
  const char* fallback;  // the default, as shown in --help
  std::function<std::string(ServerConfig&, const std::string&)> set;  // returns an error or ""
};

std::string formatSeconds(double s) {
  std::ostringstream out;
  out << s;
  return out.str();
}

std::string parseInt(const std::string& text, long long lo, long long hi, long long& out) {
  long long value = 0;
  const char* first = text.data();
  const char* last = first + text.size();
  auto [ptr, ec] = std::from_chars(first, last, value);
  if (text.empty() || ec != std::errc() || ptr != last) return "'" + text + "' is not an integer";
  if (value < lo || value > hi) {
    return "'" + text + "' is out of range [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  }
  out = value;
  return "";
}

/// A setter for a text option; with `ifEmpty`, empty text is refused with that error.
std::function<std::string(ServerConfig&, const std::string&)> textSetter(std::string ServerConfig::*member,
                                                                        const char* ifEmpty = nullptr) {
  return [member, ifEmpty](ServerConfig& c, const std::string& v) -> std::string {
    if (ifEmpty && v.empty()) return ifEmpty;
    c.*member = v;
    return "";
  };
}

template <class T>
std::function<std::string(ServerConfig&, const std::string&)> intSetter(T ServerConfig::*member,
                                                                        long long lo, long long hi) {
  return [member, lo, hi](ServerConfig& c, const std::string& v) {
    long long parsed = 0;
    std::string err = parseInt(v, lo, hi, parsed);
    if (err.empty()) c.*member = static_cast<T>(parsed);
    return err;
  };
}

std::string parseSeconds(const std::string& text, double lo, double hi, double& out) {
  double value = 0;
  auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || ec != std::errc() || ptr != text.data() + text.size() || !(value >= lo && value <= hi)) {
    return "'" + text + "' is not a number of seconds in [" + formatSeconds(lo) + ", " + formatSeconds(hi) + "]";
  }
  out = value;
  return "";
}

/// A comma-separated list without empty items ("a, b" -> {"a", "b"}).
std::string parseList(const std::string& text, std::vector<std::string>& out) {
  out.clear();
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    while (!item.empty() && item.front() == ' ') item.erase(0, 1);
    while (!item.empty() && item.back() == ' ') item.pop_back();
    if (!item.empty()) out.push_back(item);
  }
  return "";
}

std::string parseBool(const std::string& v, bool& out) {
  if (v == "1" || v == "true" || v == "yes" || v == "on") { out = true; return ""; }
  if (v == "0" || v == "false" || v == "no" || v == "off") { out = false; return ""; }
  return "'" + v + "' is not a boolean (true/false, 1/0, yes/no, on/off)";
}

const std::vector<Option>& options() {
  static const std::vector<Option> table = {
      {"port", "RUPTURE_PORT", "N", "TCP port to listen on; 0 picks a free port", "8080",
       intSetter(&ServerConfig::port, 0, 65535)},
      {"bind", "RUPTURE_BIND", "ADDR", "address to listen on (keep 127.0.0.1 unless behind a proxy)",
       "127.0.0.1",
       textSetter(&ServerConfig::bind, "an address is required")},
      {"data-dir", "RUPTURE_DATA_DIR", "DIR",
       "directory for rupture.sqlite and jobs/<id>/run-<k>.h5 (created if missing)", "./data",
       textSetter(&ServerConfig::dataDir, "a directory is required")},
      {"workers", "RUPTURE_WORKERS", "N", "runs executed at the same time; 0 = cores / threads-per-run",
       "0", intSetter(&ServerConfig::workers, 0, 1024)},
      {"threads-per-run", "RUPTURE_THREADS_PER_RUN", "N", "OpenMP threads given to each run", "1",
       intSetter(&ServerConfig::threadsPerRun, 1, 1024)},
      {"max-runs", "RUPTURE_MAX_RUNS", "N", "most runs one sweep may expand to", "1000",
       intSetter(&ServerConfig::maxRuns, 1, 10'000'000)},
      {"max-request-bytes", "RUPTURE_MAX_REQUEST_BYTES", "BYTES",
       "largest request body accepted; larger ones get 413", "1048576",
       intSetter(&ServerConfig::maxRequestBytes, 1, std::numeric_limits<int>::max())},
      {"max-elements", "RUPTURE_MAX_ELEMENTS", "N",
       "most elements (or particles) one run may hold, from the spec's size estimate; larger runs get 400",
       "5000000", intSetter(&ServerConfig::maxElements, 1, 5'000'000)},
      {"max-run-steps", "RUPTURE_MAX_RUN_STEPS", "N",
       "most time steps one run may take, from the spec's estimate (its end strain or end time over its stable "
       "time step, capped by run.max_steps); longer runs get 400",
       "100000000",  // rupture::kDefaultMaxRunSteps
       intSetter(&ServerConfig::maxRunSteps, 1, std::numeric_limits<long long>::max())},
      {"min-free-bytes", "RUPTURE_MIN_FREE_BYTES", "BYTES",
       "free space the data directory must keep: below it, queued runs wait instead of starting", "268435456",
       intSetter(&ServerConfig::minFreeBytes, 0, std::numeric_limits<long long>::max())},
      {"status-interval", "RUPTURE_STATUS_INTERVAL", "SECONDS",
       "seconds between the status lines of each running run in the log (progress, ETA, step, time, strain, "
       "the headline quantity, broken bonds, speed; as rupture run prints off a terminal); the runs are looked at "
       "once a second",
       "10", [](ServerConfig& c, const std::string& v) { return parseSeconds(v, 1, 86400, c.statusInterval); }},
      {"max-run-memory", "RUPTURE_MAX_RUN_MEMORY", "BYTES",
       "most memory one run may need, from the spec's estimate (particles, bonds, neighbour lists, "
       "snapshots); larger runs get 400. 0 = 3/4 of the machine's memory divided by the workers",
       "0", intSetter(&ServerConfig::maxRunMemory, 0, std::numeric_limits<long long>::max())},
      {"max-queued-runs", "RUPTURE_MAX_QUEUED_RUNS", "N",
       "most runs waiting to start in the whole server; a submission that would pass it gets 503 with Retry-After",
       "10000", intSetter(&ServerConfig::maxQueuedRuns, 1, 10'000'000)},
      {"max-queued-bytes", "RUPTURE_MAX_QUEUED_BYTES", "BYTES",
       "most bytes of inputs (descriptions, probes, ...) that unfinished jobs may hold in the whole server; "
       "a submission that would pass it gets 503 with Retry-After",
       "1073741824", intSetter(&ServerConfig::maxQueuedBytes, 1, std::numeric_limits<long long>::max())},
      {"max-renders", "RUPTURE_MAX_RENDERS", "N",
       "pictures (field images and thumbnails, series and summary plots as PNG or PDF) drawn at the same "
       "time; up to http-threads - 2 - N more wait (at least 1), further ones get 503 with Retry-After",
       "2", intSetter(&ServerConfig::maxRenders, 1, 64)},
      {"max-render-pixels", "RUPTURE_MAX_RENDER_PIXELS", "N",
       "largest PNG in pixels (width x height x scale^2), thumbnails and series plots included; larger "
       "requests get 400", "8000000",
       intSetter(&ServerConfig::maxRenderPixels, 76'800, 100'000'000)},
      {"token", "RUPTURE_TOKEN", "SECRET",
       "when set, POST and DELETE need 'Authorization: Bearer SECRET' (prefer the variable: "
       "flags show in ps)",
       "(none)",
       textSetter(&ServerConfig::token)},
      {"http-threads", "RUPTURE_HTTP_THREADS", "N", "threads answering HTTP requests", "8",
       intSetter(&ServerConfig::httpThreads, 1, 256)},
      {"log-requests", "RUPTURE_LOG_REQUESTS", "", "log one line per HTTP request on stderr", "off",
       [](ServerConfig& c, const std::string& v) { return parseBool(v, c.logRequests); }},
      {"executor", "RUPTURE_EXECUTOR", "local|slurm",
       "where runs execute: worker threads of this server, or one sbatch array per job on Slurm", "local",
       [](ServerConfig& c, const std::string& v) -> std::string {
         if (v != "local" && v != "slurm") return "'" + v + "' is not one of local, slurm";
         c.executor = v;
         return "";
       }},
      {"shared-dir", "RUPTURE_SHARED_DIR", "DIR",
       "slurm: directory visible to the server and the compute nodes; holds jobs/ (run files) and cache/",
       "(required with --executor slurm)",
       textSetter(&ServerConfig::sharedDir, "a directory is required")},
      {"slurm-partition", "RUPTURE_SLURM_PARTITION", "NAME", "slurm: sbatch --partition", "(cluster default)",
       [](ServerConfig& c, const std::string& v) { c.slurmPartition = v; return std::string(); }},
      {"slurm-account", "RUPTURE_SLURM_ACCOUNT", "NAME", "slurm: sbatch --account", "(none)",
       [](ServerConfig& c, const std::string& v) { c.slurmAccount = v; return std::string(); }},
      {"slurm-time", "RUPTURE_SLURM_TIME", "LIMIT", "slurm: sbatch --time per run, e.g. 2:00:00", "(partition default)",
       [](ServerConfig& c, const std::string& v) { c.slurmTime = v; return std::string(); }},
      {"slurm-checkpoint-lead", "RUPTURE_SLURM_CHECKPOINT_LEAD", "SECONDS",
       "slurm: a run is told to checkpoint and stop this long before its time limit (sbatch --signal), "
       "then submitted again to continue; give it the time one checkpoint takes, and Slurm's up to 60 s of slack",
       "120", intSetter(&ServerConfig::slurmCheckpointLead, 1, 86400)},
      {"slurm-cpus-per-run", "RUPTURE_SLURM_CPUS_PER_RUN", "N",
       "slurm: sbatch --cpus-per-task, and the OpenMP threads of each run", "1",
       intSetter(&ServerConfig::slurmCpusPerRun, 1, 1024)},
      {"slurm-max-ranks", "RUPTURE_SLURM_MAX_RANKS", "N",
       "slurm: most MPI ranks one run may ask for (the spec's run.ranks; more get 400); each rank is a task of "
       "--slurm-cpus-per-run CPUs, anywhere in the cluster", "64",
       intSetter(&ServerConfig::slurmMaxRanks, 1, 4096)},
      {"slurm-mpi", "RUPTURE_SLURM_MPI", "PLUGIN",
       "slurm: srun --mpi plugin that starts the ranks of a run of several ranks (Debian's Open MPI speaks pmix)",
       "pmix", textSetter(&ServerConfig::slurmMpi, "a plugin name is required")},
      {"slurm-option", "RUPTURE_SLURM_OPTIONS", "OPTION",
       "slurm: an extra #SBATCH line such as --qos=short; repeat the flag for more (the variable takes one "
       "per line)",
       "(none)",
       [](ServerConfig& c, const std::string& v) -> std::string {
         std::istringstream lines(v);
         for (std::string line; std::getline(lines, line);) {
           if (line.empty()) continue;
           if (line.rfind("-", 0) != 0) return "'" + line + "' is not an sbatch option (it must start with -)";
           c.slurmOptions.push_back(line);
         }
         return "";
       }},
      {"rupture-cli", "RUPTURE_CLI", "PATH",
       "the rupture binary the batch script runs on the compute nodes (slurm), or that mpirun starts on each rank "
       "of a run of several ranks (local)", "(the one beside rupture-server)",
       textSetter(&ServerConfig::ruptureCli, "a path is required")},
      {"request-timeout", "RUPTURE_REQUEST_TIMEOUT", "SECONDS",
       "deadline for receiving a whole request (line, headers and body), however slowly it trickles; "
       "408 after",
       "10", [](ServerConfig& c, const std::string& v) { return parseSeconds(v, 0.05, 3600, c.requestTimeout); }},
      {"max-connections", "RUPTURE_MAX_CONNECTIONS", "N", "open HTTP connections in all; more get 503", "512",
       intSetter(&ServerConfig::maxConnections, 1, 900)},
      {"listen-backlog", "RUPTURE_LISTEN_BACKLOG", "N",
       "connections the kernel accepts and queues before the server takes them (a burst of clients); "
       "0 = the system's limit, net.core.somaxconn, which also caps any larger value",
       "0", intSetter(&ServerConfig::listenBacklog, 0, 1'000'000)},
      {"max-connections-per-client", "RUPTURE_MAX_CONNECTIONS_PER_CLIENT", "N",
       "open HTTP connections from one client address; more get 503", "64",
       intSetter(&ServerConfig::maxConnectionsPerClient, 1, 900)},
      {"allow-origin", "RUPTURE_ALLOW_ORIGIN", "ORIGINS",
       "comma-separated Origins (e.g. https://app.example.org) whose pages may POST and DELETE; "
       "other cross-origin requests get 403",
       "(none)", [](ServerConfig& c, const std::string& v) { return parseList(v, c.allowOrigins); }},
      {"public-host", "RUPTURE_PUBLIC_HOST", "HOSTS",
       "comma-separated host names clients use to reach the server (a proxy's name); requests naming "
       "another host in Host get 421 (DNS-rebinding protection)",
       "(none)", [](ServerConfig& c, const std::string& v) { return parseList(v, c.publicHosts); }},
      {"read-token", "RUPTURE_READ_TOKEN", "SECRET",
       "when set, every route but /health needs 'Authorization: Bearer SECRET' (or the --token); "
       "set it to the --token value for one token everywhere",
       "(none)",
       textSetter(&ServerConfig::readToken)},
  };
  return table;
}

}  // namespace

int effectiveWorkers(const ServerConfig& config) {
  if (config.workers > 0) return config.workers;
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  return std::max(1, cores / std::max(1, config.threadsPerRun));
}

long long effectiveRunMemory(const ServerConfig& config) {
  if (config.maxRunMemory > 0) return config.maxRunMemory;
  long long total = 0;
  {
    std::ifstream meminfo("/proc/meminfo");
    std::string key;
    long long kib = 0;
    std::string unit;
    while (meminfo >> key >> kib >> unit) {
      if (key == "MemTotal:") { total = kib * 1024; break; }
    }
  }
  // A container's limit (cgroup v2) is what the kernel enforces, when it is lower.
  if (std::ifstream limit("/sys/fs/cgroup/memory.max"); limit) {
    std::string text;
    limit >> text;
    if (!text.empty() && text != "max") {
      try {
        const long long cgroup = std::stoll(text);
        if (cgroup > 0 && (total == 0 || cgroup < total)) total = cgroup;
      } catch (const std::exception&) {
      }
    }
  }
  if (total <= 0) total = 8LL << 30;  // unknown: assume a small machine
  return std::max(64LL << 20, total / 4 * 3 / effectiveWorkers(config));
}

EnvLookup processEnvironment() {
  return [](const std::string& name) -> std::optional<std::string> {
    const char* v = std::getenv(name.c_str());
    if (!v) return std::nullopt;
    return std::string(v);
  };
}

ConfigResult parseConfig(const std::vector<std::string>& args, const EnvLookup& env) {
  ConfigResult result;
  for (const Option& opt : options()) {
    if (auto v = env(opt.env)) {
      std::string err = opt.set(result.config, *v);
      if (!err.empty()) {
        result.error = std::string(opt.env) + ": " + err;
        return result;
      }
    }
  }
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    if (arg == "-h" || arg == "--help") { result.showHelp = true; continue; }
    if (arg == "--version") { result.showVersion = true; continue; }
    if (arg.rfind("--", 0) != 0) {
      result.error = "unexpected argument '" + arg + "' (see --help)";
      return result;
    }
    std::string name = arg.substr(2);
    std::optional<std::string> value;
    if (auto eq = name.find('='); eq != std::string::npos) {
      value = name.substr(eq + 1);
      name = name.substr(0, eq);
    }
    const Option* found = nullptr;
    for (const Option& opt : options()) {
      if (name == opt.flag) found = &opt;
    }
    if (!found) {
      result.error = "unknown option '--" + name + "' (see --help)";
      return result;
    }
    if (!value) {
      if (*found->metavar == '\0') {
        value = "true";  // a switch
      } else if (i + 1 < args.size()) {
        value = args[++i];
      } else {
        result.error = "--" + name + " needs a value (" + found->metavar + ")";
        return result;
      }
    }
    std::string err = found->set(result.config, *value);
    if (!err.empty()) {
      result.error = "--" + name + ": " + err;
      return result;
    }
  }
  if (result.config.executor == "slurm" && result.config.sharedDir.empty())
    result.error = "--executor slurm needs --shared-dir (a directory the compute nodes see)";
  return result;
}

std::string helpText() {
  std::ostringstream out;
  out << "Usage: rupture-server [OPTIONS]\n\n"
         "Serves Rupture scenarios as parameter sweeps over HTTP (OGC API - Processes shape).\n"
         "Every option can also be set by its environment variable; a flag wins over the variable.\n\n"
         "Options:\n";
  for (const Option& opt : options()) {
    std::string left = std::string("  --") + opt.flag;
    if (*opt.metavar) left += std::string(" ") + opt.metavar;
    out << left << "\n      " << opt.help << "\n      env " << opt.env << ", default " << opt.fallback
        << "\n";
  }
  out << "  -h, --help\n      show this help and exit\n"
         "  --version\n      print the version and exit\n\n"
         "Stop with SIGTERM or Ctrl-C: running runs are interrupted and re-queued for the next start.\n"
         "API description: GET /openapi.yaml\n";
  return out.str();
}

}  // namespace rupture::server
