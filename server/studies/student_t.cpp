#include "studies/student_t.hpp"

#include <cmath>
#include <stdexcept>

namespace rupture::server {
namespace {

/// The continued fraction of I_x(a, b) (modified Lentz), which converges fast for x < (a+1)/(a+b+2).
double betaContinuedFraction(double x, double a, double b) {
  constexpr double tiny = 1e-300;
  const double sum = a + b, aPlus = a + 1, aMinus = a - 1;
  double c = 1, d = 1 - sum * x / aPlus;
  if (std::abs(d) < tiny) d = tiny;
  d = 1 / d;
  double h = d;
  for (int m = 1; m <= 500; ++m) {
    const double m2 = 2.0 * m;
    double term = m * (b - m) * x / ((aMinus + m2) * (a + m2));  // even step
    d = 1 + term * d;
    if (std::abs(d) < tiny) d = tiny;
    c = 1 + term / c;
    if (std::abs(c) < tiny) c = tiny;
    d = 1 / d;
    h *= d * c;
    term = -(a + m) * (sum + m) * x / ((a + m2) * (aPlus + m2));  // odd step
    d = 1 + term * d;
    if (std::abs(d) < tiny) d = tiny;
    c = 1 + term / c;
    if (std::abs(c) < tiny) c = tiny;
    d = 1 / d;
    const double delta = d * c;
    h *= delta;
    if (std::abs(delta - 1) < 1e-15) break;
  }
  return h;
}

}  // namespace

double regularizedIncompleteBeta(double x, double a, double b) {
  if (!(a > 0) || !(b > 0)) throw std::invalid_argument("incomplete beta needs a, b > 0");
  if (x <= 0) return 0;
  if (x >= 1) return 1;
  const double logFront =
      std::lgamma(a + b) - std::lgamma(a) - std::lgamma(b) + a * std::log(x) + b * std::log1p(-x);
  // Use the symmetry I_x(a, b) = 1 - I_{1-x}(b, a) where the fraction converges slowly.
  if (x < (a + 1) / (a + b + 2)) return std::exp(logFront) * betaContinuedFraction(x, a, b) / a;
  return 1 - std::exp(logFront) * betaContinuedFraction(1 - x, b, a) / b;
}

double studentTCdf(double t, double dof) {
  if (!(dof > 0)) throw std::invalid_argument("Student t needs dof > 0");
  const double tail = 0.5 * regularizedIncompleteBeta(dof / (dof + t * t), dof / 2, 0.5);
  return t >= 0 ? 1 - tail : tail;
}

double studentTQuantile(double p, double dof) {
  if (!(p > 0 && p < 1)) throw std::invalid_argument("Student t quantile needs 0 < p < 1");
  if (!(dof > 0)) throw std::invalid_argument("Student t needs dof > 0");
  if (p < 0.5) return -studentTQuantile(1 - p, dof);
  if (p == 0.5) return 0;
  // The CDF rises monotonically: bracket, then bisect to machine precision.
  double lo = 0, hi = 1;
  while (studentTCdf(hi, dof) < p) {
    lo = hi;
    hi *= 2;
    if (hi > 1e300) return hi;
  }
  for (int i = 0; i < 200 && hi - lo > 1e-14 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (studentTCdf(mid, dof) < p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace rupture::server
