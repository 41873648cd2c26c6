#include "server.hpp"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <cerrno>
#include <cstring>
#include <limits>
#include <stdexcept>

#include <netdb.h>
#include <sys/socket.h>
#include <unistd.h>

#include <httplib.h>

#include "views/render_gate.hpp"
#include "common/log.hpp"
#include "execution/scheduler.hpp"
#include "execution/slurm_executor.hpp"

namespace rupture::server {
namespace {

/// The `rupture` CLI the Slurm batch scripts run: installed beside rupture-server, or in the build
/// tree (build/server/rupture-server, build/engine/rupture), else whatever PATH finds.
std::string defaultRuptureCli() {
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    for (const auto& candidate : {self.parent_path() / "rupture", self.parent_path().parent_path() / "engine" / "rupture"})
      if (std::filesystem::exists(candidate)) return candidate.string();
  }
  return "rupture";
}

/// Why host:port cannot be bound, asked of the kernel directly (cpp-httplib only says "no").
std::string bindFailureReason(const std::string& host, int port) {
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  hints.ai_flags = AI_PASSIVE | AI_NUMERICSERV;
  addrinfo* found = nullptr;
  if (int rc = ::getaddrinfo(host.c_str(), std::to_string(port).c_str(), &hints, &found); rc != 0) {
    return std::string("cannot resolve the address: ") + ::gai_strerror(rc);
  }
  std::string reason = "no usable address";
  for (addrinfo* a = found; a != nullptr; a = a->ai_next) {
    const int fd = ::socket(a->ai_family, a->ai_socktype | SOCK_CLOEXEC, a->ai_protocol);
    if (fd < 0) continue;
    int yes = 1;
    ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
    const bool bound = ::bind(fd, a->ai_addr, a->ai_addrlen) == 0;
    const int err = errno;
    ::close(fd);
    if (bound) {
      reason = "the port became free meanwhile; try again";
      break;
    }
    reason = err == EADDRINUSE ? "the port is in use by another process (another rupture-server?); stop it or "
                                 "choose another --port"
                               : std::string(std::strerror(err)) + " (is it an address of this machine?)";
    if (err == EADDRINUSE) break;
  }
  ::freeaddrinfo(found);
  return reason;
}

/// The kernel's largest listen queue (net.core.somaxconn; listen() caps any larger value at it).
int systemListenBacklog() {
  std::ifstream in("/proc/sys/net/core/somaxconn");
  int value = 0;
  if (in >> value && value > 0) return value;
  return SOMAXCONN;
}

}  // namespace

RuptureServer::RuptureServer(ServerConfig config) {
  m_context.config = std::move(config);
  m_context.dataDir = std::filesystem::absolute(m_context.config.dataDir);
  std::filesystem::create_directories(m_context.dataDir / "jobs");
  m_lock = std::make_unique<DataDirLock>(m_context.dataDir);  // before anything in it is opened
  m_store = std::make_unique<JobStore>((m_context.dataDir / "rupture.sqlite").string());
  if (m_context.config.executor == "slurm") {
    SlurmSettings slurm;
    slurm.sharedDir = std::filesystem::absolute(m_context.config.sharedDir);
    slurm.partition = m_context.config.slurmPartition;
    slurm.account = m_context.config.slurmAccount;
    slurm.time = m_context.config.slurmTime;
    slurm.checkpointLead = m_context.config.slurmCheckpointLead;
    slurm.cpusPerRun = m_context.config.slurmCpusPerRun;
    slurm.maxRanks = m_context.config.slurmMaxRanks;
    slurm.mpiPlugin = m_context.config.slurmMpi;
    slurm.options = m_context.config.slurmOptions;
    slurm.cli = m_context.config.ruptureCli.empty() ? defaultRuptureCli() : m_context.config.ruptureCli;
    m_context.resultsDir = slurm.sharedDir;
    m_scheduler = std::make_unique<SlurmExecutor>(*m_store, std::move(slurm));
  } else {
    auto local = std::make_unique<Scheduler>(*m_store, m_context.dataDir, effectiveWorkers(m_context.config),
                                             m_context.config.threadsPerRun);
    local->setMinFreeBytes(static_cast<std::uintmax_t>(m_context.config.minFreeBytes));
    local->setStatusInterval(m_context.config.statusInterval);
    std::string noMpi;
    std::optional<MpiLauncher> mpi =
        MpiLauncher::find(m_context.config.ruptureCli.empty() ? defaultRuptureCli() : m_context.config.ruptureCli, noMpi);
    local->setMpiLauncher(std::move(mpi), noMpi);
    m_context.resultsDir = m_context.dataDir;
    m_scheduler = std::move(local);
  }
  m_context.store = m_store.get();
  m_context.scheduler = m_scheduler.get();
  // Memory per run: the operator's figure, else this machine's share per worker. Slurm runs on
  // other machines, whose memory the batch system manages: no default limit there.
  if (m_context.config.maxRunMemory == 0 && m_context.config.executor != "slurm")
    m_context.config.maxRunMemory = effectiveRunMemory(m_context.config);
  const double runMemory = m_context.config.maxRunMemory > 0 ? static_cast<double>(m_context.config.maxRunMemory)
                                                             : std::numeric_limits<double>::infinity();
  m_context.maxRunMemory = runMemory;
  // Renders wait for their turn on HTTP handler threads: as many may wait as leave two threads to
  // /health, pages and downloads (and at least one), so that a browser's six parallel picture
  // requests of a run page are all drawn in turn while nothing else waits behind renders.
  const int renderWaiters = std::max(1, m_context.config.httpThreads - 2 - m_context.config.maxRenders);
  m_context.renders =
      std::make_shared<RenderGate>(m_context.config.maxRenders, renderWaiters, m_context.config.maxRenderPixels);
  m_refinement = std::make_unique<RefinementDriver>(*m_store, *m_scheduler,
                                                    static_cast<double>(m_context.config.maxElements), runMemory,
                                                    static_cast<double>(m_context.config.maxRunSteps));

  const ServerConfig& c = m_context.config;
  FrontendLimits limits;
  limits.requestTimeout = std::chrono::milliseconds(static_cast<long long>(c.requestTimeout * 1000));
  limits.keepAliveTimeout = std::min(limits.keepAliveTimeout, std::max(limits.requestTimeout, std::chrono::milliseconds(1000)));
  limits.maxBodyBytes = c.maxRequestBytes;
  limits.maxBufferedBytes = std::max<std::size_t>(limits.maxBufferedBytes, 4 * (c.maxRequestBytes + limits.maxHeadBytes));
  limits.handlerThreads = c.httpThreads;
  limits.maxConnections = c.maxConnections;
  limits.maxConnectionsPerClient = c.maxConnectionsPerClient;
  m_http = std::make_unique<HttpFrontend>(limits);
  // Headers and body go out in separate writes: without TCP_NODELAY, Nagle's algorithm and the
  // client's delayed ACK add ~40 ms to every small response.
  m_http->set_tcp_nodelay(true);
  registerRoutes(*m_http, m_context);
}

