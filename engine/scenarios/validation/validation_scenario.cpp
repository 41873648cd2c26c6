// The validation scenario: one published case of validation/ (docs/validation.md) run at a level,
// its numbers compared with the case's references. A run's file holds the spec, the comparison as
// JSON (/validation/result) and the verdict's counts in /summary; the job server runs the suite as a
// sweep over "case", and `rupture validate-suite` as one run per case, so both write the same files
// and the same report (include/rupture/validation.hpp).
#include <algorithm>
#include <chrono>

#include "io/result_file.hpp"
#include "io/spec_reader.hpp"
#include "scenarios/run_support.hpp"
#include "scenarios/scenario.hpp"
#include "validation/case_runner.hpp"

namespace rupture {

namespace {

constexpr const char* kScenarioName = "validation";

struct ValidationSpec {
  std::string description;
  const validation::ValidationCase* validationCase = nullptr;
  std::string level = "full";
};

const ResultFields& validationSummaryFields() {
  static const ResultFields fields = {
      {"verdict", "", "Verdict", "pass, fail, known failure (documented), or unexpected pass (a known failure that now passes)"},
      {"quantities", "1", "Quantities", "Quantities compared at this level"},
      {"passed", "1", "Passed", "Quantities within their tolerance"},
      {"failed", "1", "Failed", "Quantities outside their tolerance and not known to be"},
      {"known_failures", "1", "Known failures", "Quantities outside their tolerance for a documented reason"},
      {"unexpected_passes", "1", "Unexpected passes", "Known failures that are within their tolerance now"},
      {"worst_deviation", "1", "Worst deviation", "Largest |ours - reference| / allowed difference over the quantities (at most 1 passes)"},
      {"member_runs", "1", "Member runs", "Runs the case made"},
      {"wall_time_s", "s", "Wall time", "Wall-clock time of the case"},
      {"completed", "1", "Completed", "1 when every run of the case finished, 0 when cancelled"},
  };
  return fields;
}

ValidationSpec parseValidationSpec(const nlohmann::json& json) {
  const io::SpecReader root(json, "");
  root.choice("scenario", {kScenarioName});
  ValidationSpec s;
  s.description = root.string("description", "");
  std::vector<std::string> ids;
  for (const validation::ValidationCase& c : validation::validationCases()) ids.push_back(c.id);
  s.validationCase = validation::findValidationCase(root.choice("case", ids));
  s.level = root.choice("level", {"quick", "full"}, "full");
  if (s.level == "quick" && !s.validationCase->inQuick)
    root.fail("level", "\"full\": case " + s.validationCase->id + " has no quick level (" + s.validationCase->quickNote + ")");
  root.finish();
  return s;
}

nlohmann::json resolved(const ValidationSpec& s) {
  nlohmann::json j = {{"scenario", kScenarioName}, {"case", s.validationCase->id}, {"level", s.level}};
  if (!s.description.empty()) j["description"] = s.description;
  return j;
}

/// The largest member run, and the longest: the case's runs are made one at a time.
RunEstimate estimateValidation(const ValidationSpec& s) {
  RunEstimate largest, longest;
  for (const auto& [name, members] : validation::caseSpecs(*s.validationCase, s.level))
    for (const nlohmann::json& member : members) {
      const RunEstimate e = estimateRun(member);
      if (e.memoryBytes > largest.memoryBytes) largest = e;
      if (e.steps > longest.steps) longest = e;
    }
  largest.field = "case";
  largest.steps = longest.steps;
  largest.timeStep = longest.timeStep;
  largest.stepsBasis = "its longest run: " + longest.stepsBasis;
  largest.stepsField = largest.timeStepField = longest.steps > 0 ? "case" : "";
  return largest;
}

RunOutcome runValidation(const ValidationSpec& s, const nlohmann::json& json, const std::string& resultPath,
                         RunControl& control) {
  const auto wallStart = std::chrono::steady_clock::now();
  io::ResultFile file(resultPath, kScenarioName);
  file.writeSpec(resolved(s), json);
  const validation::ValidationCase& c = *s.validationCase;
  std::int64_t members = 0;
  for (const auto& [name, specs] : validation::caseSpecs(c, s.level)) members += static_cast<std::int64_t>(specs.size());
  logStage(control, "validation case " + c.id + " (" + s.level + "): " + std::to_string(members) + " run(s)");
  const auto data = validation::runCase(c, s.level, resultPath + ".runs", control, control.threads);
  nlohmann::json summary = {{"member_runs", members}};  // the case and level are the spec's (/spec)
  summary["wall_time_s"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - wallStart).count();
  if (!data) {
    summary["completed"] = 0;
    return finishRun(file, summary, declaredUnits<validationSummaryFields>(), false, "cancelled", control);
  }
  const nlohmann::json result = validation::evaluateCase(c, s.level, *data);
  file.file().createGroup("/validation");
  file.file().writeDataset("/validation/result", std::vector<std::string>{result.dump()}, "");
  const nlohmann::json& counts = result["counts"];
  summary["verdict"] = result["verdict"];
  summary["quantities"] = result["quantities"].size();
  summary["passed"] = counts["pass"];
  summary["failed"] = counts["fail"];
  summary["known_failures"] = counts["known_failure"];
  summary["unexpected_passes"] = counts["unexpected_pass"];
  summary["worst_deviation"] = result["worst_deviation"].is_number() ? result["worst_deviation"] : nlohmann::json(nullptr);
  summary["completed"] = 1;
  return finishRun(file, summary, declaredUnits<validationSummaryFields>(), true,
                   c.id + ": " + result["verdict"].get<std::string>(), control);
}

}  // namespace

Scenario validationScenario() {
  return scenarioOf<ValidationSpec>(kScenarioName, validationSummaryFields(), {}, parseValidationSpec,
                                    estimateValidation, runValidation);
}

}  // namespace rupture
