// dynamic-tension stopped at random steps and resumed, for each initial velocity field of the seed
// (V0, VL, VH): the result file equals an uninterrupted run's, bit for bit.
#include <gtest/gtest.h>

#include "checkpoint/checkpoint_support.hpp"
#include "engine/test_dynamic_tension_support.hpp"

namespace rupture::test {
namespace {

class ResumeDynamicTension : public ::testing::TestWithParam<const char*> {};

TEST_P(ResumeDynamicTension, ResumedRunEqualsUninterruptedRun) {
  useTestCache();
  ScratchDir dir;
  nlohmann::json spec = readJson(examplePath("dynamic-tension-small.json"));
  spec["loading"]["strain_rate"] = 1e7;  // breaks within a few thousand steps
  spec["loading"]["initial_velocity"] = GetParam();
  const nlohmann::json summary = expectResumedRunMatches(spec, dir.path());
  EXPECT_GT(summary.value("broken_bond_fraction", 0.0), 0.0) << "the resumed stretch includes fracture";
}

INSTANTIATE_TEST_SUITE_P(Fields, ResumeDynamicTension, ::testing::Values("V0", "VL", "VH"));

}  // namespace
}  // namespace rupture::test