RuptureServer::~RuptureServer() {
  stop();
  if (m_background.joinable()) m_background.join();
}

int RuptureServer::bind() {
  const ServerConfig& c = m_context.config;
  if (c.port == 0) {
    m_port = m_http->bind_to_any_port(c.bind);
  } else {
    m_port = m_http->bind_to_port(c.bind, c.port) ? c.port : -1;
  }
  if (m_port <= 0) {
    throw std::runtime_error("cannot listen on " + c.bind + ":" + std::to_string(c.port) + ": " +
                             bindFailureReason(c.bind, c.port));
  }
  // cpp-httplib listens with a queue of 5: a burst of connections beyond it waits for SYN retries
  // (1 s, 3 s, ...) before it is even accepted. The system's limit holds a burst.
  const int backlog = c.listenBacklog > 0 ? c.listenBacklog : systemListenBacklog();
  if (!m_http->setListenBacklog(backlog))
    throw std::runtime_error("cannot set the listen backlog to " + std::to_string(backlog) + ": " + std::strerror(errno));
  m_scheduler->start();
  m_refinement->start();  // resumes refinements a stop interrupted
  logLine("listening on http://" + c.bind + ":" + std::to_string(m_port) + " (backlog " + std::to_string(backlog) +
          ") with " + std::to_string(m_scheduler->workers()) + " worker(s) x " +
          std::to_string(m_scheduler->threadsPerRun()) + " thread(s), data in " + m_context.dataDir.string());
  return m_port;
}

bool RuptureServer::listen() {
  m_inListen = true;
  bool ok = true;
  if (!m_stopRequested) ok = m_http->listen_after_bind();
  m_inListen = false;
  return ok;
}

int RuptureServer::startInBackground() {
  const int port = bind();
  m_background = std::thread([this] { listen(); });
  while (!m_http->is_running() && !m_stopRequested) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  return port;
}

void RuptureServer::stopAcceptingWork() {
  m_context.stopping = true;
  if (m_refinement) m_refinement->stop();  // no round is added while runs are being stopped
  m_scheduler->requestStop();
}

void RuptureServer::stop() {
  if (m_stopped.exchange(true)) {
    if (m_background.joinable() && m_background.get_id() != std::this_thread::get_id()) m_background.join();
    return;
  }
  const auto t0 = std::chrono::steady_clock::now();
  m_stopRequested = true;
  // 1. The scheduler: no run starts from now on, running runs are told to stop; POSTs get 503.
  stopAcceptingWork();
  //    Renders in flight end at their next check and waiting ones are turned away (503), so the
  //    HTTP side's grace below is not spent drawing pictures nobody will see.
  m_context.renders->stop();
  // 2. The HTTP side. cpp-httplib's stop() is a no-op until listen() is running: keep asking while
  //    listen() is active. listen() returns once the connection hub has closed every connection.
  while (m_inListen) {
    if (m_http->is_running()) m_http->stop();
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  if (m_background.joinable()) m_background.join();
  // 3. Wait for the cancelled runs to record themselves as re-queued.
  m_scheduler->shutdown();
  if (m_port > 0) {
    logLine("stopped after " +
            std::to_string(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()) + " s");
  }
}

}  // namespace rupture::server
