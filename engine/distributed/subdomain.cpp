#include "distributed/subdomain.hpp"

#include <algorithm>
#include <map>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

namespace rupture {

namespace {

void sortUnique(std::vector<std::int32_t>& v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
}

}  // namespace

SubdomainPiece SubdomainPiece::cut(const BondedSystem& whole, const std::vector<int>& owner, int me) {
  const std::size_t n = whole.particles.size();
  if (owner.size() != n)
    throw std::invalid_argument("Subdomain: " + std::to_string(owner.size()) + " owners for " + std::to_string(n) +
                                " particles");
  SubdomainPiece piece;
  piece.wholeSize = n;

  // Owned particles, ghosts, and what each neighbour sends and receives (global indices).
  std::vector<std::uint8_t> keep(n, 0);
  for (std::size_t k = 0; k < n; ++k) keep[k] = owner[k] == me;
  std::map<int, Halo::Neighbour> lists;
  const BondStore& wb = whole.bonds;
  for (std::size_t b = 0; b < wb.size(); ++b) {
    const std::int32_t i = wb.i[b], j = wb.j[b];
    const int oi = owner[i], oj = owner[j];
    if (oi == oj) continue;
    if (oi == me) {
      keep[j] = 1;
      lists[oj].send.push_back(i);
      lists[oj].receive.push_back(j);
    } else if (oj == me) {
      keep[i] = 1;
      lists[oi].send.push_back(j);
      lists[oi].receive.push_back(i);
    }
  }

  // Only the kept particles and bonds are copied: a rank never holds a second whole sample.
  std::vector<std::int32_t> local(n, -1);
  for (std::size_t k = 0; k < n; ++k)
    if (keep[k]) {
      local[k] = static_cast<std::int32_t>(piece.global.size());
      piece.global.push_back(static_cast<std::int32_t>(k));
    }
  piece.owned.resize(piece.global.size());
  for (std::size_t k = 0; k < piece.global.size(); ++k) piece.owned[k] = owner[piece.global[k]] == me;
  // The bonds with an owned end (a bond between two ghosts is their owners' to evaluate), in the
  // whole sample's order.
  std::vector<std::uint8_t> keepBond(wb.size(), 0);
  for (std::size_t b = 0; b < wb.size(); ++b)
    if (owner[wb.i[b]] == me || owner[wb.j[b]] == me) {
      keepBond[b] = 1;
      piece.globalBond.push_back(static_cast<std::int64_t>(b));
    }
  piece.particles = whole.particles.subset(keep);
  piece.bonds = whole.bonds.subset(keepBond, local);

  for (auto& [rank, nb] : lists) {
    nb.rank = rank;
    for (auto* v : {&nb.send, &nb.receive}) {
      sortUnique(*v);
      for (std::int32_t& k : *v) k = local[k];
    }
    piece.neighbours.push_back(std::move(nb));
  }
  // For contact: the pre-cracked pairs with an owned end, in the whole sample's indices (their other
  // end may come and go as a ghost by distance), and the radii the one-process search takes its skin from.
  for (const BondStore::CutPair& c : wb.cutPairs)
    if (owner[c.i] == me || owner[c.j] == me) piece.cutPairs.push_back(c);
  const HertzContact::Radii radii = HertzContact::radiiOf(whole.particles);
  piece.meanRadius = radii.mean;
  piece.maxRadius = radii.max;
  return piece;
}

Subdomain::Subdomain(const BondedSystem& whole, const std::vector<int>& owner, Communicator comm)
    : Subdomain(whole.withoutElements(), SubdomainPiece::cut(whole, owner, comm.rank()), comm) {}

Subdomain::Subdomain(BondedSystem configuration, SubdomainPiece piece, Communicator comm) : m_comm(comm) {
  if (configuration.bondDamping > 0 && comm.size() > 1)
    throw std::invalid_argument("material.local_damping: " + std::to_string(configuration.bondDamping) +
                                " is not supported on more than one rank yet (it reads the partners' damage "
                                "index); set it to 0 or run on one rank");
  m_wholeSize = piece.wholeSize;
  m_global = std::move(piece.global);
  m_owned = std::move(piece.owned);
  m_globalBond = std::move(piece.globalBond);
  m_ownedCount = static_cast<std::size_t>(std::count(m_owned.begin(), m_owned.end(), 1));
  system = std::move(configuration);
  system.prescribe = nullptr;
  system.externalLoads = nullptr;
  system.particles = std::move(piece.particles);
  system.bonds = std::move(piece.bonds);
  m_gatheredIntact = system.bonds.intact;

  const bool rotations =
      system.visitModel([](const auto& law, const auto&) { return std::decay_t<decltype(law)>::kRotational; });
  m_halo = std::make_shared<Halo>(comm, std::move(piece.neighbours), rotations);
  if (!system.contact.parameters().enabled) {
    system.refreshGhosts = [halo = m_halo](ParticleStore& p, std::vector<double>& nodalMinimum) {
      halo->refresh(p, nodalMinimum);
    };
    return;
  }
  m_contactHalo = std::make_shared<ContactHalo>(comm, system, m_global, m_owned, std::move(piece.cutPairs),
                                                piece.meanRadius, piece.maxRadius);
  system.contact.setDomain(m_contactHalo);
  system.refreshGhosts = [halo = m_halo, contact = m_contactHalo](ParticleStore& p, std::vector<double>& nodalMinimum) {
    halo->refresh(p, nodalMinimum);
    contact->refresh(p);
  };
}

std::int32_t Subdomain::localOf(std::int32_t global) const {
  const auto it = std::lower_bound(m_global.begin(), m_global.end(), global);
  return it != m_global.end() && *it == global ? static_cast<std::int32_t>(it - m_global.begin()) : -1;
}

std::vector<std::int32_t> Subdomain::localMembers(const std::vector<std::int32_t>& members) const {
  std::vector<std::int32_t> out;
  for (std::int32_t k : members)
    if (const std::int32_t local = localOf(k); local >= 0) out.push_back(local);
  return out;
}

std::vector<double> Subdomain::gather(const std::vector<double>& local) const {
  std::vector<std::int64_t> ids;
  std::vector<double> values;
  ids.reserve(m_ownedCount);
  values.reserve(m_ownedCount);
  for (std::size_t k = 0; k < m_global.size(); ++k)
    if (m_owned[k]) {
      ids.push_back(m_global[k]);
      values.push_back(local[k]);
    }
  const std::vector<std::int64_t> allIds = m_comm.allGather(ids);
  const std::vector<double> allValues = m_comm.allGather(values);
  std::vector<double> whole(m_wholeSize, 0.0);
  for (std::size_t t = 0; t < allIds.size(); ++t) whole[static_cast<std::size_t>(allIds[t])] = allValues[t];
  return whole;
}

void Subdomain::gatherInto(BondedSystem& whole) const {
  const bool first = m_comm.rank() == 0;
  ParticleStore& w = whole.particles;
  const ParticleStore& p = system.particles;
  if (first && (w.size() != m_wholeSize || whole.bonds.size() < m_globalBond.size()))
    throw std::logic_error("Subdomain::gatherInto: not the sample this sub-domain was cut from");
  constexpr std::size_t kArrays = 13;
  const std::array<std::vector<double>*, kArrays> wholeArrays{&w.x,  &w.y,  &w.z,  &w.vx, &w.vy, &w.vz, &w.qw,
                                                              &w.qx, &w.qy, &w.qz, &w.wx, &w.wy, &w.wz};
  const std::array<const std::vector<double>*, kArrays> localArrays{&p.x,  &p.y,  &p.z,  &p.vx, &p.vy,
                                                                    &p.vz, &p.qw, &p.qx, &p.qy, &p.qz,
                                                                    &p.wx, &p.wy, &p.wz};
  std::vector<std::int64_t> ids;
  std::vector<double> values;
  ids.reserve(m_ownedCount);
  values.reserve(kArrays * m_ownedCount);
  for (std::size_t k = 0; k < m_global.size(); ++k) {
    if (!m_owned[k]) continue;
    ids.push_back(m_global[k]);
    for (const auto* a : localArrays) values.push_back((*a)[k]);
  }
  const std::vector<std::int64_t> allIds = m_comm.gatherToFirst(ids);
  const std::vector<double> allValues = m_comm.gatherToFirst(values);
  for (std::size_t t = 0; t < allIds.size(); ++t)
    for (std::size_t a = 0; a < kArrays; ++a) (*wholeArrays[a])[allIds[t]] = allValues[kArrays * t + a];
  gatherBondsInto(whole);
  if (!m_contactHalo) return;
  // The contact energy: every rank's touching pairs, summed in the order one process sums them.
  const std::vector<HertzContact::EnergyTerm> mine = system.contact.energyTerms(system.particles);
  std::vector<std::int64_t> pairs;
  std::vector<double> energies;
  for (const HertzContact::EnergyTerm& t : mine) {
    pairs.insert(pairs.end(), {t.first, t.second});
    energies.push_back(t.energy);
  }
  const std::vector<std::int64_t> allPairs = m_comm.gatherToFirst(pairs);
  const std::vector<double> allEnergies = m_comm.gatherToFirst(energies);
  if (!first) return;
  std::vector<HertzContact::EnergyTerm> terms(allEnergies.size());
  for (std::size_t t = 0; t < terms.size(); ++t) terms[t] = {allPairs[2 * t], allPairs[2 * t + 1], allEnergies[t]};
  whole.contact.adoptGatheredEnergy(HertzContact::sumEnergy(std::move(terms)));
}

void Subdomain::gatherBondsInto(BondedSystem& whole) const {
  const bool first = m_comm.rank() == 0;
  if (first && whole.bonds.size() < m_globalBond.size())
    throw std::logic_error("Subdomain::gatherBondsInto: not the sample this sub-domain was cut from");
  std::vector<std::int64_t> bondIds;
  std::vector<double> intact;
  const BondStore& b = system.bonds;
  for (std::size_t t = 0; t < b.size(); ++t)
    if (m_owned[b.i[t]] && b.intact[t] != m_gatheredIntact[t]) {
      bondIds.push_back(m_globalBond[t]);
      intact.push_back(b.intact[t]);
      m_gatheredIntact[t] = b.intact[t];
    }
  const std::vector<std::int64_t> allBonds = m_comm.gatherToFirst(bondIds);
  const std::vector<double> allIntact = m_comm.gatherToFirst(intact);
  if (!first) return;
  for (std::size_t t = 0; t < allBonds.size(); ++t) whole.bonds.intact[allBonds[t]] = allIntact[t];
  whole.brokenLastStep = 0;
  whole.adoptGatheredState(system.time, system.steps);
}

std::array<double, 3> Subdomain::sumInWholeOrder(const std::vector<std::int64_t>& ids,
                                                 const std::vector<double>& terms) const {
  const std::vector<std::int64_t> allIds = m_comm.allGather(ids);
  const std::vector<double> allTerms = m_comm.allGather(terms);
  std::vector<std::size_t> order(allIds.size());
  for (std::size_t t = 0; t < order.size(); ++t) order[t] = t;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return allIds[a] < allIds[b]; });
  std::array<double, 3> sum{0.0, 0.0, 0.0};
  for (std::size_t t : order)
    for (int c = 0; c < 3; ++c) sum[c] += allTerms[3 * t + c];
  return sum;
}

