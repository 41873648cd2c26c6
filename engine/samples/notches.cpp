#include "samples/notches.hpp"

#include <algorithm>
#include <cstdint>

namespace rupture {

namespace {
double orientation(double ax, double ay, double bx, double by, double cx, double cy) {
  return (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
}
bool within(double a, double b, double v) { return v >= std::min(a, b) && v <= std::max(a, b); }
}  // namespace

bool segmentsCross(double ax, double ay, double bx, double by, double cx, double cy, double dx, double dy) {
  const double o1 = orientation(ax, ay, bx, by, cx, cy), o2 = orientation(ax, ay, bx, by, dx, dy);
  const double o3 = orientation(cx, cy, dx, dy, ax, ay), o4 = orientation(cx, cy, dx, dy, bx, by);
  if (((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0))) return true;
  // Collinear or touching cases.
  if (o1 == 0 && within(ax, bx, cx) && within(ay, by, cy)) return true;
  if (o2 == 0 && within(ax, bx, dx) && within(ay, by, dy)) return true;
  if (o3 == 0 && within(cx, dx, ax) && within(cy, dy, ay)) return true;
  if (o4 == 0 && within(cx, dx, bx) && within(cy, dy, by)) return true;
  return false;
}

std::size_t cutNotches(const std::vector<Notch>& notches, const ParticleStore& p, BondStore& bonds) {
  if (notches.empty()) return 0;
  std::vector<std::uint8_t> keep(bonds.size(), 1);
  std::size_t removed = 0;
  for (std::size_t b = 0; b < bonds.size(); ++b) {
    const std::int32_t i = bonds.i[b], j = bonds.j[b];
    for (const Notch& n : notches)
      if (segmentsCross(p.x[i], p.y[i], p.x[j], p.y[j], n.start[0], n.start[1], n.end[0], n.end[1])) {
        keep[b] = 0;
        bonds.cutPairs.push_back({i, j, bonds.restLength[b]});
        ++removed;
        break;
      }
  }
  bonds.filter(keep);
  return removed;
}

}  // namespace rupture
