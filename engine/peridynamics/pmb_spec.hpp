#pragma once
// The parameters of bond-based PMB peridynamics as the spec gives them (material.pmb; parsed by its
// material style, bonded/materials/pmb.cpp). SI units.
#include <limits>
#include <string>

namespace rupture {

/// Bond-based prototype microelastic brittle peridynamics (material.pmb).
struct PmbSpec {
  double youngModulus = 0;      ///< E (Pa); ν is 1/4 (3D) or 1/3 (2D plane stress)
  double horizonFactor = 3.015; ///< δ / spacing (1)
  double criticalStretch = std::numeric_limits<double>::quiet_NaN();  ///< s0 (1), or NaN
  double fractureEnergy = std::numeric_limits<double>::quiet_NaN();   ///< G0 (J/m²), or NaN
  std::string criterion = "critical_stretch";  ///< critical_stretch | critical_energy
  double compressionFactor = 0;  ///< α of s0 = s00 − α s_min (1), as LAMMPS peri/pmb
  std::string partialVolume = "exact";  ///< "exact" cell–ball overlap, or "linear" (LAMMPS's ramp)
};

}  // namespace rupture
