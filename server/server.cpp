#include "server.hpp"

#include <filesystem>
#include <stdexcept>

#include <httplib.h>

#include "log.hpp"
#include "scheduler.hpp"
#include "slurm_executor.hpp"

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

}  // namespace

RuptureServer::RuptureServer(ServerConfig config) {
  m_context.config = std::move(config);
  m_context.dataDir = std::filesystem::absolute(m_context.config.dataDir);
  std::filesystem::create_directories(m_context.dataDir / "jobs");
  m_store = std::make_unique<JobStore>((m_context.dataDir / "rupture.sqlite").string());
  if (m_context.config.executor == "slurm") {
    SlurmSettings slurm;
    slurm.sharedDir = std::filesystem::absolute(m_context.config.sharedDir);
    slurm.partition = m_context.config.slurmPartition;
    slurm.account = m_context.config.slurmAccount;
    slurm.time = m_context.config.slurmTime;
    slurm.cpusPerRun = m_context.config.slurmCpusPerRun;
    slurm.options = m_context.config.slurmOptions;
    slurm.cli = m_context.config.ruptureCli.empty() ? defaultRuptureCli() : m_context.config.ruptureCli;
    m_context.resultsDir = slurm.sharedDir;
    m_scheduler = std::make_unique<SlurmExecutor>(*m_store, std::move(slurm));
  } else {
    auto local = std::make_unique<Scheduler>(*m_store, m_context.dataDir, effectiveWorkers(m_context.config),
                                             m_context.config.threadsPerRun);
    local->setMinFreeBytes(static_cast<std::uintmax_t>(m_context.config.minFreeBytes));
    m_context.resultsDir = m_context.dataDir;
    m_scheduler = std::move(local);
  }
  m_context.store = m_store.get();
  m_context.scheduler = m_scheduler.get();

  m_http = std::make_unique<httplib::Server>();
  const int httpThreads = m_context.config.httpThreads;
  m_http->new_task_queue = [httpThreads] { return new httplib::ThreadPool(static_cast<std::size_t>(httpThreads)); };
  m_http->set_payload_max_length(m_context.config.maxRequestBytes);
  m_http->set_read_timeout(10, 0);
  m_http->set_write_timeout(30, 0);
  m_http->set_keep_alive_max_count(100);
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
    throw std::runtime_error("cannot listen on " + c.bind + ":" + std::to_string(c.port) +
                             " (address in use, or not an address of this machine?)");
  }
  m_scheduler->start();
  logLine("listening on http://" + c.bind + ":" + std::to_string(m_port) + " with " +
          std::to_string(m_scheduler->workers()) + " worker(s) x " + std::to_string(m_scheduler->threadsPerRun()) +
          " thread(s), data in " + m_context.dataDir.string());
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

void RuptureServer::stop() {
  if (m_stopped.exchange(true)) {
    if (m_background.joinable() && m_background.get_id() != std::this_thread::get_id()) m_background.join();
    return;
  }
  m_stopRequested = true;
  m_context.stopping = true;
  // cpp-httplib's stop() is a no-op until listen() is running: keep asking while listen() is active.
  while (m_inListen) {
    if (m_http->is_running()) m_http->stop();
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  if (m_background.joinable()) m_background.join();
  m_scheduler->shutdown();
  logLine("stopped");
}

}  // namespace rupture::server
