// The cubic spline kernel and the equations of state (docs/references.md#eq-sph).
#include <gtest/gtest.h>

#include <cmath>

#include "sph/cubic_spline_kernel.hpp"
#include "sph/equation_of_state.hpp"

namespace rupture::sph {
namespace {

/// Σ_b W(|x_a − x_b|) dx^D over a lattice around x_a, which is offset from the sites.
double latticeSum(int dimension, double ratio, double offset) {
  const double dx = 1.0, h = ratio * dx;
  const CubicSplineKernel kernel(dimension, h);
  const int reach = static_cast<int>(std::ceil(2 * ratio)) + 1;
  double sum = 0;
  for (int k = dimension == 3 ? -reach : 0; k <= (dimension == 3 ? reach : 0); ++k)
    for (int j = -reach; j <= reach; ++j)
      for (int i = -reach; i <= reach; ++i) {
        const double x = i - offset, y = j - 0.5 * offset, z = dimension == 3 ? k + 0.25 * offset : 0.0;
        sum += kernel.value(std::sqrt(x * x + y * y + z * z)) * std::pow(dx, dimension);
      }
  return sum;
}

// The normalisation a_D makes ∫W = 1; a lattice sum is that integral's quadrature, exact enough
// once the lattice resolves the kernel (h/dx >= 2). At the simulations' h/dx = 1.3 the same sum
// is 1 within 3e-3 (the partition-of-unity error of a coarse lattice, not of a_D).
TEST(CubicSplineKernel, SumsToOneOverALatticeIn2DAnd3D) {
  for (int dimension : {2, 3}) {
    for (double offset : {0.0, 0.3}) EXPECT_NEAR(latticeSum(dimension, 1.3, offset), 1.0, 3e-3);
    for (double ratio : {2.0, 3.0})
      for (double offset : {0.0, 0.3})
        EXPECT_NEAR(latticeSum(dimension, ratio, offset), 1.0, 1e-3)
            << "dimension " << dimension << ", h/dx " << ratio << ", offset " << offset;
  }
}

TEST(CubicSplineKernel, GradientIsAntisymmetricAndTheDerivativeOfW) {
  for (int dimension : {2, 3}) {
    const CubicSplineKernel kernel(dimension, 0.013);
    const double a[3] = {0.001, -0.002, dimension == 3 ? 0.0005 : 0.0};
    for (double r : {0.002, 0.009, 0.013, 0.017, 0.025, 0.0259}) {
      const double b[3] = {a[0] + 0.6 * r, a[1] + 0.8 * r, a[2]};
      const double d = std::hypot(b[0] - a[0], b[1] - a[1]);
      const double F = kernel.gradientFactor(d);
      for (int c = 0; c < 2; ++c) {
        const double gradA = F * (a[c] - b[c]), gradB = F * (b[c] - a[c]);
        EXPECT_EQ(gradA, -gradB);
      }
      // (dW/dr)/r against a central difference of W, and the branch-free form with 1/r.
      const double e = 1e-7;
      const double dWdr = (kernel.value(d + e) - kernel.value(d - e)) / (2 * e);
      EXPECT_NEAR(F * d, dWdr, 1e-6 * std::fabs(kernel.gradientFactor(0.0)) * kernel.h()) << "r " << r;
      EXPECT_NEAR(kernel.gradientFactor(d, 1.0 / d), F, 1e-12 * std::fabs(F) + 1e-300);
    }
    EXPECT_EQ(kernel.gradientFactor(2.0 * 0.013 * 1.0001), 0.0);
    EXPECT_EQ(kernel.value(2.0 * 0.013 * 1.0001), 0.0);
  }
}

TEST(EquationOfState, TaitAndAcousticInvertAndShareTheSoundSpeed) {
  for (EosKind kind : {EosKind::Tait, EosKind::Acoustic}) {
    const EquationOfState eos{kind, 1000.0, 1450.0, 7.0};
    for (double p : {-1e5, 0.0, 2e3, 7.25e6, 5e7}) EXPECT_NEAR(eos.pressure(eos.density(p)), p, 1e-6 * std::fabs(p) + 1e-6);
    EXPECT_NEAR(eos.pressure(1001.0), eos.pressureGeneral(1001.0), 1e-9 * eos.pressure(1001.0));
    // dp/dρ at ρ0 = c0².
    const double e = 1e-4;
    EXPECT_NEAR((eos.pressure(1000.0 + e) - eos.pressure(1000.0 - e)) / (2 * e), 1450.0 * 1450.0, 1.0);
  }
}

TEST(EquationOfState, PistonShockTendsToTheAcousticJump) {
  const EquationOfState acoustic{EosKind::Acoustic, 1000.0, 20.0, 7.0};
  const PistonShock a = pistonShock(acoustic, 2.0);
  EXPECT_NEAR(a.speed, 0.5 * (2.0 + std::sqrt(4.0 + 4.0 * 400.0)), 1e-9);  // closed form
  const EquationOfState tait{EosKind::Tait, 1000.0, 1450.0, 7.0};
  const PistonShock weak = pistonShock(tait, 0.01);
  EXPECT_NEAR(weak.pressure / (1000.0 * 1450.0 * 0.01), 1.0, 1e-4);
  // Tait stiffens under compression: a strong shock runs faster than c0 + v (weak shocks:
  // U ≈ c0 + (γ + 1) v/4).
  const PistonShock strong = pistonShock(tait, 100.0);
  EXPECT_GT(strong.speed, 1450.0 + 100.0);
  EXPECT_NEAR(strong.pressure, 1000.0 * strong.speed * 100.0, 1e-6 * strong.pressure);
}

}  // namespace
}  // namespace rupture::sph
