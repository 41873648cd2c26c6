#pragma once
// Bond-based peridynamics, prototype microelastic brittle model (Silling & Askari 2005; LAMMPS
// peri/pmb; docs/references.md#eq-pd). Each pair of sites closer than the horizon δ is a central
// spring (core/central_spring_law.hpp) of stiffness k_b = c β V_i V_j / |ξ|, so that
//   F_j = −c s β V_i V_j n,   U_b = ½ c s² |ξ| β V_i V_j,   s = (|y| − |ξ|)/|ξ|
// which is the PD pairwise force density f = c s integrated over the two volumes, and Σ U_b the PD
// strain energy ∫ ½ ∫ ½ c s² |ξ| dV' dV. Micromodulus (energy equivalence under isotropic expansion):
//   3D: c = 18 K / (π δ⁴),  K = E / (3 (1 − 2ν)) with ν = 1/4
//   2D plane stress: c = 9 E / (π t δ³)  (ν = 1/3)
// Partial volumes β (the horizon cuts the cells at its edge): "exact" = the fraction of the site's
// cell (a cube or square of side V^(1/d)) inside the horizon ball, by 16^d-point midpoint
// quadrature, bonds kept while β > 0; "linear" = LAMMPS's ramp, 1 at |ξ| <= δ − dx/2 down to ½ at
// δ, bonds kept while |ξ| <= δ. No surface correction: nodes near free surfaces are softer, as in
// LAMMPS (documented in docs/peridynamics.md).
// Failure: critical stretch s0 (given, or from G0: 3D s0 = √(5 G0 / (9 K δ)), 2D √(4π G0 / (9 E δ))),
// optionally with LAMMPS's compression term α; or critical bond energy w_c (Foster et al. 2011:
// 3D w_c = 4 G0 / (π δ⁴); 2D w_c = 3 G0 / (2 t δ³), the crossing-bond integral derived in
// docs/references.md#eq-pd), compared with U_b / (β V_i V_j).
#include "core/bond_store.hpp"
#include "core/particle_store.hpp"
#include "peridynamics/pmb_spec.hpp"

namespace rupture {

/// c (N/m⁶ in 3D; 2D: per unit thickness folded in, N/m⁶ with dV = t dA).
double pmbMicromodulus(int dimension, double youngModulus, double horizon, double thickness);

/// Bulk modulus of 3D PMB (ν = 1/4): K = 2E/3 (Pa).
inline double pmbBulkModulus(double youngModulus) { return youngModulus / (3.0 * (1.0 - 2.0 * 0.25)); }

double pmbCriticalStretch(int dimension, double youngModulus, double horizon, double fractureEnergy);
double pmbCriticalEnergyDensity(int dimension, double horizon, double thickness, double fractureEnergy);

/// β for a bond of rest vector ξ (m) between sites of cell side `cell` (m).
double pmbPartialVolume(const PmbSpec& spec, double xi_x, double xi_y, double xi_z, int dimension, double cell,
                        double horizon);

/// The largest bond length the partial-volume scheme keeps (m).
double pmbBondReach(const PmbSpec& spec, int dimension, double cell, double horizon);

/// Sets every bond's stiffness k_b and failure threshold from the spec (volumes from particles.volume).
void assignPmbBonds(const PmbSpec& spec, int dimension, double spacing, double thickness,
                    const ParticleStore& particles, BondStore& bonds);

/// The stable time step of PD (Silling & Askari 2005; docs/references.md#eq-pd) equals the
/// central-spring Gershgorin bound
/// BondedSystem::criticalTimeStep gives: √(2 m_i / Σ_j k_b) = √(2 ρ / Σ_j c β V_j / |ξ|).

}  // namespace rupture
