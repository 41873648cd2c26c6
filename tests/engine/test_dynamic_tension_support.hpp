#pragma once
// Helpers shared by the dynamic-tension tests: the small example spec with overrides, a scratch
// directory, one run through rupture::runSpec, and a preliminary-run cache per test process.
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/test_support.hpp"
#include "rupture/run.hpp"

namespace rupture::test {

namespace fs = std::filesystem;
using rupture::testing::ScratchDir;
using rupture::testing::rejectedField;

inline nlohmann::json readJson(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return nlohmann::json::parse(text.str());
}

inline std::string readText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

inline fs::path examplePath(const std::string& name) { return fs::path(RUPTURE_SOURCE_DIR) / "examples" / name; }

/// The small example with loading.strain_rate and loading.initial_velocity replaced.
inline nlohmann::json smallSpec(double strainRate, const std::string& field) {
  nlohmann::json spec = readJson(examplePath("dynamic-tension-small.json"));
  spec["loading"]["strain_rate"] = strainRate;
  spec["loading"]["initial_velocity"] = field;
  spec["run"].erase("snapshot_strains");
  return spec;
}

/// Points RUPTURE_CACHE_DIR at a cache directory of this test process (removed at exit), so that
/// the runs of one test share their preliminary run and no test reads a stale entry.
inline const fs::path& useTestCache() {
  static const ScratchDir dir;
  static const bool done = ::setenv("RUPTURE_CACHE_DIR", dir.path().c_str(), 1) == 0;
  (void)done;
  return dir.path();
}

/// Runs a spec to a file in `dir` (1 thread) and returns its summary.
inline nlohmann::json runToFile(const nlohmann::json& spec, const fs::path& file) {
  useTestCache();
  RunControl control;
  RunOutcome outcome = runSpec(spec, file.string(), control, 1);
  EXPECT_TRUE(outcome.completed);
  EXPECT_DOUBLE_EQ(control.progress.load(), 1.0);
  return outcome.summary;
}

inline nlohmann::json runSmall(double strainRate, const std::string& field, const nlohmann::json& loadingExtra = {},
                               const nlohmann::json& runExtra = {}) {
  ScratchDir dir;
  nlohmann::json spec = smallSpec(strainRate, field);
  for (const auto& [k, v] : loadingExtra.items()) spec["loading"][k] = v;
  for (const auto& [k, v] : runExtra.items()) spec["run"][k] = v;
  return runToFile(spec, dir / "run.h5");
}

}  // namespace rupture::test
