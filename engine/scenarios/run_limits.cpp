// The limits every door applies to a parsed spec's estimate before it runs: a stable time step
// that is a finite positive number (always), and at most --max-run-steps steps (the operator's).
#include <algorithm>
#include <cmath>

#include "core/format_number.hpp"
#include "scenarios/scenario.hpp"

namespace rupture {

namespace {

/// The value of a dotted field as the spec holds it, for the error ("(default)" when absent).
std::string specValueAt(const nlohmann::json& spec, const std::string& field) {
  std::string pointer = "/" + field;
  std::replace(pointer.begin(), pointer.end(), '.', '/');
  try {
    const nlohmann::json::json_pointer at(pointer);
    return spec.contains(at) ? spec.at(at).dump() : std::string("(default)");
  } catch (const nlohmann::json::exception&) {
    return "(default)";
  }
}

}  // namespace

void checkStableStep(const nlohmann::json& spec, const RunEstimate& e) {
  if (e.timeStepField.empty() || (std::isfinite(e.timeStep) && e.timeStep > 0)) return;
  throw SpecError(e.timeStepField, specValueAt(spec, e.timeStepField),
                  "values giving a stable time step that is a finite positive number (this spec gives " +
                      formatNumber(e.timeStep) + " s: " + e.stepsBasis + ")");
}

void checkRunSteps(const nlohmann::json& spec, const RunEstimate& e, double maxSteps) {
  if (e.stepsField.empty() || e.steps <= maxSteps) return;  // NaN steps are refused too
  throw SpecError(e.stepsField, specValueAt(spec, e.stepsField),
                  "a run of at most " + formatNumber(maxSteps) + " time steps (--max-run-steps); this spec needs about " +
                      formatNumber(std::round(e.steps)) + " (" + e.stepsBasis +
                      "): shorten the run, coarsen the sample or lower run.max_steps");
}

}  // namespace rupture
