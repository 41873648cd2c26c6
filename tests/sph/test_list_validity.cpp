// When the SPH neighbour list is rebuilt (engine/sph/relative_displacement.hpp, SphSystem::step):
// only once two interacting particles may have closed the skin between them. What must hold:
// the bound never falls below the largest relative displacement of an interacting pair closer
// than its reach (random fields, 2D and 3D, several seeds; exact values for rigid motions), and
// along real flows every interacting pair within the kernel support is listed at every step,
// including steps where particles have moved more than half the skin since the build (the old
// rule would have rebuilt there; the test checks such steps occur).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "sph/relative_displacement.hpp"
#include "sph_test_support.hpp"

namespace rupture::testing {
namespace {

using sph::FluidParticles;
using sph::kFluid;

/// Every pair closer than `reach` with at least one fluid particle, through a grid of cells of
/// edge `reach` (brute force enough for the tests' sizes): f(a, b) with a < b.
template <class F>
void forInteractingPairs(const FluidParticles& p, int dimension, double reach, F&& f) {
  const std::size_t n = p.size();
  double lo[3] = {1e300, 1e300, 1e300};
  for (std::size_t k = 0; k < n; ++k) {
    lo[0] = std::min(lo[0], p.x[k]);
    lo[1] = std::min(lo[1], p.y[k]);
    lo[2] = std::min(lo[2], p.z[k]);
  }
  std::vector<std::array<long, 3>> cell(n);
  std::vector<std::size_t> order(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double c[3] = {p.x[k], p.y[k], p.z[k]};
    for (int a = 0; a < 3; ++a) cell[k][a] = a < dimension ? static_cast<long>(std::floor((c[a] - lo[a]) / reach)) : 0;
    order[k] = k;
  }
  std::sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) { return cell[i] < cell[j]; });
  auto first = [&](const std::array<long, 3>& c) {
    return std::lower_bound(order.begin(), order.end(), c,
                            [&](std::size_t i, const std::array<long, 3>& v) { return cell[i] < v; });
  };
  const long reachZ = dimension == 3 ? 1 : 0;
  for (std::size_t a = 0; a < n; ++a)
    for (long dz = -reachZ; dz <= reachZ; ++dz)
      for (long dy = -1; dy <= 1; ++dy)
        for (long dx = -1; dx <= 1; ++dx) {
          const std::array<long, 3> c = {cell[a][0] + dx, cell[a][1] + dy, cell[a][2] + dz};
          for (auto it = first(c); it != order.end() && cell[*it] == c; ++it) {
            const std::size_t b = *it;
            if (b <= a || (p.body[a] != kFluid && p.body[b] != kFluid)) continue;
            const double rx = p.x[a] - p.x[b], ry = p.y[a] - p.y[b], rz = dimension == 3 ? p.z[a] - p.z[b] : 0.0;
            if (rx * rx + ry * ry + rz * rz < reach * reach) f(a, b);
          }
        }
}

struct Field {
  FluidParticles particles;
  ParticleArray<double> x0, y0, z0;  // positions at the "build"
};

/// Particles scattered over a box, 70 % fluid, 20 % of a fixed body (0), 10 % of a moving body (1),
/// at mean spacing `spacing`; the list's build at the returned x0.
Field scattered(int dimension, std::uint64_t seed, std::size_t n, double spacing) {
  std::mt19937_64 rng(seed);
  const double side = spacing * std::pow(static_cast<double>(n), 1.0 / dimension);
  std::uniform_real_distribution<double> u(0.0, side), kind(0.0, 1.0);
  Field f;
  for (std::size_t k = 0; k < n; ++k) {
    const double r = kind(rng);
    const std::int32_t body = r < 0.7 ? kFluid : (r < 0.9 ? 0 : 1);
    f.particles.add(u(rng), u(rng), dimension == 3 ? u(rng) : 0.0, 1.0, 1000.0, body);
  }
  f.x0 = f.particles.x;
  f.y0 = f.particles.y;
  f.z0 = f.particles.z;
  return f;
}

double bruteForceBound(const Field& f, int dimension, double reach) {
  const FluidParticles& p = f.particles;
  double worst = 0;
  forInteractingPairs(p, dimension, reach, [&](std::size_t a, std::size_t b) {
    const double ex = (p.x[a] - f.x0[a]) - (p.x[b] - f.x0[b]), ey = (p.y[a] - f.y0[a]) - (p.y[b] - f.y0[b]),
                 ez = (p.z[a] - f.z0[a]) - (p.z[b] - f.z0[b]);
    worst = std::max(worst, std::sqrt(ex * ex + ey * ey + ez * ez));
  });
  return worst;
}

