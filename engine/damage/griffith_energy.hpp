#pragma once
// Griffith energy criterion of the lattice review (Yu et al. 2019; docs/references.md#eq-lattice):
// the energy of
// the normal spring in tension plus that of the shear spring is compared with the critical bond
// energy w_c = G_c / n_cut (J), n_cut being the number of bonds a straight crack cuts per unit
// area (lattice/lattice_geometry.hpp). The normal spring in compression stores no crack-driving
// energy, so a pair in pure compression never breaks.
#include "core/bond_law.hpp"

namespace rupture {

struct GriffithEnergyCriterion {
  static constexpr const char* kName = "griffith";
  static constexpr bool kNodalShift = false;
  double measure(const BondResponse& r) const { return r.tensileNormalEnergy + r.shearEnergy; }
};

}  // namespace rupture
