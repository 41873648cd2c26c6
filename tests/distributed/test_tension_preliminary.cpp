// The VH field's preliminary run of dynamic tension (Longchamp et al. 2024, section 3.2) over the
// ranks of the test's MPI run gives every rank the one-process result bit for bit: the captured
// velocity field of every element, the capture's strain, time and step, the first break's strain,
// and the modulus fitted to the face stresses; on three porous ceramic samples (three
// microstructures), one with contact between fragments. A cancel asked on one rank only stops
// every rank at the same step.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <tuple>
#include <vector>

#include "distributed/communicator.hpp"
#include "distributed_test_support.hpp"
#include "engine/sample_test_support.hpp"
#include "samples/sample_builder.hpp"
#include "scenarios/dynamic_tension/dynamic_tension_spec.hpp"
#include "scenarios/dynamic_tension/preliminary_velocity_field.hpp"
#include "scenarios/dynamic_tension/tension_loading.hpp"

namespace rupture {
namespace {

struct TensionSample {
  BondedSystem system;
  TensionGeometry geometry;
  PreliminaryParameters params;
};

/// The seed's porous ceramic (Table 3 beams) on the sample-builder tests' small 2D square, its
/// faces and a preliminary run as the scenario plans it by default (its time step's safety, eq. 6's
/// ramp of the default round trips at the bond network's affine wave speed, the default capture
/// rule), but at 5e5 /s instead of the default 1e5 /s, which takes five times the steps (at 1e6 /s
/// the default ramp would end after half the first break's strain on these samples, which the run
/// refuses by its capture rule).
TensionSample tensionSample(std::uint64_t seed, bool contact) {
  TensionSample t;
  const SampleSpec spec = testing::porousSpec(2, seed);
  MaterialSpec material = testing::ceramic();
  material.contact.enabled = contact;
  const SampleReport report = buildSample(spec, material, t.system);
  t.geometry = tensionGeometry(t.system, spec, report);
  const DynamicTensionSpec defaults;
  t.params.strainRate = 5e5;
  t.params.timeStep = defaults.run.timeStepSafety * t.system.criticalTimeStep();
  t.params.rampTime = defaults.loading.rampWaveRoundTrips * 2.0 * t.geometry.gaugeLength /
                      affineWaveSpeed(t.system, t.geometry);
  return t;
}

TEST(TensionPreliminary, OverTheRanksItCapturesTheOneProcessFieldBitForBit) {
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    SCOPED_TRACE("sample seed " + std::to_string(seed));
    const TensionSample t = tensionSample(seed, /*contact=*/seed == 2);
    RunControl control;
    const auto one = runPreliminary(t.system, t.geometry, t.params, control, {}, Communicator::self());
    const auto many = runPreliminary(t.system, t.geometry, t.params, control, {}, Communicator::world());
    ASSERT_TRUE(one && many);
    ASSERT_TRUE(std::isfinite(one->onsetStrain)) << "no bond broke: the capture rule was not exercised";
    EXPECT_GT(one->steps, one->captureSteps);
    const VelocityField &a = one->field, &b = many->field;
    for (const auto& [name, u, v] : {std::tuple{"vx", &a.vx, &b.vx}, std::tuple{"vy", &a.vy, &b.vy},
                                     std::tuple{"vz", &a.vz, &b.vz}, std::tuple{"wx", &a.wx, &b.wx},
                                     std::tuple{"wy", &a.wy, &b.wy}, std::tuple{"wz", &a.wz, &b.wz}})
      EXPECT_EQ(testing::firstDifference(*u, *v), -1) << name << " differs from the one-process field";
    EXPECT_EQ(one->steps, many->steps);
    EXPECT_EQ(one->captureSteps, many->captureSteps);
    EXPECT_EQ(one->captureStrain, many->captureStrain);
    EXPECT_EQ(one->captureTime, many->captureTime);
    EXPECT_EQ(one->faceVelocity, many->faceVelocity);
    EXPECT_EQ(one->onsetStrain, many->onsetStrain);
    EXPECT_EQ(one->modulus, many->modulus);
    EXPECT_EQ(one->equilibriumRatio, many->equilibriumRatio);
  }
}

TEST(TensionPreliminary, ACancelOnOneRankStopsEveryRank) {
  const TensionSample t = tensionSample(1, false);
  RunControl control;
  // The last rank alone is asked to stop: every rank must return without a field, none wait for it.
  const Communicator world = Communicator::world();
  if (world.rank() == world.size() - 1) control.cancel.store(true);
  const auto result = runPreliminary(t.system, t.geometry, t.params, control, {}, world);
  EXPECT_FALSE(result.has_value()) << "rank " << world.rank() << " went on after the cancel";
}

}  // namespace
}  // namespace rupture
