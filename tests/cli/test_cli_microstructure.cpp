// The bonded microstructure options through `rupture run`: the example with Voronoi grains,
// inclusions and local damping runs (coarsened), and its file's resolved spec keeps them.
#include <filesystem>

#include <gtest/gtest.h>

#include "cli_runner.hpp"
#include "io/hdf5_file.hpp"
#include "support/test_support.hpp"

namespace {

namespace fs = std::filesystem;
using rupture::testing::readWhole;
using rupture::testing::runCli;
using rupture::testing::ScratchDir;
using rupture::testing::writeSpec;

TEST(CliMicrostructure, GrainsInclusionsAndLocalDampingRunAndAreRecorded) {
  ScratchDir dir;
  nlohmann::json spec = nlohmann::json::parse(
      readWhole(fs::path(RUPTURE_SOURCE_DIR) / "examples" / "impact-microstructure-pmb.json"));
  spec["sample"]["spacing"] = 0.001;  // the example's plate at twice its spacing, for 20 µs
  spec["sample"]["thickness"] = 0.001;
  spec["run"] = {{"end_time", 2e-5}};
  const fs::path out = dir.path() / "micro.h5";
  const auto r = runCli("run " + writeSpec(spec, "cli-micro.json") + " -o " + out.string() + " --threads 1 --json");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const nlohmann::json summary = nlohmann::json::parse(r.out);
  EXPECT_EQ(summary["completed"], 1);
  rupture::io::Hdf5File file = rupture::io::Hdf5File::openReadOnly(out.string());
  const nlohmann::json resolved = nlohmann::json::parse(file.readAttributeString("/spec", "json"));
  EXPECT_EQ(resolved["sample"]["grains"]["count"], 40);
  EXPECT_DOUBLE_EQ(resolved["sample"]["grains"]["boundary_factor"].get<double>(), 0.6);
  EXPECT_DOUBLE_EQ(resolved["sample"]["inclusions"]["volume_fraction"].get<double>(), 0.15);
  EXPECT_DOUBLE_EQ(resolved["sample"]["inclusions"]["interface_strength_factor"].get<double>(), 0.8);
  EXPECT_DOUBLE_EQ(resolved["material"]["local_damping"].get<double>(), 1.0);

  // The same spec with a stiffness factor on beams is refused before any work, naming the field.
  nlohmann::json beams = spec;
  beams["material"] = nlohmann::json::parse(
      readWhole(fs::path(RUPTURE_SOURCE_DIR) / "examples" / "impact-branching-beam.json"))["material"];
  beams["sample"] = nlohmann::json::parse(
      readWhole(fs::path(RUPTURE_SOURCE_DIR) / "examples" / "impact-branching-beam.json"))["sample"];
  beams["sample"]["inclusions"] = spec["sample"]["inclusions"];
  const auto refused = runCli("run " + writeSpec(beams, "cli-micro-beam.json") + " -o " + (dir.path() / "b.h5").string());
  EXPECT_EQ(refused.exitCode, 2);
  EXPECT_NE(refused.err.find("sample.inclusions.stiffness_factor"), std::string::npos) << refused.err;
  EXPECT_FALSE(fs::exists(dir.path() / "b.h5"));
}

}  // namespace
