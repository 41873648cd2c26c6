// rupture validate / scenarios / schema
#include <fstream>
#include <iostream>
#include <limits>

#include "cli/cli.hpp"
#include "cli/spec_file.hpp"
#include "rupture/run.hpp"

namespace rupture::cli {

namespace {

/// A server request file (the body of POST /processes/NAME/execution) has "inputs" (the spec without
/// "scenario": the URL names it) and no "scenario" of its own.
bool isServerRequest(const nlohmann::json& doc) {
  return doc.is_object() && doc.contains("inputs") && !doc.contains("scenario");
}

/// What rupture-server's admission checks of one spec: the spec itself, then its length.
void validateForRunning(const nlohmann::json& spec, double maxRunSteps) {
  checkRunSteps(spec, parseSpec(spec).estimate(), maxRunSteps);
}

}  // namespace

int validateCommand(const Args& args) {
  constexpr const char* usage =
      "validate: usage: rupture validate SPEC.json | REQUEST.json [--scenario NAME] [--max-run-steps N]";
  std::string path, scenarioOption;
  long long maxRunSteps = static_cast<long long>(kDefaultMaxRunSteps);
  for (std::size_t k = 0; k < args.size(); ++k) {
    if (args[k] == "--scenario") {
      if (k + 1 >= args.size()) return usageError("validate: option --scenario needs a value; " + std::string(usage));
      scenarioOption = args[++k];
    } else if (args[k] == "--max-run-steps") {
      if (k + 1 >= args.size()) return usageError("validate: option --max-run-steps needs a value; " + std::string(usage));
      if (!parseIntOption("--max-run-steps", args[++k], 1, std::numeric_limits<long long>::max(), maxRunSteps)) return 2;
    } else if (!args[k].empty() && args[k][0] == '-') {
      return usageError("validate: unknown option '" + args[k] + "'; allowed: --scenario, --max-run-steps");
    } else if (path.empty()) {
      path = args[k];
    } else {
      return usageError(usage);
    }
  }
  if (path.empty()) return usageError(usage);
  nlohmann::json doc;
  if (int code = readSpecFile(path, doc)) return code;

  if (!isServerRequest(doc)) {
    if (!scenarioOption.empty())
      return usageError("validate: --scenario is for a server request file; " + path + " is a spec (it names its scenario)");
    try {
      validateForRunning(doc, static_cast<double>(maxRunSteps));
    } catch (const SpecError& e) {
      return reportSpecError(path, e);
    }
    std::cout << path << ": valid " << doc["scenario"].get<std::string>() << " spec\n";
    return 0;
  }

  // A request: its inputs are the spec; the scenario comes from --scenario or inputs.scenario.
  const nlohmann::json& inputs = doc["inputs"];
  std::string scenario = scenarioOption;
  if (inputs.is_object() && inputs.contains("scenario") && inputs["scenario"].is_string()) {
    const std::string named = inputs["scenario"].get<std::string>();
    if (!scenario.empty() && scenario != named) {
      std::cerr << path << ": a server request file whose inputs.scenario is '" << named << "' but --scenario is '"
                << scenario << "'\n";
      return 2;
    }
    scenario = named;
  }
  if (scenario.empty()) {
    std::cerr << path << ": a server request file (the body of POST /processes/NAME/execution): its scenario is "
              << "named by the URL, not the file; give it with --scenario NAME (see rupture scenarios)\n";
    return 2;
  }
  if (!inputs.is_object()) {
    std::cerr << path << ": a server request file whose \"inputs\" is " << inputs.type_name()
              << "; allowed: an object, the spec without \"scenario\"\n";
    return 2;
  }
  nlohmann::json spec = inputs;
  spec["scenario"] = scenario;
  try {
    validateForRunning(spec, static_cast<double>(maxRunSteps));
  } catch (const SpecError& e) {
    std::cerr << path << ": a server request file for " << scenario << "; in its inputs: " << e.what() << "\n";
    return 2;
  }
  std::cout << path << ": a server request file for POST /processes/" << scenario
            << "/execution; its inputs are a valid " << scenario << " spec"
            << (doc.contains("sweep") || doc.contains("refine") || doc.contains("replicates")
                    ? " (the sweep, refine and replicates members are checked by the server)"
                    : "")
            << "\n";
  return 0;
}

int scenariosCommand(const Args& args) {
  if (!args.empty()) return usageError("scenarios: takes no arguments");
  for (const ScenarioInfo& s : listScenarios()) std::cout << s.name << "\t" << s.title << "\n";
  return 0;
}

int schemaCommand(const Args& args) {
  if (args.size() != 1) return usageError("schema: usage: rupture schema SCENARIO");
  try {
    std::cout << scenarioSchema(args[0]).dump(2) << "\n";
  } catch (const SpecError& e) {
    return usageError(std::string("schema: ") + e.what());
  }
  return 0;
}

}  // namespace rupture::cli
