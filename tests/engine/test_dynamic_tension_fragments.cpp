// Fragments, separation and cracks across the section (bond_network), and the equilibrium ratio of
// the loading branch (TensionObservables), on states built by hand.
#include <cmath>
#include <vector>

#include "samples/sample_builder.hpp"
#include "scenarios/bonded/intact_network.hpp"
#include "scenarios/dynamic_tension/dynamic_tension_spec.hpp"
#include "scenarios/dynamic_tension/tension_loading.hpp"
#include "scenarios/dynamic_tension/tension_observables.hpp"
#include "test_dynamic_tension_support.hpp"

namespace rupture::test {
namespace {

/// The small example's sample (about 1,600 elements, two pores) and its loaded faces; built once
/// per process, copied by each test.
struct SmallSample {
  DynamicTensionSpec spec;
  BondedSystem system;
  TensionGeometry geometry;
  SmallSample() { *this = built(); }
  static const SmallSample& built() {
    static const SmallSample sample(0);
    return sample;
  }
  explicit SmallSample(int) : spec(parseDynamicTensionSpec(readJson(examplePath("dynamic-tension-small.json")))) {
    const SampleReport report = buildSample(spec.sample, spec.material, system);
    geometry = tensionGeometry(system, spec.sample, report);
  }
  std::size_t n() const { return system.particles.size(); }
  /// Breaks every bond whose two elements lie on either side of x = `x` and, when given, whose
  /// midpoint lies below y = `yMax` (a crack from the lateral face y = 0 that stops there).
  void cut(double x, double yMax = INFINITY) {
    const ParticleStore& p = system.particles;
    BondStore& b = system.bonds;
    for (std::size_t k = 0; k < b.size(); ++k) {
      const double xi = p.x[b.i[k]], xj = p.x[b.j[k]];
      if ((xi - x) * (xj - x) < 0 && 0.5 * (p.y[b.i[k]] + p.y[b.j[k]]) < yMax) b.intact[k] = 0;
    }
  }
  bool separated() const { return !groupsConnected(system.bonds, n(), geometry.xmin, geometry.xmax); }
  std::size_t cracks(const FragmentAnalysis& f) const {
    const double spacing = 2 * spec.sample.elementRadius;
    return cracksCrossing(system.particles, 2, f.elementFragment, spacing, spacing);
  }
  std::size_t minFragment() const { return static_cast<std::size_t>(std::ceil(0.01 * static_cast<double>(n()))); }
};

TEST(DynamicTensionFragments, IntactSampleIsOneFragmentJoiningTheFaces) {
  const SmallSample s;
  const FragmentAnalysis f = analyseFragments(s.system.bonds, s.n(), s.minFragment());
  ASSERT_EQ(f.fragmentSizes.size(), 1u);
  EXPECT_EQ(f.fragmentSizes[0] + static_cast<std::int64_t>(f.debrisElements), static_cast<std::int64_t>(s.n()));
  EXPECT_FALSE(s.separated());
  EXPECT_EQ(s.cracks(f), 0u);
}

TEST(DynamicTensionFragments, OneStraightCrackGivesTwoFragmentsAndSeparates) {
  SmallSample s;
  const double mid = 0.5 * (s.geometry.xminCentre + s.geometry.xmaxCentre);
  s.cut(mid);
  const FragmentAnalysis f = analyseFragments(s.system.bonds, s.n(), s.minFragment());
  ASSERT_EQ(f.fragmentSizes.size(), 2u);
  EXPECT_EQ(f.debris, 0u);  // a straight cut frees no element
  EXPECT_EQ(f.fragmentSizes[0] + f.fragmentSizes[1], static_cast<std::int64_t>(s.n()));
  // Every element left of the cut is in one fragment, every element right of it in the other.
  const ParticleStore& p = s.system.particles;
  for (std::size_t k = 1; k < s.n(); ++k)
    EXPECT_EQ(f.elementFragment[k] == f.elementFragment[0], (p.x[k] < mid) == (p.x[0] < mid)) << k;
  EXPECT_TRUE(s.separated());
  EXPECT_EQ(s.cracks(f), 1u);

  // A second straight crack: three fragments, two cracks across the section.
  s.cut(s.geometry.xminCentre + 0.25 * (s.geometry.xmaxCentre - s.geometry.xminCentre));
  const FragmentAnalysis g = analyseFragments(s.system.bonds, s.n(), s.minFragment());
  EXPECT_EQ(g.fragmentSizes.size(), 3u);
  EXPECT_EQ(s.cracks(g), 2u);
}

TEST(DynamicTensionFragments, CrackStoppingInsideTheSampleNeitherSeparatesNorCounts) {
  SmallSample s;
  s.cut(0.5 * (s.geometry.xminCentre + s.geometry.xmaxCentre), 0.8e-6);  // 80 % of the height
  const FragmentAnalysis f = analyseFragments(s.system.bonds, s.n(), s.minFragment());
  EXPECT_EQ(f.fragmentSizes.size(), 1u);
  EXPECT_FALSE(s.separated());
  EXPECT_EQ(s.cracks(f), 0u);
}

TEST(DynamicTensionFragments, SmallPiecesAreDebris) {
  SmallSample s;
  // Free the first element of the X_min face: one debris component of one element.
  const std::int32_t freed = s.geometry.xmin.front();
  for (std::size_t k = 0; k < s.system.bonds.size(); ++k)
    if (s.system.bonds.i[k] == freed || s.system.bonds.j[k] == freed) s.system.bonds.intact[k] = 0;
  const FragmentAnalysis f = analyseFragments(s.system.bonds, s.n(), s.minFragment());
  EXPECT_EQ(f.fragmentSizes.size(), 1u);
  EXPECT_EQ(f.debris, 1u);
  EXPECT_EQ(f.debrisElements, 1u);
  EXPECT_EQ(f.elementFragment[freed], -1);
  EXPECT_FALSE(s.separated());  // the rest of the face still holds
}

// R_eq = Σ |σ_Xmax − σ_Xmin| / Σ σ̄ over ¼ ε_peak ≤ ε ≤ ε_peak: what happens before ¼ ε_peak and
// after the peak does not count, whatever the number of steps (checkpoints thinned past 4096).
TEST(DynamicTensionFragments, EquilibriumRatioOfTheLoadingBranch) {
  for (std::size_t steps : {400u, 100000u}) {
    SCOPED_TRACE(steps);
    TensionObservables o(100);
    const double peakStrain = 1e-3;
    for (std::size_t s = 1; s <= steps; ++s) {
      const double strain = 2 * peakStrain * static_cast<double>(s) / static_cast<double>(steps);
      const double mean = strain <= peakStrain ? 1e11 * strain : 1e11 * (2 * peakStrain - strain);
      // 50 % apart before ¼ ε_peak and after the peak, 10 % apart in the window.
      const double gap = strain < 0.25 * peakStrain || strain > peakStrain ? 0.5 : 0.1;
      o.observe(1e-12 * static_cast<double>(s), strain, {mean * (1 - gap / 2), mean * (1 + gap / 2), mean}, 0);
    }
    const nlohmann::json summary = o.summary();
    EXPECT_NEAR(summary["strain_at_peak"].get<double>(), peakStrain, 2 * peakStrain / static_cast<double>(steps));
    EXPECT_NEAR(summary["equilibrium_ratio"].get<double>(), 0.1, steps > 1000 ? 1e-3 : 2e-2);
    EXPECT_NEAR(summary["equilibrium_ratio_at_peak"].get<double>(), 0.1, 1e-12);
    EXPECT_EQ(summary["separated"], 0);
    EXPECT_TRUE(summary["separation_strain"].is_null());
  }
}

TEST(DynamicTensionFragments, SettlesOnlyAfterSeparationAndAQuietSpell) {
  TensionObservables o(10);
  o.observe(1e-9, 1e-4, {1, 1, 1}, 1);
  EXPECT_FALSE(o.settledAfterSeparation(5e-9, 1e-9));  // not separated
  o.markSeparated(2e-9, 2e-4);
  o.observe(2.5e-9, 2.5e-4, {0, 0, 0}, 2);  // a crack still running
  EXPECT_FALSE(o.settledAfterSeparation(3e-9, 1e-9));
  EXPECT_TRUE(o.settledAfterSeparation(3.6e-9, 1e-9));
  o.markSeparated(4e-9, 4e-4);  // the first separation counts
  EXPECT_DOUBLE_EQ(o.summary()["separation_strain"].get<double>(), 2e-4);
  EXPECT_EQ(o.summary()["separated"], 1);
}

// A broken sample still joined by a ligament stops once quiet and unloaded on average.
TEST(DynamicTensionFragments, UnloadedAndQuietNeedsBothAndAnAverage) {
  TensionObservables o(10);
  o.setAveragingTime(1e-9);
  double t = 0;
  auto step = [&](double mean, std::size_t broken) {
    t += 1e-12;
    o.observe(t, 1e-3 * t / 1e-9, {mean, mean, mean}, broken);
  };
  for (int k = 0; k < 1000; ++k) step(100.0 * k / 1000, 0);  // loading to 100
  step(100, 1);                                              // peak, first break
  for (int k = 0; k < 500; ++k) step(k % 2 ? 30.0 : -30.0, 0);  // ringing around zero, quiet
  EXPECT_FALSE(o.unloadedAndQuiet(t, 1e-9, 0.1));  // quiet for 0.5 ns only
  EXPECT_FALSE(o.unloadedAndQuiet(t + 0.6e-9, 1e-9, 0.1));  // quiet long enough, but the average
  // still remembers the loading (it decays as exp(−t / 1 ns) from about 40)
  for (int k = 0; k < 3000; ++k) step(k % 2 ? 30.0 : -30.0, 0);
  EXPECT_TRUE(o.unloadedAndQuiet(t, 1e-9, 0.1));   // |σ̄| 30 % of the peak at each step, 0 on average
  EXPECT_FALSE(o.unloadedAndQuiet(t, 1e-9, 0.0));  // 0 disables the rule
  for (int k = 0; k < 3000; ++k) step(40.0, 0);    // a ligament carrying 40 % of the peak
  EXPECT_FALSE(o.unloadedAndQuiet(t, 1e-9, 0.1));
  EXPECT_EQ(o.summary()["separated"], 0);
}

}  // namespace
}  // namespace rupture::test
