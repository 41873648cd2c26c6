#include "render/round_ticks.hpp"

#include <cmath>

namespace rupture::render {

RoundTicks roundTicks(double lo, double hi, int intervals) {
  RoundTicks out;
  const double span = hi - lo;
  if (!(span > 0) || !std::isfinite(span) || intervals < 1) return out;
  const double raw = span / intervals;
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  const double r = raw / magnitude;
  out.step = magnitude * (r < 1.5 ? 1 : r < 3.5 ? 2 : r < 7.5 ? 5 : 10);
  // Multiples of the step by index, not by repeated addition: 0.1 + 0.2 would drift off 0.3.
  const long first = static_cast<long>(std::ceil(lo / out.step - 1e-9));
  for (long k = first; out.values.size() < 20; ++k) {
    const double t = static_cast<double>(k) * out.step;
    if (t > hi + 1e-9 * span) break;
    out.values.push_back(std::abs(t) < 1e-12 * span ? 0.0 : t);
  }
  return out;
}

double scaleBarLength(double span) {
  if (!(span > 0) || !std::isfinite(span)) return 0;
  const double most = 0.25 * span * (1 + 1e-9);
  const double decade = std::pow(10.0, std::floor(std::log10(most)));
  return most >= 5 * decade ? 5 * decade : most >= 2 * decade ? 2 * decade : decade;
}

}  // namespace rupture::render
