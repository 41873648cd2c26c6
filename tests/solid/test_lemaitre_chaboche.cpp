// Lemaitre–Chaboche damage with delay (Caleyron et al. 2013, eqs. 9–12; docs/references.md): one
// material point under imposed paths.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <algorithm>

#include "damage/lemaitre_chaboche.hpp"
#include "plasticity/von_mises.hpp"
#include "rupture/spec_error.hpp"

namespace rupture {
namespace {

TEST(LemaitreChaboche, NoDamageBelowTheThreshold) {
  const LemaitreChabocheDamage d;
  for (const double eta : {0.0, 1.0 / 3.0, 2.0 / 3.0}) {
    DamageState s;
    const double pOnset = d.thresholdPlasticStrain / d.triaxialityFunction(eta);
    const int steps = 1000;
    for (int n = 0; n < steps; ++n) {
      const double p = 0.999 * pOnset * n / steps;
      advanceDamage(d, s, p, 0.999 * pOnset / steps, eta, 1.0e-6);
    }
    EXPECT_EQ(s.undelayed, 0.0);
    EXPECT_EQ(s.damage, 0.0);
    advanceDamage(d, s, 0.999 * pOnset, 0.01 * pOnset, eta, 1.0e-6);  // crosses the threshold
    EXPECT_GT(s.undelayed, 0.0);
  }
}

// R_ν(1/3) = 1 for any ν: eq. (9) reduces to p > ε_p^s in uniaxial tension.
TEST(LemaitreChaboche, TriaxialityFunctionIsOneInUniaxialTension) {
  LemaitreChabocheDamage d;
  for (const double nu : {0.2, 0.3, 0.33, 0.45}) {
    d.poissonRatio = nu;
    EXPECT_NEAR(d.triaxialityFunction(1.0 / 3.0), 1.0, 1e-14);
  }
}

// Eq. (10) along a plasticity-driven path: equibiaxial plane stress (η = 2/3) and plane-stress
// uniaxial-like shear (η = 0), with the triaxiality taken from the computed stress.
TEST(LemaitreChaboche, UndelayedRateMatchesEquationTen) {
  const ElasticPlasticMaterial m;
  LemaitreChabocheDamage d;
  d.poissonRatio = m.poissonRatio;
  d.delayTime = 1.0;  // a slow delay: D stays far below D_c, so D_nc runs along the whole path
  struct Path { PlaneTensor direction; double eta; };
  for (const Path path : {Path{{1.0, 1.0, 0.0}, 2.0 / 3.0}, Path{{0.0, 0.0, 1.0}, 0.0}}) {
    PlaneTensor plastic{0.0, 0.0, 0.0}, stress{};
    double p = 0.0;
    DamageState s;
    for (int n = 1; n <= 3000; ++n) {
      const double e = n * 1.0e-4;
      const double pBefore = p;
      const double undelayedBefore = s.undelayed;
      planeStressPointUpdate(m, {e * path.direction[0], e * path.direction[1], e * path.direction[2]}, plastic, p,
                             stress);
      const double eta = triaxiality(hydrostaticStress(stress), vonMisesStress(stress));
      EXPECT_NEAR(eta, path.eta, 1e-9);
      advanceDamage(d, s, pBefore, p - pBefore, eta, 1.0e-7);
      if (d.triaxialityFunction(eta) * pBefore > d.thresholdPlasticStrain && p > pBefore) {
        const double rate = (s.undelayed - undelayedBefore) / (p - pBefore);
        EXPECT_NEAR(rate, d.undelayedSlope() * d.triaxialityFunction(path.eta), 1e-9 * rate);
      }
    }
    EXPECT_GT(s.undelayed, 0.1);  // the path went well past the threshold
  }
}

TEST(LemaitreChaboche, DelayedRateNeverExceedsTheBound) {
  const LemaitreChabocheDamage d;
  for (const double dt : {1.0e-9, 1.0e-7, 1.0e-6, 1.0e-4}) {
    DamageState s;
    // A sudden large plastic increment: D_nc jumps far above D.
    advanceDamage(d, s, 0.0, 1.0, 1.0 / 3.0, dt);
    double previous = s.damage;
    EXPECT_LE(previous / dt, 1.0 / d.delayTime * (1.0 + 1e-12));
    for (int n = 0; n < 50 && !s.fractured; ++n) {
      advanceDamage(d, s, 1.0, 0.0, 1.0 / 3.0, dt);
      EXPECT_LE((s.damage - previous) / dt, 1.0 / d.delayTime * (1.0 + 1e-12));
      EXPECT_LE(s.damage, s.undelayed);
      previous = s.damage;
    }
  }
  EXPECT_LE(d.delayedRate(10.0, 0.0), 1.0 / d.delayTime);
  EXPECT_EQ(d.delayedRate(0.1, 0.2), 0.0);
}

// Constant ṗ at constant η: past the onset D_nc = r t (r = slope R_ν ṗ) and eq. (12) for the lag
// e = D_nc − D, ė = r − (1 − exp(−a e))/τ_c, integrates to
//   e(t) = (1/a) ln( ((α + β) exp(a α t) − β) / α ),  α = r − 1/τ_c, β = 1/τ_c,
// so D(t) = r t − e(t) and the time to D_c solves D(t_c) = D_c.
TEST(LemaitreChaboche, ReachesCriticalDamageAtTheAnalyticTime) {
  LemaitreChabocheDamage d;
  d.delaySharpness = 2.0;
  const double eta = 1.0 / 3.0;
  for (const double pRate : {2.0e5, 1.0e6, 5.0e6}) {
    const double r = d.undelayedSlope() * d.triaxialityFunction(eta) * pRate;
    const double a = d.delaySharpness, beta = 1.0 / d.delayTime, alpha = r - beta;
    auto damageAt = [&](double t) {
      const double e = std::log(((alpha + beta) * std::exp(a * alpha * t) - beta) / alpha) / a;
      return r * t - e;
    };
    double lo = 0.0, hi = d.delayTime;
    while (damageAt(hi) < d.criticalDamage) hi *= 2.0;
    for (int i = 0; i < 200; ++i) (damageAt(0.5 * (lo + hi)) < d.criticalDamage ? lo : hi) = 0.5 * (lo + hi);
    const double tOnset = d.thresholdPlasticStrain / pRate;
    const double tCritical = tOnset + 0.5 * (lo + hi);

    DamageState s;
    const double dt = tCritical / 20000.0;
    double t = 0.0;
    while (!s.fractured && t < 2.0 * tCritical) {
      advanceDamage(d, s, pRate * t, pRate * dt, eta, dt);
      t += dt;
    }
    ASSERT_TRUE(s.fractured) << "p rate " << pRate << ", analytic time " << tCritical << " s";
    EXPECT_NEAR(t, tCritical, 2e-3 * tCritical) << "p rate " << pRate;
  }
}

// A sudden D_nc = D0 (step path): (1/a) ln((e^{a D0} − 1)/(e^{a (D0 − D)} − 1)) = t/τ_c.
TEST(LemaitreChaboche, StepPathReachesCriticalDamageAtTheAnalyticTime) {
  const LemaitreChabocheDamage d;
  const double eta = 1.0 / 3.0;
  const double dp = d.thresholdPlasticStrain + 2.0 * (d.criticalPlasticStrain - d.thresholdPlasticStrain);
  DamageState s;
  const double dt = d.delayTime / 5000.0;
  advanceDamage(d, s, 0.0, dp, eta, dt);
  const double D0 = s.undelayed, a = d.delaySharpness;
  ASSERT_GT(D0, d.criticalDamage);
  const double tExact = d.delayTime / a * std::log((std::exp(a * D0) - 1.0) / (std::exp(a * (D0 - d.criticalDamage)) - 1.0));
  double t = dt;
  while (!s.fractured && t < 10.0 * tExact) {
    advanceDamage(d, s, dp, 0.0, eta, dt);
    t += dt;
  }
  ASSERT_TRUE(s.fractured);
  EXPECT_NEAR(t, tExact, 2e-3 * tExact);
}

TEST(LemaitreChaboche, FracturedPointCarriesNoStress) {
  const LemaitreChabocheDamage d;
  DamageState s;
  s.undelayed = 1.0;
  s.damage = 0.5 * d.criticalDamage;
  EXPECT_NEAR(stressFactor(s), 1.0 - 0.5 * d.criticalDamage, 1e-15);
  for (int n = 0; n < 100000 && !s.fractured; ++n) advanceDamage(d, s, 1.0, 0.0, 0.0, 1.0e-8);
  ASSERT_TRUE(s.fractured);
  EXPECT_EQ(stressFactor(s), 0.0);
}

TEST(LemaitreChaboche, BadParametersNameTheField) {
  LemaitreChabocheDamage d;
  d.criticalPlasticStrain = 0.5 * d.thresholdPlasticStrain;
  try {
    validateDamage(d, "shell.damage");
    FAIL();
  } catch (const SpecError& e) {
    EXPECT_EQ(e.field(), "shell.damage.critical_plastic_strain");
  }
  d = LemaitreChabocheDamage{};
  d.criticalDamage = 1.0;
  try {
    validateDamage(d, "x");
    FAIL();
  } catch (const SpecError& e) {
    EXPECT_EQ(e.field(), "x.critical_damage");
  }
  d = LemaitreChabocheDamage{};
  d.delayTime = 0.0;
  EXPECT_THROW(validateDamage(d, "x"), SpecError);
}

// The delay's backward-Euler step decides most bisection midpoints from a Newton estimate of the
// root instead of evaluating the exponential: it must land on the very damage of the plain
// bisection (every midpoint evaluated), bit for bit, over the states, steps and sharpnesses a
// plate meets (dt/τ_c from 1e-3 to 10, gaps from round-off to 1).
TEST(LemaitreChaboche, DelayStepIsThePlainBisectionBitForBit) {
  auto plainBisection = [](const LemaitreChabocheDamage& d, double undelayed, double damage, double dt) {
    double lo = damage, hi = undelayed;
    for (int it = 0; it < 80 && hi - lo > 1e-16; ++it) {
      const double mid = 0.5 * (lo + hi);
      if (mid - damage - dt * d.delayedRate(undelayed, mid) < 0.0) lo = mid; else hi = mid;
    }
    return lo;
  };
  std::uint64_t state = 12345;
  auto uniform = [&state]() {  // a fixed linear congruential sequence: the same cases every run
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(state >> 11) * 0x1.0p-53;
  };
  int cases = 0;
  for (const double sharpness : {0.3, 1.0, 5.0})
    for (const double ratio : {1e-3, 0.05, 0.3, 1.0, 10.0})
      for (int k = 0; k < 400; ++k) {
        LemaitreChabocheDamage d;
        d.delaySharpness = sharpness;
        d.criticalDamage = 0.999;  // no clamp at D_c: compare the step itself
        const double damage = 0.9 * uniform();
        const double gap = std::pow(10.0, -15.0 * uniform());  // 1e-15 .. 1
        const double undelayed = std::min(damage + gap, 0.99);
        if (!(undelayed > damage)) continue;
        DamageState s;
        s.damage = damage;
        s.undelayed = undelayed;
        const double dt = ratio * d.delayTime;
        advanceDamage(d, s, 0.0, 0.0, 1.0 / 3.0, dt);  // no plastic increment: the delay alone
        const double expected = plainBisection(d, undelayed, damage, dt);
        ASSERT_EQ(s.damage, expected) << "D_n " << damage << ", D_nc " << undelayed << ", dt/tau " << ratio
                                      << ", a " << sharpness;
        ++cases;
      }
  EXPECT_GT(cases, 5000);
}

}  // namespace
}  // namespace rupture
