#pragma once
// The parameters of Hookean and Born lattice springs as the spec gives them (material.hookean /
// material.born; parsed by their material style, bonded/materials/springs.cpp). SI units.
#include <limits>
#include <string>

namespace rupture {

/// Hookean or Born lattice springs (material.hookean / material.born).
struct LatticeSpringSpec {
  double youngModulus = 0;                                        ///< target E (Pa)
  double poissonRatio = std::numeric_limits<double>::quiet_NaN(); ///< target ν (1); Hookean: the lattice's
  std::string criterion = "critical_stretch";  ///< critical_stretch | critical_energy | stress | griffith
  double criticalValue = std::numeric_limits<double>::infinity();  ///< s0 (1), w_c (J), σ_c (Pa) or G_c (J/m²)
};

}  // namespace rupture
