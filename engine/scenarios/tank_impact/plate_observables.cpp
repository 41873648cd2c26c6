#include "scenarios/tank_impact/plate_observables.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <map>
#include <numbers>
#include <utility>

namespace rupture {

double deflectionAtRadius(const SphShell& shell, const PlateGeometry& geometry, double radius) {
  const ShellNodes& nodes = geometry.nodes;
  // Rings by radius (to 0.1 µm; rings are at least plate.thickness / 20 apart) → (sum of −z, intact nodes).
  std::map<long, std::pair<double, int>> rings;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    auto& ring = rings[std::lround(std::hypot(nodes.x[i], nodes.y[i]) * 1e7)];
    if (shell.fractured(i)) continue;
    ring.first -= shell.deflection(i);
    ++ring.second;
  }
  auto mean = [&](std::map<long, std::pair<double, int>>::const_iterator it) {
    return it == rings.end() || it->second.second == 0 ? std::numeric_limits<double>::quiet_NaN()
                                                       : it->second.first / it->second.second;
  };
  // The rings on either side of the radius and where it lies between them.
  auto above = rings.upper_bound(std::lround(radius * 1e7));
  if (above == rings.begin() || above == rings.end()) return std::numeric_limits<double>::quiet_NaN();
  const auto below = std::prev(above);
  const double f = (radius * 1e7 - static_cast<double>(below->first)) / static_cast<double>(above->first - below->first);
  const double w0 = mean(below), w1 = mean(above);
  if (!std::isnan(w0) && !std::isnan(w1)) return (1.0 - f) * w0 + f * w1;
  if (!std::isnan(w0) && f <= 0.5) return w0;
  if (!std::isnan(w1) && f >= 0.5) return w1;
  return std::numeric_limits<double>::quiet_NaN();
}

double tongueOpeningAngle(const SphShell& shell, const PlateGeometry& geometry, const PlateSpec& plate) {
  if (plate.precrack.shape != PrecrackShape::U || geometry.tongueNodes.empty()) return 0.0;
  const auto& a = geometry.hinge.a;
  const auto& b = geometry.hinge.b;
  const double len = std::hypot(b[0] - a[0], b[1] - a[1]);
  // In-plane unit normal of the hinge, pointing into the tongue.
  double mx = -(b[1] - a[1]) / len, my = (b[0] - a[0]) / len;
  double side = 0.0;
  for (std::size_t i : geometry.tongueNodes) side += (geometry.nodes.x[i] - a[0]) * mx + (geometry.nodes.y[i] - a[1]) * my;
  if (side < 0.0) { mx = -mx; my = -my; }
  // Each intact node in the plane normal to the hinge: d its reference distance from the hinge,
  // (u, w) its current in-plane distance and height. The sums are taken about their means (Σ d̃ ũ =
  // Σ d u − Σd Σu / n), so that the plate's own sinking and drawing-in at the hinge (it dishes by
  // millimetres under the water) is a translation, not read as rotation.
  double n = 0.0, sd = 0.0, su = 0.0, sw = 0.0, sdu = 0.0, sdw = 0.0;
  for (std::size_t i : geometry.tongueNodes) {
    if (shell.fractured(i)) continue;
    const auto& x = shell.positions()[i];
    const double d = (geometry.nodes.x[i] - a[0]) * mx + (geometry.nodes.y[i] - a[1]) * my;
    const double u = (x[0] - a[0]) * mx + (x[1] - a[1]) * my, w = x[2];
    n += 1.0, sd += d, su += u, sw += w, sdu += d * u, sdw += d * w;
  }
  if (n == 0.0) return 0.0;
  const double along = sdu - sd * su / n, down = -(sdw - sd * sw / n);
  return std::atan2(down, along);
}

double crackedLength(const SphShell& shell, const PlateGeometry& geometry) {
  double length = 0.0;
  for (std::size_t i = 0; i < geometry.nodes.size(); ++i)
    if (shell.fractured(i)) length += std::sqrt(geometry.nodes.kernelVolume[i]);
  return length;
}

double rimTornFraction(const SphShell& shell, const PlateGeometry& geometry, double rimRadius, double band) {
  constexpr double kTwoPi = 2.0 * std::numbers::pi;
  // Each fractured cell near the rim as an arc [θ − w/2, θ + w/2] of [0, 2π); an arc across 0 is
  // split in two.
  std::vector<std::pair<double, double>> arcs;
  const ShellNodes& nodes = geometry.nodes;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const double r = std::hypot(nodes.x[i], nodes.y[i]);
    if (!shell.fractured(i) || std::abs(r - rimRadius) > band || r == 0.0) continue;
    const double half = std::min(0.5 * std::sqrt(nodes.kernelVolume[i]) / r, std::numbers::pi);
    double theta = std::atan2(nodes.y[i], nodes.x[i]);
    if (theta < 0.0) theta += kTwoPi;
    const double lo = theta - half, hi = theta + half;
    if (lo < 0.0) {
      arcs.emplace_back(0.0, hi);
      arcs.emplace_back(lo + kTwoPi, kTwoPi);
    } else if (hi > kTwoPi) {
      arcs.emplace_back(lo, kTwoPi);
      arcs.emplace_back(0.0, hi - kTwoPi);
    } else {
      arcs.emplace_back(lo, hi);
    }
  }
  std::sort(arcs.begin(), arcs.end());
  double covered = 0.0, end = 0.0;
  for (const auto& [lo, hi] : arcs) {  // the union's length, sweeping the sorted arcs
    if (hi <= end) continue;
    covered += hi - std::max(lo, end);
    end = hi;
  }
  return covered / kTwoPi;
}

std::vector<std::array<double, 2>> crackPath(const SphShell& shell, const PlateGeometry& geometry) {
  std::vector<std::array<double, 2>> path;
  path.reserve(shell.fractureOrder().size());
  for (std::size_t i : shell.fractureOrder()) path.push_back({geometry.nodes.x[i], geometry.nodes.y[i]});
  return path;
}

}  // namespace rupture
