#pragma once
// When a Verlet list stops being complete. A pair farther apart than the list's cutoff when the
// list was built can only have come within the kernel support since if the two particles'
// displacements differ by more than the skin (cutoff − support). Bounding that difference by twice
// the largest displacement (every particle within half the skin) is safe but wasteful where
// neighbours move together: next to a fixed wall the difference is the fluid's own displacement
// (a full skin, not half), and between fluid neighbours it is the shear across a support.
//
// This bounds max |Δd_a − Δd_b| over the pairs that interact (fluid–fluid and fluid–boundary)
// and are closer than a reach now (SphSystem passes the cutoff). Particles are binned by position
// into cells of edge >= reach, so such a pair lies in one cell or in two adjacent ones; each cell
// keeps the box spanned by its fluid particles' displacements and the one spanned by its boundary
// particles'; the bound is the largest diagonal of the union of a fluid box with any box of the
// same or an adjacent cell. Boundary–boundary pairs do not interact and are left out, so a piston
// sliding along a fixed tube does not count. A maximum is exact in any order, so the rebuild
// decision is the same for any thread count.
#include <cstdint>
#include <span>
#include <vector>

#include "sph/cell_grid.hpp"
#include "sph/fluid_particles.hpp"

namespace rupture::sph {

class RelativeDisplacementBound {
public:
  /// Lays the cells over the particles' current box (edge >= reach, m) and notes which
  /// particles can move: fluid and the members of bodies with bodyMoves[b] != 0 (a fixed body's
  /// members keep a zero displacement and are not visited again). Call at each list build;
  /// particles that later leave the box are counted in its border cells (which only widens the
  /// bound).
  void reset(const FluidParticles& p, int dimension, double reach, const std::vector<char>& bodyMoves);

  /// The bound (m) for the displacements (x − x0, y − y0, z − z0) since the last build, over the
  /// interacting pairs closer than the reach.
  double evaluate(const FluidParticles& p, std::span<const double> x0, std::span<const double> y0,
                  std::span<const double> z0);

private:
  /// A box of displacements; empty while lo > hi.
  struct Box {
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
    bool empty() const { return lo[0] > hi[0]; }
    void widen(const double lower[3], const double upper[3]) {
      for (int a = 0; a < 3; ++a) {
        lo[a] = lower[a] < lo[a] ? lower[a] : lo[a];
        hi[a] = upper[a] > hi[a] ? upper[a] : hi[a];
      }
    }
    void widen(const Box& b) { widen(b.lo, b.hi); }
  };
  int m_dimension = 3;
  CellGrid m_grid;
  // Per thread, 2 boxes a cell (fluid, boundary); all empty between calls. Then the merged boxes.
  std::vector<Box> m_threadBoxes, m_merged;
  std::vector<std::int32_t> m_movers;  // the particles that can move, in index order
  std::vector<char> m_fixedIn;         // per cell: holds a member of a fixed body (displacement 0)
};

}  // namespace rupture::sph
