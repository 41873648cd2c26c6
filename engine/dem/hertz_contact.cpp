#include "dem/hertz_contact.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

#include "core/parallel.hpp"

namespace rupture {

namespace {

struct PairLoad {
  double fx, fy, fz;  // force on i
  double tix, tiy, tiz, tkx, tky, tkz;
  bool active;
};

// Hertz–Coulomb load on i from k (see header); torques from the friction force at the contact point.
// reach: the centre distance at which the pair starts to touch.
inline PairLoad pairLoad(const ContactParameters& c, const ParticleStore& p, std::int32_t i,
                         std::int32_t k, double reach) {
  PairLoad out{};
  const double dx = p.x[k] - p.x[i], dy = p.y[k] - p.y[i], dz = p.z[k] - p.z[i];
  const double d2 = dx * dx + dy * dy + dz * dz;
  if (d2 >= reach * reach || d2 == 0.0) return out;
  const double d = std::sqrt(d2);
  const double nx = dx / d, ny = dy / d, nz = dz / d;
  const double overlap = reach - d;
  const double rStar = p.radius[i] * p.radius[k] / (p.radius[i] + p.radius[k]);
  const double eStar = c.youngModulus / (2.0 * (1.0 - c.poissonRatio * c.poissonRatio));
  const double mStar = p.mass[i] * p.mass[k] / (p.mass[i] + p.mass[k]);
  const double sqrtRd = std::sqrt(rStar * overlap);
  const double kTangent = 2.0 * eStar * sqrtRd;
  const double damping = 2.0 * c.dampingRatio * std::sqrt(mStar * kTangent);

  // Relative velocity of k's surface point with respect to i's, at the contact point.
  const double ri = p.radius[i], rk = p.radius[k];
  const double vix = p.vx[i] + (p.wy[i] * nz - p.wz[i] * ny) * ri;
  const double viy = p.vy[i] + (p.wz[i] * nx - p.wx[i] * nz) * ri;
  const double viz = p.vz[i] + (p.wx[i] * ny - p.wy[i] * nx) * ri;
  const double vkx = p.vx[k] - (p.wy[k] * nz - p.wz[k] * ny) * rk;
  const double vky = p.vy[k] - (p.wz[k] * nx - p.wx[k] * nz) * rk;
  const double vkz = p.vz[k] - (p.wx[k] * ny - p.wy[k] * nx) * rk;
  const double rvx = vkx - vix, rvy = vky - viy, rvz = vkz - viz;
  const double vn = rvx * nx + rvy * ny + rvz * nz;  // < 0 when approaching
  const double normal = std::max(0.0, 4.0 / 3.0 * eStar * sqrtRd * overlap - damping * vn);

  const double vtx = rvx - vn * nx, vty = rvy - vn * ny, vtz = rvz - vn * nz;
  const double vt = std::sqrt(vtx * vtx + vty * vty + vtz * vtz);
  const double friction = vt > 0 ? std::min(c.friction * normal, damping * vt) / vt : 0.0;
  const double ftx = friction * vtx, fty = friction * vty, ftz = friction * vtz;  // drags i along

  out.fx = -normal * nx + ftx;
  out.fy = -normal * ny + fty;
  out.fz = -normal * nz + ftz;
  // Torque on i: (R_i n) × F_t; on k: (−R_k n) × (−F_t) = R_k n × F_t.
  out.tix = ri * (ny * ftz - nz * fty);
  out.tiy = ri * (nz * ftx - nx * ftz);
  out.tiz = ri * (nx * fty - ny * ftx);
  out.tkx = rk * (ny * ftz - nz * fty);
  out.tky = rk * (nz * ftx - nx * ftz);
  out.tkz = rk * (nx * fty - ny * ftx);
  out.active = true;
  return out;
}

// The pairs a pre-crack cut (BondStore::cutPairs) and their rest lengths, keyed by both orders.
using CutLengths = std::unordered_map<std::uint64_t, double>;

std::uint64_t pairKey(std::int32_t i, std::int32_t k) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(i)) << 32) | static_cast<std::uint32_t>(k);
}

