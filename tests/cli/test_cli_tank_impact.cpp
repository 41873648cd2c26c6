// `rupture run` on a tank-impact spec through the real binary: a tiny run prints the summary with
// the documented scalars and writes a snapshot cloud holding the water and the plate nodes; a bad
// field exits 2 naming it.
#include <filesystem>

#include <gtest/gtest.h>

#include "cli_runner.hpp"
#include "io/hdf5_file.hpp"
#include "support/test_support.hpp"

namespace {

namespace fs = std::filesystem;
using rupture::testing::runCli;
using rupture::testing::ScratchDir;
using rupture::testing::writeSpec;

nlohmann::json tinyTank() {
  return {{"scenario", "tank-impact"},
          {"tank", {{"inner_diameter", 0.04}, {"water_height", 0.03}}},
          {"impactor", {{"mass", 5.0}, {"speed", 2.0}}},
          {"plate", {{"thickness", 0.002}, {"spacing", 0.004}, {"precrack", {{"shape", "hole"}, {"hole_diameter", 0.012}}}}},
          {"resolution", {{"spacing", 0.005}}},
          {"run", {{"end_time", 2e-5}, {"snapshot_times", {0.0}}}}};
}

TEST(CliTankImpact, RunsAndWritesWaterAndPlateSnapshots) {
  ScratchDir dir;
  const fs::path out = dir.path() / "tank.h5";
  const auto r = runCli("run " + writeSpec(tinyTank(), "cli-tank.json") + " -o " + out.string() + " --threads 1 --json");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const nlohmann::json summary = nlohmann::json::parse(r.out);
  EXPECT_EQ(summary["completed"], 1);
  for (const char* name : {"first_pressure_peak", "max_jet_speed", "jet_front_speed", "final_outflow_speed",
                           "max_deflection", "time_to_fracture", "cracked_length"})
    EXPECT_TRUE(summary.contains(name)) << name;
  EXPECT_TRUE(summary["time_to_fracture"].is_null());  // 20 µs at 2 m/s tears nothing
  EXPECT_EQ(summary["contact_method"], "pinball");
  EXPECT_TRUE(fs::exists(dir.path() / "tank.xdmf2"));

  // The snapshot cloud: every particle, then the plate nodes (body 2) with damage and fractured.
  rupture::io::Hdf5File file = rupture::io::Hdf5File::openReadOnly(out.string());
  const std::vector<std::int64_t> body = file.readDatasetInt("/snapshots/000000/body");
  const std::int64_t plateNodes = summary["plate_nodes"];
  ASSERT_GT(plateNodes, 0);
  ASSERT_EQ(static_cast<std::int64_t>(body.size()), summary["particles"].get<std::int64_t>() + plateNodes);
  EXPECT_EQ(std::count(body.begin(), body.end(), 2), plateNodes);
  EXPECT_TRUE(file.exists("/snapshots/000000/damage"));
  EXPECT_TRUE(file.exists("/snapshots/000000/fractured"));
  EXPECT_EQ(file.readAttributeString("/summary", "max_jet_speed_unit"), "m/s");
  EXPECT_EQ(file.readAttributeString("/summary", "jet_front_speed_unit"), "m/s");
  EXPECT_EQ(file.readAttributeString("/series/jet_front_speed", "unit"), "m/s");
  EXPECT_EQ(file.readAttributeString("/series/outflow_speed", "unit"), "m/s");
}

TEST(CliTankImpact, BadFieldExitsTwoNamingIt) {
  nlohmann::json spec = tinyTank();
  spec["contact"] = {{"method", "glue"}};
  const auto r = runCli("run " + writeSpec(spec, "cli-tank-bad.json") + " -o /dev/null --threads 1");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("contact.method"), std::string::npos) << r.err;
  nlohmann::json estimate = tinyTank();
  estimate["plate"]["step_estimate"] = "exact";
  const auto e = runCli("run " + writeSpec(estimate, "cli-tank-bad-estimate.json") + " -o /dev/null --threads 1");
  EXPECT_EQ(e.exitCode, 2);
  EXPECT_NE(e.err.find("plate.step_estimate"), std::string::npos) << e.err;
  EXPECT_NE(e.err.find("spectral"), std::string::npos) << "names what is allowed: " << e.err;
}

}  // namespace

// The campaign request of docs/tank-impact.md#the-campaign and the failure rule's study are valid
// server requests, and a spec naming a specimen runs from the CLI with the seed's measurements in
// its summary.
TEST(CliTankImpact, CampaignRequestValidatesAndASpecimenRunReportsTheSeed) {
  for (const char* name : {"tank-campaign.json", "tank-fracture-rule.json", "tank-thin-specimens.json"}) {
    const std::string request = (fs::path(RUPTURE_SOURCE_DIR) / "examples" / name).string();
    const auto valid = runCli("validate " + request + " --scenario tank-impact");
    EXPECT_EQ(valid.exitCode, 0) << name << ": " << valid.err;
  }
  const nlohmann::json spec = {{"scenario", "tank-impact"}, {"specimen", "E20A5"},
                               {"plate", {{"spacing", 0.004}}}, {"resolution", {{"spacing", 0.01}}},
                               {"run", {{"end_time", 1e-5}}}};
  ScratchDir dir;
  const auto r = runCli("run " + writeSpec(spec, "cli-tank-specimen.json") + " -o " + (dir.path() / "s.h5").string() +
                        " --threads 1 --json");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const nlohmann::json summary = nlohmann::json::parse(r.out);
  EXPECT_EQ(summary["specimen"], "E20A5");
  EXPECT_DOUBLE_EQ(summary["seed_jet_speed"].get<double>(), 92.0);
  EXPECT_EQ(summary["impactor_model"], "elastic_piston");
  EXPECT_EQ(summary["rim_torn_fraction"].get<double>(), 0.0);  // nothing torn in 10 µs
  const auto bad = runCli("run " + writeSpec({{"scenario", "tank-impact"}, {"specimen", "E99"}, {"resolution", {{"spacing", 0.01}}}},
                                             "cli-tank-bad-specimen.json") + " -o /dev/null --threads 1");
  EXPECT_EQ(bad.exitCode, 2);
  EXPECT_NE(bad.err.find("specimen"), std::string::npos) << bad.err;
}
