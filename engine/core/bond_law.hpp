#pragma once
// The contract between a bond law and the bonded loop (core/bond_loop.hpp). A law is a small struct:
//   static constexpr bool kRotational;   // reads the end orientations and produces torques
//   BondResponse response(const BondGeometry&) const;   // pure, inline, branch-free
//   BondStiffness stiffness(const BondGeometry&) const; // for the Gershgorin time step
// plus its parameters, validated once by the model factory (bonded/materials/). The loop over
// bonds, the gather, the failure hand-over to contact, the damage index and the recorder are
// written once, for every law; a failure criterion (engine/damage/) reads the response.
namespace rupture {

/// Everything a law may read about one bond (SI). Quaternions are (w, x, y, z); they are read from
/// the particle store only for rotational laws.
struct BondGeometry {
  double dx, dy, dz;           ///< x_j − x_i, current (m)
  double restLength;           ///< L0 (m)
  double invRestLength;        ///< 1/L0 (1/m): every caller fills it as 1.0 / restLength (a correctly rounded
                               ///< division, so every path has the same bits); the central loop's compact
                               ///< form reads it from its kind table instead of dividing per slot
  double n0x, n0y, n0z;        ///< reference unit direction i -> j
  double radiusI, radiusJ;     ///< element radii (m)
  double stiffness;            ///< BondStore::stiffness: central laws' k (N/m), the beam law's factor on E_μ (1)
  double qiw, qix, qiy, qiz;   ///< orientation of i
  double qjw, qjx, qjy, qjz;   ///< orientation of j
};

/// What one evaluation of a law produces. Central laws leave the torques at zero.
struct BondResponse {
  double fjx, fjy, fjz;        ///< force on j (N); the force on i is its opposite
  double tix, tiy, tiz;        ///< torque on i (N·m)
  double tjx, tjy, tjz;        ///< torque on j (N·m)
  double energy;               ///< stored elastic energy (J)
  double stretch;              ///< (L − L0)/L0 (1)
  double normalForce;          ///< axial force, tension positive (N)
  double tensileNormalEnergy;  ///< energy of the normal spring when stretched, 0 in compression (J)
  double shearEnergy;          ///< energy of the shear / bending part (J)
  double equivalentStress;     ///< Rankine σ_eq of the beam section (Pa); 0 for laws without a section
};

/// Stiffness of one bond for the Gershgorin time-step bound (docs/references.md#eq-gershgorin).
struct BondStiffness {
  double translational;  ///< N/m
  double rotational;     ///< N·m/rad (0 for central laws)
};

}  // namespace rupture
