#pragma once
// Branch-free elementary functions for the bond kernels. std::atan2 is a library call that stops
// GCC from vectorising a loop; this one is plain arithmetic and selects, so a `#pragma omp simd`
// loop over bonds stays vectorised. Accuracy: a few ulp (tested against std::atan2).
#include <cmath>
#include <numbers>

namespace rupture {

/// atan(x) for |x| <= 0.66 (Cephes atan.c rational approximation, relative error ~1e-16).
[[gnu::always_inline]] inline double atanSmall(double x) {
  constexpr double P0 = -8.750608600031904122785e-1, P1 = -1.615753718733365076637e1,
                   P2 = -7.500855792314704667340e1, P3 = -1.228866684490136173410e2,
                   P4 = -6.485021904942025371773e1;
  constexpr double Q0 = 2.485846490142306297962e1, Q1 = 1.650270098316988542046e2,
                   Q2 = 4.328810604912902668951e2, Q3 = 4.853903996359136964868e2,
                   Q4 = 1.945506571482613964425e2;
  const double z = x * x;
  const double p = (((P0 * z + P1) * z + P2) * z + P3) * z + P4;
  const double q = ((((z + Q0) * z + Q1) * z + Q2) * z + Q3) * z + Q4;
  return x + x * z * p / q;
}

/// atan2(y, x) in (-π, π], branch-free. Returns 0 for (0, 0).
[[gnu::always_inline]] inline double atan2Branchless(double y, double x) {
  constexpr double pi = std::numbers::pi;
  const double ax = std::fabs(x);
  const double ay = std::fabs(y);
  const double big = (ax > ay ? ax : ay);
  const double small = (ax > ay ? ay : ax);
  const double t = small / (big > 1e-300 ? big : 1e-300);  // t in [0, 1]; 0 for (0, 0)
  // Reduce t in (0.66, 1] to (t-1)/(t+1) in (-0.21, 0] with atan(t) = π/4 + atan((t-1)/(t+1)).
  // Every branch is a select between two computed values, so GCC keeps the loop vectorised.
  const bool reduce = t > 0.66;
  const double reduced = (t - 1.0) / (t + 1.0);
  const double u = reduce ? reduced : t;
  const double offset = reduce ? 0.25 * pi : 0.0;
  double a = offset + atanSmall(u);
  const double complement = 0.5 * pi - a;
  a = ay > ax ? complement : a;
  const double supplement = pi - a;
  a = x < 0 ? supplement : a;
  return std::copysign(a, y);
}

}  // namespace rupture
