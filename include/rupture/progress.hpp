#pragma once
// One estimator of the time a run still needs, shared by the CLI's progress bar and the job
// server's progress documents, so the two never disagree; and one rule for the fraction they show.
#include <algorithm>

namespace rupture {

/// The largest fraction shown while a run is still running: 100 % means finished. (A scenario's
/// progress follows its time stepping, which may reach its end well before the run has counted its
/// fragments and written its file.)
inline constexpr double kMostWhileRunning = 0.99;

/// The fraction a watcher shows of a run still running: `fraction` clamped to [0, 0.99].
inline double runningFraction(double fraction) {
  return std::clamp(fraction >= 0 ? fraction : 0.0, 0.0, kMostWhileRunning);
}

/// Seconds left if the rate so far holds: elapsed · (1 − f) / f. Negative (unknown) below 1 % done,
/// where the rate says too little, and for a non-finite or negative input.
inline double estimateRemainingSeconds(double elapsedSeconds, double fraction) {
  if (!(elapsedSeconds >= 0) || !(fraction >= 0.01)) return -1.0;
  if (fraction >= 1.0) return 0.0;
  return elapsedSeconds * (1.0 - fraction) / fraction;
}

}  // namespace rupture
