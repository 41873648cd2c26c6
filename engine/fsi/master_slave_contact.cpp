#include "fsi/master_slave_contact.hpp"

#include <cmath>
#include <limits>

namespace rupture::fsi {

namespace {

struct Weighted {
  std::int32_t node;
  double weight;  ///< ŵ (normalised)
};

struct Contact {
  std::int32_t particle;
  std::size_t begin, end;   ///< its nodes in the weight list
  double point[3], normal[3], velocity[3];
};

}  // namespace

ContactOutcome resolveMasterSlaveContact(sph::FluidParticles& p, const SphShell& shell, const ShellNodeGrid& grid,
                                         const ContactGeometry& g, double /*dt*/) {
  ContactOutcome out;
  out.impulse.assign(shell.size(), {0.0, 0.0, 0.0});
  const auto& xn = shell.positions();
  const auto& vn = shell.velocities();
  const auto& nn = shell.normals();
  const double standOff = g.standOff(), cell2 = g.cellRadius * g.cellRadius;
  const double support = g.surfaceSupport();

  // 1. Slaves on a surface: nearest intact node, then the surface interpolated around it.
  std::vector<Contact> contacts;
  std::vector<Weighted> weights;
  std::vector<double> share(shell.size(), 0.0);  // Σ ŵ of the contacts each node carries
  for (std::size_t f = 0; f < p.size(); ++f) {
    if (!p.isFluid(f) || !grid.near(p.x[f], p.y[f], p.z[f])) continue;
    std::size_t nearest = shell.size();
    double best = std::numeric_limits<double>::infinity();
    grid.forEachNear(p.x[f], p.y[f], p.z[f], [&](std::size_t n) {
      const double dx = p.x[f] - xn[n][0], dy = p.y[f] - xn[n][1], dz = p.z[f] - xn[n][2];
      const double r2 = dx * dx + dy * dy + dz * dz;
      if (r2 < best) { best = r2; nearest = n; }
    });
    if (nearest == shell.size()) continue;
    const auto& n0 = nn[nearest];
    const double d0[3] = {p.x[f] - xn[nearest][0], p.y[f] - xn[nearest][1], p.z[f] - xn[nearest][2]};
    const double s0 = d0[0] * n0[0] + d0[1] * n0[1] + d0[2] * n0[2];
    if (std::fabs(s0) >= standOff + g.fluidRadius || best - s0 * s0 >= cell2) continue;  // no surface here

    Contact c{static_cast<std::int32_t>(f), weights.size(), 0, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    double sum = 0;
    grid.forEachNear(p.x[f], p.y[f], p.z[f], [&](std::size_t n) {
      const double d[3] = {p.x[f] - xn[n][0], p.y[f] - xn[n][1], p.z[f] - xn[n][2]};
      const double s = d[0] * n0[0] + d[1] * n0[1] + d[2] * n0[2];
      const double rho = std::sqrt(std::max(0.0, d[0] * d[0] + d[1] * d[1] + d[2] * d[2] - s * s));
      if (rho >= support || std::fabs(s) >= standOff + g.fluidRadius) return;
      const double w = (1.0 - rho / support) * (1.0 - rho / support);
      weights.push_back({static_cast<std::int32_t>(n), w});
      sum += w;
    });
    c.end = weights.size();
    double normal2 = 0;
    for (std::size_t k = c.begin; k < c.end; ++k) {
      Weighted& w = weights[k];
      w.weight /= sum;
      for (int a = 0; a < 3; ++a) {
        c.point[a] += w.weight * xn[w.node][a];
        c.normal[a] += w.weight * nn[w.node][a];
        c.velocity[a] += w.weight * vn[w.node][a];
      }
    }
    for (int a = 0; a < 3; ++a) normal2 += c.normal[a] * c.normal[a];
    const double inverse = 1.0 / std::sqrt(normal2);
    for (int a = 0; a < 3; ++a) c.normal[a] *= inverse;
    const double s = (p.x[f] - c.point[0]) * c.normal[0] + (p.y[f] - c.point[1]) * c.normal[1] +
                     (p.z[f] - c.point[2]) * c.normal[2];
    if (std::fabs(s) >= standOff) { weights.resize(c.begin); continue; }
    const double sigma = s >= 0.0 ? 1.0 : -1.0;
    for (int a = 0; a < 3; ++a) c.normal[a] *= sigma;  // towards the slave's side
    // Back onto the offset surface: a position correction, no momentum.
    const double push = standOff - std::fabs(s);
    p.x[f] += push * c.normal[0];
    p.y[f] += push * c.normal[1];
    p.z[f] += push * c.normal[2];
    for (std::size_t k = c.begin; k < c.end; ++k) share[weights[k].node] += weights[k].weight;
    contacts.push_back(c);
  }
  out.particles = out.pairs = contacts.size();

  // 2. Normal impulses cancelling the approach (no pull: the fluid may leave the plate).
  for (const Contact& c : contacts) {
    const std::size_t f = c.particle;
    const double u = (p.vx[f] - c.velocity[0]) * c.normal[0] + (p.vy[f] - c.velocity[1]) * c.normal[1] +
                     (p.vz[f] - c.velocity[2]) * c.normal[2];
    if (u >= 0.0) continue;
    double inverseMaster = 0;
    for (std::size_t k = c.begin; k < c.end; ++k) {
      const std::size_t n = weights[k].node;
      if (shell.clamped(n) || !(shell.mass(n) > 0)) continue;
      inverseMaster += weights[k].weight * weights[k].weight * std::max(1.0, share[n]) / shell.mass(n);
    }
    const double mf = p.mass[f];
    const double J = -u / (1.0 / mf + inverseMaster);
    p.vx[f] += J / mf * c.normal[0];
    p.vy[f] += J / mf * c.normal[1];
    p.vz[f] += J / mf * c.normal[2];
    for (std::size_t k = c.begin; k < c.end; ++k)
      for (int a = 0; a < 3; ++a) out.impulse[weights[k].node][a] -= weights[k].weight * J * c.normal[a];
  }
  return out;
}

}  // namespace rupture::fsi
