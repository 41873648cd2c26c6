// elastic-properties stopped at random relaxation steps and resumed: the strength test (both of its
// stages), the beam fit and the strength fit (many tests: the finished ones are replayed from the
// checkpoint's journal, the one under way continues), and a spring lattice's single measurement;
// the result file equals an uninterrupted run's, bit for bit.
#include <gtest/gtest.h>

#include "checkpoint/checkpoint_support.hpp"
#include "engine/test_elastic_properties_support.hpp"

namespace rupture::test {
namespace {

nlohmann::json beamSample() { return smallBeamElasticPropertiesSpec(); }

TEST(ResumeElasticProperties, StrengthTestAcrossBothStages) {
  rupture::testing::ScratchDir dir;
  const nlohmann::json summary = expectResumedRunMatches(beamSample(), dir.path(), 3);
  EXPECT_GT(summary.value("tensile_strength", 0.0), 0.0);
}

TEST(ResumeElasticProperties, BeamAndStrengthFitsReplayTheirFinishedTests) {
  rupture::testing::ScratchDir dir;
  nlohmann::json spec = beamSample();
  spec["target"] = {{"young_modulus", 150e9}, {"poisson_ratio", 0.3}, {"tensile_strength", 70e6}};
  const nlohmann::json summary = expectResumedRunMatches(spec, dir.path(), 5);
  EXPECT_GT(summary.value("evaluations", 0), 1) << "the fit runs several tests";
  EXPECT_GT(summary.value("strength_evaluations", 0), 1);
}

TEST(ResumeElasticProperties, SpringLatticeMeasurement) {
  rupture::testing::ScratchDir dir;
  const nlohmann::json spec = {
      {"scenario", "elastic-properties"},
      {"dimension", 2},
      {"sample", {{"lattice", "triangular"}, {"size", {0.01, 0.005}}, {"spacing", 2.5e-4}}},
      {"material", {{"model", "born"}, {"density", 2440}, {"born", {{"young_modulus", 72e9}, {"poisson_ratio", 0.22}}}}}};
  const nlohmann::json summary = expectResumedRunMatches(spec, dir.path(), 2);
  EXPECT_EQ(summary.value("converged", 0), 1);
}

}  // namespace
}  // namespace rupture::test
