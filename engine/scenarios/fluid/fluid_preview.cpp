#include "scenarios/fluid/fluid_preview.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "rupture/quantity_text.hpp"

namespace rupture {

std::array<double, 3> fluidExtent(const sph::SphSystem& s) {
  const sph::FluidParticles& p = s.particles;
  std::array<double, 3> lo, hi;
  lo.fill(std::numeric_limits<double>::infinity());
  hi.fill(-std::numeric_limits<double>::infinity());
  for (std::size_t k = 0; k < p.size(); ++k) {
    if (!p.isFluid(k)) continue;
    const double at[3] = {p.x[k], p.y[k], p.z[k]};
    for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], at[a]), hi[a] = std::max(hi[a], at[a]);
  }
  std::array<double, 3> size{0, 0, 0};
  for (int a = 0; a < 3; ++a) if (hi[a] >= lo[a]) size[a] = hi[a] - lo[a];
  return size;
}

SamplePreview fluidLatticePreview(const sph::SphSystem& s, int dimension, double spacing, double depthMiddle,
                                  const std::string& title) {
  const sph::FluidParticles& p = s.particles;
  SamplePreview out;
  out.dimension = dimension;
  out.elementsName = "particles";
  out.elements = p.size();
  out.groups.push_back("fluid");
  for (const sph::RigidBody& b : s.bodies) out.groups.push_back(b.name.empty() ? "wall" : b.name);
  PreviewPanel panel;
  panel.title = title;
  panel.uAxis = "x";
  panel.vAxis = dimension == 3 ? "z" : "y";
  // 3-D: the layer of lattice sites nearest the middle of the depth, one spacing thick.
  double layer = std::numeric_limits<double>::infinity();
  if (dimension == 3)
    for (std::size_t k = 0; k < p.size(); ++k) layer = std::min(layer, std::fabs(p.y[k] - depthMiddle));
  std::size_t fluid = 0;
  for (std::size_t k = 0; k < p.size(); ++k) {
    if (p.isFluid(k)) ++fluid;
    if (dimension == 3 && std::fabs(std::fabs(p.y[k] - depthMiddle) - layer) > 0.25 * spacing) continue;
    if (dimension == 3 && p.y[k] < depthMiddle) continue;  // its mirror layer would cover the same sites
    panel.u.push_back(p.x[k]);
    panel.v.push_back(dimension == 3 ? p.z[k] : p.y[k]);
    panel.radius.push_back(0.5 * spacing);
    panel.group.push_back(static_cast<std::uint8_t>(p.isFluid(k) ? 0 : std::min(p.body[k] + 1, 254)));
  }
  out.panels.push_back(std::move(panel));
  out.size = fluidExtent(s);
  if (dimension == 2) out.size[2] = 0;
  out.facts.push_back(formatQuantity(static_cast<double>(p.size()), "1") + " particles: " +
                      formatQuantity(static_cast<double>(fluid), "1") + " fluid and " +
                      formatQuantity(static_cast<double>(p.size() - fluid), "1") + " boundary, spacing " +
                      formatQuantity(spacing, "m"));
  return out;
}

}  // namespace rupture