CutLengths cutLengths(const BondStore& bonds) {
  CutLengths out;
  out.reserve(2 * bonds.cutPairs.size());
  for (const BondStore::CutPair& c : bonds.cutPairs) {
    out[pairKey(c.i, c.j)] = c.restLength;
    out[pairKey(c.j, c.i)] = c.restLength;
  }
  return out;
}

// The contact distance of a pair: R_i + R_k, or the rest length of their broken (or cut) bond if
// shorter; negative when an intact bond holds the pair (no contact then).
double contactReach(const ParticleStore& p, const BondStore& bonds, const CutLengths& cut, std::int32_t i,
                    std::int32_t k) {
  double reach = p.radius[i] + p.radius[k];
  if (!cut.empty()) {
    const auto found = cut.find(pairKey(i, k));
    if (found != cut.end()) reach = std::min(reach, found->second);
  }
  for (std::int32_t s = bonds.incidenceStart[i]; s < bonds.incidenceStart[i + 1]; ++s) {
    const std::int32_t b = bonds.incidence[s] >> 1;
    if (bonds.i[b] != k && bonds.j[b] != k) continue;
    if (bonds.intact[b] > 0.0) return -1.0;  // bonded (partly damaged bonds too)
    reach = std::min(reach, bonds.restLength[b]);
  }
  return reach;
}

}  // namespace

template <bool kInPlane>
double HertzContact::largestDisplacement(const ParticleStore& p) const {
  // The largest squared displacement: a max reduction vectorises, a short-circuit "any" does not.
  // kInPlane: z is the rebuild's z, dz = 0 exactly, so leaving it out gives the same number.
  const std::ptrdiff_t n = static_cast<std::ptrdiff_t>(p.size());
  const double *x = p.x.data(), *y = p.y.data(), *z = p.z.data();
  const double *x0 = m_x0.data(), *y0 = m_y0.data(), *z0 = m_z0.data();
  double largest = 0;
#pragma omp parallel for simd reduction(max : largest) schedule(static) if (worthParallel(p.size()))
  for (std::ptrdiff_t k = 0; k < n; ++k) {
    const double dx = x[k] - x0[k], dy = y[k] - y0[k];
    if constexpr (kInPlane) {
      largest = std::max(largest, dx * dx + dy * dy);
    } else {
      const double dz = z[k] - z0[k];
      largest = std::max(largest, dx * dx + dy * dy + dz * dz);
    }
  }
  return std::sqrt(largest);
}

void HertzContact::selectActive(double level) {
  // Slack for the rounding of the distances (1e-9 of the gap scale): never drops a pair that touches.
  const double limit = 2.0 * level * (1.0 + 1e-9) + 1e-9 * m_skin;
  const std::size_t n = m_start.empty() ? 0 : m_start.size() - 1;
  m_activeStart.assign(n + 1, 0);
  m_activeNeighbors.clear();
  m_activeReach.clear();
  for (std::size_t a = 0; a < n; ++a) {
    for (std::int32_t s = m_start[a]; s < m_start[a + 1]; ++s)
      if (m_gap0[s] < limit) {
        m_activeNeighbors.push_back(m_neighbors[s]);
        m_activeReach.push_back(m_reach[s]);
      }
    m_activeStart[a + 1] = static_cast<std::int32_t>(m_activeNeighbors.size());
  }
  m_activeLevel = level;
}

HertzContact::Radii HertzContact::radiiOf(const ParticleStore& p) {
  Radii r;
  for (double radius : p.radius) { r.max = std::max(r.max, radius); r.mean += radius; }
  r.mean /= static_cast<double>(std::max<std::size_t>(p.size(), 1));
  return r;
}

