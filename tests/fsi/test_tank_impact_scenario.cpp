// The tank-impact scenario end to end on the seed's tests (examples/tank-impact-*.json). E20A5 at
// a coarse resolution (fluid dx = 6 mm, plate spacing 4 mm: ~25 s on one thread), 3 ms of impact as
// the examples; E14A5 and E14A2 as shipped (the seed's fluid 2 mm) up to their first peak; FUA5 and
// FXA5 on their coarse variants, fluid 4 mm (at dx = 6 mm FUA5's tongue is 7° narrower than at 2 mm,
// and FXA5's cracks, which start at 1.95 ms, do not start within 3 ms). TF14A5 as shipped (about 20
// minutes on two threads) is the validation case tank-TF14A5-fracture, at the suite's full level.
// The figures of the full runs are in docs/tank-impact.md.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "io/hdf5_file.hpp"
#include "rupture/run.hpp"
#include "scenarios/tank_impact/plate_geometry.hpp"
#include "scenarios/tank_impact/tank_impact_spec.hpp"
#include "support/test_support.hpp"

namespace rupture {
namespace {

namespace fs = std::filesystem;

nlohmann::json example(const std::string& name) {
  std::ifstream in(fs::path(RUPTURE_SOURCE_DIR) / "examples" / ("tank-impact-" + name + ".json"));
  return nlohmann::json::parse(in);
}

nlohmann::json coarseExample(const std::string& name) {
  nlohmann::json spec = example(name);
  spec["resolution"]["spacing"] = 0.006;
  spec["plate"]["spacing"] = 0.004;
  return spec;
}

// Runs the spec on one thread in a scratch directory and returns its summary.
nlohmann::json summaryOfRun(const std::string& name, const nlohmann::json& spec) {
  testing::ScratchDir dir;
  RunControl control;
  const RunOutcome out = runSpec(spec, (dir.path() / (name + ".h5")).string(), control, 1);
  EXPECT_TRUE(out.completed);
  return out.summary;
}

// E20A5: 25 mm plate with a 20 mm hole, 245 kg at 5 m/s. The wave reaches the gauge with at least
// the acoustic pressure ρ0 c0 V and at most four times it (the steel piston's face moves at up to
// 2 V, and a rigid bottom doubles the wave); the water jets through the hole no faster than the
// largest pressure can drive it (Bernoulli, √(2 p/ρ0)).
TEST(TankImpactScenario, E20A5ReportsAJetAndAFirstPressurePeak) {
  testing::ScratchDir dir;
  const std::string file = (dir.path() / "E20A5.h5").string();
  RunControl control;
  const RunOutcome out = runSpec(coarseExample("E20A5"), file, control, 1);
  ASSERT_TRUE(out.completed);
  const nlohmann::json& s = out.summary;
  EXPECT_NEAR(s["final_time"].get<double>(), 3e-3, 1e-9);
  const double acoustic = s["acoustic_pressure"];
  EXPECT_GE(s["first_pressure_peak"].get<double>(), 0.9 * acoustic);
  EXPECT_LE(s["first_pressure_peak"].get<double>(), 4.0 * acoustic);
  EXPECT_GT(s["time_of_first_peak"].get<double>(), 0.0);
  ASSERT_FALSE(s["max_jet_speed"].is_null());
  EXPECT_GT(s["max_jet_speed"].get<double>(), 5.0);  // faster than the carriage: the hole is 1/16 of the section
  EXPECT_LT(s["max_jet_speed"].get<double>(), std::sqrt(2.0 * s["peak_gauge_pressure"].get<double>() / 1000.0));
  EXPECT_GT(s["fluid_below_final"].get<int>(), 0);
  // Under the 10 MPa peak a few particles squeeze into the cylinder wall's dummy layers at the
  // plate's rim (0.4 % at this resolution, docs/fsi-contact.md); none goes through the piston.
  EXPECT_LT(s["particles_outside_max"].get<double>(), 0.01 * s["fluid_particles"].get<double>());
  EXPECT_LT(s["carriage_final_speed"].get<double>(), 5.0);

  // The jet's front, what a film tracks, left first, driven by the first wave: it outruns the
  // water leaving the plate at the end, and it is no faster than Bernoulli's bound either.
  const double bernoulli = std::sqrt(2.0 * s["peak_gauge_pressure"].get<double>() / 1000.0);
  ASSERT_FALSE(s["jet_front_speed"].is_null());
  ASSERT_FALSE(s["final_outflow_speed"].is_null());
  const double front = s["jet_front_speed"], outflow = s["final_outflow_speed"];
  EXPECT_GT(outflow, 5.0);
  EXPECT_GT(front, outflow);
  EXPECT_LT(front, bernoulli);
  // The steady jet leaves the plate no faster than the piston's displacement can feed it
  // (continuity through the hole, 1/16 of the bore, at the carriage's initial speed at most).
  ASSERT_FALSE(s["mean_outflow_speed"].is_null());
  const double steady = s["mean_outflow_speed"];
  EXPECT_GT(steady, 5.0);
  EXPECT_LT(steady, 1.05 * 16.0 * 5.0);
  // The front's speed is the rate at which the water's lowest point went down: its depth below the
  // plate's face in the last snapshot over the time since the first water came through agrees with
  // it (within 15 %: the front slows a little as it flies, by pressure within the jet).
  const io::Hdf5File h5 = io::Hdf5File::openReadOnly(file);
  const std::vector<double> time = h5.readDatasetDouble("/series/time");
  const std::vector<double> below = h5.readDatasetDouble("/series/fluid_below");
  std::size_t first = 0;
  while (first < below.size() && below[first] == 0) ++first;
  ASSERT_GT(first, 0u);
  ASSERT_LT(first, below.size());
  const std::vector<std::string> snapshots = h5.listGroup("/snapshots");
  ASSERT_FALSE(snapshots.empty());
  const std::string last = "/snapshots/" + snapshots.back();
  const std::vector<double> position = h5.readDatasetDouble(last + "/position");
  const std::vector<std::int64_t> body = h5.readDatasetInt(last + "/body");
  double lowest = 0.0;
  for (std::size_t k = 0; k < body.size(); ++k)
    if (body[k] == -1) lowest = std::min(lowest, position[3 * k + 2]);
  const double face = -0.5 * 0.025;  // the 25 mm bottom's lower face
  const double flight = time.back() - 0.5 * (time[first - 1] + time[first]);
  EXPECT_NEAR((face - lowest) / flight, front, 0.15 * front);
}

// E14A5 and E14A2 as shipped (the seed's fluid dx = 2 mm, plate 2 mm, the elastic piston tied to
// the carriage), to 0.35 ms: past the first peak's window t <= 2.5 H/c0 = 0.31 ms, so the first
// peak is the full run's (the validation cases tank-E14A5-pressure and tank-E14A2-pressure run the
// same files to 3 ms). The seed measured 210-277 bar (four repeats) and 58-83 bar (three): ours must
// lie within those ranges widened by 20 % (issue #27's acceptance). The one-body rigid impactor, on
// the coarse variant (fluid 4 mm, whose peaks are lower still), stays below them: the piston's own
// leap off the carriage is what makes the peak (docs/tank-impact.md#impactor).
TEST(TankImpactScenario, E14FirstPeaksOfTheShippedExamplesLieInTheMeasuredRanges) {
  struct Case { const char* name; double low, high; };
  for (const Case& c : {Case{"E14A5", 210e5, 277e5}, Case{"E14A2", 58e5, 83e5}}) {
    SCOPED_TRACE(c.name);
    nlohmann::json spec = example(c.name);
    spec["run"]["end_time"] = 3.5e-4;
    const double peak = summaryOfRun(c.name, spec)["first_pressure_peak"].get<double>();
    EXPECT_GE(peak, 0.8 * c.low);
    EXPECT_LE(peak, 1.2 * c.high);
    nlohmann::json rigid = example(std::string(c.name) + "-coarse");
    rigid["run"]["end_time"] = 3.5e-4;
    rigid["impactor"]["model"] = "rigid";
    EXPECT_LT(summaryOfRun(c.name, rigid)["first_pressure_peak"].get<double>(), 0.8 * c.low);
  }
}

// FUA5's coarse variant (fluid 4 mm, plate 2 mm, 3 ms): the U tongue opens to the seed's α ≈ 50° within
// issue #27's 10° (§5.2, Fig. 31: the experiment's, and its own simulation's at 10 ms), read as
// the tongue's inclination to the plate's plane. 43.0° here; 48.0° at the seed's fluid 2 mm (the
// validation case tank-FUA5-tongue), 51.0° at 4 mm and 10 ms (docs/tank-impact.md#the-tongues-angle;
// 43.0° again with the least rotary inertia beside the step, 2026-12-03; the others are of 2026-12-01).
TEST(TankImpactScenario, FUA5TongueOpensToTheSeedsAngle) {
  const nlohmann::json s = summaryOfRun("FUA5", example("FUA5-coarse"));
  ASSERT_FALSE(s["final_tongue_angle"].is_null());
  EXPECT_NEAR(s["final_tongue_angle"].get<double>() * 180.0 / std::numbers::pi, 50.0, 10.0);
  EXPECT_GT(s["max_jet_speed"].get<double>(), 0.0);  // the water goes through the opened U
  EXPECT_EQ(s["fractured_nodes"].get<int>(), 0);     // §3.2: FUA5 did not crack
}

// FXA5: 2 mm plate with an X of two 30 mm pre-cracks. Cracks propagate from the pre-cracks: stress
// points fracture, and the first one to fail lies at a pre-crack tip (within 2 node spacings).
TEST(TankImpactScenario, FXA5PropagatesCracksFromThePrecracks) {
  const nlohmann::json spec = example("FXA5-coarse");
  testing::ScratchDir dir;
  const std::string file = (dir.path() / "FXA5.h5").string();
  RunControl control;
  const RunOutcome out = runSpec(spec, file, control, 1);
  ASSERT_TRUE(out.completed);
  const nlohmann::json& s = out.summary;
  ASSERT_FALSE(s["time_to_fracture"].is_null());
  EXPECT_GT(s["cracked_length"].get<double>(), 0.0);
  EXPECT_GT(s["fractured_nodes"].get<int>(), 0);

  const TankImpactSpec parsed = parseTankImpactSpec(spec);
  const PlateGeometry geometry = plateGeometry(parsed.plate);
  const std::vector<double> path = io::Hdf5File::openReadOnly(file).readDatasetDouble("/crack_path");
  ASSERT_GE(path.size(), 2u);
  double nearest = 1.0;
  for (const PlateSegment& c : geometry.precracks)
    for (const auto& tip : {c.a, c.b}) nearest = std::min(nearest, std::hypot(path[0] - tip[0], path[1] - tip[1]));
  EXPECT_LT(nearest, 2.0 * geometry.nodes.spacing) << "first fractured node at " << path[0] << ", " << path[1];
}

// The shell's step from its measured spectrum (plate.step_estimate "spectral") against the bound's
// single rate, on FXA5's coarse variant to just past its first fracture: the same first pressure
// peak within 2 % and the same time to fracture within 0.05 ms (issue #58's tolerances), at a
// fraction of the shell steps. Measured 2026-12-06 on 2 threads: 1.950 ms (bound) and 1.993 ms
// (spectral), peaks 93.80 and 93.90 bar, 51,724 and 12,976 shell steps to 3 ms.
TEST(TankImpactScenario, SpectralStepEstimateKeepsTheSingleRatesPeakAndFracture) {
  nlohmann::json bound = example("FXA5-coarse");
  bound["run"]["end_time"] = 2.1e-3;
  bound["run"].erase("snapshot_times");
  bound["plate"]["subcycling"] = false;
  bound["plate"]["step_estimate"] = "bound";
  nlohmann::json spectral = bound;
  spectral["plate"]["step_estimate"] = "spectral";
  const nlohmann::json a = summaryOfRun("FXA5-bound", bound), b = summaryOfRun("FXA5-spectral", spectral);
  ASSERT_FALSE(a["time_to_fracture"].is_null());
  ASSERT_FALSE(b["time_to_fracture"].is_null());
  EXPECT_NEAR(b["time_to_fracture"].get<double>(), a["time_to_fracture"].get<double>(), 0.05e-3);
  EXPECT_NEAR(b["first_pressure_peak"].get<double>(), a["first_pressure_peak"].get<double>(),
              0.02 * a["first_pressure_peak"].get<double>());
  EXPECT_TRUE(a["shell_max_frequency"].is_null());
  EXPECT_GT(b["shell_spectrum_measurements"].get<int>(), 0);
  EXPECT_LT(3 * b["shell_steps"].get<double>(), a["shell_steps"].get<double>());
}

}  // namespace
}  // namespace rupture
