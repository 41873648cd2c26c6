#pragma once
// Bounds the renders: every picture drawn on an HTTP handler thread (a run's field, its thumbnails,
// its series plot, the summary plot as PNG or PDF) takes a slot here first. A render takes seconds
// and hundreds of MB at large sizes: at most `running` draw at once and at most `waiting` more wait
// for a turn; a request beyond those is answered 503 with Retry-After at once. The server sizes
// `waiting` so that renders never occupy every handler thread, so /health, job pages and downloads
// keep being answered however many pictures are asked for.
//
// stop() (the server is stopping) turns the waiters away with 503 and makes stopRequested() true,
// which the renders in flight poll (render::StopCheck) so that none holds the shutdown.
#include <atomic>
#include <condition_variable>
#include <mutex>
#include <string>

#include "common/problem.hpp"

namespace rupture::server {

class RenderGate {
public:
  RenderGate(int running, int waiting, long long maxPixels)
      : m_running(running), m_waitingMax(waiting), m_maxPixels(maxPixels) {}

  long long maxPixels() const { return m_maxPixels; }
  int maxRunning() const { return m_running; }
  int maxWaiting() const { return m_waitingMax; }

  /// Holds one render slot for its lifetime.
  class Slot {
  public:
    explicit Slot(RenderGate& gate) : m_gate(gate) {}
    ~Slot() { m_gate.release(); }
    Slot(const Slot&) = delete;
    Slot& operator=(const Slot&) = delete;

  private:
    RenderGate& m_gate;
  };

  /// Waits for a slot when all are busy and fewer than `waiting` requests wait already; throws
  /// ApiError(503) otherwise, and when the server is stopping.
  [[nodiscard]] Slot acquire() {
    std::unique_lock lock(m_mutex);
    if (m_stopping) throw stoppingError();
    if (m_busy >= m_running) {
      if (m_waiting >= m_waitingMax) {
        throw ApiError(503, problem::kUnavailable, "Service Unavailable",
                       "the server is rendering as many pictures as it allows (" + std::to_string(m_running) +
                           " at once, --max-renders) and more are waiting; retry in a few seconds, or ask for SVG",
                       "", Json{{"retry_after_s", 2}});
      }
      ++m_waiting;
      m_free.wait(lock, [this] { return m_busy < m_running || m_stopping; });
      --m_waiting;
      if (m_stopping) throw stoppingError();
    }
    ++m_busy;
    return Slot(*this);
  }

  /// The server is stopping: waiters get 503, renders in flight are asked to end (stopRequested).
  void stop() {
    {
      std::lock_guard lock(m_mutex);
      m_stopping = true;
    }
    m_free.notify_all();
  }

  /// What a render polls between its stages (a render::StopCheck).
  bool stopRequested() const { return m_stopping; }

  /// The answer to a render that stop() ended or turned away.
  static ApiError stoppingError() {
    return ApiError(503, problem::kShuttingDown, "Service Unavailable",
                    "the server is stopping; ask for the picture again once it is back", "",
                    Json{{"retry_after_s", 5}});
  }

  /// Renders drawing now and waiting for a turn (GET /health shows them).
  int running() const {
    std::lock_guard lock(m_mutex);
    return m_busy;
  }
  int waiting() const {
    std::lock_guard lock(m_mutex);
    return m_waiting;
  }

private:
  void release() {
    {
      std::lock_guard lock(m_mutex);
      --m_busy;
    }
    m_free.notify_one();
  }

  mutable std::mutex m_mutex;
  std::condition_variable m_free;
  const int m_running, m_waitingMax;
  const long long m_maxPixels;
  int m_busy = 0, m_waiting = 0;
  std::atomic<bool> m_stopping{false};
};

}  // namespace rupture::server
