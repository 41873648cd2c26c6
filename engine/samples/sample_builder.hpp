#pragma once
// Builds a bonded sample: a dense random packing of polydisperse disks (2D) or spheres (3D) in a
// box, beams between neighbours, then pores. Seeded and reproducible.
//
// Packing: "collective rearrangement": radii are drawn uniformly in R·[1 − d, 1 + d] until the
// solid fraction reaches a target just below random close packing (0.84 in 2D, 0.58 in 3D), centres
// are placed at random, and overlaps are relaxed (Jacobi sweeps with a cell list, walls included)
// until the largest overlap is below 1 % of the mean radius. Pairs closer than
// (R_i + R_j)(1 + gap/2) are bonded, with the beam rest state taken in that configuration.
// Pores: radii uniform in [r_min, r_max] until their volume reaches the target porosity, placed
// at random inside the box without overlap, then all scaled by one common factor (found by
// bisection, typically within a few % of 1) so that the volume of the elements whose centres fall
// inside a pore matches the porosity; those elements are removed, then any element left without bonds.
// Masses: the element density is set so that the dense packing has the material's bulk density
// (ρ_el = ρ V_box / Σ V_i); in 2D an element is a disk of thickness t = R_DE (the section S = L × R_DE
// of the seed's eq. 4).
#include <array>
#include <vector>

#include "core/cancellation.hpp"
#include "bonded/bonded_system.hpp"
#include "samples/pores.hpp"
#include "bonded/sample_spec.hpp"

namespace rupture {

struct SampleReport {
  std::size_t elements = 0, bonds = 0;
  double meanCoordination = 0;     ///< 2 × bonds / elements
  double packingFraction = 0;      ///< solid fraction of the dense packing (before pores)
  double porosity = 0;             ///< achieved: removed element volume / dense element volume
  double thickness = 0;            ///< out-of-plane thickness used in 2D (m); 0 in 3D
  double elementDensity = 0;       ///< ρ_el (kg/m³)
  double relaxationOverlap = 0;    ///< largest residual overlap after packing / mean radius
  std::vector<Pore> pores;
};

/// Fills `system` (particles, bonds, beam and contact parameters) from the spec and initialises it.
/// Removes the elements left without any bond (they would float free), renumbering the bonds.
void dropUnbondedElements(BondedSystem& system);

/// Every stage polls `cancel` at least every ~0.1 s of wall time (inside packing sweeps too) and
/// throws RunCancelled once it is set; `system` is then not for use.
SampleReport buildSample(const SampleSpec& sample, const MaterialSpec& material, BondedSystem& system,
                         const Cancellation& cancel = {});

/// The two halves of buildSample for a random packing (sample.lattice == "random"), so that the
/// packed geometry can be cached (scenarios/bonded/sample_cache.hpp): packRandomSample packs, bonds, sets
/// the masses and carves the pores (everything but elements, bonds and coordination in the report);
/// finishRandomSample cuts the notches, assigns the material, initialises and completes the report.
SampleReport packRandomSample(const SampleSpec& sample, const MaterialSpec& material, BondedSystem& system,
                              const Cancellation& cancel = {});
void finishRandomSample(const SampleSpec& sample, const MaterialSpec& material, BondedSystem& system,
                        SampleReport& report, const Cancellation& cancel = {});

}  // namespace rupture
