// `rupture preview`: the picture of a spec's discretisation, its counts the run's own (the run's
// summary after a step), SVG by extension, an existing picture kept without --force, and a
// validation spec, which has no single sample, exiting 2.
#include <gtest/gtest.h>

#include <filesystem>

#include "cli_runner.hpp"
#include "support/png_probe.hpp"
#include "support/test_support.hpp"

namespace {

namespace fs = std::filesystem;
using rupture::testing::readWhole;
using rupture::testing::runCli;
using rupture::testing::ScratchDir;
using rupture::testing::writeSpec;

TEST(CliPreview, DrawsTheSampleTheRunBuilds) {
  ScratchDir dir;
  nlohmann::json spec = rupture::testing::quickSmallSpec();
  spec["run"]["max_steps"] = 1;
  const std::string file = writeSpec(spec, "cli-preview.json");
  const fs::path picture = dir.path() / "sample.png";
  const auto r = runCli("preview " + file + " -o " + picture.string());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto png = rupture::testing::probePng(readWhole(picture));
  EXPECT_EQ(png.width, 900);
  EXPECT_EQ(png.height, 600);
  EXPECT_GT(png.near(0, 115, 178), 10000u) << "the elements, in the first group's colour";

  const auto run = runCli("run " + file + " -o " + (dir.path() / "run.h5").string() + " --threads 1 --json");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const auto summary = nlohmann::json::parse(run.out);
  const std::string elements = std::to_string(summary.at("elements").get<long long>()) + " elements, " +
                               std::to_string(summary.at("bonds").get<long long>()) + " bonds";
  EXPECT_NE(r.out.find(elements), std::string::npos) << r.out << " vs the run's " << elements;

  const auto again = runCli("preview " + file + " -o " + picture.string());
  EXPECT_EQ(again.exitCode, 2);
  EXPECT_NE(again.err.find("--force"), std::string::npos) << again.err;
  const fs::path svg = dir.path() / "sample.svg";
  ASSERT_EQ(runCli("preview " + file + " -o " + svg.string()).exitCode, 0);
  EXPECT_NE(readWhole(svg).find("<svg"), std::string::npos);

  const nlohmann::json validation = {{"scenario", "validation"}, {"case", "piston-column-first-peak"}, {"level", "quick"}};
  const auto none = runCli("preview " + writeSpec(validation, "cli-preview-validation.json") + " -o " +
                           (dir.path() / "v.png").string());
  EXPECT_EQ(none.exitCode, 2);
  EXPECT_NE(none.err.find("no single sample"), std::string::npos) << none.err;
}

}  // namespace
