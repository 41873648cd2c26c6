// The impact scenario: spec validation naming the field, the crack observables on hand-built damage
// fields, and a notched plate of every bonded model cracking from its notch tip.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "io/hdf5_file.hpp"
#include "rupture/spec_error.hpp"
#include "scenarios/impact/crack_tracking.hpp"
#include "scenarios/impact/impact_spec.hpp"
#include "support/test_support.hpp"
#include "test_dynamic_tension_support.hpp"

namespace rupture::test {
namespace {

using rupture::testing::rejectedField;

/// A 20 × 10 mm plate notched from the left edge to 8 mm, pulled apart by its top and bottom rows.
nlohmann::json notchedPlate(const std::string& model) {
  nlohmann::json sample = {{"lattice", model == "pmb" ? "square" : "triangular"}, {"size", {0.02, 0.01}}, {"spacing", 2.5e-4},
                           {"notches", {{{"start", {0.0, 0.005}}, {"end", {0.008, 0.005}}}}}};
  nlohmann::json material;
  if (model == "hookean") material = {{"model", "hookean"}, {"density", 2440}, {"hookean", {{"young_modulus", 72e9}, {"criterion", "griffith"}, {"fracture_energy", 3.8}}}};
  if (model == "born") material = {{"model", "born"}, {"density", 2440}, {"born", {{"young_modulus", 72e9}, {"poisson_ratio", 0.22}, {"criterion", "critical_stretch"}, {"critical_stretch", 1.5e-3}}}};
  if (model == "pmb") material = {{"model", "pmb"}, {"density", 2440}, {"pmb", {{"young_modulus", 72e9}, {"fracture_energy", 3.8}}}};
  if (model == "beam") {
    sample = {{"size", {0.02, 0.01}}, {"element_radius", 1.25e-4}, {"seed", 3}, {"notches", sample["notches"]}};
    material = {{"model", "beam"}, {"density", 2440}, {"beam", {{"young_modulus", 8e11}, {"poisson_ratio", 0.3}, {"radius_ratio", 0.3}, {"failure_stress", 1.5e9}}}};
  }
  // The driven rows and their neighbours never break: the crack must come from the notch.
  material["no_failure_regions"] = {{{"min", {0.0, 0.0}}, {"max", {0.02, 0.0015}}}, {{"min", {0.0, 0.0085}}, {"max", {0.02, 0.01}}}};
  return {{"scenario", "impact"},
          {"dimension", 2},
          {"sample", sample},
          {"material", material},
          {"loading", {{"velocity_regions", {{{"min", {0.0, 0.0095}}, {"max", {0.02, 0.01}}, {"velocity", {0.0, 4.0}}, {"ramp_time", 1e-6}},
                                             {{"min", {0.0, 0.0}}, {"max", {0.02, 0.0005}}, {"velocity", {0.0, -4.0}}, {"ramp_time", 1e-6}}}}}},
          {"run", {{"end_time", 8e-6}, {"snapshot_times", {4e-6}}}}};
}

TEST(ImpactSpec, ExamplesAndTheContractKeys) {
  EXPECT_EQ(rejectedField(readJson(examplePath("impact-branching-pmb.json"))), "");
  EXPECT_EQ(rejectedField(readJson(examplePath("impact-branching-born.json"))), "");
  EXPECT_EQ(rejectedField(readJson(examplePath("impact-kalthoff-winkler-pmb.json"))), "");
  nlohmann::json spec = notchedPlate("pmb");
  spec["loading"]["projectile"] = {{"radius", 1e-3}, {"mass", 1e-3}, {"position", {0.01, 0.012}}, {"velocity", {0.0, -50.0}}};
  spec["loading"]["tractions"] = {{{"min", {0.0, 0.0}}, {"max", {0.001, 0.01}}, {"traction", {-1e6, 0.0}}}};
  EXPECT_EQ(rejectedField(spec), "");
  const nlohmann::json schema = scenarioSchema("impact");
  for (const char* key : {"lattice", "spacing", "thickness", "notches"}) EXPECT_TRUE(schema["properties"]["sample"]["properties"].contains(key)) << key;
  for (const char* key : {"projectile", "velocity_regions", "tractions"}) EXPECT_TRUE(schema["properties"]["loading"]["properties"].contains(key)) << key;
  EXPECT_TRUE(schema["properties"]["material"]["properties"]["pmb"]["properties"].contains("horizon_factor"));
  EXPECT_TRUE(schema["properties"]["material"]["properties"].contains("no_failure_regions"));
  EXPECT_TRUE(schema["properties"]["run"]["properties"].contains("end_time"));
  // Every key of the resolved spec (all defaults filled in) is in the schema.
  const nlohmann::json resolved = toJson(parseImpactSpec(spec));
  for (const auto& [key, value] : resolved.items()) {
    ASSERT_TRUE(schema["properties"].contains(key)) << key;
    if (!value.is_object()) continue;
    for (const auto& [sub, unused] : value.items())
      EXPECT_TRUE(schema["properties"][key]["properties"].contains(sub)) << key << "." << sub;
  }
  // The resolved spec parses back to the same resolved spec.
  EXPECT_EQ(toJson(parseImpactSpec(toJson(parseImpactSpec(spec)))), toJson(parseImpactSpec(spec)));
}

TEST(ImpactSpec, ErrorsNameTheField) {
  auto with = [](const std::function<void(nlohmann::json&)>& edit) {
    nlohmann::json spec = notchedPlate("pmb");
    edit(spec);
    return rejectedField(spec);
  };
  EXPECT_EQ(with([](auto& s) { s["loading"] = nlohmann::json::object(); }), "loading.projectile");
  EXPECT_EQ(with([](auto& s) { s["loading"]["projectile"] = {{"radius", -1.0}, {"mass", 1.0}, {"position", {0, 0}}, {"velocity", {0, 0}}}; }), "loading.projectile.radius");
  EXPECT_EQ(with([](auto& s) { s["loading"]["velocity_regions"][0]["velocity"] = {1.0}; }), "loading.velocity_regions[0].velocity");
  EXPECT_EQ(with([](auto& s) { s["run"].erase("end_time"); }), "run.end_time");
  EXPECT_EQ(with([](auto& s) { s["run"]["snapshot_times"] = {2e-6, 1e-6}; }), "run.snapshot_times");
  EXPECT_EQ(with([](auto& s) { s["sample"]["notches"][0]["end"] = {0.0, 0.005}; }), "sample.notches[0].end");
  EXPECT_EQ(with([](auto& s) { s["sample"]["notches"][0]["colour"] = 1; }), "sample.notches[0].colour");
}

TEST(CrackTracking, TipAndBranchesOfHandBuiltDamageFields) {
  const double h = 1e-3;
  ParticleStore p;
  p.dimension = 2;
  std::vector<double> damage;
  // A straight crack along x from the origin to 30 h, then two branches at ±30° from 30 h to 60 h.
  for (int k = 0; k <= 30; ++k) { p.add(k * h, 0, 0, 0.4 * h); damage.push_back(0.5); }
  std::vector<double> straight = damage;
  for (int k = 1; k <= 30; ++k)
    for (double sign : {1.0, -1.0}) {
      p.add((30 + k * std::cos(0.52)) * h, sign * k * std::sin(0.52) * h, 0, 0.4 * h);
      damage.push_back(0.5);
      straight.push_back(0.0);
    }
  p.add(100 * h, 0, 0, 0.4 * h);  // an undamaged particle farther away is not the tip
  damage.push_back(0.1);
  straight.push_back(0.1);
  p.add(0, 80 * h, 0, 0.4 * h);   // nor a cracked one not connected to the crack
  damage.push_back(0.9);
  straight.push_back(0.9);
  EXPECT_EQ(countCrackBranches(p, straight, 0.25, {0, 0, 0}, h), 1);
  EXPECT_EQ(countCrackBranches(p, damage, 0.25, {0, 0, 0}, h), 2);
  CrackTracker tracker({0, 0, 0}, 0.25, h, 1);
  tracker.observe(0.0, p, straight);
  EXPECT_NEAR(tracker.tip().distance, 30 * h, 1e-12);
  const double speed = tracker.observe(1e-5, p, damage);  // the tip moved to a branch end
  const double far = std::hypot(30 + 30 * std::cos(0.52), 30 * std::sin(0.52)) * h;
  EXPECT_NEAR(tracker.tip().distance, far, 1e-9);
  EXPECT_NEAR(speed, (far - 30 * h) / 1e-5, 1e-6);
  EXPECT_EQ(countCrackBranches(p, std::vector<double>(p.size(), 0.0), 0.25, {0, 0, 0}, h), 0);
}

TEST(CrackTracking, AZoneJoiningAheadIsAJumpNotASpeed) {
  // A crack runs along x at one spacing per 1 µs (1 km/s) from the origin; a zone 20 to 30
  // spacings ahead cracks on its own from the start (a reflected wave), and at 8 µs the ligament
  // between them breaks at once: the tip moves from 7 to 30 spacings in one row. With a bound of
  // 5 km/s that is a jump, not a 23 km/s crack.
  const double h = 1e-3, dt = 1e-6;
  ParticleStore p;
  p.dimension = 2;
  for (int k = 0; k <= 40; ++k) p.add(k * h, 0, 0, 0.4 * h);
  CrackTracker tracker({0, 0, 0}, 0.25, h, 1, 5000.0);
  CrackTracker unbounded({0, 0, 0}, 0.25, h, 1);
  double fastest = 0, fastestUnbounded = 0;
  int jumpRow = -1;
  for (int row = 0; row <= 12; ++row) {
    std::vector<double> damage(p.size(), 0.0);
    for (int k = 0; k <= 40; ++k) {
      const bool crack = k <= row || (row >= 8 && k <= 30);
      const bool ahead = k >= 20 && k <= 30;
      damage[static_cast<std::size_t>(k)] = crack || ahead ? 0.5 : 0.0;
    }
    fastest = std::max(fastest, tracker.observe(row * dt, p, damage));
    fastestUnbounded = std::max(fastestUnbounded, unbounded.observe(row * dt, p, damage));
    if (tracker.jump() > 0) jumpRow = row;
  }
  EXPECT_EQ(jumpRow, 8);
  EXPECT_EQ(tracker.jumps(), 1);
  EXPECT_NEAR(tracker.jumpedLength(), 23 * h, 1e-12);
  EXPECT_NEAR(tracker.tip().distance, 30 * h, 1e-12) << "the crack is as long as it is";
  EXPECT_NEAR(fastest, 1000.0, 1e-6) << "the speed is the crack's own";
  EXPECT_GT(fastestUnbounded, 20000.0) << "without the bound the joining reads as a 23 km/s crack";

  // A crack that is merely fast (3 spacings per µs, 3 km/s) is no jump.
  CrackTracker fast({0, 0, 0}, 0.25, h, 1, 5000.0);
  for (int row = 0; row <= 12; ++row) {
    std::vector<double> damage(p.size(), 0.0);
    for (int k = 0; k <= std::min(40, 3 * row); ++k) damage[static_cast<std::size_t>(k)] = 0.5;
    fast.observe(row * dt, p, damage);
  }
  EXPECT_EQ(fast.jumps(), 0);
  EXPECT_NEAR(fast.maxSpeed(), 3000.0, 1e-6);
}

TEST(CrackTracking, TheAngleIsTheTipsDirectionFromTheNotch) {
  // A notch along +x ending at the origin; a straight crack kinked by θ (the tracker finds its far
  // end): the angle is θ, signed in 2D, unsigned in 3D, whatever the notch's own direction.
  const double h = 1e-3;
  for (double theta : {1.22, -1.22, 0.0, 0.3, 2.5}) {
    for (double notchDirection : {0.0, 0.7}) {
      ParticleStore p;
      p.dimension = 2;
      std::vector<double> damage;
      const double phi = notchDirection + theta;
      for (int k = 0; k <= 20; ++k) {
        p.add(k * h * std::cos(phi), k * h * std::sin(phi), 0, 0.4 * h);
        damage.push_back(0.5);
      }
      CrackTracker tracker({0, 0, 0}, 0.25, h, 1);
      tracker.observe(0.0, p, damage);
      const std::array<double, 3> start{-0.05 * std::cos(notchDirection), -0.05 * std::sin(notchDirection), 0};
      const auto angle2d = crackAngle(tracker.tip(), start, {0, 0, 0}, 2);
      ASSERT_TRUE(angle2d);
      EXPECT_NEAR(*angle2d, theta, 1e-9) << theta << " " << notchDirection;
      EXPECT_NEAR(*crackAngle(tracker.tip(), start, {0, 0, 0}, 3), std::abs(theta), 1e-9);
    }
  }
  // No crack, or a notch of no length: no angle.
  EXPECT_FALSE(crackAngle(CrackTip{}, {-1, 0, 0}, {0, 0, 0}, 2));
  EXPECT_FALSE(crackAngle(CrackTip{1, 1, 0, 1.4, true}, {0, 0, 0}, {0, 0, 0}, 2));
}

class ImpactEveryModel : public ::testing::TestWithParam<std::string> {};

TEST_P(ImpactEveryModel, ANotchedPlateCracksFromItsNotchTip) {
  rupture::testing::ScratchDir dir;
  RunControl control;
  const RunOutcome out = runSpec(notchedPlate(GetParam()), (dir / "impact.h5").string(), control, 1);
  ASSERT_TRUE(out.completed);
  const nlohmann::json& s = out.summary;
  EXPECT_GT(s["broken_bonds"].get<double>(), 0) << s.dump();
  EXPECT_GT(s["crack_length"].get<double>(), 0) << s.dump();
  EXPECT_GE(s["branches"].get<int>(), 1);
  // Opened in tension (mode I), the crack runs on in the notch's direction.
  EXPECT_LT(std::abs(s["crack_angle"].get<double>()), 0.35) << GetParam();
  // The crack runs ahead of the notch: its tip lies right of the notch end, near mid-height.
  io::Hdf5File file = io::Hdf5File::openReadOnly((dir / "impact.h5").string());
  const std::vector<double> tipX = file.readDatasetDouble("/series/crack_tip_x");
  ASSERT_FALSE(tipX.empty());
  EXPECT_GT(tipX.back(), 0.008) << GetParam();
  // The crack starts at the notch tip: the particles just ahead of it are cracked.
  const std::vector<double> damage = file.readDatasetDouble("/snapshots/000001/damage");
  const std::vector<double> position = file.readDatasetDouble("/snapshots/000001/position");
  double nearTip = 0;
  for (std::size_t k = 0; k < damage.size(); ++k)
    if (std::hypot(position[3 * k] - 0.0085, position[3 * k + 1] - 0.005) < 1e-3) nearTip = std::max(nearTip, damage[k]);
  EXPECT_GT(nearTip, 0.25) << GetParam();
}

// A traction on the top edge of a free, unnotched plate: by Newton's second law the plate's
// momentum at time t is the applied force t × σ × L × thickness, whatever the waves inside do.
// The thickness is the one the sample's masses are built with (sample.thickness on lattices, R_DE
// on random packings), so the check is Σ m v_y = σ L t_h T with m = ρ_el V.
TEST_P(ImpactEveryModel, ATractionGivesThePlateItsImpulse) {
  nlohmann::json spec = notchedPlate(GetParam());
  spec["sample"].erase("notches");
  spec["material"].erase("no_failure_regions");
  const double sigma = 2e6, length = 0.02;
  spec["loading"] = {{"tractions", {{{"min", {0.0, 0.0095}}, {"max", {0.02, 0.01}}, {"traction", {0.0, sigma}}}}}};
  spec["run"] = {{"end_time", 3e-6}, {"snapshot_times", {2e-6}}};
  rupture::testing::ScratchDir dir;
  RunControl control;
  const RunOutcome out = runSpec(spec, (dir / "traction.h5").string(), control, 1);
  ASSERT_TRUE(out.completed);
  io::Hdf5File file = io::Hdf5File::openReadOnly((dir / "traction.h5").string());
  const double t = file.readAttributeDouble("/snapshots/000001", "time");
  const std::vector<double> velocity = file.readDatasetDouble("/snapshots/000001/velocity");
  const std::vector<double> volume = file.readDatasetDouble("/sample/volume");
  const bool random = GetParam() == "beam";
  const double thickness = random ? 1.25e-4 : 2.5e-4;  // R_DE, or the default: the spacing
  // Element density: ρ on lattices; on a dense random packing, ρ × box volume / Σ V (the dense
  // sample has the bulk density, samples/sample_builder.hpp).
  double totalVolume = 0;
  for (double v : volume) totalVolume += v;
  const double density = 2440 * (random ? 0.02 * 0.01 * thickness / totalVolume : 1.0);
  double momentumX = 0, momentumY = 0;
  for (std::size_t k = 0; k < volume.size(); ++k) {
    momentumX += density * volume[k] * velocity[3 * k];
    momentumY += density * volume[k] * velocity[3 * k + 1];
  }
  const double impulse = sigma * length * thickness * t;
  EXPECT_NEAR(momentumY, impulse, 1e-6 * impulse) << GetParam();
  EXPECT_NEAR(momentumX, 0.0, 1e-6 * impulse) << GetParam();
}

// An unloaded notched plate stays at rest: the pairs a notch separates touch at their packed
// distance (as broken bonds do), so those a random packing left overlapping across the notch are
// not pushed apart by contact at the first step.
TEST_P(ImpactEveryModel, AnUnloadedNotchedPlateStaysAtRest) {
  nlohmann::json spec = notchedPlate(GetParam());
  spec["loading"] = {{"tractions", {{{"min", {0.0, 0.0095}}, {"max", {0.02, 0.01}}, {"traction", {0.0, 0.0}}}}}};
  spec["run"] = {{"end_time", 3e-6}};
  rupture::testing::ScratchDir dir;
  RunControl control;
  const RunOutcome out = runSpec(spec, (dir / "rest.h5").string(), control, 1);
  ASSERT_TRUE(out.completed);
  EXPECT_EQ(out.summary["broken_bonds"].get<double>(), 0) << GetParam();
  // 1e-15 J: far below the 1e-8 J an element of this plate moving at 1 mm/s would carry.
  EXPECT_LT(out.summary["kinetic_energy"].get<double>(), 1e-15) << GetParam();
}

INSTANTIATE_TEST_SUITE_P(EveryModel, ImpactEveryModel, ::testing::Values("beam", "hookean", "born", "pmb"));

}  // namespace
}  // namespace rupture::test

