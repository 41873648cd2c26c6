#include "scenarios/bonded/bonded_run.hpp"

#include <cstdint>

#include "scenarios/run_support.hpp"

namespace rupture {

std::optional<SampleReport> buildRunSample(const SampleSpec& sample, const MaterialSpec& material, BondedSystem& system,
                                           RunControl& control, const std::string& directory, SampleCacheUse* use) {
  control.progress.store(0.0);
  logStage(control, "building the sample");
  enterPhase(control, "building the sample");
  SampleCacheUse ignored;
  try {
    return buildSampleCached(sample, material, system, directory, control.cancel, use ? *use : ignored);
  } catch (const RunCancelled&) {
    return std::nullopt;
  }
}

nlohmann::json bondedRunScalars(const BondedSystem& system, double timeStep, double criticalTimeStep,
                                const SampleReport& report) {
  return {{"final_time", system.time},
          {"steps", static_cast<std::int64_t>(system.steps)},
          {"time_step", timeStep},
          {"critical_time_step", criticalTimeStep},
          {"elements", static_cast<std::int64_t>(report.elements)},
          {"bonds", static_cast<std::int64_t>(report.bonds)}};
}

}  // namespace rupture
