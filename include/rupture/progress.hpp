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

/// Seconds over which a run must have progressed before its rate is trusted.
inline constexpr double kMinRateWindowSeconds = 2.0;

/// Seconds left at the run's own rate: the fraction gained since its anchor (the first progress
/// above 0 it reported, at anchorSeconds) over the time since then, so that building the sample or
/// waiting in a queue (no progress) does not count as slow progress. `fraction` was reported at
/// fractionSeconds and it is nowSeconds: the time since then counts as time without progress (the
/// rate falls while a run reports nothing new), so the estimate is never 0 before the fraction is
/// 1. Negative (unknown) before the run has progressed over kMinRateWindowSeconds, or for inputs
/// that say nothing.
inline double remainingSeconds(double anchorSeconds, double anchorFraction, double fractionSeconds, double fraction,
                               double nowSeconds) {
  if (fraction >= 1.0) return 0.0;
  const double window = fractionSeconds - anchorSeconds, gained = fraction - anchorFraction;
  if (!(anchorSeconds >= 0) || !(window >= kMinRateWindowSeconds) || !(gained > 0) || !(fraction > 0)) return -1.0;
  const double rate = gained / (window + std::max(0.0, nowSeconds - fractionSeconds));
  return (1.0 - fraction) / rate;
}

/// remainingSeconds for a watcher that sees the progress as it comes (the CLI's bar and progress
/// file): it keeps the anchor (the first sample above 0) and the latest sample.
class RemainingTime {
public:
  /// A sample: `fraction` done at `seconds` (any clock, the same for every call).
  void observe(double seconds, double fraction) {
    if (m_anchorSeconds < 0 && fraction > 0) m_anchorSeconds = seconds, m_anchorFraction = fraction;
    m_seconds = seconds;
    m_fraction = fraction;
  }
  /// Seconds left at `nowSeconds`; negative while unknown.
  double at(double nowSeconds) const {
    return remainingSeconds(m_anchorSeconds, m_anchorFraction, m_seconds, m_fraction, nowSeconds);
  }

private:
  double m_anchorSeconds = -1, m_anchorFraction = 0, m_seconds = -1, m_fraction = 0;
};

}  // namespace rupture
