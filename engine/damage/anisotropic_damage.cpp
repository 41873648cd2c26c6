#include "damage/anisotropic_damage.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>

namespace rupture {

FrameAxes frameAxes(const FrameAngles& degrees, int dimension) {
  constexpr double radian = std::numbers::pi / 180.0;
  if (dimension == 2) {
    const double c = std::cos(degrees[0] * radian), s = std::sin(degrees[0] * radian);
    return {{{c, s, 0}, {-s, c, 0}, {0, 0, 1}}};
  }
  const double ca = std::cos(degrees[0] * radian), sa = std::sin(degrees[0] * radian);
  const double cb = std::cos(degrees[1] * radian), sb = std::sin(degrees[1] * radian);
  const double cg = std::cos(degrees[2] * radian), sg = std::sin(degrees[2] * radian);
  // R = R_z(γ) R_y(β) R_x(α); axis k is column k of R.
  const double r[3][3] = {{cg * cb, cg * sb * sa - sg * ca, cg * sb * ca + sg * sa},
                          {sg * cb, sg * sb * sa + cg * ca, sg * sb * ca - cg * sa},
                          {-sb, cb * sa, cb * ca}};
  FrameAxes axes{};
  for (int k = 0; k < 3; ++k)
    for (int row = 0; row < 3; ++row) axes[k][row] = r[row][k];
  return axes;
}

BondFibres bondFibres(const std::array<double, 3>& n0, const FrameAxes& frameI, const FrameAxes& frameJ,
                      const std::vector<double>& criticalFactors, int dimension) {
  const std::size_t d = static_cast<std::size_t>(dimension);
  std::array<double, 3> weight{0, 0, 0};
  for (std::size_t k = 0; k < d; ++k) {
    const double ci = n0[0] * frameI[k][0] + n0[1] * frameI[k][1] + n0[2] * frameI[k][2];
    const double cj = n0[0] * frameJ[k][0] + n0[1] * frameJ[k][1] + n0[2] * frameJ[k][2];
    weight[k] = 0.5 * (ci * ci + cj * cj);
  }
  std::array<std::size_t, 3> order{0, 1, 2};
  std::stable_sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(d),
                   [&](std::size_t a, std::size_t b) { return criticalFactors[a] < criticalFactors[b]; });
  BondFibres fibres;
  fibres.factor.fill(std::numeric_limits<double>::infinity());
  fibres.integrity.fill(0.0);
  for (std::size_t c = 0; c < d; ++c) {
    fibres.factor[c] = criticalFactors[order[c]];
    // What is left once fibres 0 … c have failed: the sum of the others' weights, so that the last
    // leaves exactly 0 (1 − Σ would leave rounding).
    double left = 0;
    for (std::size_t later = c + 1; later < d; ++later) left += weight[order[later]];
    fibres.integrity[c] = left;
  }
  return fibres;
}

}  // namespace rupture
