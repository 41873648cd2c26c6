#pragma once
// The node set of an initially flat SPH shell: one layer of nodes in the mid-surface (z = 0,
// reference normal +z). Each node carries the quadrature volume V of the kernel sums (its cell
// area, m²) and the integration area ω of the energy sums (the part of its cell inside the
// structure: a clamped node on the rim carries the half cell inside the plate, clamped nodes
// outside carry none). Clamped nodes keep their position and pseudo-normal.
#include <cstdint>
#include <vector>

namespace rupture {

struct ShellNodes {
  std::vector<double> x, y;              ///< reference mid-surface positions (m)
  std::vector<double> kernelVolume;      ///< V (m²)
  std::vector<double> integrationArea;   ///< ω (m²)
  std::vector<std::uint8_t> clamped;     ///< 1: position and normal held
  /// t per node (m), for a plate whose thickness steps (a thin spot face in a thick bottom);
  /// empty: the shell's uniform ShellParameters::thickness.
  std::vector<double> thickness;
  double spacing = 0.0;                  ///< nominal node spacing Δ (m)

  std::size_t size() const { return x.size(); }
};

/// A circular plate of radius a clamped at its rim: concentric rings r_k = k Δ with Δ = a/K,
/// K = round(a / spacing), round(2π k) nodes on ring k (staggered by half a pitch from ring to
/// ring), the centre node, the clamped ring at r = a (it carries the half annulus inside the
/// plate) and `outerRings` further clamped rings outside (0 is the clamp to use with this shell:
/// nodes beyond a would see a kink in w'' through their kernels). Integration areas are the exact annuli, so they sum to πa².
ShellNodes clampedDiskNodes(double radius, double spacing, int outerRings);

}  // namespace rupture
