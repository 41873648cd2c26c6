#pragma once
// Small helpers every scenario driver uses to talk to its watcher (RunControl) and to write numbers
// into messages.
#include <algorithm>
#include <map>
#include <string>

#include "core/format_number.hpp"
#include "rupture/run.hpp"

namespace rupture {

/// A stage message for the watcher (progress line, server log), if it listens.
inline void logStage(const RunControl& control, const std::string& message) {
  if (control.log) control.log(message);
}

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
  file.writeAttributes("/summary", summary, units);
  file.finish(completed);
  if (completed) reportProgress(control, 1.0);
  logStage(control, completed ? "done: " + stopReason : "cancelled: file marked incomplete");
  return {summary, completed};
}

}  // namespace rupture
