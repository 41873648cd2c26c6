// Von Mises plasticity: return mappings against closed-form strain paths.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "plasticity/von_mises.hpp"
#include "rupture/spec_error.hpp"

namespace rupture {
namespace {

ElasticPlasticMaterial linearMaterial() {
  ElasticPlasticMaterial m;
  m.hardening = {HardeningKind::linear, 300.0e6, 1.0e9, 1.0};
  return m;
}

/// Root of a decreasing function by bisection (the analytic side of the tests).
template <class F>
double bisect(F&& f, double lo, double hi) {
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (f(mid) > 0.0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// Uniaxial strain ε11 = e (3D): ε^p = p diag(1, −½, −½), so σ11 − σ22 = 2G (e − 3p/2) = σ_y(p)
// and the mean stress stays K e.
TEST(Plasticity, UniaxialStrainPathFollowsTheHardeningCurve) {
  for (const HardeningKind kind : {HardeningKind::linear, HardeningKind::johnsonCook}) {
    ElasticPlasticMaterial m;  // 2024-T351 defaults (Johnson–Cook)
    if (kind == HardeningKind::linear) m = linearMaterial();
    const double G = m.shearModulus(), K = m.bulkModulus();
    std::vector<SymTensor3> stress(1, SymTensor3{}), increment(1, SymTensor3{});
    std::vector<double> p(1, 0.0);
    const double step = 1.0e-4;
    increment[0][0] = step;
    for (int n = 1; n <= 1000; ++n) {
      updateStress3D(m, increment, stress, p);
      const double e = n * step;
      const double sigmaEq = stress[0][0] - stress[0][1];
      EXPECT_NEAR(hydrostaticStress(stress[0]), K * e, 1e-9 * K * e);
      if (2.0 * G * e <= m.hardening.yieldStress(0.0)) {
        EXPECT_EQ(p[0], 0.0);
        EXPECT_NEAR(sigmaEq, 2.0 * G * e, 1e-6);
      } else {
        const double pExact = bisect([&](double q) { return 2.0 * G * (e - 1.5 * q) - m.hardening.yieldStress(q); },
                                     0.0, e);
        EXPECT_NEAR(p[0], pExact, 1e-9 + 1e-7 * pExact) << "e = " << e;
        EXPECT_NEAR(sigmaEq, m.hardening.yieldStress(pExact), 1e-6 * sigmaEq);
      }
    }
    EXPECT_GT(p[0], 0.05);  // the path went deep into the plastic range
  }
}

// Equibiaxial strain ε11 = ε22 = e in plane stress: σ11 = σ22 = s = σ_eq, ε^p_11 = ε^p_22 = p/2,
// s = E/(1−ν) (e − p/2) = σ_y(p).
TEST(Plasticity, PlaneStressEquibiaxialPathFollowsTheHardeningCurve) {
  for (const HardeningKind kind : {HardeningKind::linear, HardeningKind::johnsonCook}) {
    ElasticPlasticMaterial m;
    if (kind == HardeningKind::linear) m = linearMaterial();
    const double c = m.youngModulus / (1.0 - m.poissonRatio);
    PlaneTensor plastic{0.0, 0.0, 0.0}, stress{};
    double p = 0.0;
    for (int n = 1; n <= 800; ++n) {
      const double e = n * 1.0e-4;
      planeStressPointUpdate(m, {e, e, 0.0}, plastic, p, stress);
      const double pExact = c * e <= m.hardening.yieldStress(0.0)
                                ? 0.0
                                : bisect([&](double q) { return c * (e - 0.5 * q) - m.hardening.yieldStress(q); }, 0.0, 2.0 * e);
      EXPECT_NEAR(p, pExact, 1e-9 + 1e-7 * pExact) << "e = " << e;
      EXPECT_NEAR(stress[0], stress[1], 1e-6 * std::abs(stress[0]));
      EXPECT_NEAR(stress[0], c * (e - 0.5 * pExact), 1e-6 * std::abs(stress[0]));
      EXPECT_NEAR(plastic[0], 0.5 * p, 1e-12);
    }
    EXPECT_GT(p, 0.05);
  }
}

TEST(Plasticity, ReturnMappingLandsOnTheYieldSurface) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0), up(0.0, 0.3);
  for (const HardeningKind kind : {HardeningKind::linear, HardeningKind::johnsonCook}) {
    ElasticPlasticMaterial m;
    if (kind == HardeningKind::linear) m = linearMaterial();
    for (int trial = 0; trial < 500; ++trial) {
      const double p = up(rng), scale = 2.0e9;
      SymTensor3 s3{};
      for (double& c : s3) c = scale * u(rng);
      const SymTensor3 before = s3;
      const ReturnMapping r3 = radialReturn3D(m, s3, p);
      if (vonMisesStress(before) > m.hardening.yieldStress(p)) {
        ASSERT_TRUE(r3.plastic);
        EXPECT_NEAR(vonMisesStress(s3), m.hardening.yieldStress(p + r3.plasticStrainIncrement),
                    1e-12 * vonMisesStress(before));
        EXPECT_NEAR(hydrostaticStress(s3), hydrostaticStress(before), 1e-12 * scale);
      }
      PlaneTensor s2 = {scale * u(rng), scale * u(rng), scale * u(rng)};
      const PlaneTensor trial2 = s2;
      const ReturnMapping r2 = planeStressReturn(m, s2, p);
      if (vonMisesStress(trial2) > m.hardening.yieldStress(p)) {
        ASSERT_TRUE(r2.plastic);
        EXPECT_NEAR(vonMisesStress(s2), m.hardening.yieldStress(p + r2.plasticStrainIncrement),
                    1e-12 * vonMisesStress(trial2));
      }
    }
  }
}

// A shell layer's return with its transverse shears σ13, σ23: on a pure-shear state (σ12, σ13,
// σ23; σ11 = σ22 = σ33 = 0) the 3D radial return keeps the normal stresses zero, so the shell's
// plane-stress return must give the 3D answer exactly; on any state it lands on the yield surface.
TEST(Plasticity, ShellReturnWithTransverseShearMatchesThe3DReturnInPureShear) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0), up(0.0, 0.3);
  for (const HardeningKind kind : {HardeningKind::linear, HardeningKind::johnsonCook}) {
    ElasticPlasticMaterial m;
    if (kind == HardeningKind::linear) m = linearMaterial();
    for (int trial = 0; trial < 300; ++trial) {
      const double p = up(rng), scale = 1.0e9;
      PlaneTensor s = {0.0, 0.0, scale * u(rng)};
      TransverseShear q = {scale * u(rng), scale * u(rng)};
      SymTensor3 s3 = {0.0, 0.0, 0.0, q[1], q[0], s[2]};  // (xx, yy, zz, yz, xz, xy)
      const ReturnMapping r = shellReturn(m, s, q, p);
      const ReturnMapping r3 = radialReturn3D(m, s3, p);
      ASSERT_EQ(r.plastic, r3.plastic);
      EXPECT_NEAR(r.plasticStrainIncrement, r3.plasticStrainIncrement, 1e-12);
      EXPECT_NEAR(s[2], s3[5], 1e-9 * scale);
      EXPECT_NEAR(q[0], s3[4], 1e-9 * scale);
      EXPECT_NEAR(q[1], s3[3], 1e-9 * scale);
      EXPECT_NEAR(s[0], 0.0, 1e-9 * scale);

      PlaneTensor g = {scale * u(rng), scale * u(rng), scale * u(rng)};
      TransverseShear gq = {scale * u(rng), scale * u(rng)};
      const double before = vonMisesStress(g, gq);
      const ReturnMapping rg = shellReturn(m, g, gq, p);
      if (before > m.hardening.yieldStress(p)) {
        ASSERT_TRUE(rg.plastic);
        EXPECT_NEAR(vonMisesStress(g, gq), m.hardening.yieldStress(p + rg.plasticStrainIncrement), 1e-12 * before);
      }
    }
  }
  // A layer in pure transverse shear of a perfectly plastic material yields at τ = σ_y/√3.
  ElasticPlasticMaterial perfect;
  perfect.hardening = {HardeningKind::linear, 300.0e6, 0.0, 1.0};
  PlaneTensor plastic{0.0, 0.0, 0.0}, stress{};
  TransverseShear plasticShear{0.0, 0.0}, shear{};
  double pAcc = 0.0;
  shellPointUpdate(perfect, {0.0, 0.0, 0.0}, {0.01, 0.0}, plastic, plasticShear, pAcc, stress, shear);
  EXPECT_NEAR(shear[0], 300.0e6 / std::sqrt(3.0), 1e-6 * 300.0e6);
  EXPECT_GT(plasticShear[0], 0.0);
  EXPECT_NEAR(2.0 * perfect.shearModulus() * (0.01 - plasticShear[0]), shear[0], 1e-6 * 300.0e6);
}

