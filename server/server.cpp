#include "server.hpp"

#include <filesystem>
#include <stdexcept>

#include <httplib.h>

#include "log.hpp"

namespace rupture::server {

RuptureServer::RuptureServer(ServerConfig config) {
  m_context.config = std::move(config);
  m_context.dataDir = std::filesystem::absolute(m_context.config.dataDir);
  std::filesystem::create_directories(m_context.dataDir / "jobs");
  m_store = std::make_unique<JobStore>((m_context.dataDir / "rupture.sqlite").string());
  m_scheduler = std::make_unique<Scheduler>(*m_store, m_context.dataDir, effectiveWorkers(m_context.config),
                                            m_context.config.threadsPerRun);
  m_scheduler->setMinFreeBytes(static_cast<std::uintmax_t>(m_context.config.minFreeBytes));
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
