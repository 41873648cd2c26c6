// impact stopped at random steps and resumed, for each bonded model (peridynamic PMB, Born and
// Hookean springs, DEM beams with contacts) and with a projectile: the result file equals an
// uninterrupted run's, bit for bit.
#include <gtest/gtest.h>

#include "checkpoint/checkpoint_support.hpp"

namespace rupture::test {
namespace {

/// A 10 × 5 mm plate notched from the left edge to 4 mm, pulled apart by its top and bottom rows
/// hard enough to crack within the run.
nlohmann::json notchedPlate(const std::string& model) {
  nlohmann::json sample = {{"lattice", model == "pmb" ? "square" : "triangular"}, {"size", {0.01, 0.005}},
                           {"spacing", 2.5e-4}, {"notches", {{{"start", {0.0, 0.0025}}, {"end", {0.004, 0.0025}}}}}};
  nlohmann::json material;
  if (model == "hookean")
    material = {{"model", "hookean"}, {"density", 2440},
                {"hookean", {{"young_modulus", 72e9}, {"criterion", "griffith"}, {"fracture_energy", 3.8}}}};
  if (model == "born")
    material = {{"model", "born"}, {"density", 2440},
                {"born", {{"young_modulus", 72e9}, {"poisson_ratio", 0.22}, {"criterion", "critical_stretch"},
                          {"critical_stretch", 1.5e-3}}}};
  if (model == "pmb")
    material = {{"model", "pmb"}, {"density", 2440}, {"pmb", {{"young_modulus", 72e9}, {"fracture_energy", 3.8}}}};
  if (model == "beam") {
    sample = {{"size", {0.01, 0.005}}, {"element_radius", 1.25e-4}, {"seed", 3}, {"notches", sample["notches"]}};
    material = {{"model", "beam"}, {"density", 2440},
                {"beam", {{"young_modulus", 8e11}, {"poisson_ratio", 0.3}, {"radius_ratio", 0.3}, {"failure_stress", 1.5e9}}}};
  }
  return {{"scenario", "impact"},
          {"dimension", 2},
          {"sample", sample},
          {"material", material},
          {"loading", {{"velocity_regions", {{{"min", {0.0, 0.0045}}, {"max", {0.01, 0.005}}, {"velocity", {0.0, 8.0}}, {"ramp_time", 5e-7}},
                                             {{"min", {0.0, 0.0}}, {"max", {0.01, 0.0005}}, {"velocity", {0.0, -8.0}}, {"ramp_time", 5e-7}}}}}},
          {"run", {{"end_time", 4e-6}, {"snapshot_times", {2e-6}}}}};
}

class ResumeImpact : public ::testing::TestWithParam<const char*> {};

TEST_P(ResumeImpact, ResumedRunEqualsUninterruptedRun) {
  rupture::testing::ScratchDir dir;
  const nlohmann::json summary = expectResumedRunMatches(notchedPlate(GetParam()), dir.path());
  EXPECT_GT(summary.value("broken_bonds", std::int64_t{0}), 0) << "the resumed stretch includes fracture";
}

INSTANTIATE_TEST_SUITE_P(Models, ResumeImpact, ::testing::Values("pmb", "born", "hookean", "beam"));

TEST(ResumeImpact, ProjectileStateIsResumed) {
  rupture::testing::ScratchDir dir;
  nlohmann::json spec = notchedPlate("pmb");
  spec["loading"].erase("velocity_regions");
  spec["loading"]["projectile"] = {{"radius", 1e-3}, {"mass", 1e-3}, {"position", {0.005, 0.0061}}, {"velocity", {0.0, -200.0}}};
  const nlohmann::json summary = expectResumedRunMatches(spec, dir.path());
  EXPECT_LT(summary.value("projectile_final_speed", 200.0), 200.0) << "the projectile hit the plate";
}

}  // namespace
}  // namespace rupture::test
