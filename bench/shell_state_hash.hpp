#pragma once
// A hash of a shell's kinematic state (positions, directors, velocities, spins: their bytes): two
// runs that print the same hash moved every node bit for bit the same way, the check that a
// rewrite of a loop kept the arithmetic (a different thread count, a new data layout).
#include <cstdint>
#include <cstring>
#include <vector>

#include "shell/sph_shell.hpp"

namespace rupture::bench {

inline std::uint64_t shellStateHash(const SphShell& shell) {
  std::uint64_t hash = 1469598103934665603ull;  // FNV-1a, 64 bit
  auto mix = [&hash](const std::vector<ShellVec3>& values) {
    for (const auto& v : values)
      for (double x : v) {
        std::uint64_t bits;
        std::memcpy(&bits, &x, sizeof bits);
        for (int b = 0; b < 8; ++b) hash = (hash ^ ((bits >> (8 * b)) & 0xffu)) * 1099511628211ull;
      }
  };
  mix(shell.positions());
  mix(shell.normals());
  mix(shell.velocities());
  mix(shell.spins());
  return hash;
}

}  // namespace rupture::bench
