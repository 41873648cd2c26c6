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
  double spacing = 0.0;                  ///< nominal node spacing Δ (m): the coarsest, where nodeSpacing is given
  /// Δ_i per node (m), for a node set refined somewhere (ringDiskNodes); empty: `spacing` everywhere.
  /// The shell's kernel between nodes i and j has h_ij = (h/Δ) (Δ_i + Δ_j)/2.
  std::vector<double> nodeSpacing;

  std::size_t size() const { return x.size(); }
};

/// A circular plate of radius a clamped at its rim: concentric rings r_k = k Δ with Δ = a/K,
/// K = round(a / spacing), round(2π k) nodes on ring k (staggered by half a pitch from ring to
/// ring), the centre node, the clamped ring at r = a (it carries the half annulus inside the
/// plate) and `outerRings` further clamped rings outside (0 is the clamp to use with this shell:
/// nodes beyond a would see a kink in w'' through their kernels). Integration areas are the exact annuli, so they sum to πa².
ShellNodes clampedDiskNodes(double radius, double spacing, int outerRings);

/// A circular plate on concentric rings of the given radii 0 < r_1 < … < r_K, clamped on the last
/// (the rim), for a plate refined where it needs to be (near a step): ring k has round(2π r_k / Δ_k)
/// nodes, Δ_k = (r_{k+1} − r_{k−1}) / 2 its radial spacing (r_0 = 0, r_{K+1} = 2 r_K − r_{K−1}),
/// staggered by half a pitch from ring to ring, plus the centre node (Δ_0 = r_1). Kernel volumes are
/// the annuli between the midpoints of neighbouring rings shared among the ring's nodes, integration
/// areas the same but the rim's, which carries the half inside the plate: they sum to π r_K².
/// nodeSpacing holds Δ_k, `spacing` the largest. Uniform radii k Δ give clampedDiskNodes' nodes.
ShellNodes ringDiskNodes(const std::vector<double>& radii);

/// The number of nodes ringDiskNodes(radii) makes, without making them (a spec's size check).
std::size_t ringDiskNodeCount(const std::vector<double>& radii);

/// Ring radii for ringDiskNodes out to the rim r = `rim` at spacing ≈ `coarse`, refined to `fine`
/// about the circle r = `at` (a thickness step): rings at `at` ± (m + ½) fine for m < `fineRings`, so
/// the circle falls midway between two rings; from the band the spacing grows by a factor of at
/// most kRingGrowth per ring up to `coarse` on both sides, and the rest is uniform, the last ring at
/// the rim. Throws std::invalid_argument when the band and its grading do not fit in (0, rim).
std::vector<double> refinedRingRadii(double rim, double coarse, double fine, double at, int fineRings);

/// The largest ratio of neighbouring ring spacings in refinedRingRadii's graded part (where the
/// uniform parts join it, rounding to whole rings may give up to 1.5 on a short stretch).
inline constexpr double kRingGrowth = 1.3;

}  // namespace rupture
