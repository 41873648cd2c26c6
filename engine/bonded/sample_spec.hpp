#pragma once
// The sample and material part shared by every bonded scenario (plain data; parsed and validated
// in bonded/bonded_spec.cpp, built in samples/sample_builder.cpp). SI units.
#include <array>
#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "damage/anisotropic_damage.hpp"
#include "dem/beam_bond.hpp"
#include "dem/hertz_contact.hpp"
#include "lattice/spring_spec.hpp"
#include "peridynamics/pmb_spec.hpp"

namespace rupture {

/// A pre-crack: bonds whose segment crosses it are never created. In 2D the segment [start, end];
/// in 3D the strip swept by that segment along z through the whole sample (m).
struct Notch {
  std::array<double, 3> start{0, 0, 0}, end{0, 0, 0};
};

/// A box [min, max] (m); in 2D the z bounds are ±infinity.
struct Box {
  std::array<double, 3> min{0, 0, 0}, max{0, 0, 0};
  bool contains(double x, double y, double z) const {
    return x >= min[0] && x <= max[0] && y >= min[1] && y <= max[1] && z >= min[2] && z <= max[2];
  }
};

/// A block of the sample (region, grain, phase): the particles whose centre is in the box at
/// build time get its id (later blocks override earlier ones; particles in no block are block 1).
struct BlockRegion {
  int id = 1;
  Box box;
};

/// Voronoi grains (samples/grains.hpp): `count` grains (0: none); bonds across grain boundaries have
/// their failure threshold multiplied by `boundaryFactor`.
struct GrainSpec {
  int count = 0;
  double boundaryFactor = 1.0;
};

/// Second-phase inclusions (samples/inclusions.hpp): their volume fraction of the box (0: none), radii,
/// and the factors on the matrix's properties.
struct InclusionSpec {
  double volumeFraction = 0;                 ///< (1)
  std::array<double, 2> radius{0, 0};        ///< [min, max] (m)
  double stiffnessFactor = 1;                ///< on the bond stiffness inside an inclusion (1)
  double strengthFactor = 1;                 ///< on the failure threshold inside (1)
  double interfaceStrengthFactor = 1;        ///< on the threshold of bonds crossing the interface (1)
  double densityFactor = 1;                  ///< on the mass of elements inside (1)
};

struct SampleSpec {
  int dimension = 2;                     ///< 2 (disks in the x-y plane) or 3 (spheres)
  std::string lattice = "random";        ///< "random" packing, or a regular lattice (lattice/lattice_geometry.hpp)
  double spacing = 0;                    ///< lattice nearest-neighbour distance (m); lattices only
  double thickness = 0;                  ///< 2D out-of-plane thickness (m); 0: R_DE (random) or spacing (lattices)
  std::vector<Notch> notches;            ///< pre-cracks
  std::vector<BlockRegion> blocks;       ///< blocks for interblock critical values
  GrainSpec grains;                      ///< Voronoi grains and their boundary strength
  InclusionSpec inclusions;              ///< second-phase inclusions
  std::array<double, 3> size{0, 0, 0};   ///< box edges (m); size[2] unused in 2D
  double elementRadius = 0;              ///< mean element radius R_DE (m)
  double radiusDispersion = 0.2;         ///< radii uniform in R_DE·[1 − d, 1 + d] (1)
  double porosity = 0;                   ///< target fraction of element volume removed by pores (1)
  std::array<double, 2> poreRadius{0, 0};///< pore radii drawn uniformly in [min, max] (m)
  std::uint64_t seed = 1;                ///< random seed: same seed, same sample
  double bondGap = 0.1;                  ///< pairs closer than (R_i + R_j)(1 + gap/2) are bonded (1)
};

/// The distribution of a random per-bond factor of mean 1 (samples/bond_disorder.hpp).
struct FactorDistribution {
  enum class Kind { None, Weibull, Normal };
  Kind kind = Kind::None;
  double weibullModulus = 0;  ///< m of a Weibull factor, scaled to mean 1 (1)
  double variation = 0;       ///< coefficient of variation of a normal factor, truncated at ±3 sd (1)
};

/// Disorder of the bonds (material.disorder): each bond's critical value (its strength, in its
/// criterion's measure) and its stiffness are multiplied by independent random factors of mean 1,
/// drawn from `seed` (Ostoja-Starzewski & Wang 2006; Li, Pan & Sinka 2011's Weibull strengths;
/// docs/references.md#eq-disorder).
struct BondDisorder {
  FactorDistribution strength, stiffness;
  std::uint64_t seed = 1;
  bool any() const {
    return strength.kind != FactorDistribution::Kind::None || stiffness.kind != FactorDistribution::Kind::None;
  }
};

/// Anisotropic damage (material.anisotropic_damage; damage/anisotropic_damage.hpp): each bond is a
/// parallel bundle of one fibre per material axis, fibre k carrying the fraction (n0·a_k)² of the bond
/// and failing at criticalFactors[k] times the bond's critical value.
struct AnisotropicDamageSpec {
  std::vector<double> criticalFactors;  ///< one per axis (dimension values; empty: isotropic damage)
  FrameAngles angles{0, 0, 0};          ///< the frame of particles in no listed block (degrees)
  std::map<int, FrameAngles> blockAngles;  ///< frames of sample.blocks ids (degrees)
  bool randomGrainFrames = false;       ///< each Voronoi grain its own uniformly random frame
  bool enabled() const { return !criticalFactors.empty(); }
};

struct MaterialSpec {
  std::string model = "beam";  ///< a registered material style (bonded/materials/registry.cpp)
  double density = 0;          ///< bulk density of the dense material (kg/m³)
  BeamParameters beam;
  LatticeSpringSpec springs;   ///< when model is hookean or born
  PmbSpec pmb;                 ///< when model is pmb
  ContactParameters contact;
  std::vector<Box> noFailureRegions;  ///< bonds with an end inside never break
  BondDisorder disorder;              ///< random per-bond strength and stiffness (none by default)
  AnisotropicDamageSpec anisotropicDamage;  ///< direction-dependent partial damage (none by default)
  /// Interblock critical stretch (PeriLab "Interblock Damage", docs/references.md#perilabdamage):
  /// the s0 of bonds from
  /// block a to block b, keyed a * 1000 + b; a bond of the store breaks at the smaller of its two
  /// orientations' values (the block's own s0 for a missing orientation).
  std::map<int, double> interblock;
  /// Silling's local damping coefficient d of bonds around damage (Bobaru et al. 2016, eq. 2.34, as
  /// PeriLab gives it; docs/references.md#eq-pd; 0: none) and the bar
  /// wave speed √(E/ρ) it is scaled by, E being the model's Young's modulus (m/s).
  double localDamping = 0;
  double dampingWaveSpeed = 0;
  /// Beams: the spec left material.contact.young_modulus / poisson_ratio to their defaults, which
  /// follow the beams (beamContactModulus, ν_μ): a calibration that changes the beams changes them.
  bool contactModulusFromBeams = false;
  bool contactPoissonFromBeams = false;
};

/// The default contact modulus of beams: about the macroscopic modulus they give (E_M ∝ E_μ r_μ²,
/// André et al. 2012 §4, docs/references.md#eq-calibration; on our 2D packings E_M ≈ 0.9 E_μ
/// ratio²), not the fictitious E_μ.
inline double beamContactModulus(const BeamParameters& beam) {
  return beam.youngModulus * beam.radiusRatio * beam.radiusRatio;
}

}  // namespace rupture