const std::vector<char> kBodyMoves = {0, 1};  // body 0 fixed, body 1 moves

TEST(RelativeDisplacementBound, NeverBelowTheLargestRelativeDisplacementOfAnInteractingPair) {
  const double spacing = 0.01, reach = 0.028;
  for (int dimension : {2, 3})
    for (std::uint64_t seed : {1u, 2u, 3u}) {
      Field f = scattered(dimension, seed, dimension == 3 ? 12000 : 6000, spacing);
      sph::RelativeDisplacementBound bound;
      bound.reset(f.particles, dimension, reach, kBodyMoves);
      // A shear flow with noise for the fluid, a translation for body 1, nothing for body 0. Some
      // particles leave the box the cells were laid over.
      std::mt19937_64 rng(seed + 100);
      std::normal_distribution<double> noise(0.0, 0.1 * spacing);
      FluidParticles& p = f.particles;
      for (std::size_t k = 0; k < p.size(); ++k) {
        double d[3] = {0, 0, 0};
        if (p.body[k] == kFluid) {
          d[0] = 2.0 * spacing * std::sin(20.0 * p.y[k]) + noise(rng);
          d[1] = 1.5 * spacing * std::cos(15.0 * p.x[k]) + noise(rng);
          d[2] = dimension == 3 ? -3.0 * spacing * p.x[k] / 0.2 + noise(rng) : 0.0;
        } else if (p.body[k] == 1) {
          d[0] = 0.7 * spacing;
          d[1] = -0.4 * spacing;
        }
        p.x[k] += d[0];
        p.y[k] += d[1];
        p.z[k] += d[2];
      }
      const double exact = bruteForceBound(f, dimension, reach);
      const double b = bound.evaluate(p, f.x0, f.y0, f.z0);
      EXPECT_GE(b, exact) << dimension << "D, seed " << seed;
      EXPECT_GT(exact, 0.0);
      // Not vacuous: the bound is local, below the diagonal of the box of all displacements (what
      // the difference of any two could reach).
      double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
      for (std::size_t k = 0; k < p.size(); ++k) {
        const double d[3] = {p.x[k] - f.x0[k], p.y[k] - f.y0[k], p.z[k] - f.z0[k]};
        for (int a = 0; a < 3; ++a) {
          lo[a] = std::min(lo[a], d[a]);
          hi[a] = std::max(hi[a], d[a]);
        }
      }
      const double span = std::hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
      EXPECT_LT(b, span) << dimension << "D, seed " << seed;
    }
}

TEST(RelativeDisplacementBound, RigidMotionsGiveTheirExactValues) {
  const double spacing = 0.01, reach = 0.028;
  for (int dimension : {2, 3}) {
    Field f = scattered(dimension, 7, dimension == 3 ? 8000 : 4000, spacing);
    FluidParticles& p = f.particles;
    sph::RelativeDisplacementBound bound;
    bound.reset(p, dimension, reach, kBodyMoves);
    // Fluid and body 1 translated together, body 0 fixed: fluid–fluid and fluid–body-1 pairs have
    // not moved relative to each other, fluid–body-0 pairs by the translation.
    const double t[3] = {0.3 * spacing, -0.2 * spacing, dimension == 3 ? 0.6 * spacing : 0.0};
    for (std::size_t k = 0; k < p.size(); ++k)
      if (p.body[k] != 0) {
        p.x[k] += t[0];
        p.y[k] += t[1];
        p.z[k] += t[2];
      }
    const double length = std::sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
    EXPECT_NEAR(bound.evaluate(p, f.x0, f.y0, f.z0), length, 1e-15) << dimension << "D";

    // Only the bodies move (a piston sliding along a fixed tube, no fluid moving): boundary pairs
    // do not interact, so nothing counts.
    Field g = scattered(dimension, 8, dimension == 3 ? 8000 : 4000, spacing);
    sph::RelativeDisplacementBound still;
    still.reset(g.particles, dimension, reach, kBodyMoves);
    for (std::size_t k = 0; k < g.particles.size(); ++k)
      if (g.particles.body[k] == 1) g.particles.y[k] += 5.0 * spacing;
    EXPECT_NEAR(still.evaluate(g.particles, g.x0, g.y0, g.z0), 5.0 * spacing, 1e-15) << "fluid next to the moving body";
    for (std::size_t k = 0; k < g.particles.size(); ++k)
      if (g.particles.body[k] == kFluid) g.particles.body[k] = 0;  // no fluid left at all
    sph::RelativeDisplacementBound dry;
    dry.reset(g.particles, dimension, reach, kBodyMoves);
    EXPECT_EQ(dry.evaluate(g.particles, g.x0, g.y0, g.z0), 0.0) << dimension << "D";
  }
}

