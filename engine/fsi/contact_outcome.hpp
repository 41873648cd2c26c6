#pragma once
// What one contact resolution did: the pairs it found and the impulses it exchanged. The fluid's
// velocities were changed by −(what the nodes receive): Σ m_f Δv_f + Σ_n I_n = 0 exactly.
#include <array>
#include <cstddef>
#include <vector>

namespace rupture::fsi {

struct ContactOutcome {
  std::size_t pairs = 0;                       ///< contacting (particle, node) pairs or (particle, surface) contacts
  std::size_t particles = 0;                   ///< fluid particles in contact
  std::vector<std::array<double, 3>> impulse;  ///< per shell node: the impulse the fluid gave it (N s)
};

}  // namespace rupture::fsi
