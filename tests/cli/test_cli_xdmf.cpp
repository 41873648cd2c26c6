// `rupture xdmf` on a real run file: an existing sidecar (the one `rupture run` wrote beside it, or
// one of -o's) is not replaced without --force, as run and plot refuse (exit 2 naming the file and
// --force, the file left as it was); with --force it is written again.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "cli_runner.hpp"
#include "support/test_support.hpp"

namespace {

namespace fs = std::filesystem;
using rupture::testing::readWhole;
using rupture::testing::runCli;
using rupture::testing::ScratchDir;
using rupture::testing::writeSpec;

TEST(CliXdmf, NeverReplacesASidecarUnasked) {
  ScratchDir dir;
  const nlohmann::json spec = rupture::testing::quickSmallSpec();
  const fs::path run = dir.path() / "run.h5";
  ASSERT_EQ(runCli("run " + writeSpec(spec, "cli-xdmf.json") + " -o " + run.string() + " --threads 1").exitCode, 0);
  const fs::path beside = dir.path() / "run.xdmf2";
  ASSERT_TRUE(fs::exists(beside)) << "rupture run writes the sidecar";

  std::ofstream(beside) << "kept";
  const auto refused = runCli("xdmf " + run.string());
  EXPECT_EQ(refused.exitCode, 2);
  EXPECT_NE(refused.err.find("'" + beside.string() + "' exists"), std::string::npos) << refused.err;
  EXPECT_NE(refused.err.find("--force"), std::string::npos) << refused.err;
  EXPECT_EQ(readWhole(beside), "kept") << "a refusal leaves the file as it was";
  const auto forced = runCli("xdmf " + run.string() + " --force");
  ASSERT_EQ(forced.exitCode, 0) << forced.err;
  EXPECT_NE(readWhole(beside).find("<Xdmf"), std::string::npos);

  const fs::path other = dir.path() / "other.xdmf2";
  ASSERT_EQ(runCli("xdmf " + run.string() + " -o " + other.string()).exitCode, 0) << "a new file needs no --force";
  const auto again = runCli("xdmf " + run.string() + " -o " + other.string());
  EXPECT_EQ(again.exitCode, 2);
  EXPECT_NE(again.err.find(other.string()), std::string::npos) << again.err;
  EXPECT_EQ(runCli("xdmf --force " + run.string() + " -o " + other.string()).exitCode, 0);
}

}  // namespace
