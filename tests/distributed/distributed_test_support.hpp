#pragma once
// What the distributed tests share: a bitwise comparison of fields, and a PMB block on a simple
// cubic lattice (14 × 10 × 8 mm, 1 mm spacing, horizon 3.015 spacings), glass-like, without contact.
#include <cstddef>
#include <cstring>
#include <vector>

#include "samples/sample_builder.hpp"

namespace rupture::testing {

/// Index of the first element where two fields differ in any bit (-1: none).
inline std::ptrdiff_t firstDifference(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) return 0;
  for (std::size_t k = 0; k < a.size(); ++k)
    if (std::memcmp(&a[k], &b[k], sizeof(double)) != 0) return static_cast<std::ptrdiff_t>(k);
  return -1;
}

inline BondedSystem pmbBlock(double compressionFactor = 0.0) {
  SampleSpec s;
  s.dimension = 3;
  s.lattice = "simple-cubic";
  s.spacing = 1e-3;
  s.elementRadius = 0.5e-3;
  s.size = {14e-3, 10e-3, 8e-3};
  MaterialSpec m;
  m.model = "pmb";
  m.density = 2200;
  m.pmb.youngModulus = 22e9;
  m.pmb.horizonFactor = 3.015;
  m.pmb.criticalStretch = 5e-4;
  m.pmb.compressionFactor = compressionFactor;
  m.contact.enabled = false;
  BondedSystem system;
  buildSample(s, m, system);
  return system;
}

}  // namespace rupture::testing
