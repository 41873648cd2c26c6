// The parts of the dynamic-tension scenario, checked by hand: velocity ramp, damage and fragments,
// virial stress of a stretched pair, the cache key hash.
#include <cmath>
#include <numbers>

#include "dem/beam_forces.hpp"
#include "scenarios/bonded/intact_network.hpp"
#include "scenarios/dynamic_tension/preliminary_field_cache.hpp"
#include "scenarios/dynamic_tension/tension_loading.hpp"
#include "scenarios/dynamic_tension/virial_stress.hpp"
#include "test_dynamic_tension_support.hpp"

namespace rupture::test {
namespace {

TEST(DynamicTensionParts, VelocityRampIsTheSeedsHalfCosine) {
  const VelocityRamp ramp{2.0, 1e-9};
  EXPECT_DOUBLE_EQ(ramp.velocity(0.0), 0.0);
  EXPECT_NEAR(ramp.velocity(0.5e-9), 1.0, 1e-12);
  EXPECT_NEAR(ramp.velocity(0.25e-9), 2.0 * 0.5 * (1.0 - std::cos(std::numbers::pi / 4)), 1e-12);
  EXPECT_DOUBLE_EQ(ramp.velocity(1e-9), 2.0);
  EXPECT_DOUBLE_EQ(ramp.velocity(5e-9), 2.0);
  const VelocityRamp none{3.0, 0.0};  // VL, VH: the face starts at V_max
  EXPECT_DOUBLE_EQ(none.velocity(0.0), 3.0);

  // Displacement ∫V: V Δt / 2 at the end of the ramp, then V (t − Δt/2); timeToReach inverts it.
  EXPECT_NEAR(ramp.displacement(1e-9), 1e-9, 1e-21);
  EXPECT_NEAR(ramp.displacement(3e-9), 2.0 * 2.5e-9, 1e-21);
  for (double t : {0.1e-9, 0.5e-9, 0.9e-9, 1e-9, 4e-9}) EXPECT_NEAR(ramp.timeToReach(ramp.displacement(t)), t, 1e-18);
  EXPECT_NEAR(none.timeToReach(3.0 * 2e-9), 2e-9, 1e-21);
}

/// Four elements in a row (0-1-2-3) plus an isolated one (4).
BondStore chain() {
  ParticleStore p;
  p.dimension = 2;
  for (int k = 0; k < 5; ++k) p.add(k * 2e-9, 0, 0, 1e-9);
  BondStore b;
  b.add(p, 0, 1);
  b.add(p, 1, 2);
  b.add(p, 2, 3);
  b.finalize(p.size());
  return b;
}

TEST(DynamicTensionParts, DamageAndFragments) {
  BondStore b = chain();
  EXPECT_EQ(countFragments(b, 5), 1u);  // the isolated element is not a fragment
  EXPECT_EQ(countFragments(b, 5, 1), 2u);
  b.intact[1] = 0;  // break 1-2
  EXPECT_EQ(countFragments(b, 5), 2u);
  const auto d = elementDamage(b, 5);
  EXPECT_DOUBLE_EQ(d[0], 0.0);
  EXPECT_DOUBLE_EQ(d[1], 0.5);
  EXPECT_DOUBLE_EQ(d[2], 0.5);
  EXPECT_DOUBLE_EQ(d[3], 0.0);
  EXPECT_DOUBLE_EQ(d[4], 0.0);
  b.intact[0] = 0;
  EXPECT_EQ(countFragments(b, 5), 1u);  // {2, 3}; 0 and 1 are single elements
  EXPECT_DOUBLE_EQ(elementDamage(b, 5)[1], 1.0);
}

// Two elements along x, bond stretched by δ: tension F = k δ along the bond, and
// σ_xx = (1 / 2Ω) · L F on both, Ω = π R² t / φ; every other component zero.
TEST(DynamicTensionParts, VirialStressOfAStretchedPair) {
  BondedSystem s;
  s.particles.dimension = 2;
  const double R = 1e-8, t = R, phi = 0.8;
  s.particles.add(0, 0, 0, R);
  s.particles.add(2 * R, 0, 0, R);
  s.particles.setMassFromDensity(5000, t);
  s.bonds.add(s.particles, 0, 1);
  s.beam = {1e11, 0.3, 0.3, 1e20};
  s.contact.setParameters({1e11, 0.3, 0.3, 0.1, false});
  s.initialize();
  const double delta = 1e-11;
  s.particles.x[1] += delta;
  s.initialize();  // loads in the stretched configuration
  const BeamResponse r = beamResponseOf(s.beam, s.particles, s.bonds, 0);
  const double force = -r.fjx;  // tension: the bond pulls j back towards i
  const double area = std::numbers::pi * std::pow(0.3 * R, 2);
  EXPECT_NEAR(force, 1e11 * area / (2 * R) * delta, 1e-9 * force);
  const auto sigma = virialStress(s, phi, t);
  const double omega = std::numbers::pi * R * R * t / phi;
  const double expected = (2 * R + delta) * force / (2 * omega);
  for (int k = 0; k < 2; ++k) {
    EXPECT_NEAR(sigma[9 * k + 0], expected, 1e-9 * expected);
    for (int e = 1; e < 9; ++e) EXPECT_NEAR(sigma[9 * k + e], 0.0, 1e-9 * expected);
  }
}

TEST(DynamicTensionParts, CacheKeyHash) {
  EXPECT_EQ(fnv1aHex(""), "cbf29ce484222325");
  EXPECT_EQ(fnv1aHex("a"), "af63dc4c8601ec8c");
  EXPECT_EQ(fnv1aHex("foobar"), "85944171f73967e8");
  const nlohmann::json key = {{"a", 1}};
  EXPECT_EQ(preliminaryCacheFile("/c", key), "/c/dynamic-tension-preliminary-" + fnv1aHex(key.dump()) + ".h5");
}

}  // namespace
}  // namespace rupture::test
