// The bonded microstructure options through `rupture run`: the example with Voronoi grains,
// inclusions and local damping runs (coarsened) with Weibull bond strengths, and its file's resolved
// spec keeps them.
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
  spec["material"]["disorder"] = {{"strength", {{"distribution", "weibull"}, {"modulus", 8}}}};
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
  // The disorder's seed defaults to the sample's and is written out.
  EXPECT_EQ(resolved["material"]["disorder"]["seed"], resolved["sample"]["seed"]);
  EXPECT_DOUBLE_EQ(resolved["material"]["disorder"]["strength"]["modulus"].get<double>(), 8.0);

  // A disorder the spec cannot have is refused before any work, naming the field.
  nlohmann::json disordered = spec;
  disordered["material"]["disorder"] = {{"strength", {{"distribution", "weibull"}, {"modulus", 0}}}};
  const auto refused =
      runCli("run " + writeSpec(disordered, "cli-micro-disorder.json") + " -o " + (dir.path() / "b.h5").string());
  EXPECT_EQ(refused.exitCode, 2);
  EXPECT_NE(refused.err.find("material.disorder.strength.modulus"), std::string::npos) << refused.err;
  EXPECT_FALSE(fs::exists(dir.path() / "b.h5"));
}

}  // namespace
