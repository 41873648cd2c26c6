#pragma once
// Anisotropic damage: a bond as a parallel bundle of fibres along the material axes.
//
// The seed's damage table lists anisotropic variants of critical stretch and critical energy
// (PeriLab's "Anisotropic Damage", docs/references.md#perilabdamage). Formulation (ours; see
// docs/peridynamics.md, "Anisotropic damage", for how it differs from PeriLab's): the material frame
// at a particle has unit axes a_k (k = 1 … d), set by rotation angles per block or grain. Bond b of
// reference direction n0 is d fibres in parallel; fibre k carries the fraction
//   w_k = ½ [(n0·a_k(i))² + (n0·a_k(j))²]        (Σ_k w_k = 1; both ends' frames, symmetric)
// of the bond, and fails once the bond's failure measure (its stretch, energy, … undamaged, so a
// fibre's failure depends on the deformation only) reaches f_k times the bond's critical value.
// The bond's integrity χ (BondStore::intact, the factor on its loads) is the weight of its intact
// fibres: it drops by w_k as fibre k fails, reaches 0 with the last, never grows back. With equal
// factors every fibre fails at once: χ jumps from 1 to 0 as under the isotropic criterion, bit for
// bit when the factors are 1.
#include <array>
#include <cstddef>
#include <vector>

namespace rupture {

/// Rotation angles of a material frame (degrees, as the spec gives them). 2D: [θ] about z; 3D:
/// R = R_z(γ) R_y(β) R_x(α) for [α, β, γ] (about the fixed x, then y, then z axes).
using FrameAngles = std::array<double, 3>;

/// The frame's axes a_1, a_2, a_3 (columns of R) as unit vectors.
using FrameAxes = std::array<std::array<double, 3>, 3>;
FrameAxes frameAxes(const FrameAngles& angles, int dimension);

/// One bond's fibres in the order they fail (ascending factor; ties keep the axis order): the factor
/// of each and the integrity the bond keeps once it has failed. Fibres beyond the dimension have
/// factor +inf; the last real fibre leaves exactly 0.
struct BondFibres {
  std::array<double, 3> factor, integrity;
};
BondFibres bondFibres(const std::array<double, 3>& n0, const FrameAxes& frameI, const FrameAxes& frameJ,
                      const std::vector<double>& criticalFactors, int dimension);

}  // namespace rupture
