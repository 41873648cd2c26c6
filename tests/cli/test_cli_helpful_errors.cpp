// Errors that help: a misspelled key is named as unknown, before any required key is found
// missing, with the nearest allowed key; a missing output directory fails at once, naming it.
#include <filesystem>

#include <gtest/gtest.h>

#include "cli_runner.hpp"

namespace {

namespace fs = std::filesystem;
using rupture::testing::runCli;
using rupture::testing::smallExampleSpec;
using rupture::testing::writeSpec;

TEST(CliHelpfulErrors, MisspelledRequiredKeyIsNamedWithTheNearestOne) {
  nlohmann::json spec = smallExampleSpec();
  spec["loading"]["strain_rte"] = spec["loading"]["strain_rate"];
  spec["loading"].erase("strain_rate");
  const std::string file = writeSpec(spec, "typo.json");
  for (const std::string& command : {"validate " + file, "run " + file + " -o /tmp/never-written.h5"}) {
    const auto r = runCli(command);
    EXPECT_EQ(r.exitCode, 2) << command << ": " << r.err;
    EXPECT_NE(r.err.find("'loading.strain_rte'"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("did you mean 'strain_rate'?"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("(missing)"), std::string::npos) << "the unknown key comes first: " << r.err;
  }
  EXPECT_FALSE(fs::exists("/tmp/never-written.h5"));
}

TEST(CliHelpfulErrors, TyposAtEveryLevelAndNoGuessForStrangers) {
  nlohmann::json spec = smallExampleSpec();
  spec["sample"]["porosty"] = 0.1;
  spec["sample"].erase("porosity");
  auto r = runCli("validate " + writeSpec(spec, "typo2.json"));
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("'sample.porosty'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("did you mean 'porosity'?"), std::string::npos) << r.err;

  spec = smallExampleSpec();
  spec["colour"] = "blue";  // nothing close: no guess, but the keys that are allowed
  r = runCli("validate " + writeSpec(spec, "stranger.json"));
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("'colour'"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("did you mean"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("known keys here: description, dimension, loading"), std::string::npos) << r.err;
}

TEST(CliHelpfulErrors, MissingOutputDirectoryFailsBeforeAnyWork) {
  const std::string file = writeSpec(smallExampleSpec(), "ok.json");
  const auto r = runCli("run " + file + " -o /nonexistent-dir/run.h5");
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_NE(r.err.find("'/nonexistent-dir' does not exist"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("sample:"), std::string::npos) << "nothing was built: " << r.err;
}

}  // namespace
