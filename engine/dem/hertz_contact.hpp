#pragma once
// Contact between elements that are not held by an intact bond (fragments after failure, or pairs
// that come into contact): Hertz normal force, a viscous normal term and Coulomb friction.
//   δ = R_i + R_k − d > 0,  R* = R_i R_k / (R_i + R_k),  E* = E / (2 (1 − ν²))
//   F_n = (4/3) E* √R* δ^{3/2} + c_n δ̇,   c_n = 2 ζ √(m* k_n),  k_n = 2 E* √(R* δ)  (tangent stiffness)
//   F_t = −min(μ F_n, c_n |v_t|) v_t/|v_t|   (Coulomb limit, viscous regularisation: no history)
// The normal force never pulls (F_n >= 0). Energy stored: (8/15) E* √R* δ^{5/2}.
// A pair whose bond broke, or was cut by a pre-crack (BondStore::cutPairs), touches at
// min(R_i + R_k, L0): packings leave bonded pairs slightly overlapping, and measuring the overlap
// from R_i + R_k would push them apart with a force of the order of the bond's strength at the
// very step it breaks (or, across a notch, at the first step).
// Neighbour search: cell list and a Verlet list with a skin, rebuilt when a particle has moved more
// than half the skin; pairs whose bond breaks between rebuilds join the list at once. Each step
// visits only the listed pairs that the displacements since the rebuild could have brought into touch.
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "core/bond_store.hpp"
#include "core/cell_list.hpp"
#include "core/particle_store.hpp"

namespace rupture {

struct ContactParameters {
  double youngModulus = 0;    ///< E of the elements (Pa)
  double poissonRatio = 0.3;  ///< ν (1)
  double friction = 0.3;      ///< Coulomb coefficient μ (1)
  double dampingRatio = 0.1;  ///< ζ (1), fraction of critical damping of the normal contact
  bool enabled = true;
};

/// What a decomposed run adds to the contact search (distributed/contact_halo.hpp): only the owned
/// particles' contacts are evaluated, the lists keep the whole sample's order, every rank decides a
/// rebuild at once from the largest displacement over the ranks, and before a rebuild the particles
/// of other ranks that could come into reach are brought in as ghosts.
class ContactDomain {
public:
  virtual ~ContactDomain() = default;
  /// 1 for each particle whose contacts are evaluated here (the owned ones), 0 for the ghosts.
  virtual const std::vector<std::uint8_t>& evaluated() const = 0;
  /// Each particle's index in the whole sample: the order of the neighbour lists and of the energy.
  virtual const std::vector<std::int32_t>& wholeIndex() const = 0;
  virtual double largestOverRanks(double value) const = 0;
  /// The whole sample's mean and largest radius (m): the skin and the reach of the search.
  virtual double wholeMeanRadius() const = 0;
  virtual double wholeMaxRadius() const = 0;
  /// Collective, before a rebuild: brings in, with their current kinematics, the particles of other
  /// ranks that lie within R_k + maxRadius + skin of this rank's owned ones.
  virtual void gatherCandidates(double skin, double maxRadius) = 0;
};

class HertzContact {
public:
  explicit HertzContact(ContactParameters p = {}) : m_params(p) {}
  const ContactParameters& parameters() const { return m_params; }
  void setParameters(const ContactParameters& p) { m_params = p; m_listValid = false; }

  /// Adds contact forces and torques on every particle (after the bond loads were gathered).
  /// inPlane: z never moves (BondedSystem::planarMotion), so the rebuild check skips it.
  void addForces(ParticleStore& p, const BondStore& bonds, bool inPlane = false);

  /// Call when a bond broke: its pair becomes a contact candidate immediately, touching at
  /// min(R_i + R_j, restLength).
  void onBondBroken(std::int32_t i, std::int32_t j, double restLength) { m_brokenPairs.push_back({i, j, restLength}); }

  /// Elastic energy stored in the current contacts (J): the touching pairs' terms added in the
  /// order of their whole-sample indices (first, second), so that any decomposition sums the same
  /// terms in the same order.
  double energy(const ParticleStore& p) const;

  /// One touching pair's stored energy, keyed by its ends' whole-sample indices (first < second).
  struct EnergyTerm {
    std::int64_t first, second;
    double energy;
  };
  /// The terms of `energy` this system holds: on a sub-domain, the pairs whose first end it owns.
  std::vector<EnergyTerm> energyTerms(const ParticleStore& p) const;
  /// Σ of terms in the order of (first, second).
  static double sumEnergy(std::vector<EnergyTerm> terms);
  /// A decomposed run's whole system, which is not stepped, takes the ranks' energy (until its next evaluation).
  void adoptGatheredEnergy(double e) { m_gatheredEnergy = e; }

  /// The mean and the largest radius of a sample (m), from which a rebuild takes its skin and its
  /// reach: a sub-domain takes its whole sample's, summed as one process sums them.
  struct Radii {
    double mean = 0, max = 0;
  };
  static Radii radiiOf(const ParticleStore& p);

  /// Makes this the contact of one rank's sub-domain (nullptr: of the whole sample, as on one process).
  void setDomain(std::shared_ptr<ContactDomain> domain) { m_domain = std::move(domain); m_listValid = false; }

  /// The neighbour list and what decides its next rebuild (the cell grid is rebuilt with it).
  void exchangeState(StateArchive& archive);


private:
  void rebuild(const ParticleStore& p, const BondStore& bonds);
  template <bool kInPlane>
  double largestDisplacement(const ParticleStore& p) const;
  void selectActive(double level);

  ContactParameters m_params;
  std::shared_ptr<ContactDomain> m_domain;
  std::optional<double> m_gatheredEnergy;
  bool m_listValid = false;
  double m_skin = 0;
  CellList m_cells;
  std::vector<std::int32_t> m_start, m_neighbors;     // full list: both (i, k) and (k, i)
  std::vector<double> m_reach;                        // contact distance of each listed pair (m)
  std::vector<double> m_gap0;                         // centre distance − reach of each listed pair at the rebuild (m)
  std::vector<double> m_x0, m_y0, m_z0;               // positions at the last rebuild
  // The listed pairs that can touch while no particle moved more than m_activeLevel since the rebuild
  // (gap0 < 2 level): a pair's distance shrinks by at most the two displacements. Same order as the list.
  double m_activeLevel = -1;
  std::vector<std::int32_t> m_activeStart, m_activeNeighbors;
  std::vector<double> m_activeReach;
  struct Pair { std::int32_t i, j; double restLength; };
  std::vector<Pair> m_brokenPairs;                    // since the last rebuild
};

}  // namespace rupture
