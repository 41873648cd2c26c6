#pragma once
// Bounds the PNG renders: a render takes seconds and hundreds of MB at large sizes, and runs on an
// HTTP handler thread. At most `running` render at once and as many more wait for a turn; a request
// beyond those is answered 503 with Retry-After at once, so renders can never occupy every handler
// thread and /health, job pages and downloads keep being answered.
#include <condition_variable>
#include <mutex>

#include "common/problem.hpp"

namespace rupture::server {

class RenderGate {
public:
  RenderGate(int running, long long maxPixels) : m_running(running), m_waitingMax(running), m_maxPixels(maxPixels) {}

  long long maxPixels() const { return m_maxPixels; }

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

  /// Waits for a slot when all are busy and fewer than `running` requests wait already; throws
  /// ApiError(503) otherwise.
  [[nodiscard]] Slot acquire() {
    std::unique_lock lock(m_mutex);
    if (m_busy >= m_running) {
      if (m_waiting >= m_waitingMax) {
        throw ApiError(503, problem::kUnavailable, "Service Unavailable",
                       "the server is rendering as many plots as it allows (" + std::to_string(m_running) +
                           " at once, --max-renders) and more are waiting; retry in a few seconds, or ask for SVG",
                       "", Json{{"retry_after_s", 2}});
      }
      ++m_waiting;
      m_free.wait(lock, [this] { return m_busy < m_running; });
      --m_waiting;
    }
    ++m_busy;
    return Slot(*this);
  }

private:
  void release() {
    {
      std::lock_guard lock(m_mutex);
      --m_busy;
    }
    m_free.notify_one();
  }

  std::mutex m_mutex;
  std::condition_variable m_free;
  int m_running, m_waitingMax;
  long long m_maxPixels;
  int m_busy = 0, m_waiting = 0;
};

}  // namespace rupture::server