// Linear hardening in 3D has the closed form Δp = (σ_eq^tr − σ_y(p_n)) / (3G + H).
TEST(Plasticity, PlasticIncrementOfAKnownStep) {
  const ElasticPlasticMaterial m = linearMaterial();
  SymTensor3 s = {500.0e6, 100.0e6, -50.0e6, 20.0e6, 0.0, 80.0e6};
  const double p = 0.02, trial = vonMisesStress(s);
  const ReturnMapping r = radialReturn3D(m, s, p);
  const double expected = (trial - m.hardening.yieldStress(p)) / (3.0 * m.shearModulus() + m.hardening.modulus);
  EXPECT_NEAR(r.plasticStrainIncrement, expected, 1e-14);
}

TEST(Plasticity, UnloadingIsElastic) {
  const ElasticPlasticMaterial m;
  PlaneTensor plastic{0.0, 0.0, 0.0}, stress{};
  double p = 0.0;
  planeStressPointUpdate(m, {0.02, 0.0, 0.0}, plastic, p, stress);  // loads well beyond yield
  const double pLoaded = p;
  const PlaneTensor loaded = stress, plasticLoaded = plastic;
  ASSERT_GT(pLoaded, 0.0);
  planeStressPointUpdate(m, {0.018, 0.0, 0.0}, plastic, p, stress);  // strain decreases
  EXPECT_EQ(p, pLoaded);
  EXPECT_EQ(plastic, plasticLoaded);
  const PlaneTensor change = planeStressElastic(m, {-0.002, 0.0, 0.0});
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(stress[c] - loaded[c], change[c], 1e-6);
  EXPECT_LT(vonMisesStress(stress), m.hardening.yieldStress(p));
}

