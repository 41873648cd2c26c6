#pragma once
// What a run's step estimate is made of (RunEstimate::steps, rupture/run.hpp): its time loops, each
// a simulated duration over an estimated stable step, capped by the spec's run.max_steps. The
// scenarios fill these from the parsed spec, before anything is built, for --max-run-steps.
#include <cstdint>
#include <string>
#include <vector>

#include "rupture/run.hpp"

namespace rupture::io {

/// One time loop of a run (the main run, a preliminary run, a relaxation).
struct RunLoop {
  double duration = 0;            ///< simulated time to its end (s)
  double timeStep = 0;            ///< the estimated step (s)
  double maxSteps = 0;            ///< the spec's cap on its steps (run.max_steps), or +inf
  std::string field;              ///< the spec field that sets its duration ("loading.strain_rate")
  std::string what;               ///< its duration in words ("run.max_strain / loading.strain_rate")
};

/// Fills e.steps (the loops' capped steps added up), e.timeStep (the smallest loop step),
/// e.stepsField (the field of the loop with the most steps), e.timeStepField and e.stepsBasis (the
/// loops' durations and steps in words, then `stepRule`, how the step was estimated).
void addRunLength(RunEstimate& e, const std::vector<RunLoop>& loops, const std::string& timeStepField,
                  const std::string& stepRule);

}  // namespace rupture::io
