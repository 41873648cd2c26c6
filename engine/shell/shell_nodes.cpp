#include "shell/shell_nodes.hpp"

#include <algorithm>
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

namespace {

void checkRingRadii(const std::vector<double>& radii) {
  if (radii.size() < 2 || !(radii[0] > 0.0))
    throw std::invalid_argument("ringDiskNodes: need at least two rings of radius > 0");
  for (std::size_t k = 1; k < radii.size(); ++k)
    if (!(radii[k] > radii[k - 1])) throw std::invalid_argument("ringDiskNodes: ring radii must increase");
}

/// Ring k of ringDiskNodes (k = 1 … K): r_0 = 0 and the mirror ring r_{K+1} beyond the rim.
double ringRadius(const std::vector<double>& radii, long k) {
  const long K = static_cast<long>(radii.size());
  if (k <= 0) return 0.0;
  if (k > K) return 2.0 * radii[radii.size() - 1] - radii[radii.size() - 2];
  return radii[static_cast<std::size_t>(k - 1)];
}

/// Ring k's radial spacing Δ_k = (r_{k+1} − r_{k−1}) / 2.
double ringSpacing(const std::vector<double>& radii, long k) {
  return 0.5 * (ringRadius(radii, k + 1) - ringRadius(radii, k - 1));
}

/// The nodes on ring k: round(2π r_k / Δ_k), at least 3.
long ringNodes(const std::vector<double>& radii, long k) {
  return std::max(3L, std::lround(2.0 * std::numbers::pi * ringRadius(radii, k) / ringSpacing(radii, k)));
}

}  // namespace

std::size_t ringDiskNodeCount(const std::vector<double>& radii) {
  checkRingRadii(radii);
  std::size_t count = 1;  // the centre
  for (long k = 1; k <= static_cast<long>(radii.size()); ++k) count += static_cast<std::size_t>(ringNodes(radii, k));
  return count;
}

ShellNodes ringDiskNodes(const std::vector<double>& radii) {
  checkRingRadii(radii);
  const long K = static_cast<long>(radii.size());
  const double pi = std::numbers::pi;
  auto radius = [&](long k) { return ringRadius(radii, k); };
  ShellNodes nodes;
  auto add = [&](double x, double y, double volume, double area, bool clamped, double spacing) {
    nodes.x.push_back(x);
    nodes.y.push_back(y);
    nodes.kernelVolume.push_back(volume);
    nodes.integrationArea.push_back(area);
    nodes.clamped.push_back(clamped ? 1 : 0);
    nodes.nodeSpacing.push_back(spacing);
    nodes.spacing = std::max(nodes.spacing, spacing);
  };
  const double inner = 0.5 * radius(1);
  add(0.0, 0.0, pi * inner * inner, pi * inner * inner, false, radius(1));
  for (long k = 1; k <= K; ++k) {
    const double r = radius(k), lower = 0.5 * (radius(k - 1) + r), upper = 0.5 * (r + radius(k + 1));
    const double d = ringSpacing(radii, k);
    const long n = ringNodes(radii, k);
    const bool rim = k == K;
    const double annulus = pi * (upper * upper - lower * lower);
    const double area = rim ? pi * (r * r - lower * lower) : annulus;
    for (long m = 0; m < n; ++m) {
      const double phi = 2.0 * pi * (static_cast<double>(m) + 0.5 * static_cast<double>(k % 2)) / static_cast<double>(n);
      add(r * std::cos(phi), r * std::sin(phi), annulus / static_cast<double>(n), area / static_cast<double>(n), rim, d);
    }
  }
  return nodes;
}

std::vector<double> refinedRingRadii(double rim, double coarse, double fine, double at, int fineRings) {
  if (!(fine > 0.0 && fine <= coarse && at > 0.0 && at < rim && fineRings >= 1))
    throw std::invalid_argument("refinedRingRadii: need 0 < fine <= coarse, 0 < at < rim, fineRings >= 1");
  std::vector<double> radii;
  for (int m = 0; m < fineRings; ++m) {
    radii.push_back(at - (m + 0.5) * fine);
    radii.push_back(at + (m + 0.5) * fine);
  }
  // Grades the spacing from `fine` to `coarse` away from the band (direction ±1) and returns the
  // last ring placed.
  auto grade = [&](double from, double direction) {
    double r = from, spacing = fine;
    while (spacing < coarse) {
      spacing = std::min(coarse, kRingGrowth * spacing);
      r += direction * spacing;
      radii.push_back(r);
    }
    return r;
  };
  const double inner = grade(at - (fineRings - 0.5) * fine, -1.0);
  const double outer = grade(at + (fineRings - 0.5) * fine, +1.0);
  if (!(inner > 0.5 * coarse && outer < rim))
    throw std::invalid_argument("refinedRingRadii: the refined band and its grading do not fit inside the plate");
  // Uniform rings inside (from the centre to the graded part) and outside (to the rim).
  const long nIn = std::max(1L, std::lround(inner / coarse));
  for (long k = 1; k < nIn; ++k) radii.push_back(inner * static_cast<double>(k) / static_cast<double>(nIn));
  const long nOut = std::max(1L, std::lround((rim - outer) / coarse));
  for (long k = 1; k <= nOut; ++k) radii.push_back(outer + (rim - outer) * static_cast<double>(k) / static_cast<double>(nOut));
  radii.back() = rim;
  std::sort(radii.begin(), radii.end());
  return radii;
}

}  // namespace rupture
