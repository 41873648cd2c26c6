// The tank-impact scenario end to end on the seed's tests (examples/tank-impact-*.json) at a coarse
// resolution (fluid dx = 6 mm instead of the examples' 4 mm, plate spacing 4 mm instead of 2 mm:
// each run ~25 s on one thread instead of ~100 s; the full-size figures are in docs/tank-impact.md).
// The physics is the examples': same tank, carriage, plate, pre-cracks, 3 ms of impact.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "rupture/run.hpp"
#include "scenarios/tank_impact/plate_geometry.hpp"
#include "support/test_support.hpp"

namespace rupture {
namespace {

namespace fs = std::filesystem;

nlohmann::json coarseExample(const std::string& name) {
  std::ifstream in(fs::path(RUPTURE_SOURCE_DIR) / "examples" / ("tank-impact-" + name + ".json"));
  nlohmann::json spec = nlohmann::json::parse(in);
  spec["resolution"]["spacing"] = 0.006;
  spec["plate"]["spacing"] = 0.004;
  return spec;
}

nlohmann::json runCoarse(const std::string& name, const nlohmann::json& spec) {
  testing::ScratchDir dir;
  RunControl control;
  const RunOutcome out = runSpec(spec, (dir.path() / (name + ".h5")).string(), control, 1);
  EXPECT_TRUE(out.completed);
  return out.summary;
}

// E20A5: 25 mm plate with a 20 mm hole, 245 kg at 5 m/s. The wave reaches the gauge with at least
// the acoustic pressure ρ0 c0 V and at most twice it (reflection on a rigid bottom); the water
// jets through the hole no faster than the largest pressure can drive it (Bernoulli, √(2 p/ρ0));
// no water leaves through the cylinder or the piston.
TEST(TankImpactScenario, E20A5ReportsAJetAndAFirstPressurePeak) {
  const nlohmann::json s = runCoarse("E20A5", coarseExample("E20A5"));
  EXPECT_NEAR(s["final_time"].get<double>(), 3e-3, 1e-9);
  const double acoustic = s["acoustic_pressure"];
  EXPECT_GE(s["first_pressure_peak"].get<double>(), 0.9 * acoustic);
  EXPECT_LE(s["first_pressure_peak"].get<double>(), 2.2 * acoustic);
  EXPECT_GT(s["time_of_first_peak"].get<double>(), 0.0);
  ASSERT_FALSE(s["max_jet_speed"].is_null());
  EXPECT_GT(s["max_jet_speed"].get<double>(), 5.0);  // faster than the carriage: the hole is 1/16 of the section
  EXPECT_LT(s["max_jet_speed"].get<double>(), std::sqrt(2.0 * s["peak_gauge_pressure"].get<double>() / 1000.0));
  EXPECT_GT(s["fluid_below_final"].get<int>(), 0);
  EXPECT_EQ(s["particles_outside_max"].get<int>(), 0);
  EXPECT_LT(s["carriage_final_speed"].get<double>(), 5.0);
}

// FUA5: 2 mm plate with a U pre-crack: the tongue opens downwards (0 < angle < 90°).
TEST(TankImpactScenario, FUA5ReportsATongueAngle) {
  const nlohmann::json s = runCoarse("FUA5", coarseExample("FUA5"));
  ASSERT_FALSE(s["final_tongue_angle"].is_null());
  EXPECT_GT(s["final_tongue_angle"].get<double>(), 0.0);
  EXPECT_LT(s["final_tongue_angle"].get<double>(), 0.5 * std::numbers::pi);
  EXPECT_GT(s["max_jet_speed"].get<double>(), 0.0);  // the water goes through the opened U
}

}  // namespace
}  // namespace rupture