TEST(Plasticity, BadParametersNameTheField) {
  ElasticPlasticMaterial m;
  m.poissonRatio = 0.6;
  try {
    validateElasticPlastic(m, "shell.material");
    FAIL();
  } catch (const SpecError& e) {
    EXPECT_EQ(e.field(), "shell.material.poisson_ratio");
  }
  m = ElasticPlasticMaterial{};
  m.hardening.exponent = 1.5;
  EXPECT_THROW(validateElasticPlastic(m, "m"), SpecError);
  m = ElasticPlasticMaterial{};
  m.hardening.initialYieldStress = -1.0;
  try {
    validateElasticPlastic(m, "m");
    FAIL();
  } catch (const SpecError& e) {
    EXPECT_EQ(e.field(), "m.initial_yield_stress");
  }
  EXPECT_THROW(hardeningKindFromName("ludwig", "m.hardening"), SpecError);
}

}  // namespace
}  // namespace rupture

#include "plasticity/material_presets.hpp"

namespace rupture {
namespace {

TEST(MaterialPresets, PresetsAreValidAndNamed) {
  for (const char* name : {"au4g_2024_t351", "au4g_2024_t351_seed", "steel_4340"}) {
    const MaterialPreset p = materialPreset(name, "material");
    EXPECT_STREQ(p.name, name);
    EXPECT_NO_THROW(validateElasticPlastic(p.material, "material"));
    EXPECT_NO_THROW(validateDamage(p.damage, "damage"));
    EXPECT_EQ(p.damage.poissonRatio, p.material.poissonRatio);
  }
  // Johnson & Cook (1983): 2024-T351 flows at A = 265 MPa and hardens to A + B at p = 1.
  const MaterialPreset al = au4g2024T351();
  EXPECT_DOUBLE_EQ(al.material.hardening.yieldStress(1.0), 691.0e6);
  try {
    materialPreset("au4g", "shell.material.preset");
    FAIL();
  } catch (const SpecError& e) {
    EXPECT_EQ(e.field(), "shell.material.preset");
  }
}

}  // namespace
}  // namespace rupture
