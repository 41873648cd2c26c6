#include "scenarios/impact/crack_tracking.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <unordered_map>

namespace rupture {

double CrackTracker::observe(double t, const ParticleStore& p, const std::vector<double>& damage) {
  // Cracked particles binned on a grid of the link length; a breadth-first search from the
  // origin's neighbourhood follows the crack.
  const double link = 2.5 * m_spacing, link2 = link * link, seed2 = 9.0 * m_spacing * m_spacing;
  std::unordered_map<std::int64_t, std::vector<std::size_t>> grid;
  auto cellOf = [&](double v, int a) { return static_cast<std::int64_t>(std::floor((v - m_origin[a]) / link)); };
  auto key = [](std::int64_t a, std::int64_t b, std::int64_t c) { return (a * 1000003 + b) * 1000033 + c; };
  std::vector<std::size_t> frontier;
  std::vector<std::uint8_t> seen(p.size(), 0);
  for (std::size_t k = 0; k < p.size(); ++k) {
    if (damage[k] <= m_threshold) continue;
    grid[key(cellOf(p.x[k], 0), cellOf(p.y[k], 1), cellOf(p.z[k], 2))].push_back(k);
    const double dx = p.x[k] - m_origin[0], dy = p.y[k] - m_origin[1], dz = p.z[k] - m_origin[2];
    if (dx * dx + dy * dy + dz * dz < seed2) { frontier.push_back(k); seen[k] = 1; }
  }
  while (!frontier.empty()) {
    const std::size_t k = frontier.back();
    frontier.pop_back();
    const double dx = p.x[k] - m_origin[0], dy = p.y[k] - m_origin[1], dz = p.z[k] - m_origin[2];
    const double r = std::sqrt(dx * dx + dy * dy + dz * dz);
    if (!m_tip.found || r > m_tip.distance) m_tip = {p.x[k], p.y[k], p.z[k], r, true};
    const std::int64_t cx = cellOf(p.x[k], 0), cy = cellOf(p.y[k], 1), cz = cellOf(p.z[k], 2);
    for (std::int64_t a = -1; a <= 1; ++a)
      for (std::int64_t b = -1; b <= 1; ++b)
        for (std::int64_t c = -1; c <= 1; ++c) {
          auto it = grid.find(key(cx + a, cy + b, cz + c));
          if (it == grid.end()) continue;
          for (std::size_t m : it->second) {
            if (seen[m]) continue;
            const double ex = p.x[m] - p.x[k], ey = p.y[m] - p.y[k], ez = p.z[m] - p.z[k];
            if (ex * ex + ey * ey + ez * ez < link2) { seen[m] = 1; frontier.push_back(m); }
          }
        }
  }
  // A gain no crack could make in the time since the last row is a jump: two zones joined.
  m_jump = 0;
  if (m_lastFound && !m_times.empty()) {
    const double gained = m_tip.distance - m_lastDistance, elapsed = t - m_times.back();
    if (gained > m_jumpSpeed * elapsed + 2 * m_spacing) {
      m_jump = gained;
      m_jumped += gained;
      ++m_jumps;
    }
  }
  m_lastFound = m_tip.found;
  m_lastDistance = m_tip.distance;
  m_times.push_back(t);
  m_distances.push_back(m_tip.distance - m_jumped);
  const std::size_t n = m_times.size();
  if (n <= m_window) return 0.0;
  const double speed = (m_distances[n - 1] - m_distances[n - 1 - m_window]) / (m_times[n - 1] - m_times[n - 1 - m_window]);
  m_maxSpeed = std::max(m_maxSpeed, speed);
  return speed;
}

std::optional<double> crackAngle(const CrackTip& tip, std::array<double, 3> from, std::array<double, 3> to,
                                 int dimension) {
  const std::array<double, 3> notch{to[0] - from[0], to[1] - from[1], to[2] - from[2]};
  const std::array<double, 3> crack{tip.x - to[0], tip.y - to[1], tip.z - to[2]};
  const double notchLength = std::hypot(notch[0], notch[1], notch[2]);
  if (!tip.found || tip.distance == 0 || notchLength == 0) return std::nullopt;
  const double dot = notch[0] * crack[0] + notch[1] * crack[1] + notch[2] * crack[2];
  if (dimension == 2) return std::atan2(notch[0] * crack[1] - notch[1] * crack[0], dot);
  const double cx = notch[1] * crack[2] - notch[2] * crack[1], cy = notch[2] * crack[0] - notch[0] * crack[2],
               cz = notch[0] * crack[1] - notch[1] * crack[0];
  return std::atan2(std::hypot(cx, cy, cz), dot);
}

int countCrackBranches(const ParticleStore& p, const std::vector<double>& damage, double threshold,
                       std::array<double, 3> origin, double spacing) {
  std::vector<std::size_t> cracked;
  std::vector<double> radius;
  for (std::size_t k = 0; k < p.size(); ++k)
    if (damage[k] > threshold) {
      cracked.push_back(k);
      radius.push_back(std::sqrt((p.x[k] - origin[0]) * (p.x[k] - origin[0]) + (p.y[k] - origin[1]) * (p.y[k] - origin[1]) +
                                 (p.z[k] - origin[2]) * (p.z[k] - origin[2])));
    }
  if (cracked.empty()) return 0;
  const double width = 4 * spacing, link2 = 6.25 * spacing * spacing;
  const double rMax = *std::max_element(radius.begin(), radius.end());
  int best = 1;
  for (double r0 = 6 * spacing; r0 + width <= rMax; r0 += 0.5 * width) {
    std::vector<std::size_t> shell;
    for (std::size_t c = 0; c < cracked.size(); ++c)
      if (radius[c] >= r0 && radius[c] < r0 + width) shell.push_back(cracked[c]);
    // Union–find over the shell (a few hundred particles at most: pairwise is fine).
    std::vector<std::size_t> parent(shell.size());
    std::iota(parent.begin(), parent.end(), std::size_t{0});
    auto root = [&](std::size_t a) { while (parent[a] != a) a = parent[a] = parent[parent[a]]; return a; };
    for (std::size_t a = 0; a < shell.size(); ++a)
      for (std::size_t b = a + 1; b < shell.size(); ++b) {
        const std::size_t i = shell[a], j = shell[b];
        const double d2 = (p.x[i] - p.x[j]) * (p.x[i] - p.x[j]) + (p.y[i] - p.y[j]) * (p.y[i] - p.y[j]) +
                          (p.z[i] - p.z[j]) * (p.z[i] - p.z[j]);
        if (d2 < link2) parent[root(a)] = root(b);
      }
    std::vector<std::size_t> size(shell.size(), 0);
    for (std::size_t a = 0; a < shell.size(); ++a) ++size[root(a)];
    int clusters = 0;
    for (std::size_t a = 0; a < shell.size(); ++a) clusters += parent[a] == a && size[a] >= 3;
    best = std::max(best, clusters);
  }
  return best;
}

}  // namespace rupture
