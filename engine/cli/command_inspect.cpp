// rupture validate / scenarios / schema
#include <fstream>
#include <iostream>

#include "cli/cli.hpp"
#include "cli/spec_file.hpp"
#include "rupture/run.hpp"

namespace rupture::cli {

int validateCommand(const Args& args) {
  if (args.size() != 1) return usageError("validate: usage: rupture validate SPEC.json");
  nlohmann::json spec;
  if (int code = readSpecFile(args[0], spec)) return code;
  try {
    validateSpec(spec);
  } catch (const SpecError& e) {
    return reportSpecError(args[0], e);
  }
  std::cout << args[0] << ": valid " << spec["scenario"].get<std::string>() << " spec\n";
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
