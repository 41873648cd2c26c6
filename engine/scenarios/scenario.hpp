#pragma once
// A scenario = a registered name, its description, a parser, an estimate and a run function. The registry
// (scenarios/registry.cpp) lists them explicitly: adding a scenario is one file plus one line there.
#include <functional>
#include <memory>
#include <type_traits>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "rupture/run.hpp"
#include "rupture/sample_preview.hpp"

namespace rupture {

/// A registered scenario. Its spec is parsed once into the scenario's typed value (held behind
/// `const void*`, typed again by scenarioOf), which the estimate and the run read.
struct Scenario {
  ScenarioInfo info;
  /// Parses and validates a spec (the "scenario" key and unknown keys already checked); throws
  /// SpecError for the first invalid field.
  std::function<std::shared_ptr<const void>(const nlohmann::json& spec)> parse;
  /// Size of a parsed spec's run (optional: scenarios without one report particles = 0).
  std::function<RunEstimate(const void* parsed)> estimate;
  /// Runs a parsed spec (`spec` is the JSON it came from, recorded in the file); see
  /// rupture::runSpec for the file contract.
  std::function<RunOutcome(const void* parsed, const nlohmann::json& spec, const std::string& resultPath,
                           RunControl& control)>
      run;
  /// Builds a parsed spec's discretisation as the run starts, without stepping it (optional: a
  /// scenario without one has no preview picture; rupture/sample_preview.hpp).
  std::function<SamplePreview(const void* parsed, const std::atomic<bool>& cancel, const std::string& cacheDirectory)>
      preview;
};

/// A scenario's info: `name`, the title and description of its embedded JSON Schema, and its result
/// declarations. Throws std::logic_error when the build embedded no schema of that name.
ScenarioInfo describedScenario(const std::string& name, ResultFields summary, ResultFields series);

/// The one way a scenario file builds its Scenario: its name (the title and description come from its
/// JSON Schema, api/schemas/<name>.schema.json, where they are written once), its result declarations, and
/// its parse, estimate and run functions over its own spec type.
template <class Spec>
Scenario scenarioOf(const std::string& name, ResultFields summary, ResultFields series,
                    Spec (*parse)(const nlohmann::json&),
                    std::type_identity_t<RunEstimate (*)(const Spec&)> estimate,
                    std::type_identity_t<RunOutcome (*)(const Spec&, const nlohmann::json&, const std::string&,
                                                        RunControl&)>
                        run) {
  Scenario s;
  s.info = describedScenario(name, std::move(summary), std::move(series));
  s.parse = [parse](const nlohmann::json& spec) -> std::shared_ptr<const void> {
    return std::make_shared<const Spec>(parse(spec));
  };
  if (estimate) s.estimate = [estimate](const void* parsed) { return estimate(*static_cast<const Spec*>(parsed)); };
  s.run = [run](const void* parsed, const nlohmann::json& spec, const std::string& resultPath, RunControl& control) {
    return run(*static_cast<const Spec*>(parsed), spec, resultPath, control);
  };
  return s;
}

/// `s` with its preview: `build` over the scenario's own spec type, calling the builders its run calls.
template <class Spec>
Scenario withPreview(Scenario s, SamplePreview (*build)(const Spec&, const std::atomic<bool>&, const std::string&)) {
  s.preview = [build](const void* parsed, const std::atomic<bool>& cancel, const std::string& cacheDirectory) {
    return build(*static_cast<const Spec*>(parsed), cancel, cacheDirectory);
  };
  return s;
}

/// All registered scenarios, in a fixed order.
const std::vector<Scenario>& scenarioRegistry();

/// The scenario named by spec["scenario"]; throws SpecError(field "scenario") otherwise.
const Scenario& scenarioFor(const nlohmann::json& spec);

/// Throws SpecError naming e.timeStepField unless the estimate's stable time step is a finite
/// positive number (parseSpec checks every spec; run_limits.cpp).
void checkStableStep(const nlohmann::json& spec, const RunEstimate& e);

/// The embedded JSON Schema text of a scenario (api/schemas/<name>.schema.json); empty if none.
std::string embeddedSchema(const std::string& name);

}  // namespace rupture
