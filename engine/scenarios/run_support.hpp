#pragma once
// Small helpers every scenario driver uses to talk to its watcher (RunControl) and to write numbers
// into messages.
#include <algorithm>
#include <sstream>
#include <string>

#include "rupture/run.hpp"

namespace rupture {

/// A number as the shortest stream text ("1e+06", "0.0003").
inline std::string formatNumber(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

/// A stage message for the watcher (progress line, server log), if it listens.
inline void logStage(const RunControl& control, const std::string& message) {
  if (control.log) control.log(message);
}

/// Monotone progress in [0, 1]: a value below the last one reported is ignored.
inline void reportProgress(RunControl& control, double fraction) {
  fraction = std::clamp(fraction, 0.0, 1.0);
  if (fraction > control.progress.load(std::memory_order_relaxed)) control.progress.store(fraction);
}

}  // namespace rupture
