#pragma once
// Gauss–Legendre points through the shell thickness, ξ in [−t/2, t/2]. Two or more points
// integrate the elastic resultants N = ∫σ dξ and M = ∫σ ξ dξ exactly; five is Caleyron et al.'s
// choice for their Q4GS finite elements (Caleyron et al. 2013, §4.1; docs/references.md), and the
// default here.
#include <array>
#include <stdexcept>
#include <vector>

namespace rupture {

struct ThroughThicknessRule {
  std::vector<double> xi;      ///< positions (m)
  std::vector<double> weight;  ///< weights (m), sum = t
};

inline ThroughThicknessRule gaussLegendreThickness(int n, double thickness) {
  static const std::array<std::vector<double>, 7> points = {{
      {0.0},
      {-0.5773502691896258, 0.5773502691896258},
      {-0.7745966692414834, 0.0, 0.7745966692414834},
      {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563, 0.8611363115940526},
      {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831, 0.9061798459386640},
      {-0.9324695142031521, -0.6612093864662645, -0.2386191860831969, 0.2386191860831969,
       0.6612093864662645, 0.9324695142031521},
      {-0.9491079123427585, -0.7415311855993945, -0.4058451513773972, 0.0, 0.4058451513773972,
       0.7415311855993945, 0.9491079123427585}}};
  static const std::array<std::vector<double>, 7> weights = {{
      {2.0},
      {1.0, 1.0},
      {0.5555555555555556, 0.8888888888888888, 0.5555555555555556},
      {0.3478548451374538, 0.6521451548625461, 0.6521451548625461, 0.3478548451374538},
      {0.2369268850561891, 0.4786286704993665, 0.5688888888888889, 0.4786286704993665,
       0.2369268850561891},
      {0.1713244923791704, 0.3607615730481386, 0.4679139345726910, 0.4679139345726910,
       0.3607615730481386, 0.1713244923791704},
      {0.1294849661688697, 0.2797053914892766, 0.3818300505051189, 0.4179591836734694,
       0.3818300505051189, 0.2797053914892766, 0.1294849661688697}}};
  if (n < 2 || n > 7) throw std::invalid_argument("through-thickness points must be in [2, 7]");
  ThroughThicknessRule rule;
  for (int k = 0; k < n; ++k) {
    rule.xi.push_back(0.5 * thickness * points[n - 1][k]);
    rule.weight.push_back(0.5 * thickness * weights[n - 1][k]);
  }
  return rule;
}

}  // namespace rupture