std::uint64_t Subdomain::brokenBonds() const {
  std::uint64_t broken = 0;
  const BondStore& b = system.bonds;
  for (std::size_t t = 0; t < b.size(); ++t)
    if (m_owned[b.i[t]] && b.intact[t] <= 0.0) ++broken;
  return m_comm.sum(broken);
}

std::uint64_t Subdomain::brokenLastStepHere() const {
  std::uint64_t broken = 0;
  for (std::size_t b : system.bondsBrokenLastStep())
    if (m_owned[system.bonds.i[b]]) ++broken;
  return broken;
}

double Subdomain::kineticEnergy() const {
  const ParticleStore& p = system.particles;
  return sumOwned([&](std::size_t k) {
    return 0.5 * p.mass[k] * (p.vx[k] * p.vx[k] + p.vy[k] * p.vy[k] + p.vz[k] * p.vz[k]) +
           0.5 * p.inertia[k] * (p.wx[k] * p.wx[k] + p.wy[k] * p.wy[k] + p.wz[k] * p.wz[k]);
  });
}

void Subdomain::exchangeState(StateArchive& archive) {
  StateGroup group(archive, "subdomain");
  if (m_contactHalo) m_contactHalo->exchangeState(archive);  // first: it sets the particle count
  system.exchangeState(archive);
  archive.array("gathered_intact", m_gatheredIntact);
}

}  // namespace rupture
