#include "scenarios/dynamic_tension/tension_stop_forecast.hpp"

#include <algorithm>
#include <cmath>

namespace rupture {
namespace {

// Measured on 13 runs of examples/dynamic-tension-small.json's sample (VL; sample seeds 1-8, no
// pores; 1e5-1e7 /s) and checked on 6 others (docs/dynamic-tension.md, "Progress"): the crossing
// took 0.2-4 times the onset time, the breaking after the separation 1.5-5 S. The forecast takes
// the long end of each, so the progress lags rather than runs ahead.
/// The crack's crossing, from the first break to the separation, over the time of the first break.
constexpr double kCrossingOverOnset = 1.0;
/// The breaking that goes on after the separation, over the settle time S, before any is seen.
constexpr double kBreakingOverSettle = 5.0;
/// Breaking that has gone on for a time g goes on for kBreakingGrowth × g more.
constexpr double kBreakingGrowth = 2.0;

/// Breaking still to come after `goneOn` seconds of it, of which the last `quiet` without a break:
/// kBreakingGrowth times what has gone on (at least the prior's rest), less as the quiet spell
/// nears S (at S the run stops) but slowly (as the square root of what is left of S), since
/// breaking often starts again after a spell of most of S.
double breakingToCome(double goneOn, double quiet, double settleTime) {
  const double expected = std::max(kBreakingOverSettle * settleTime - goneOn, kBreakingGrowth * goneOn);
  return settleTime > 0 ? expected * std::sqrt(std::max(0.0, 1.0 - quiet / settleTime)) : expected;
}

}  // namespace

double forecastStopTime(double time, const TensionObservables& observed, const TensionStopRules& rules,
                        double onsetEstimate) {
  const double settle = rules.settleTime;
  double stop = rules.capTime;
  if (observed.separated()) {
    const double separation = observed.separationTime();
    const double lastEvent = std::max(separation, observed.lastBreakTime());
    stop = lastEvent + breakingToCome(lastEvent - separation, time - lastEvent, settle) + settle;
  } else if (observed.broken() > 0) {
    const double onset = observed.onsetTime();
    const double separation = onset + std::max(kCrossingOverOnset * onset, 2.0 * (time - onset));
    stop = separation + breakingToCome(0.0, 0.0, settle) + settle;
  } else if (onsetEstimate > 0) {
    stop = onsetEstimate * (1.0 + kCrossingOverOnset) + breakingToCome(0.0, 0.0, settle) + settle;
  }
  stop = std::min(stop, rules.capTime);
  // While it runs, it has not stopped: the forecast is past now by at least a hundredth of it.
  return std::max(stop, time * 1.01);
}

}  // namespace rupture
