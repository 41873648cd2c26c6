#pragma once
// Cooperative cancellation for long engine stages (packing, bonding, pore carving). The watcher
// (CLI signal handler, server worker) sets an atomic flag; a stage polls it between units of work
// that take well under 0.2 s and unwinds with RunCancelled. Polling is one relaxed atomic load,
// cheap enough for every iteration of an outer loop.
#include <atomic>
#include <stdexcept>

namespace rupture {

/// Thrown out of a stage that noticed the cancel flag; no result of the stage is usable.
class RunCancelled : public std::runtime_error {
public:
  RunCancelled() : std::runtime_error("cancelled") {}
};

class Cancellation {
public:
  Cancellation() = default;
  /// Not explicit, so a stage can take `&control.cancel` directly; nullptr never cancels.
  Cancellation(const std::atomic<bool>* flag) : m_flag(flag) {}  // NOLINT(google-explicit-constructor)
  /// `finishFirst`: while it is set, the flag does not interrupt the stage: a run stopped to be
  /// continued (RunControl::checkpointOnCancel) ends its step whole, to checkpoint it.
  Cancellation(const std::atomic<bool>* flag, const std::atomic<bool>* finishFirst)
      : m_flag(flag), m_finishFirst(finishFirst) {}

  bool requested() const noexcept {
    return m_flag != nullptr && m_flag->load(std::memory_order_relaxed) &&
           !(m_finishFirst != nullptr && m_finishFirst->load(std::memory_order_relaxed));
  }
  void throwIfRequested() const {
    if (requested()) throw RunCancelled();
  }

private:
  const std::atomic<bool>* m_flag = nullptr;
  const std::atomic<bool>* m_finishFirst = nullptr;
};

}  // namespace rupture
