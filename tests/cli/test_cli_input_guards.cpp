// Inputs that used to crash or mislead the CLI: JSON nested deep enough to overflow a recursive
// dump, numbers beyond the double range, a spec file that cannot be read, and a result file on a
// full disk (HDF5 used to leave a half-closed file behind and segfault at exit).
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "cli_runner.hpp"
#include "support/small_filesystem.hpp"

namespace {

namespace fs = std::filesystem;
using rupture::testing::readWhole;
using rupture::testing::runCli;
using rupture::testing::SmallFilesystem;
using rupture::testing::writeSpec;

std::string writeText(const std::string& text, const std::string& name) {
  const auto path = fs::temp_directory_path() / ("rupture-cli-guards-" + name);
  std::ofstream(path, std::ios::binary) << text;
  return path.string();
}

TEST(CliInputGuards, DeeplyNestedJsonExits2) {
  const std::string deep = std::string(70000, '[') + std::string(70000, ']');
  const std::string file = writeText(deep, "deep.json");
  for (const std::string& args : {"validate " + file, "run " + file + " -o /dev/null"}) {
    const auto r = runCli(args);
    EXPECT_EQ(r.exitCode, 2) << args << r.err;
    EXPECT_NE(r.err.find("nested more than 64 levels"), std::string::npos) << r.err;
  }
}

TEST(CliInputGuards, NumbersBeyondTheDoubleRangeExit2NamingTheField) {
  nlohmann::json spec = nlohmann::json::parse(readWhole(fs::path(RUPTURE_SOURCE_DIR) / "examples" / "dynamic-tension-small.json"));
  std::string text = spec.dump();
  const std::string key = "\"strain_rate\":";
  const auto at = text.find(key);
  ASSERT_NE(at, std::string::npos);
  const auto end = text.find_first_of(",}", at + key.size());
  text = text.substr(0, at + key.size()) + "1e400" + text.substr(end);
  const auto r = runCli("validate " + writeText(text, "huge.json"));
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_NE(r.err.find("'loading.strain_rate' = 1e400"), std::string::npos) << r.err;
}

TEST(CliInputGuards, AnUnreadableSpecFileSaysWhy) {
  const auto r = runCli("validate /nonexistent/spec.json");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("No such file or directory"), std::string::npos) << r.err;
}

TEST(CliInputGuards, AFullDiskFailsTheRunCleanly) {
  SmallFilesystem disk(200 * 1024);  // the small example's result file is several hundred kB
  if (!disk.mounted()) GTEST_SKIP() << disk.whyNot();
  nlohmann::json spec = nlohmann::json::parse(readWhole(fs::path(RUPTURE_SOURCE_DIR) / "examples" / "dynamic-tension-small.json"));
  spec["loading"] = {{"strain_rate", 1e7}, {"initial_velocity", "VL"}};
  const fs::path out = disk.path() / "run.h5";
  const auto r = runCli("run " + writeSpec(spec, "full-disk.json") + " -o " + out.string() + " --threads 1");
  EXPECT_EQ(r.exitCode, 1) << "a crash shows as -1: " << r.err;  // not 139 (SIGSEGV in HDF5's exit handler)
  EXPECT_NE(r.err.find("No space left on device"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("0x"), std::string::npos) << "no buffer addresses in messages: " << r.err;
  EXPECT_TRUE(fs::is_empty(disk.path())) << "nothing half-written is left";
}

}  // namespace
