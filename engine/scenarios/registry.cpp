#include <omp.h>

#include <algorithm>
#include <stdexcept>

#include "scenarios/scenario.hpp"
#include "io/checkpoint_file.hpp"
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
Scenario validationScenario();     // scenarios/validation/

const std::vector<Scenario>& scenarioRegistry() {
  static const std::vector<Scenario> registry = {dynamicTensionScenario(), elasticPropertiesScenario(),
                                                 damBreakScenario(), pistonColumnScenario(), impactScenario(),
                                                 tankImpactScenario(), validationScenario()};
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

ScenarioInfo describedScenario(const std::string& name, ResultFields summary, ResultFields series) {
  const std::string text = embeddedSchema(name);
  if (text.empty()) throw std::logic_error("scenario \"" + name + "\" has no embedded schema");
  const nlohmann::json schema = nlohmann::json::parse(text);
  return {name, schema.at("title").get<std::string>(), schema.at("description").get<std::string>(),
          std::move(summary), std::move(series)};
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

ParsedSpec parseSpec(const nlohmann::json& spec) {
  ParsedSpec parsed;
  parsed.m_scenario = &scenarioWithKnownKeys(spec);
  parsed.m_value = parsed.m_scenario->parse(spec);
  parsed.m_json = std::make_shared<const nlohmann::json>(spec);
  checkStableStep(spec, parsed.estimate());
  return parsed;
}

const std::string& ParsedSpec::scenarioName() const { return m_scenario->info.name; }

RunEstimate ParsedSpec::estimate() const {
  return m_scenario->estimate ? m_scenario->estimate(m_value.get()) : RunEstimate{};
}

void validateSpec(const nlohmann::json& spec) { parseSpec(spec); }

RunEstimate estimateRun(const nlohmann::json& spec) { return parseSpec(spec).estimate(); }

RunOutcome runSpec(const ParsedSpec& spec, const std::string& resultPath, RunControl& control, int threads) {
  // OpenMP's thread count is per calling thread: each server worker sets its own.
  omp_set_num_threads(std::max(1, threads));
  control.threads = std::max(1, threads);
  control.phases.enter("setting up");
  // The breakdown's last phase ends with the run, however it ends.
  struct PhasesFinisher {
    RunPhases& phases;
    ~PhasesFinisher() { phases.finish(); }
  } finisher{control.phases};
  if (control.resume) {
    const std::string checkpoint = io::checkpointPathFor(resultPath);
    io::checkCheckpointFits(io::readCheckpointHeader(checkpoint), checkpoint, spec.scenarioName(), spec.json());
  }
  return spec.m_scenario->run(spec.m_value.get(), spec.json(), resultPath, control);
}

RunOutcome runSpec(const nlohmann::json& spec, const std::string& resultPath, RunControl& control, int threads) {
  return runSpec(parseSpec(spec), resultPath, control, threads);
}

}  // namespace rupture
