#include "shell/shell_nodes.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace rupture {

ShellNodes clampedDiskNodes(double radius, double spacing, int outerRings) {
  if (!(radius > 0.0 && spacing > 0.0 && spacing <= radius / 2.0) || outerRings < 0)
    throw std::invalid_argument("clampedDiskNodes: need radius > 0, 0 < spacing <= radius/2, outerRings >= 0");
  const double pi = std::numbers::pi;
  const int K = static_cast<int>(std::lround(radius / spacing));
  const double d = radius / K;
  ShellNodes nodes;
  nodes.spacing = d;
  auto add = [&](double x, double y, double volume, double area, bool clamped) {
    nodes.x.push_back(x);
    nodes.y.push_back(y);
    nodes.kernelVolume.push_back(volume);
    nodes.integrationArea.push_back(area);
    nodes.clamped.push_back(clamped ? 1 : 0);
  };
  add(0.0, 0.0, pi * d * d / 4.0, pi * d * d / 4.0, false);
  for (int k = 1; k <= K + outerRings; ++k) {
    const double r = k * d;
    const int n = static_cast<int>(std::lround(2.0 * pi * k));
    const double ringArea = 2.0 * pi * r * d;  // annulus [r − d/2, r + d/2]
    double area = ringArea;
    if (k == K) area = pi * (radius * radius - (radius - 0.5 * d) * (radius - 0.5 * d));
    if (k > K) area = 0.0;
    for (int m = 0; m < n; ++m) {
      const double phi = 2.0 * pi * (m + 0.5 * (k % 2)) / n;
      add(r * std::cos(phi), r * std::sin(phi), ringArea / n, area / n, k >= K);
    }
  }
  return nodes;
}

}  // namespace rupture
