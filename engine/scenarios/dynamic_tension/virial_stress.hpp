#pragma once
// Per-element virial stress of a bonded sample (André et al., CMAME 265, 2013;
// docs/references.md#eq-virial), from the bond loads of the last step:
//
//   σ_i = 1/(2 Ω_i) Σ_b ½ (r_ij ⊗ f_ij + f_ij ⊗ r_ij)
//
// r_ij = x_j − x_i is the branch vector to the other end of bond b and f_ij the force of the bond
// on i (BondStore::fj is the force on j, so f_ij = −F_j for end i and +F_j for end j: both ends get
// the same tensor −½(d ⊗ F_j + F_j ⊗ d) with d = x_j − x_i). Tension is positive. The 1/(2Ω) factor
// places each bond's force at mid-bond. Ω_i = V_i / φ, the element volume divided by the packing
// fraction of the dense packing (V_i = π R_i² t in 2D, 4/3 π R_i³ in 3D). Contact forces and the
// kinetic term are left out (brittle, bonded solid).
#include <vector>

#include "bonded/bonded_system.hpp"

namespace rupture {

/// Row-major 3×3 tensors, 9 values per element (Pa).
std::vector<double> virialStress(const BondedSystem& system, double packingFraction, double thickness2d);

}  // namespace rupture
