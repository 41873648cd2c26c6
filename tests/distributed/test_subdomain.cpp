// A bonded sample decomposed over the ranks of the run (distributed/subdomain.hpp) against the
// same sample on one process: a PMB block torn apart (with the compression term's nodal shift), a
// spring lattice with a pre-crack opened by a velocity field, and porous ceramic beam samples in
// tension (several microstructures) give the one-process trajectories, damage and broken bonds bit
// for bit; a bond across the partition breaks on both of its ranks in the same step; two halves
// driven into each other across the partition touch through the contact's ghosts by distance, bit
// for bit, with the one-process contact energy; momentum is conserved to round-off. Run by ctest on
// one rank and under mpiexec on two and three.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "distributed/coordinate_bisection.hpp"
#include "distributed/subdomain.hpp"
#include "distributed_test_support.hpp"
#include "engine/sample_test_support.hpp"

namespace rupture {
namespace {

/// Sets a system's initial velocities and prescribed degrees of freedom from positions alone, so
/// that the whole sample and each sub-domain get the same loading.
using Loading = std::function<void(BondedSystem&)>;

struct Outcome {
  std::vector<double> x, y, z, vx, vy, vz, damage;
  std::uint64_t broken = 0;
  double kinetic = 0;
  std::array<double, 3> momentum{0, 0, 0};
  double contactEnergy = 0;
  std::size_t contactGhosts = 0;  // on every rank together
};

Outcome runWhole(BondedSystem s, const Loading& load, int steps, double dt) {
  load(s);
  s.initialize();
  for (int t = 0; t < steps; ++t) s.step(dt);
  const ParticleStore& p = s.particles;
  Outcome o{p.x, p.y, p.z, p.vx, p.vy, p.vz, s.damageIndex(), 0, s.kineticEnergy(), {}};
  o.broken = s.bonds.size() - s.bonds.intactCount();
  o.contactEnergy = s.contact.energy(p);
  for (std::size_t k = 0; k < p.size(); ++k) {
    o.momentum[0] += p.mass[k] * p.vx[k]; o.momentum[1] += p.mass[k] * p.vy[k]; o.momentum[2] += p.mass[k] * p.vz[k];
  }
  return o;
}

/// The crossing bonds (one end owned, the other a ghost) that broke, as (step, global i, global j).
using CrossingBreaks = std::vector<std::int64_t>;

Outcome runDecomposed(const BondedSystem& whole, const Loading& load, int steps, double dt,
                      CrossingBreaks* crossing = nullptr) {
  const Communicator comm = Communicator::world();
  Subdomain d(whole, bisectCoordinates(whole.particles, whole.bonds, comm.size()), comm);
  BondedSystem& s = d.system;
  load(s);
  s.initialize();
  const auto& g = d.globalIndex();
  std::vector<std::uint8_t> seen(s.bonds.size(), 0);
  for (int t = 0; t < steps; ++t) {
    s.step(dt);
    if (!crossing) continue;
    for (std::size_t b = 0; b < s.bonds.size(); ++b) {
      if (seen[b] || s.bonds.intact[b] > 0.0 || d.owns(s.bonds.i[b]) == d.owns(s.bonds.j[b])) continue;
      seen[b] = 1;
      crossing->insert(crossing->end(), {t, g[s.bonds.i[b]], g[s.bonds.j[b]]});
    }
  }
  const ParticleStore& p = s.particles;
  Outcome o{d.gather(p.x), d.gather(p.y), d.gather(p.z), d.gather(p.vx), d.gather(p.vy), d.gather(p.vz),
            d.gather(s.damageIndex()), d.brokenBonds(), d.kineticEnergy(), {}};
  o.momentum = {d.sumOwned([&](std::size_t k) { return p.mass[k] * p.vx[k]; }),
                d.sumOwned([&](std::size_t k) { return p.mass[k] * p.vy[k]; }),
                d.sumOwned([&](std::size_t k) { return p.mass[k] * p.vz[k]; })};
  if (whole.contact.parameters().enabled) {  // the ranks' contact energy, as a scenario's outputs read it
    BondedSystem gathered = whole;
    load(gathered);
    gathered.initialize();
    d.gatherInto(gathered);  // into the first rank's whole only: its energy sent to every rank
    const double energy = comm.rank() == 0 ? gathered.contact.energy(gathered.particles) : 0.0;
    o.contactEnergy = comm.sum(energy);  // one term and zeros: exact
    o.contactGhosts = static_cast<std::size_t>(comm.sum(static_cast<std::uint64_t>(d.contactHalo()->ghostCount())));
  }
  return o;
}

void expectSameRun(const Outcome& one, const Outcome& many, double kineticScale) {
  const int ranks = Communicator::world().size();
  EXPECT_EQ(testing::firstDifference(one.x, many.x), -1) << ranks << " ranks";
  EXPECT_EQ(testing::firstDifference(one.y, many.y), -1) << ranks << " ranks";
  EXPECT_EQ(testing::firstDifference(one.z, many.z), -1) << ranks << " ranks";
  EXPECT_EQ(testing::firstDifference(one.vx, many.vx), -1) << ranks << " ranks";
  EXPECT_EQ(testing::firstDifference(one.vy, many.vy), -1) << ranks << " ranks";
  EXPECT_EQ(testing::firstDifference(one.vz, many.vz), -1) << ranks << " ranks";
  EXPECT_EQ(testing::firstDifference(one.damage, many.damage), -1) << ranks << " ranks";
  EXPECT_EQ(one.broken, many.broken) << ranks << " ranks";
  // Reductions: each rank's share, then the ranks: round-off apart from the one-process sum.
  EXPECT_NEAR(many.kinetic, one.kinetic, 1e-12 * kineticScale) << ranks << " ranks";
  // The contact energy is summed in the whole sample's pair order on any rank count.
  EXPECT_EQ(testing::firstDifference({one.contactEnergy}, {many.contactEnergy}), -1)
      << ranks << " ranks: " << one.contactEnergy << " against " << many.contactEnergy;
}

/// Stretches the block along x (v from −2 to 2 m/s): it tears apart in the middle, across the cut
/// of two ranks and between those of three.
const Loading kStretchAlongX = [](BondedSystem& s) {
  for (std::size_t k = 0; k < s.particles.size(); ++k) s.particles.vx[k] = 4.0 * (s.particles.x[k] / 14e-3 - 0.5);
};

TEST(Subdomain, APmbBlockTornApartFollowsTheOneProcessRunBitForBit) {
  const BondedSystem whole = testing::pmbBlock(0.25);  // the nodal shift: ghosts take their owners' s_min
  const double dt = 0.5 * whole.criticalTimeStep();
  const Outcome one = runWhole(whole, kStretchAlongX, 150, dt);
  CrossingBreaks crossing;
  const Outcome many = runDecomposed(whole, kStretchAlongX, 150, dt, &crossing);
  ASSERT_GT(one.broken, 100u);  // it did tear
  expectSameRun(one, many, one.kinetic);

  // Every crossing bond that broke is reported by both of its ranks, at the same step.
  const Communicator comm = Communicator::world();
  const std::vector<std::int64_t> all = comm.allGather(crossing);
  std::map<std::array<std::int64_t, 3>, int> reports;
  for (std::size_t t = 0; t + 2 < all.size(); t += 3) ++reports[{all[t], all[t + 1], all[t + 2]}];
  std::map<std::array<std::int64_t, 2>, int> bondReports;
  for (const auto& [key, count] : reports) {
    EXPECT_EQ(count, 2) << "bond " << key[1] << "-" << key[2] << " at step " << key[0];
    ++bondReports[{key[1], key[2]}];
  }
  for (const auto& [bond, steps] : bondReports) EXPECT_EQ(steps, 1) << "bond " << bond[0] << "-" << bond[1];
  if (comm.size() > 1) {
    EXPECT_GT(reports.size(), 10u);  // the tear runs along the cut
  }
}

TEST(Subdomain, MomentumIsConservedToRoundOffAcrossTheSubdomains) {
  const BondedSystem whole = testing::pmbBlock(0.25);  // the nodal shift: ghosts take their owners' s_min
  const double dt = 0.5 * whole.criticalTimeStep();
  double scale = 0;  // Σ m |v| at the start
  for (std::size_t k = 0; k < whole.particles.size(); ++k)
    scale += whole.particles.mass[k] * std::fabs(4.0 * (whole.particles.x[k] / 14e-3 - 0.5));
  const Outcome many = runDecomposed(whole, kStretchAlongX, 150, dt);
  double start = 0;
  for (std::size_t k = 0; k < whole.particles.size(); ++k)
    start += whole.particles.mass[k] * 4.0 * (whole.particles.x[k] / 14e-3 - 0.5);
  EXPECT_NEAR(many.momentum[0], start, 1e-13 * scale);
  EXPECT_NEAR(many.momentum[1], 0.0, 1e-13 * scale);
  EXPECT_NEAR(many.momentum[2], 0.0, 1e-13 * scale);
}

TEST(Subdomain, ASpringLatticeWithAPreCrackFollowsTheOneProcessRunBitForBit) {
  SampleSpec s;
  s.dimension = 2;
  s.lattice = "triangular";
  s.spacing = 1e-4;
  s.elementRadius = 0.5e-4;
  s.thickness = 1e-4;
  s.size = {6e-3, 4e-3, 0};
  s.notches.push_back({{0, 2e-3, 0}, {2e-3, 2e-3, 0}});
  MaterialSpec m;
  m.model = "hookean";
  m.density = 2500;
  m.springs.youngModulus = 70e9;
  m.springs.poissonRatio = 0.25;
  m.springs.criterion = "critical_stretch";
  m.springs.criticalValue = 2e-3;
  m.contact.enabled = true;  // the pre-crack's faces touch at their cut bonds' rest length
  BondedSystem whole;
  buildSample(s, m, whole);
  // Opens the crack: v_y from −15 to 15 m/s across the height.
  const Loading open = [](BondedSystem& sys) {
    for (std::size_t k = 0; k < sys.particles.size(); ++k) sys.particles.vy[k] = 30.0 * (sys.particles.y[k] / 4e-3 - 0.5);
  };
  const double dt = 0.5 * whole.criticalTimeStep();
  const Outcome one = runWhole(whole, open, 400, dt);
  const Outcome many = runDecomposed(whole, open, 400, dt);
  ASSERT_GT(one.broken, 20u);  // the crack ran
  expectSameRun(one, many, one.kinetic);
}

/// The seed's porous ceramic (Table 3 beams) on a small 2D square (the sample-builder tests'),
/// its microstructure drawn from `seed`, with or without contact between fragments.
BondedSystem ceramicSample(std::uint64_t seed, double& size, bool contact = false) {
  const SampleSpec s = testing::porousSpec(2, seed);
  MaterialSpec m = testing::ceramic();
  m.contact.enabled = contact;
  BondedSystem system;
  buildSample(s, m, system);
  size = s.size[0];
  return system;
}

TEST(Subdomain, PorousBeamSamplesInTensionFollowTheOneProcessRunBitForBit) {
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    double size = 0;
    const BondedSystem whole = ceramicSample(seed, size, /*contact=*/seed != 1);
    const double band = 2 * 3.3e-9, speed = 20.0;
    const Loading pull = [=](BondedSystem& sys) {
      ParticleStore& p = sys.particles;
      for (std::size_t k = 0; k < p.size(); ++k)
        if (p.x[k] < band || p.x[k] > size - band) p.fixedDofs[k] |= kFixX;
      sys.prescribe = [=](ParticleStore& ps, double) {
        for (std::size_t k = 0; k < ps.size(); ++k)
          if (ps.fixedDofs[k] & kFixX) ps.vx[k] = ps.x[k] < 0.5 * size ? -speed : speed;
      };
      sys.prescribe(p, 0.0);
    };
    const double dt = 0.5 * whole.criticalTimeStep();
    const Outcome one = runWhole(whole, pull, 600, dt);
    const Outcome many = runDecomposed(whole, pull, 600, dt);
    ASSERT_GT(one.broken, 0u) << "seed " << seed;
    SCOPED_TRACE("seed " + std::to_string(seed));
    expectSameRun(one, many, one.kinetic);
  }
}

/// The PMB block cut in two across x = 7 mm (every bond across the plane broken) and its halves
/// driven into each other at 5 m/s each: they touch at once, along a plane the partition cuts or
/// follows, so contacts join particles of different ranks.
BondedSystem halvesInContact() {
  BondedSystem whole = testing::pmbBlock(0.25);
  whole.contact.setParameters({22e9, 0.25, 0.3, 0.1, true});
  BondStore& b = whole.bonds;
  const ParticleStore& p = whole.particles;
  for (std::size_t t = 0; t < b.size(); ++t)
    if ((p.x[b.i[t]] < 7e-3) != (p.x[b.j[t]] < 7e-3)) b.intact[t] = 0.0;
  return whole;
}

const Loading kHalvesTogether = [](BondedSystem& s) {
  for (std::size_t k = 0; k < s.particles.size(); ++k) s.particles.vx[k] = s.particles.x[k] < 7e-3 ? 5.0 : -5.0;
};

TEST(Subdomain, HalvesInContactAcrossTheRanksFollowTheOneProcessRunBitForBit) {
  const BondedSystem whole = halvesInContact();
  const double dt = 0.5 * whole.criticalTimeStep();
  for (int steps : {1, 40, 300}) {
    SCOPED_TRACE(std::to_string(steps) + " steps");
    const Outcome one = runWhole(whole, kHalvesTogether, steps, dt);
    const Outcome many = runDecomposed(whole, kHalvesTogether, steps, dt);
    ASSERT_GT(one.contactEnergy, 0.0);  // they touch
    expectSameRun(one, many, one.kinetic);
    // While the halves press on each other, contacts join particles of different ranks (by 300
    // steps they have rebounded apart; the contacts left are between fragments of one half).
    if (Communicator::world().size() > 1 && steps <= 40) {
      EXPECT_GT(many.contactGhosts, 0u);
    }
  }
}

TEST(Subdomain, MomentumIsConservedToRoundOffThroughContactsAcrossTheRanks) {
  const BondedSystem whole = halvesInContact();
  const double dt = 0.5 * whole.criticalTimeStep();
  double scale = 0;  // Σ m |v| at the start; the total is 0
  for (std::size_t k = 0; k < whole.particles.size(); ++k) scale += whole.particles.mass[k] * 5.0;
  const Outcome many = runDecomposed(whole, kHalvesTogether, 300, dt);
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(many.momentum[a], 0.0, 1e-13 * scale) << "axis " << a;
}

TEST(Subdomain, IsCutFromTheWholeSampleWithEveryBondOfItsOwnedParticles) {
  // The sub-domain copies only its particles and bonds (no copy of the whole sample): each is the
  // whole's, with every array, and each bond with an owned end is there once, in the whole's order.
  const BondedSystem whole = testing::pmbBlock(0.25);
  const Communicator comm = Communicator::world();
  const std::vector<int> owner = bisectCoordinates(whole.particles, whole.bonds, comm.size());
  const Subdomain d(whole, owner, comm);
  const ParticleStore &w = whole.particles, &p = d.system.particles;
  const std::vector<std::int32_t>& g = d.globalIndex();
  ASSERT_EQ(p.size(), g.size());
  for (std::size_t k = 0; k < g.size(); ++k) {
    const auto wk = static_cast<std::size_t>(g[k]);
    ASSERT_EQ(d.owns(k), owner[wk] == comm.rank()) << "particle " << wk;
    EXPECT_EQ(p.x[k], w.x[wk]); EXPECT_EQ(p.y[k], w.y[wk]); EXPECT_EQ(p.z[k], w.z[wk]);
    EXPECT_EQ(p.radius[k], w.radius[wk]); EXPECT_EQ(p.mass[k], w.mass[wk]); EXPECT_EQ(p.volume[k], w.volume[wk]);
    EXPECT_EQ(p.fixedDofs[k], w.fixedDofs[wk]);
  }
  // The whole's bonds with an owned end, in order, against the sub-domain's mapped back.
  std::vector<std::size_t> expected;
  for (std::size_t b = 0; b < whole.bonds.size(); ++b)
    if (owner[whole.bonds.i[b]] == comm.rank() || owner[whole.bonds.j[b]] == comm.rank()) expected.push_back(b);
  const BondStore& bonds = d.system.bonds;
  ASSERT_EQ(bonds.size(), expected.size());
  for (std::size_t t = 0; t < expected.size(); ++t) {
    const std::size_t b = expected[t];
    ASSERT_EQ(g[bonds.i[t]], whole.bonds.i[b]) << "bond " << b;
    ASSERT_EQ(g[bonds.j[t]], whole.bonds.j[b]) << "bond " << b;
    EXPECT_EQ(bonds.restLength[t], whole.bonds.restLength[b]);
    EXPECT_EQ(bonds.n0x[t], whole.bonds.n0x[b]);
    EXPECT_EQ(bonds.stiffness[t], whole.bonds.stiffness[b]);
    EXPECT_EQ(bonds.threshold[t], whole.bonds.threshold[b]);
    EXPECT_EQ(bonds.strength[t], whole.bonds.strength[b]);
    EXPECT_EQ(bonds.intact[t], whole.bonds.intact[b]);
  }
}

TEST(Subdomain, GathersTheOutputsIntoTheFirstRanksWholeOnlyAndTheOthersNeedNone) {
  // The outputs are the first rank's: it gathers the ranks' state into its whole sample, while the
  // other ranks send theirs and may have dropped the whole (BondedSystem::withoutElements).
  const BondedSystem whole = testing::pmbBlock(0.25);
  const double dt = 0.5 * whole.criticalTimeStep();
  const Outcome one = runWhole(whole, kStretchAlongX, 150, dt);
  const Communicator comm = Communicator::world();
  Subdomain d(whole, bisectCoordinates(whole.particles, whole.bonds, comm.size()), comm);
  kStretchAlongX(d.system);
  d.system.initialize();
  for (int t = 0; t < 150; ++t) d.system.step(dt);
  BondedSystem gathered = comm.rank() == 0 ? whole : whole.withoutElements();
  if (comm.rank() == 0) {
    kStretchAlongX(gathered);
    gathered.initialize();
  }
  d.gatherInto(gathered);
  if (comm.rank() != 0) {
    EXPECT_EQ(gathered.particles.size(), 0u);
    EXPECT_EQ(gathered.bonds.size(), 0u);
    return;
  }
  EXPECT_EQ(gathered.time, d.system.time);
  EXPECT_EQ(gathered.steps, 150u);
  EXPECT_EQ(testing::firstDifference(gathered.particles.x, one.x), -1);
  EXPECT_EQ(testing::firstDifference(gathered.particles.vy, one.vy), -1);
  EXPECT_EQ(gathered.bonds.size() - gathered.bonds.intactCount(), one.broken);
  EXPECT_GT(one.broken, 0u);  // it tore
}

}  // namespace
}  // namespace rupture
