#pragma once
// A scenario = a registered name, its description, a validator and a run function. The registry
// (scenarios/registry.cpp) lists them explicitly: adding a scenario is one file plus one line there.
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "rupture/run.hpp"

namespace rupture {

struct Scenario {
  ScenarioInfo info;
  /// Throws SpecError for the first invalid field (the "scenario" key is already checked).
  std::function<void(const nlohmann::json& spec)> validate;
  /// Size of a spec's run; validates like `validate` (optional: scenarios without one report
  /// particles = 0).
  std::function<RunEstimate(const nlohmann::json& spec)> estimate;
  /// Runs a valid spec; see rupture::runSpec for the file contract.
  std::function<RunOutcome(const nlohmann::json& spec, const std::string& resultPath, RunControl& control)> run;
};

/// All registered scenarios, in a fixed order.
const std::vector<Scenario>& scenarioRegistry();

/// The scenario named by spec["scenario"]; throws SpecError(field "scenario") otherwise.
const Scenario& scenarioFor(const nlohmann::json& spec);

/// The embedded JSON Schema text of a scenario (api/schemas/<name>.schema.json); empty if none.
std::string embeddedSchema(const std::string& name);

}  // namespace rupture
