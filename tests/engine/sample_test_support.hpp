#pragma once
// The porous ceramic sample the sample-builder tests share: the seed's material (Table 3 beams)
// on a small square (2D) or cube (3D) with 11 % porosity.
#include <array>
#include <cstdint>

#include "samples/sample_builder.hpp"

namespace rupture::testing {

inline SampleSpec porousSpec(int dimension, std::uint64_t seed) {
  SampleSpec s;
  s.dimension = dimension;
  s.size = dimension == 2 ? std::array<double, 3>{0.3e-6, 0.3e-6, 0} : std::array<double, 3>{0.12e-6, 0.12e-6, 0.12e-6};
  s.elementRadius = dimension == 2 ? 3.3e-9 : 5e-9;
  s.porosity = 0.11;
  s.poreRadius = dimension == 2 ? std::array<double, 2>{0.02e-6, 0.06e-6} : std::array<double, 2>{0.015e-6, 0.03e-6};
  s.seed = seed;
  return s;
}

inline MaterialSpec ceramic(double density = 6060) {
  MaterialSpec m;
  m.density = density;
  m.beam = {2865e9, 0.3, 0.3, 4e9};
  m.contact.youngModulus = 2865e9;
  return m;
}

/// A square lattice of beams, rows × columns elements 0.1 mm apart (2D): every bond along x or y,
/// so a pull along x loads the x bonds alone. For the weakest-link and anisotropic-damage tests.
inline SampleSpec squareBeamLattice(int rows, int columns) {
  SampleSpec s;
  s.dimension = 2;
  s.lattice = "square";
  s.spacing = 1e-4;
  s.elementRadius = 0.5e-4;
  s.thickness = 1e-4;
  s.size = {columns * 1e-4, rows * 1e-4, 0};
  return s;
}

/// Glass-like beams (E_μ 70 GPa, ν_μ 0.3, radius ratio 0.5, σ_f 100 MPa) with their default contact.
inline MaterialSpec glassBeams() {
  MaterialSpec m;
  m.model = "beam";
  m.density = 2500;
  m.beam.youngModulus = 70e9;
  m.beam.poissonRatio = 0.3;
  m.beam.radiusRatio = 0.5;
  m.beam.failureStress = 100e6;
  m.contact.youngModulus = beamContactModulus(m.beam);
  m.contact.poissonRatio = 0.3;
  return m;
}

}  // namespace rupture::testing