/// Runs `steps` steps and checks after each that every interacting pair within the support is
/// listed: a fluid–fluid pair in one of its two fluid lists, a fluid–boundary pair in the fluid
/// particle's list and in the boundary particle's (the pressure extrapolation's). Returns the
/// largest displacement since the last build seen at a step that did not rebuild, in skins.
double checkListsAlongTheFlow(sph::SphSystem& s, int steps) {
  const int dimension = s.model.dimension;
  const double support = s.model.kernel().support(), skin = support * s.skinFraction;
  ParticleArray<double> x0 = s.particles.x, y0 = s.particles.y, z0 = s.particles.z;
  std::size_t builds = s.listBuilds();
  double largestKept = 0;
  for (int step = 0; step < steps; ++step) {
    s.step(s.stableTimeStep(0.2));
    const FluidParticles& p = s.particles;
    if (s.listBuilds() != builds) {  // rebuilt (and perhaps re-sorted): positions at the build
      builds = s.listBuilds();
      x0 = p.x;
      y0 = p.y;
      z0 = p.z;
      continue;
    }
    double moved = 0;
    for (std::size_t k = 0; k < p.size(); ++k) {
      const double ex = p.x[k] - x0[k], ey = p.y[k] - y0[k], ez = p.z[k] - z0[k];
      moved = std::max(moved, std::sqrt(ex * ex + ey * ey + ez * ez));
    }
    largestKept = std::max(largestKept, moved / skin);
    const sph::NeighbourList& list = s.neighbourList();
    auto listed = [&](std::size_t a, std::size_t b, bool fluidOnly) {
      const std::int32_t* nb = list.neighbours(a);
      const int count = fluidOnly ? list.fluidCount(a) : list.count(a);
      return std::find(nb, nb + count, static_cast<std::int32_t>(b)) != nb + count;
    };
    int missing = 0;
    forInteractingPairs(p, dimension, support, [&](std::size_t a, std::size_t b) {
      const bool fa = p.isFluid(a), fb = p.isFluid(b);
      // Fluid–fluid: once, in either fluid list; fluid–boundary: in both particles' lists.
      const bool ok = fa && fb ? listed(a, b, true) || listed(b, a, true) : listed(a, b, false) && listed(b, a, false);
      if (!ok) ++missing;
    });
    EXPECT_EQ(missing, 0) << "step " << step << ", t = " << s.time << " s, " << moved / skin
                          << " skins moved since the build";
    if (missing) break;
  }
  return largestKept;
}

TEST(SphNeighbourList, StaysCompleteWhileItLivesAlongADamBreakAndAPistonStroke) {
  auto damBreak = [](int dimension, const nlohmann::json& geometry, double spacing, int steps) {
    const nlohmann::json spec = {{"scenario", "dam-break"},
                                 {"dimension", dimension},
                                 {"geometry", geometry},
                                 {"resolution", {{"spacing", spacing}}}};
    sph::SphSystem s;
    buildDamBreak(s, parseDamBreakSpec(spec));
    s.initialise();
    EXPECT_GT(checkListsAlongTheFlow(s, steps), 0.5)
        << dimension << "D: no step kept a list past half a skin of motion";
  };
  // The 2D Martin & Moyce column of the dam-break tests, into the surge.
  damBreak(2, {{"column_width", 0.057}, {"column_height", 0.114}, {"tank_length", 0.4}, {"tank_height", 0.2}}, 0.0025,
           1500);
  // A 3D column collapsing in a tank.
  damBreak(3, {{"column_width", 0.1}, {"column_height", 0.15}, {"tank_length", 0.3}, {"tank_height", 0.2}, {"width", 0.06}},
           0.01, 400);
  {  // A piston driven into a 2D column: a moving body next to a fixed tube.
    nlohmann::json spec = {{"scenario", "piston-column"},
                           {"dimension", 2},
                           {"geometry", {{"diameter", 0.04}, {"column_height", 0.08}}},
                           {"resolution", {{"spacing", 0.002}}},
                           {"fluid", {{"sound_speed", 50.0}}},
                           {"piston", {{"motion", "prescribed"}, {"speed", 5.0}}}};
    sph::SphSystem s;
    buildPistonColumn(s, parsePistonColumnSpec(spec));
    s.initialise();
    checkListsAlongTheFlow(s, 400);
  }
}

}  // namespace
}  // namespace rupture::testing
