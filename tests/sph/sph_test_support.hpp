#pragma once
// Helpers for the SPH tests: systems built by the scenarios' own builders from a spec, so the
// tests exercise what users run.
#include <nlohmann/json.hpp>

#include "scenarios/dam_break/dam_break_lattice.hpp"
#include "scenarios/piston_column/piston_column_lattice.hpp"

namespace rupture::testing {

/// A water column filling a 2D tank of width `width` to height `height` (a dam break whose column
/// is as wide as the tank, so nothing flows).
inline nlohmann::json restingColumnSpec(double width, double height, double spacing, const std::string& diffusion) {
  return {{"scenario", "dam-break"},
          {"dimension", 2},
          {"geometry", {{"column_width", width}, {"column_height", height}, {"tank_length", width},
                        {"tank_height", 1.25 * height}}},
          {"resolution", {{"spacing", spacing}}},
          {"fluid", {{"density_diffusion", {{"model", diffusion}}}}}};
}

/// Fluid particles of a system whose centre is outside the box [lo, hi] (per axis; 2D ignores z).
inline int particlesOutside(const sph::SphSystem& s, const double lo[3], const double hi[3]) {
  int outside = 0;
  const sph::FluidParticles& p = s.particles;
  for (std::size_t k = 0; k < p.size(); ++k) {
    if (!p.isFluid(k)) continue;
    const double c[3] = {p.x[k], p.y[k], p.z[k]};
    for (int a = 0; a < s.model.dimension; ++a)
      if (c[a] < lo[a] || c[a] > hi[a]) {
        ++outside;
        break;
      }
  }
  return outside;
}

}  // namespace rupture::testing