void HertzContact::rebuild(const ParticleStore& p, const BondStore& bonds) {
  const Radii radii = m_domain ? Radii{m_domain->wholeMeanRadius(), m_domain->wholeMaxRadius()} : radiiOf(p);
  const double maxRadius = radii.max, meanRadius = radii.mean;
  m_skin = 0.3 * meanRadius;
  if (m_domain) m_domain->gatherCandidates(m_skin, maxRadius);  // may change p's size
  const std::size_t n = p.size();
  m_cells.build(p, 2.0 * maxRadius + m_skin);

  const CutLengths cut = cutLengths(bonds);
  const std::uint8_t* evaluated = m_domain ? m_domain->evaluated().data() : nullptr;
  const std::int32_t* whole = m_domain ? m_domain->wholeIndex().data() : nullptr;
  std::vector<std::vector<std::pair<std::int32_t, double>>> perParticle(n);
#pragma omp parallel for schedule(dynamic, 256) if (worthParallel(n))
  for (std::size_t a = 0; a < n; ++a) {
    if (evaluated && !evaluated[a]) continue;  // a ghost: its owner evaluates its contacts
    const auto i = static_cast<std::int32_t>(a);
    m_cells.forEachNear(p.x[a], p.y[a], p.z[a], [&](std::int32_t k) {
      if (k == i) return;
      const double dx = p.x[k] - p.x[a], dy = p.y[k] - p.y[a], dz = p.z[k] - p.z[a];
      const double search = p.radius[a] + p.radius[k] + m_skin;
      if (dx * dx + dy * dy + dz * dz >= search * search) return;
      const double reach = contactReach(p, bonds, cut, i, k);
      if (reach > 0) perParticle[a].push_back({k, reach});
    });
    // Fixed order, the whole sample's (a sub-domain's ghosts by distance follow its own particles).
    if (whole)
      std::sort(perParticle[a].begin(), perParticle[a].end(),
                [whole](const auto& u, const auto& v) { return whole[u.first] < whole[v.first]; });
    else
      std::sort(perParticle[a].begin(), perParticle[a].end());
  }
  m_start.assign(n + 1, 0);
  for (std::size_t a = 0; a < n; ++a) m_start[a + 1] = m_start[a] + perParticle[a].size();
  m_neighbors.resize(m_start[n]);
  m_reach.resize(m_start[n]);
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t e = 0; e < perParticle[a].size(); ++e) {
      m_neighbors[m_start[a] + e] = perParticle[a][e].first;
      m_reach[m_start[a] + e] = perParticle[a][e].second;
    }
  m_gap0.resize(m_start[n]);
  for (std::size_t a = 0; a < n; ++a)
    for (std::int32_t s = m_start[a]; s < m_start[a + 1]; ++s) {
      const std::int32_t k = m_neighbors[s];
      const double dx = p.x[k] - p.x[a], dy = p.y[k] - p.y[a], dz = p.z[k] - p.z[a];
      m_gap0[s] = std::sqrt(dx * dx + dy * dy + dz * dz) - m_reach[s];
    }
  m_x0 = p.x; m_y0 = p.y; m_z0 = p.z;
  m_brokenPairs.clear();
  m_listValid = true;
  m_activeLevel = -1;
}

void HertzContact::addForces(ParticleStore& p, const BondStore& bonds, bool inPlane) {
  if (!m_params.enabled || (p.size() == 0 && !m_domain)) return;
  m_gatheredEnergy.reset();
  // A sub-domain's size changes only in a rebuild, which every rank takes at once.
  const bool current = m_listValid && (m_domain || m_x0.size() == p.size());
  double moved = 0;
  if (current) {
    moved = inPlane ? largestDisplacement<true>(p) : largestDisplacement<false>(p);
    if (m_domain) moved = m_domain->largestOverRanks(moved);
  }
  if (!current || moved > 0.5 * m_skin) {
    rebuild(p, bonds);
    moved = 0;
  }
  // Re-select in steps of an eighth of the skin: at most four selections per rebuild.
  if (moved > m_activeLevel) selectActive(std::min(moved + 0.125 * m_skin, 0.5 * m_skin));
  const std::size_t n = p.size();
  // Full list: each particle sums the loads it receives; no two threads write the same particle.
  // Contacts cluster where fragments are: dynamic chunks balance the threads.
#pragma omp parallel for schedule(dynamic, 2048) if (worthParallel(n))
  for (std::size_t a = 0; a < n; ++a) {
    for (std::int32_t s = m_activeStart[a]; s < m_activeStart[a + 1]; ++s) {
      const PairLoad l =
          pairLoad(m_params, p, static_cast<std::int32_t>(a), m_activeNeighbors[s], m_activeReach[s]);
      if (!l.active) continue;
      p.fx[a] += l.fx; p.fy[a] += l.fy; p.fz[a] += l.fz;
      p.tx[a] += l.tix; p.ty[a] += l.tiy; p.tz[a] += l.tiz;
    }
  }
  // Pairs whose bond broke since the last rebuild: few, handled serially on both particles.
  for (const Pair& pair : m_brokenPairs) {
    const PairLoad l = pairLoad(m_params, p, pair.i, pair.j, std::min(p.radius[pair.i] + p.radius[pair.j], pair.restLength));
    if (!l.active) continue;
    p.fx[pair.i] += l.fx; p.fy[pair.i] += l.fy; p.fz[pair.i] += l.fz;
    p.tx[pair.i] += l.tix; p.ty[pair.i] += l.tiy; p.tz[pair.i] += l.tiz;
    p.fx[pair.j] -= l.fx; p.fy[pair.j] -= l.fy; p.fz[pair.j] -= l.fz;
    p.tx[pair.j] += l.tkx; p.ty[pair.j] += l.tky; p.tz[pair.j] += l.tkz;
  }
}