namespace rupture::test {
namespace {

// A loading box that holds no particle of the built sample would load nothing: the run stops
// before writing anything, with an error naming the region.
TEST(ImpactRun, ALoadingBoxWithNoParticleNamesItsField) {
  // Outside the 20 mm plate: refused from the spec alone. Inside it but between two columns of
  // the 0.25 mm lattice (a tenth of a spacing wide): refused once the sample is built.
  const double column = 0.01, dx = 2.5e-4;
  const std::vector<std::pair<nlohmann::json, std::string>> boxes = {
      {{{"min", {0.03, 0.0}}, {"max", {0.04, 0.001}}}, "overlapping the sample"},
      {{{"min", {column + 0.1 * dx, 0.0}}, {"max", {column + 0.2 * dx, 0.01}}}, "at least one particle"}};
  for (const auto& [box, message] : boxes)
    for (const char* list : {"tractions", "velocity_regions"}) {
      nlohmann::json spec = notchedPlate("pmb");
      nlohmann::json region = box;
      if (std::string(list) == "tractions") region["traction"] = {0.0, 1e6};
      else region["velocity"] = {0.0, 1.0};
      spec["loading"] = {{"velocity_regions", spec["loading"]["velocity_regions"]}};
      spec["loading"][list].push_back(region);
      const std::size_t index = spec["loading"][list].size() - 1;
      rupture::testing::ScratchDir dir;
      RunControl control;
      try {
        runSpec(spec, (dir / "empty.h5").string(), control, 1);
        ADD_FAILURE() << list << ": no error";
      } catch (const SpecError& e) {
        EXPECT_EQ(e.field(), "loading." + std::string(list) + "[" + std::to_string(index) + "]");
        EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
      }
      EXPECT_FALSE(std::filesystem::exists(dir / "empty.h5"));
      EXPECT_FALSE(std::filesystem::exists(dir / "empty.h5.part"));
    }
}

TEST(ImpactRun, CancelledBeforeTheSampleIsBuiltLeavesASpecAndSummaryOnly) {
  // Issue 7's contract for every bonded scenario: a run cancelled while its sample is built stops
  // at once and leaves a valid file marked incomplete, with the spec and a summary saying so.
  rupture::testing::ScratchDir dir;
  RunControl control;
  control.cancel = true;
  const RunOutcome out = runSpec(notchedPlate("pmb"), (dir / "cancelled.h5").string(), control, 1);
  EXPECT_FALSE(out.completed);
  EXPECT_EQ(out.summary["completed"], 0);
  EXPECT_EQ(out.summary["stop_reason"], "cancelled");
  const io::Hdf5File f = io::Hdf5File::openReadOnly((dir / "cancelled.h5").string());
  EXPECT_EQ(f.readAttributeInt("/", "completed"), 0);
  EXPECT_EQ(f.readAttributeInt("/summary", "completed"), 0);
  EXPECT_TRUE(f.hasAttribute("/spec", "json"));
  EXPECT_FALSE(std::filesystem::exists(dir / "cancelled.h5.part"));
}

}  // namespace
}  // namespace rupture::test
