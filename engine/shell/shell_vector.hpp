#pragma once
// The products of the shell's 3-vectors (positions, directors, forces), shared by its passes
// (sph_shell.cpp) and the probe of its spectrum (shell_spectrum.cpp).
#include <array>

namespace rupture {

using ShellVec3 = std::array<double, 3>;

inline ShellVec3 cross(const ShellVec3& a, const ShellVec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double dot(const ShellVec3& a, const ShellVec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

}  // namespace rupture