double HertzContact::energy(const ParticleStore& p) const {
  if (m_gatheredEnergy) return *m_gatheredEnergy;
  return sumEnergy(energyTerms(p));
}

std::vector<HertzContact::EnergyTerm> HertzContact::energyTerms(const ParticleStore& p) const {
  std::vector<EnergyTerm> terms;
  if (!m_params.enabled || !m_listValid) return terms;
  const double eStar = m_params.youngModulus / (2.0 * (1.0 - m_params.poissonRatio * m_params.poissonRatio));
  const std::uint8_t* evaluated = m_domain ? m_domain->evaluated().data() : nullptr;
  const std::int32_t* whole = m_domain ? m_domain->wholeIndex().data() : nullptr;
  auto key = [whole](std::int32_t k) { return static_cast<std::int64_t>(whole ? whole[k] : k); };
  // Each touching pair once, by the owner of its end of lower whole index.
  auto add = [&](std::int32_t i, std::int32_t k, double reach) {
    const std::int32_t first = key(i) < key(k) ? i : k;
    if (evaluated && !evaluated[first]) return;
    const double dx = p.x[k] - p.x[i], dy = p.y[k] - p.y[i], dz = p.z[k] - p.z[i];
    const double d = std::sqrt(dx * dx + dy * dy + dz * dz);
    const double overlap = reach - d;
    if (overlap <= 0) return;
    const double rStar = p.radius[i] * p.radius[k] / (p.radius[i] + p.radius[k]);
    terms.push_back({std::min(key(i), key(k)), std::max(key(i), key(k)),
                     8.0 / 15.0 * eStar * std::sqrt(rStar) * std::pow(overlap, 2.5)});
  };
  const std::size_t rows = m_start.empty() ? 0 : m_start.size() - 1;
  for (std::size_t a = 0; a < rows; ++a)
    for (std::int32_t s = m_start[a]; s < m_start[a + 1]; ++s)
      if (key(static_cast<std::int32_t>(a)) < key(m_neighbors[s])) add(static_cast<std::int32_t>(a), m_neighbors[s], m_reach[s]);
  for (const Pair& pair : m_brokenPairs)
    add(pair.i, pair.j, std::min(p.radius[pair.i] + p.radius[pair.j], pair.restLength));
  return terms;
}

double HertzContact::sumEnergy(std::vector<EnergyTerm> terms) {
  std::stable_sort(terms.begin(), terms.end(), [](const EnergyTerm& u, const EnergyTerm& v) {
    return u.first != v.first ? u.first < v.first : u.second < v.second;
  });
  double e = 0;
  for (const EnergyTerm& t : terms) e += t.energy;
  return e;
}

void HertzContact::exchangeState(StateArchive& archive) {
  StateGroup group(archive, "contact");
  archive.value("list_valid", m_listValid);
  archive.value("skin", m_skin);
  archive.array("start", m_start), archive.array("neighbors", m_neighbors);
  archive.array("reach", m_reach), archive.array("gap0", m_gap0);
  archive.array("x0", m_x0), archive.array("y0", m_y0), archive.array("z0", m_z0);
  archive.value("active_level", m_activeLevel);
  archive.array("active_start", m_activeStart), archive.array("active_neighbors", m_activeNeighbors);
  archive.array("active_reach", m_activeReach);
  archive.records("broken_pairs", m_brokenPairs);
}

}  // namespace rupture
