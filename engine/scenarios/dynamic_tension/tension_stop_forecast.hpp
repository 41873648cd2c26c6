#pragma once
// When the main dynamic-tension run will stop, forecast from its stop rules and what it has seen
// so far, and revised at every call; its progress is the simulated time done over that stop time
// (the steps are equal in time, so this is the fraction of its steps). docs/dynamic-tension.md,
// "Progress", gives the model and the runs it was measured on.
//
// The run stops at the first of: separated and no bond broken for the settle time S (a wave round
// trip) since the separation and the last break; broken, quiet and unloaded; run.max_strain;
// run.max_steps. So its stop time is
//   T = t_separation + (breaking after the separation) + S
// with each term known once it has happened and forecast before:
// - before the first break, t_onset from the worst bond (its stress over its strength grows about
//   linearly with the strain, which extrapolates the onset), and t_separation = t_onset + the
//   crack's crossing, forecast as kCrossingOverOnset × t_onset;
// - after the first break and before the separation, that crossing from the onset on, at least
//   twice the time since the onset (a crack that has run that long runs about as long again);
// - after the separation, the breaking that goes on (fragments and debris ringing) forecast as
//   kBreakingOverSettle × S, or, once it has gone on for g, kBreakingGrowth × g more; shrinking
//   over a quiet spell as the run nears its stop;
// and T is at most the time of run.max_strain or run.max_steps. A VH preliminary run's steps are
// added by the caller (dynamic_tension.cpp).
#include "scenarios/dynamic_tension/tension_observables.hpp"

namespace rupture {

struct TensionStopRules {
  double settleTime = 0;  ///< S: quiet time after separation (s)
  double capTime = 0;     ///< time at run.max_strain or run.max_steps, whichever comes first (s)
};

/// The forecast stop time (s), above `time` while the run runs; `onsetEstimate` is the time of the
/// first break extrapolated from the worst bond (s; NaN or ≤ 0: not known yet).
double forecastStopTime(double time, const TensionObservables& observed, const TensionStopRules& rules,
                        double onsetEstimate);

}  // namespace rupture
