#include "render/colour_map.hpp"

#include <cmath>

namespace rupture::render {

Rgb viridis(double t) {
  // matplotlib's viridis at t = 0, 0.1, ..., 1 (#440154, #482475, ..., #fde725).
  static constexpr std::array<std::array<int, 3>, 11> stops = {{{68, 1, 84},
                                                                  {72, 36, 117},
                                                                  {65, 68, 135},
                                                                  {53, 95, 141},
                                                                  {42, 120, 142},
                                                                  {33, 145, 140},
                                                                  {34, 168, 132},
                                                                  {68, 191, 112},
                                                                  {122, 209, 81},
                                                                  {189, 223, 38},
                                                                  {253, 231, 37}}};
  if (std::isnan(t)) return {0.6, 0.6, 0.6};
  t = t < 0 ? 0 : (t > 1 ? 1 : t);
  const double position = t * 10;
  const int k = position >= 10 ? 9 : static_cast<int>(position);
  const double f = position - k;
  const auto& a = stops[static_cast<std::size_t>(k)];
  const auto& b = stops[static_cast<std::size_t>(k) + 1];
  auto mix = [f](int x, int y) { return ((1 - f) * x + f * y) / 255.0; };
  return {mix(a[0], b[0]), mix(a[1], b[1]), mix(a[2], b[2])};
}

}  // namespace rupture::render
