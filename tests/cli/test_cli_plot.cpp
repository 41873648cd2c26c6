// `rupture plot` on a real run file: the damage picture (a PNG of the asked size with the field's
// colours, not one colour), the series plot, the formats by extension, and bad options exiting 2
// naming the option; an existing picture is not replaced without --force; the picture's colour
// range is the run's across snapshots (numbered from 0) unless --range snapshot.
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

TEST(CliPlot, DrawsTheFieldAndTheSeriesOfARun) {
  ScratchDir dir;
  const nlohmann::json spec = rupture::testing::quickSmallSpec();
  const fs::path run = dir.path() / "run.h5";
  ASSERT_EQ(runCli("run " + writeSpec(spec, "cli-plot.json") + " -o " + run.string() + " --threads 1").exitCode, 0);

  const fs::path picture = dir.path() / "damage.png";
  const auto r = runCli("plot " + run.string() + " -o " + picture.string() + " --width 640 --height 480");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.err.find("damage at t = "), std::string::npos) << r.err;
  const auto png = rupture::testing::probePng(readWhole(picture));
  EXPECT_EQ(png.width, 640);
  EXPECT_EQ(png.height, 480);
  EXPECT_GT(png.colours, 50u) << "a field picture, not one colour";
  EXPECT_GT(png.near(68, 1, 84), 10000u) << "undamaged elements in viridis' first colour";
  EXPECT_GT(png.near(214, 38, 41, 30), 50u) << "the broken bonds of a run that broke, in red";

  const auto again = runCli("plot " + run.string() + " -o " + picture.string());
  EXPECT_EQ(again.exitCode, 2);
  EXPECT_NE(again.err.find("--force"), std::string::npos) << again.err;
  EXPECT_EQ(runCli("plot " + run.string() + " -o " + picture.string() + " --force --field von_mises --snapshot 0").exitCode, 0);

  // The same measurable picture as the server's: snapshots numbered from 0, the colour range the
  // run's unless --range snapshot, axes with their unit and the loading named in the SVG.
  const fs::path vector = dir.path() / "von-mises.svg";
  const auto first = runCli("plot " + run.string() + " -o " + vector.string() + " --field von_mises --snapshot 0");
  ASSERT_EQ(first.exitCode, 0) << first.err;
  EXPECT_NE(first.err.find("(snapshot 0 of 0 to "), std::string::npos) << first.err;
  EXPECT_NE(first.err.find("(over every snapshot)"), std::string::npos) << first.err;
  const std::string svg = readWhole(vector);
  EXPECT_NE(svg.find("x axis (µm)"), std::string::npos);
  EXPECT_NE(svg.find("loading: pulled at"), std::string::npos);
  const auto last = runCli("plot " + run.string() + " -o " + vector.string() + " --force --field von_mises");
  ASSERT_EQ(last.exitCode, 0) << last.err;
  auto colours = [](const std::string& said) { return said.substr(said.find("colours ")); };
  EXPECT_EQ(colours(first.err), colours(last.err)) << "one range for every snapshot";
  const auto own = runCli("plot " + run.string() + " -o " + vector.string() + " --force --field von_mises "
                          "--snapshot 0 --range snapshot");
  ASSERT_EQ(own.exitCode, 0) << own.err;
  EXPECT_NE(own.err.find("(this snapshot)"), std::string::npos) << own.err;
  EXPECT_NE(colours(own.err), colours(first.err));
  const auto badRange = runCli("plot " + run.string() + " -o " + vector.string() + " --force --range job");
  EXPECT_EQ(badRange.exitCode, 2);
  EXPECT_NE(badRange.err.find("--range"), std::string::npos) << badRange.err;

  const fs::path series = dir.path() / "stress.svg";
  const auto s = runCli("plot " + run.string() + " --series stress_mean -o " + series.string());
  ASSERT_EQ(s.exitCode, 0) << s.err;
  EXPECT_NE(readWhole(series).find("<svg"), std::string::npos);
  const fs::path pdf = dir.path() / "damage.pdf";
  ASSERT_EQ(runCli("plot " + run.string() + " -o " + pdf.string()).exitCode, 0);
  EXPECT_EQ(readWhole(pdf).rfind("%PDF", 0), 0u);

  const auto badField = runCli("plot " + run.string() + " --field pressure -o " + (dir.path() / "p.png").string());
  EXPECT_EQ(badField.exitCode, 2);
  EXPECT_NE(badField.err.find("--field"), std::string::npos) << badField.err;
  EXPECT_NE(badField.err.find("damage"), std::string::npos) << "the allowed fields are listed: " << badField.err;
  const auto badSnapshot = runCli("plot " + run.string() + " --snapshot 99 -o " + (dir.path() / "q.png").string());
  EXPECT_EQ(badSnapshot.exitCode, 2);
  EXPECT_NE(badSnapshot.err.find("--snapshot"), std::string::npos) << badSnapshot.err;
  const auto badFormat = runCli("plot " + run.string() + " -o " + (dir.path() / "d.jpg").string());
  EXPECT_EQ(badFormat.exitCode, 2);
  EXPECT_NE(badFormat.err.find(".png"), std::string::npos) << badFormat.err;
  EXPECT_FALSE(fs::exists(dir.path() / "p.png"));
  EXPECT_FALSE(fs::exists(dir.path() / "d.jpg"));
}

}  // namespace
