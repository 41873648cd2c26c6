#pragma once
// Small helpers every scenario driver uses to talk to its watcher (RunControl) and to write numbers
// into messages.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <string>

#include "core/format_number.hpp"
#include "rupture/run.hpp"

namespace rupture {

/// A summary scalar that may be unknown: NaN (and ±inf) are written as null.
inline nlohmann::json nullIfNaN(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

/// The next output time once the clock has passed `next`: next + k interval, the first above
/// `reached`, as `while (next <= reached) next += interval` finds it, in a bounded number of
/// additions. That loop never ends when interval falls below the precision of the clock (5e-26 s
/// after 1e-8 s) and takes billions of rounds when the step is billions of intervals; here a
/// clock far ahead is caught up in one multiplication, and one that the additions cannot pass is
/// passed by one ulp.
inline double nextOutputTime(double next, double reached, double interval) {
  constexpr double kDirectRounds = 64;  // fewer behind: the additions themselves, bit for bit as before
  if (const double behind = (reached - next) / interval; behind > kDirectRounds)
    next += std::floor(behind - 1) * interval;
  for (int round = 0; next <= reached; ++round) {
    const double advanced = next + interval;
    if (!(advanced > next) || round > 4 * kDirectRounds) return std::nextafter(reached, INFINITY);
    next = advanced;
  }
  return next;
}

/// A stage message for the watcher (progress line, server log), if it listens.
inline void logStage(const RunControl& control, const std::string& message) {
  if (control.log) control.log(message);
}

/// Starts a phase of the run's timing breakdown (RunPhases): it lasts until the next one.
inline void enterPhase(RunControl& control, const std::string& name) { control.phases.enter(name); }

/// Where the run is now, for the watcher's periodic status line.
inline void reportStatus(RunControl& control, const RunStatus& status) { control.status.publish(status); }

/// Monotone progress in [0, 1]: a value below the last one reported is ignored.
inline void reportProgress(RunControl& control, double fraction) {
  fraction = std::clamp(fraction, 0.0, 1.0);
  if (fraction > control.progress.load(std::memory_order_relaxed)) control.progress.store(fraction);
}

/// The end every run shares: the summary written with its units, the file closed (kept and marked
/// incomplete when cancelled), the watcher told. `File` is any result writer with
/// writeAttributes(group, values, units) and finish(completed).
template <class File>
RunOutcome finishRun(File& file, const nlohmann::json& summary, const std::map<std::string, std::string>& units,
                     bool completed, const std::string& stopReason, RunControl& control) {
  enterPhase(control, "writing the result");
  file.writeAttributes("/summary", summary, units);
  file.finish(completed);
  if (completed) reportProgress(control, 1.0);
  logStage(control, completed ? "done: " + stopReason : "cancelled: file marked incomplete");
  return {summary, completed};
}

/// A run cancelled before it had a state to record (its sample or lattice still being built): the
/// file holds the spec and a summary saying so (completed 0, stop reason, wall time, and the
/// scenario's `known` scalars), and is marked incomplete. `File` as for finishRun, with writeSpec.
template <class File>
RunOutcome cancelledBeforeStart(File& file, const nlohmann::json& resolvedSpec, const nlohmann::json& inputSpec,
                                nlohmann::json known, const std::map<std::string, std::string>& units,
                                const std::string& stage, RunControl& control,
                                std::chrono::steady_clock::time_point wallStart) {
  file.writeSpec(resolvedSpec, inputSpec);
  nlohmann::json summary = std::move(known);
  summary["completed"] = 0;
  summary["stop_reason"] = "cancelled";
  summary["wall_time_s"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - wallStart).count();
  file.writeAttributes("/summary", summary, units);
  file.finish(false);
  logStage(control, "cancelled while " + stage + ": file marked incomplete");
  return {summary, false};
}

}  // namespace rupture
