#pragma once
// Wendland C2 kernel in 2D (Wendland 1995; Dehnen & Aly 2012, Table 1), support radius 2h:
//   W(q) = 7 / (4π h²) (1 − q/2)⁴ (1 + 2q),   q = r/h in [0, 2]
//   dW/dr = −35 / (4π h³) q (1 − q/2)³
// Used on the shell's flat reference configuration (total Lagrangian: evaluated once). Wendland
// kernels have no pairing instability and a positive Fourier transform.
#include <numbers>

namespace rupture {

struct WendlandC2Kernel2D {
  double h = 1.0;  ///< smoothing length (m); support radius 2h

  double supportRadius() const { return 2.0 * h; }
  double value(double r) const {
    const double q = r / h;
    if (q >= 2.0) return 0.0;
    const double a = 1.0 - 0.5 * q;
    return 7.0 / (4.0 * std::numbers::pi * h * h) * a * a * a * a * (1.0 + 2.0 * q);
  }
  double derivative(double r) const {
    const double q = r / h;
    if (q >= 2.0) return 0.0;
    const double a = 1.0 - 0.5 * q;
    return -35.0 / (4.0 * std::numbers::pi * h * h * h) * q * a * a * a;
  }
};

}  // namespace rupture
