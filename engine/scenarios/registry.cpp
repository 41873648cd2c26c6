#include <omp.h>

#include <algorithm>

#include "scenarios/scenario.hpp"
#include "io/spec_reader.hpp"
#include "io/unknown_keys.hpp"

namespace rupture {

// One factory per scenario file.
Scenario dynamicTensionScenario();
Scenario elasticPropertiesScenario();
Scenario damBreakScenario();      // scenarios/dam_break/
Scenario pistonColumnScenario();   // scenarios/piston_column/
Scenario impactScenario();         // scenarios/impact/
Scenario tankImpactScenario();     // scenarios/tank_impact/

const std::vector<Scenario>& scenarioRegistry() {
  static const std::vector<Scenario> registry = {dynamicTensionScenario(), elasticPropertiesScenario(),
                                                 damBreakScenario(), pistonColumnScenario(), impactScenario(),
                                                 tankImpactScenario()};
  return registry;
}

std::string embeddedSchema(const std::string& name) {
  struct Entry { const char* name; const char* text; };
  static const Entry entries[] = {
#include "rupture_schemas.inc"
      {"", ""}};
  for (const Entry& e : entries)
    if (name == e.name) return e.text;
  return {};
}

const Scenario& scenarioFor(const nlohmann::json& spec) {
  std::string names;
  for (const Scenario& s : scenarioRegistry()) names += (names.empty() ? "\"" : ", \"") + s.info.name + "\"";
  if (!spec.is_object()) throw SpecError("(root)", io::describeValue(spec), "a JSON object with a \"scenario\" field");
  auto it = spec.find("scenario");
  if (it == spec.end()) throw SpecError("scenario", "(missing)", "one of " + names + " (required)");
  if (it->is_string())
    for (const Scenario& s : scenarioRegistry())
      if (s.info.name == it->get<std::string>()) return s;
  throw SpecError("scenario", io::describeValue(*it), "one of " + names);
}

const ScenarioInfo* findScenario(const std::string& name) {
  for (const Scenario& s : scenarioRegistry())
    if (s.info.name == name) return &s.info;
  return nullptr;
}

std::vector<ScenarioInfo> listScenarios() {
  std::vector<ScenarioInfo> out;
  for (const Scenario& s : scenarioRegistry()) out.push_back(s.info);
  return out;
}

nlohmann::json scenarioSchema(const std::string& name) {
  for (const Scenario& s : scenarioRegistry())
    if (s.info.name == name) return nlohmann::json::parse(embeddedSchema(name));
  return scenarioFor({{"scenario", name}}), nlohmann::json();  // throws SpecError naming the field
}

namespace {

/// The scenario of a spec whose keys its schema all knows (unknown keys are reported first, with
/// the nearest allowed key, before any value is read and any required key is found missing).
const Scenario& scenarioWithKnownKeys(const nlohmann::json& spec) {
  const Scenario& scenario = scenarioFor(spec);
  static const std::vector<nlohmann::json> schemas = [] {
    std::vector<nlohmann::json> out;
    for (const Scenario& s : scenarioRegistry()) out.push_back(nlohmann::json::parse(embeddedSchema(s.info.name)));
    return out;
  }();
  io::rejectUnknownKeys(spec, schemas[static_cast<std::size_t>(&scenario - scenarioRegistry().data())]);
  return scenario;
}

}  // namespace

void validateSpec(const nlohmann::json& spec) { scenarioWithKnownKeys(spec).validate(spec); }

RunEstimate estimateRun(const nlohmann::json& spec) {
  const Scenario& scenario = scenarioWithKnownKeys(spec);
  if (scenario.estimate) return scenario.estimate(spec);  // parses, so it validates too
  scenario.validate(spec);
  return {};
}

RunOutcome runSpec(const nlohmann::json& spec, const std::string& resultPath, RunControl& control, int threads) {
  const Scenario& scenario = scenarioWithKnownKeys(spec);
  scenario.validate(spec);
  // OpenMP's thread count is per calling thread: each server worker sets its own.
  omp_set_num_threads(std::max(1, threads));
  return scenario.run(spec, resultPath, control);
}

}  // namespace rupture
