#include "fsi/pinball_contact.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rupture::fsi {

namespace {

struct Pair {
  std::int32_t particle, node;
  double s;  ///< signed normal distance (x_f − x_n)·n_n (m)
};

}  // namespace

ContactOutcome resolvePinballContact(sph::FluidParticles& p, const SphShell& shell, const ShellNodeGrid& grid,
                                     const ContactGeometry& g, double /*dt*/) {
  ContactOutcome out;
  out.impulse.assign(shell.size(), {0.0, 0.0, 0.0});
  const auto& xn = shell.positions();
  const auto& vn = shell.velocities();
  const auto& nn = shell.normals();
  const double standOff = g.standOff(), cell2 = g.cellRadius * g.cellRadius;

  // 1. Interpenetrating pairs, grouped by particle (eq. 6 for a sphere against a cylinder).
  std::vector<Pair> pairs;
  for (std::size_t f = 0; f < p.size(); ++f) {
    if (!p.isFluid(f) || !grid.near(p.x[f], p.y[f], p.z[f])) continue;
    grid.forEachNear(p.x[f], p.y[f], p.z[f], [&](std::size_t n) {
      const double d[3] = {p.x[f] - xn[n][0], p.y[f] - xn[n][1], p.z[f] - xn[n][2]};
      const double s = d[0] * nn[n][0] + d[1] * nn[n][1] + d[2] * nn[n][2];
      if (std::fabs(s) >= standOff) return;
      const double rho2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2] - s * s;
      if (rho2 >= cell2) return;
      pairs.push_back({static_cast<std::int32_t>(f), static_cast<std::int32_t>(n), s});
    });
  }
  out.pairs = pairs.size();
  if (pairs.empty()) return out;

  // 2. Each node's inertia is shared among the particles pressing on it.
  std::vector<int> contacts(shell.size(), 0);
  for (const Pair& c : pairs) ++contacts[c.node];

  // 3. Impulses: particle by particle, its pairs in turn (Gauss–Seidel on the particle).
  std::int32_t last = -1;
  for (const Pair& c : pairs) {
    const std::size_t f = c.particle, n = c.node;
    if (c.particle != last) { ++out.particles; last = c.particle; }
    const double sigma = c.s >= 0.0 ? 1.0 : -1.0;
    const double nx = sigma * nn[n][0], ny = sigma * nn[n][1], nz = sigma * nn[n][2];
    // Out of the pinball along its normal (from the particle's current position: an earlier pair
    // may have moved it already): a position correction, no momentum.
    const double depth = standOff - ((p.x[f] - xn[n][0]) * nx + (p.y[f] - xn[n][1]) * ny + (p.z[f] - xn[n][2]) * nz);
    if (depth > 0.0) {
      p.x[f] += depth * nx;
      p.y[f] += depth * ny;
      p.z[f] += depth * nz;
    }
    const double u = (p.vx[f] - vn[n][0]) * nx + (p.vy[f] - vn[n][1]) * ny + (p.vz[f] - vn[n][2]) * nz;
    if (u >= 0.0) continue;
    const double mf = p.mass[f];
    const double inverseShare = shell.clamped(n) || !(shell.mass(n) > 0) ? 0.0 : contacts[n] / shell.mass(n);
    const double J = -u / (1.0 / mf + inverseShare);
    p.vx[f] += J / mf * nx;
    p.vy[f] += J / mf * ny;
    p.vz[f] += J / mf * nz;
    out.impulse[n][0] -= J * nx;
    out.impulse[n][1] -= J * ny;
    out.impulse[n][2] -= J * nz;
  }
  return out;
}

}  // namespace rupture::fsi
