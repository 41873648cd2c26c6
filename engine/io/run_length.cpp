#include "io/run_length.hpp"

#include <cmath>
#include <cstdio>

namespace rupture::io {

namespace {
/// Three significant digits: the loops' figures are estimates.
std::string threeDigits(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", v);
  return text;
}
}  // namespace

void addRunLength(RunEstimate& e, const std::vector<RunLoop>& loops, const std::string& timeStepField,
                  const std::string& stepRule) {
  e.steps = 0;
  e.timeStep = loops.empty() ? 0 : loops.front().timeStep;
  e.timeStepField = timeStepField;
  double most = -1;
  std::string basis;
  for (const RunLoop& loop : loops) {
    // NaN (a step that is not a number) stays NaN, so that admission refuses it.
    const double natural = loop.duration / loop.timeStep;
    const double steps = natural > loop.maxSteps ? loop.maxSteps : natural;
    e.steps += steps;
    if (!(loop.timeStep >= e.timeStep)) e.timeStep = loop.timeStep;
    if (!(steps <= most)) {
      most = steps;
      e.stepsField = loop.field;
    }
    basis += (basis.empty() ? "" : "; ") + loop.what + " " + threeDigits(loop.duration) + " s over " +
             threeDigits(loop.timeStep) + " s steps" +
             (natural > loop.maxSteps ? " (" + threeDigits(natural) + ", capped by run.max_steps " +
                                            threeDigits(loop.maxSteps) + ")"
                                      : "");
  }
  e.stepsBasis = basis + "; " + stepRule;
}

}  // namespace rupture::io
