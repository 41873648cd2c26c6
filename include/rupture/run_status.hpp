#pragma once
// What a running simulation tells its watcher about where it is, for the periodic status line
// (the CLI off a terminal, the server's log; engine/io/status_line.hpp writes it) and the timing
// breakdown at the end of a run. Written by the run about every 0.1 s of wall time, read by the
// watcher from another thread.
#include <chrono>
#include <cstdint>
#include <limits>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace rupture {

/// The run's state now, in SI units; a field the scenario does not have stays at its "none" value.
struct RunStatus {
  static constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
  std::int64_t step = -1;      ///< time steps done (-1: not stepping yet)
  double time = kNone;         ///< simulated time (s)
  double strain = kNone;       ///< imposed strain (1), for the strain-driven scenarios
  std::string headlineName;    ///< what the headline quantity is, in words ("mean stress")
  std::string headlineUnit;    ///< its SI unit ("Pa")
  double headline = kNone;     ///< the quantity a reader watches, e.g. the mean boundary stress
  std::int64_t brokenBonds = -1;  ///< -1: the scenario has no bonds
  double particles = 0;        ///< elements or particles stepped (for the particle-steps/s)
};

/// The latest RunStatus, shared between the run (publish) and its watcher (latest).
class RunStatusBoard {
public:
  void publish(const RunStatus& status) {
    std::lock_guard lock(m_mutex);
    m_status = status;
  }
  RunStatus latest() const {
    std::lock_guard lock(m_mutex);
    return m_status;
  }

private:
  mutable std::mutex m_mutex;
  RunStatus m_status;
};

/// The phase in which a run takes the time steps its RunStatus counts (the timing breakdown's
/// speed is over it).
inline constexpr const char* kSteppingPhase = "time stepping";

/// Wall time of a run by phase ("building the sample", "time stepping", "writing the result"),
/// for the breakdown printed at the end: a phase lasts from its enter() to the next; charge()
/// moves time spent inside the current phase on an interleaved task (writing checkpoints or
/// snapshots during the stepping) to that task's own line.
class RunPhases {
public:
  struct Phase {
    std::string name;
    double seconds = 0;
  };

  void enter(const std::string& name) {
    std::lock_guard lock(m_mutex);
    closeCurrent();
    m_current = indexOf(name);
  }
  void charge(const std::string& name, double seconds) {
    std::lock_guard lock(m_mutex);
    const std::size_t k = indexOf(name);
    m_phases[k].seconds += seconds;
    if (m_current) m_phases[*m_current].seconds -= seconds;
  }
  /// Ends the current phase (at the end of the run; a later enter() starts a new one).
  void finish() {
    std::lock_guard lock(m_mutex);
    closeCurrent();
    m_current.reset();
  }
  /// Every phase in the order first entered, the current one counted up to now.
  std::vector<Phase> totals() const {
    std::lock_guard lock(m_mutex);
    std::vector<Phase> out = m_phases;
    if (m_current) out[*m_current].seconds += secondsSince(m_since);
    return out;
  }

private:
  using Clock = std::chrono::steady_clock;
  static double secondsSince(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }
  void closeCurrent() {
    if (m_current) m_phases[*m_current].seconds += secondsSince(m_since);
    m_since = Clock::now();
  }
  std::size_t indexOf(const std::string& name) {
    for (std::size_t k = 0; k < m_phases.size(); ++k)
      if (m_phases[k].name == name) return k;
    m_phases.push_back({name, 0.0});
    return m_phases.size() - 1;
  }

  mutable std::mutex m_mutex;
  std::vector<Phase> m_phases;
  std::optional<std::size_t> m_current;
  Clock::time_point m_since = Clock::now();
};

}  // namespace rupture
