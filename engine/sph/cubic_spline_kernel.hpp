#pragma once
// Cubic B-spline smoothing kernel (Monaghan & Lattanzio 1985), support 2h, normalised per
// dimension (docs/references.md#eq-sph). W(r) = a_D w(q), q = r/h,
//   w = 1 − 1.5 q² + 0.75 q³ (0 ≤ q < 1),  0.25 (2 − q)³ (1 ≤ q < 2),  0 (q ≥ 2)
//   a_D = 2/(3h) (1D), 10/(7π h²) (2D), 1/(π h³) (3D).
// The pair loops need only gradientFactor: ∇_a W_ab = gradientFactor(r) · (x_a − x_b).
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace rupture::sph {

class CubicSplineKernel {
public:
  CubicSplineKernel(int dimension, double h) : m_h(h), m_invH(1.0 / h) {
    if (!(h > 0)) throw std::invalid_argument("CubicSplineKernel: smoothing length must be > 0");
    switch (dimension) {
      case 1: m_aD = 2.0 / (3.0 * h); break;
      case 2: m_aD = 10.0 / (7.0 * std::numbers::pi * h * h); break;
      case 3: m_aD = 1.0 / (std::numbers::pi * h * h * h); break;
      default: throw std::invalid_argument("CubicSplineKernel: dimension must be 1, 2 or 3");
    }
  }

  double h() const { return m_h; }
  double support() const { return 2.0 * m_h; }
  double normalisation() const { return m_aD; }

  /// W(r) (1/m^D).
  double value(double r) const {
    const double q = r * m_invH;
    const double near = 1.0 - 1.5 * q * q + 0.75 * q * q * q;
    const double t = 2.0 - q;
    const double far = 0.25 * t * t * t;
    return m_aD * (q < 1.0 ? near : (q < 2.0 ? far : 0.0));
  }

  /// (dW/dr)/r (1/m^(D+2)), finite at r = 0 (−3 a_D/h²). Branch-free so pair loops vectorise.
  [[gnu::always_inline]] double gradientFactor(double r) const {
    const double q = r * m_invH;
    const double t = 2.0 - q;
    const double near = -3.0 + 2.25 * q;                        // (dw/dq)/q for q < 1
    const double far = -0.75 * t * t / (q > 1e-12 ? q : 1e-12);  // (dw/dq)/q for 1 ≤ q < 2
    const double dwq = q < 1.0 ? near : (q < 2.0 ? far : 0.0);
    return m_aD * m_invH * m_invH * dwq;
  }

  /// The same from r and 1/r (the pair loops have both): no division, so cheaper in a SIMD loop.
  [[gnu::always_inline]] double gradientFactor(double r, double inverseR) const {
    const double q = r * m_invH;
    const double t = 2.0 - q;
    const double near = -3.0 + 2.25 * q;
    const double far = -0.75 * t * t * m_h * inverseR;
    const double dwq = q < 1.0 ? near : (q < 2.0 ? far : 0.0);
    return m_aD * m_invH * m_invH * dwq;
  }

private:
  double m_h, m_invH, m_aD = 0;
};

}  // namespace rupture::sph
