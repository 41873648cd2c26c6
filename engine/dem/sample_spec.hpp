#pragma once
// The sample and material part shared by every bonded scenario (plain data; parsed and validated
// in io/bonded_spec.cpp, built in dem/sample_builder.cpp). SI units.
#include <array>
#include <cstdint>
#include <string>

#include "dem/beam_bond.hpp"
#include "dem/hertz_contact.hpp"

namespace rupture {

struct SampleSpec {
  int dimension = 2;                     ///< 2 (disks in the x-y plane) or 3 (spheres)
  std::array<double, 3> size{0, 0, 0};   ///< box edges (m); size[2] unused in 2D
  double elementRadius = 0;              ///< mean element radius R_DE (m)
  double radiusDispersion = 0.2;         ///< radii uniform in R_DE·[1 − d, 1 + d] (1)
  double porosity = 0;                   ///< target fraction of element volume removed by pores (1)
  std::array<double, 2> poreRadius{0, 0};///< pore radii drawn uniformly in [min, max] (m)
  std::uint64_t seed = 1;                ///< random seed: same seed, same sample
  double bondGap = 0.1;                  ///< pairs closer than (R_i + R_j)(1 + gap/2) are bonded (1)
};

struct MaterialSpec {
  std::string model = "beam";  ///< bond law registry key
  double density = 0;          ///< bulk density of the dense material (kg/m³)
  BeamParameters beam;
  ContactParameters contact;
};

}  // namespace rupture
