#pragma once
// RuptureServer: owns the job store, the scheduler and the HTTP server, and their lifecycle.
//   RuptureServer server(config);
//   int port = server.bind();   // opens the data directory, starts the workers, binds the port
//   server.listen();            // serves until stop() (from another thread, e.g. a sigwait thread)
// stop() is safe before, during and after listen(), from any thread, and more than once.
// Only one server may use a data directory at a time (an flock on <data-dir>/rupture.lock).
#include <atomic>
#include <memory>
#include <thread>

#include "common/config.hpp"
#include "data_dir_lock.hpp"
#include "http/http_frontend.hpp"
#include "studies/refinement.hpp"
#include "routes/routes.hpp"

namespace rupture::server {

class RuptureServer {
public:
  /// Opens (creating) the data directory and the job store. Throws std::runtime_error on failure.
  explicit RuptureServer(ServerConfig config);
  ~RuptureServer();
  RuptureServer(const RuptureServer&) = delete;
  RuptureServer& operator=(const RuptureServer&) = delete;

  /// Starts the scheduler (re-queueing interrupted runs) and binds the port (0 = any free one).
  /// Returns the bound port; throws std::runtime_error if the address cannot be bound.
  int bind();
  /// Serves requests until stop(). Returns false if the server could not listen.
  bool listen();
  /// bind() + listen() on a background thread; returns once requests are being answered.
  int startInBackground();
  /// Stops the scheduler first (no run starts from now on, running runs are cancelled and re-queued
  /// for the next start, new submissions get 503), then the HTTP side (idle and half-sent
  /// connections are closed at once, responses in flight get up to a second), then waits for the
  /// runs to end. Blocks until all of that is done.
  void stop();
  /// The first step of stop(), on its own: from now on no run starts, running runs are cancelled
  /// and re-queued, and submissions get 503, while the HTTP side keeps answering. Idempotent.
  void stopAcceptingWork();

  int port() const { return m_port; }
  /// HTTP connections open now (idle, being read or being answered).
  int openConnections() const { return m_http->openConnections(); }
  const ServerConfig& config() const { return m_context.config; }
  /// The render gate (tests hold its slots to fill it deterministically).
  RenderGate& renderGate() { return *m_context.renders; }

private:
  ServerContext m_context;
  std::unique_ptr<DataDirLock> m_lock;
  std::unique_ptr<JobStore> m_store;
  std::unique_ptr<Executor> m_scheduler;
  std::unique_ptr<RefinementDriver> m_refinement;  ///< adds refinement rounds to jobs that ask for them
  std::unique_ptr<HttpFrontend> m_http;
  std::thread m_background;
  std::atomic<bool> m_stopRequested{false};
  std::atomic<bool> m_inListen{false};
  std::atomic<bool> m_stopped{false};
  int m_port = -1;
};

}  // namespace rupture::server
