#pragma once
// Runs the real `rupture` binary in a shell and captures its exit code, stdout and stderr.
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

namespace rupture::testing {

struct CliResult {
  int exitCode = -1;
  std::string out, err;
};

inline std::string readWhole(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Runs `rupture ARGS` (arguments are passed through the shell as written).
inline CliResult runCli(const std::string& args) {
  static int counter = 0;
  const auto dir = std::filesystem::temp_directory_path() / ("rupture-cli-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto out = dir / ("out" + std::to_string(counter) + ".txt");
  const auto err = dir / ("err" + std::to_string(counter++) + ".txt");
  const std::string command = std::string(RUPTURE_CLI) + " " + args + " > " + out.string() + " 2> " + err.string();
  const int status = std::system(command.c_str());
  CliResult r;
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = readWhole(out);
  r.err = readWhole(err);
  return r;
}

/// Writes a JSON spec to a temporary file and returns its path.
inline std::string writeSpec(const nlohmann::json& spec, const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("rupture-cli-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto path = dir / name;
  std::ofstream(path) << spec.dump(2);
  return path.string();
}

/// The small example (examples/dynamic-tension-small.json) as shipped.
inline nlohmann::json smallExampleSpec() {
  return nlohmann::json::parse(readWhole(std::filesystem::path(RUPTURE_SOURCE_DIR) / "examples" / "dynamic-tension-small.json"));
}

/// The small example (examples/dynamic-tension-small.json) pulled fast, at 1e7 /s from the VL
/// field: a run of a few seconds, for the tests that need a real run file.
inline nlohmann::json quickSmallSpec() {
  nlohmann::json spec = smallExampleSpec();
  spec["loading"] = {{"strain_rate", 1e7}, {"initial_velocity", "VL"}};
  return spec;
}

}  // namespace rupture::testing
