#include "distributed/contact_halo.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

namespace rupture {

namespace {

/// What a rank sends of each particle when it first becomes another's ghost, in message order.
constexpr std::size_t kCandidateValues = 13;  // whole index, x, v, ω (9), radius, mass, inertia
/// What a ghost takes from its owner each step: position, velocity, spin.
constexpr std::size_t kStepValues = 9;

template <class F>
void forEachStepArray(ParticleStore& p, F&& f) {
  for (auto* v : {&p.x, &p.y, &p.z, &p.vx, &p.vy, &p.vz, &p.wx, &p.wy, &p.wz}) f(*v);
}

}  // namespace

ContactHalo::ContactHalo(Communicator comm, BondedSystem& system, std::vector<std::int32_t> global,
                         std::vector<std::uint8_t> owned, std::vector<BondStore::CutPair> cutPairs, double meanRadius,
                         double maxRadius)
    : m_comm(comm),
      m_system(&system),
      m_base(global.size()),
      m_baseGlobal(std::move(global)),
      m_baseOwned(std::move(owned)),
      m_cutPairs(std::move(cutPairs)),
      m_meanRadius(meanRadius),
      m_maxRadius(maxRadius),
      m_send(static_cast<std::size_t>(comm.size())),
      m_receive(static_cast<std::size_t>(comm.size())) {
  adoptGhosts({});
}

std::int32_t ContactHalo::baseLocalOf(std::int32_t global) const {
  const auto it = std::lower_bound(m_baseGlobal.begin(), m_baseGlobal.end(), global);
  return it != m_baseGlobal.end() && *it == global ? static_cast<std::int32_t>(it - m_baseGlobal.begin()) : -1;
}

void ContactHalo::adoptGhosts(const std::vector<std::int32_t>& appended) {
  m_evaluated = m_baseOwned;
  m_evaluated.resize(m_base + appended.size(), 0);
  m_wholeIndex = m_baseGlobal;
  m_wholeIndex.insert(m_wholeIndex.end(), appended.begin(), appended.end());
  // The pre-cracked pairs both of whose ends are here, in local indices: contact touches them at
  // their rest length (HertzContact's reach).
  auto localOf = [&](std::int32_t g) -> std::int32_t {
    if (const std::int32_t k = baseLocalOf(g); k >= 0) return k;
    const auto it = std::lower_bound(appended.begin(), appended.end(), g);
    return it != appended.end() && *it == g ? static_cast<std::int32_t>(m_base + (it - appended.begin())) : -1;
  };
  std::vector<BondStore::CutPair>& cut = m_system->bonds.cutPairs;
  cut.clear();
  for (const BondStore::CutPair& c : m_cutPairs) {
    const std::int32_t i = localOf(c.i), j = localOf(c.j);
    if (i >= 0 && j >= 0) cut.push_back({i, j, c.restLength});
  }
  m_sendBuffers.resize(m_send.size());
  m_receiveBuffers.resize(m_receive.size());
  for (std::size_t r = 0; r < m_send.size(); ++r) {
    m_sendBuffers[r].assign(kStepValues * m_send[r].size(), 0.0);
    m_receiveBuffers[r].assign(kStepValues * m_receive[r].size(), 0.0);
  }
}

void ContactHalo::gatherCandidates(double skin, double maxRadius) {
  const int ranks = m_comm.size(), me = m_comm.rank();
  m_system->setParticleCount(m_base, m_base);  // the last rebuild's ghosts by distance go
  ParticleStore& p = m_system->particles;

  // The owned particles' bounding box (empty: lower above upper), every rank's on every rank.
  constexpr double inf = std::numeric_limits<double>::infinity();
  std::vector<double> box{inf, inf, inf, -inf, -inf, -inf};
  for (std::size_t k = 0; k < m_base; ++k) {
    if (!m_baseOwned[k]) continue;
    const std::array<double, 3> at{p.x[k], p.y[k], p.z[k]};
    for (int a = 0; a < 3; ++a) {
      box[a] = std::min(box[a], at[a]);
      box[3 + a] = std::max(box[3 + a], at[a]);
    }
  }
  const std::vector<double> boxes = m_comm.allGather(box);

  // Each other rank gets the owned particles that could touch one of its own before the next
  // rebuild: the centre distance of a listed pair is below R_i + R_k + skin.
  for (int r = 0; r < ranks; ++r) {
    std::vector<std::int32_t>& send = m_send[static_cast<std::size_t>(r)];
    send.clear();
    if (r == me) continue;
    const double* lo = &boxes[6 * static_cast<std::size_t>(r)];
    const double* hi = lo + 3;
    if (lo[0] > hi[0]) continue;  // it owns nothing
    for (std::size_t k = 0; k < m_base; ++k) {
      if (!m_baseOwned[k]) continue;
      const std::array<double, 3> at{p.x[k], p.y[k], p.z[k]};
      double d2 = 0;
      for (int a = 0; a < 3; ++a) {
        const double out = std::max({0.0, lo[a] - at[a], at[a] - hi[a]});
        d2 += out * out;
      }
      // A relative slack of 1e-9: the box distance and a pair's distance round differently, and
      // a candidate too many costs nothing (the lists test every pair's own distance).
      const double reach = (p.radius[k] + maxRadius + skin) * (1.0 + 1e-9);
      if (d2 < reach * reach) send.push_back(static_cast<std::int32_t>(k));
    }
  }

  // How many each rank sends each other, then the particles.
  std::vector<double> countOut(static_cast<std::size_t>(ranks), 0.0), countIn(static_cast<std::size_t>(ranks), 0.0);
  std::vector<Communicator::Message> sends, receives;
  for (int r = 0; r < ranks; ++r) {
    if (r == me) continue;
    countOut[r] = static_cast<double>(m_send[r].size());
    sends.push_back({r, &countOut[r], 1});
    receives.push_back({r, &countIn[r], 1});
  }
  m_comm.exchange(sends, receives);
  std::vector<std::vector<double>> out(static_cast<std::size_t>(ranks)), in(static_cast<std::size_t>(ranks));
  sends.clear();
  receives.clear();
  for (int r = 0; r < ranks; ++r) {
    if (r == me) continue;
    for (std::int32_t k : m_send[r])
      out[r].insert(out[r].end(), {static_cast<double>(m_baseGlobal[k]), p.x[k], p.y[k], p.z[k], p.vx[k], p.vy[k], p.vz[k],
                                   p.wx[k], p.wy[k], p.wz[k], p.radius[k], p.mass[k], p.inertia[k]});
    in[r].resize(kCandidateValues * static_cast<std::size_t>(countIn[r]));
    if (!out[r].empty()) sends.push_back({r, out[r].data(), out[r].size()});
    if (!in[r].empty()) receives.push_back({r, in[r].data(), in[r].size()});
  }
  m_comm.exchange(sends, receives);

  // The received particles this rank does not hold yet are appended in whole-sample order.
  std::vector<std::int32_t> appended;
  for (int r = 0; r < ranks; ++r)
    for (std::size_t t = 0; t < in[r].size(); t += kCandidateValues) {
      const auto g = static_cast<std::int32_t>(in[r][t]);
      if (baseLocalOf(g) < 0) appended.push_back(g);
    }
  std::sort(appended.begin(), appended.end());
  if (std::adjacent_find(appended.begin(), appended.end()) != appended.end())
    throw std::logic_error("ContactHalo: a particle received from two ranks");
  m_system->setParticleCount(m_base + appended.size(), m_base);
  for (int r = 0; r < ranks; ++r) {
    std::vector<std::int32_t>& receive = m_receive[static_cast<std::size_t>(r)];
    receive.clear();
    for (std::size_t t = 0; t < in[r].size(); t += kCandidateValues) {
      const double* v = &in[r][t];
      const auto g = static_cast<std::int32_t>(v[0]);
      std::int32_t k = baseLocalOf(g);
      if (k < 0) k = static_cast<std::int32_t>(m_base + (std::lower_bound(appended.begin(), appended.end(), g) - appended.begin()));
      receive.push_back(k);
      p.x[k] = v[1]; p.y[k] = v[2]; p.z[k] = v[3];
      p.vx[k] = v[4]; p.vy[k] = v[5]; p.vz[k] = v[6];
      p.wx[k] = v[7]; p.wy[k] = v[8]; p.wz[k] = v[9];
      p.radius[k] = v[10]; p.mass[k] = v[11]; p.inertia[k] = v[12];
    }
  }
  adoptGhosts(appended);
}

void ContactHalo::refresh(ParticleStore& p) {
  std::vector<Communicator::Message> sends, receives;
  for (std::size_t r = 0; r < m_send.size(); ++r) {
    if (!m_send[r].empty()) {
      double* out = m_sendBuffers[r].data();
      forEachStepArray(p, [&](const std::vector<double>& v) {
        for (std::int32_t k : m_send[r]) *out++ = v[k];
      });
      sends.push_back({static_cast<int>(r), m_sendBuffers[r].data(), m_sendBuffers[r].size()});
    }
    if (!m_receive[r].empty())
      receives.push_back({static_cast<int>(r), m_receiveBuffers[r].data(), m_receiveBuffers[r].size()});
  }
  if (sends.empty() && receives.empty()) return;
  m_comm.exchange(sends, receives);
  for (std::size_t r = 0; r < m_receive.size(); ++r) {
    const double* in = m_receiveBuffers[r].data();
    forEachStepArray(p, [&](std::vector<double>& v) {
      for (std::int32_t k : m_receive[r]) v[k] = *in++;
    });
  }
}

std::size_t ContactHalo::ghostCount() const {
  std::size_t n = 0;
  for (const auto& r : m_receive) n += r.size();
  return n;
}

std::size_t ContactHalo::bytesSent() const {
  std::size_t bytes = 0;
  for (const auto& b : m_sendBuffers) bytes += b.size() * sizeof(double);
  return bytes;
}

void ContactHalo::exchangeState(StateArchive& archive) {
  StateGroup group(archive, "contact_ghosts");
  ParticleStore& p = m_system->particles;
  std::vector<std::int32_t> appended(m_wholeIndex.begin() + static_cast<std::ptrdiff_t>(m_base), m_wholeIndex.end());
  std::vector<double> radius, mass, inertia;
  if (!archive.loading())
    for (std::size_t k = m_base; k < p.size(); ++k) {
      radius.push_back(p.radius[k]);
      mass.push_back(p.mass[k]);
      inertia.push_back(p.inertia[k]);
    }
  archive.array("appended", appended);
  archive.array("radius", radius), archive.array("mass", mass), archive.array("inertia", inertia);
  // Each rank's send and receive lists, flattened with their lengths.
  std::vector<std::int32_t> sendCounts, sends, receiveCounts, receivesFlat;
  if (!archive.loading())
    for (std::size_t r = 0; r < m_send.size(); ++r) {
      sendCounts.push_back(static_cast<std::int32_t>(m_send[r].size()));
      sends.insert(sends.end(), m_send[r].begin(), m_send[r].end());
      receiveCounts.push_back(static_cast<std::int32_t>(m_receive[r].size()));
      receivesFlat.insert(receivesFlat.end(), m_receive[r].begin(), m_receive[r].end());
    }
  archive.array("send_counts", sendCounts), archive.array("send", sends);
  archive.array("receive_counts", receiveCounts), archive.array("receive", receivesFlat);
  if (!archive.loading()) return;

  if (sendCounts.size() != m_send.size() || receiveCounts.size() != m_receive.size() ||
      radius.size() != appended.size() || mass.size() != appended.size() || inertia.size() != appended.size())
    throw CheckpointError("the checkpoint's contact ghosts were saved for another rank count");
  // A damaged file must not index outside the sub-domain.
  auto countsAdd = [](const std::vector<std::int32_t>& counts, std::size_t listed) {
    std::size_t sum = 0;
    for (std::int32_t c : counts) {
      if (c < 0) return false;
      sum += static_cast<std::size_t>(c);
    }
    return sum == listed;
  };
  const auto size = static_cast<std::int32_t>(m_base + appended.size());
  auto outside = [size](const std::vector<std::int32_t>& v) {
    return std::any_of(v.begin(), v.end(), [size](std::int32_t k) { return k < 0 || k >= size; });
  };
  if (!countsAdd(sendCounts, sends.size()) || !countsAdd(receiveCounts, receivesFlat.size()) || outside(sends) ||
      outside(receivesFlat) || !std::is_sorted(appended.begin(), appended.end()))
    throw CheckpointError("the checkpoint's contact ghosts' lists are inconsistent");
  for (std::size_t r = 0, s = 0, t = 0; r < m_send.size(); ++r) {
    m_send[r].assign(sends.begin() + static_cast<std::ptrdiff_t>(s), sends.begin() + static_cast<std::ptrdiff_t>(s + sendCounts[r]));
    m_receive[r].assign(receivesFlat.begin() + static_cast<std::ptrdiff_t>(t),
                        receivesFlat.begin() + static_cast<std::ptrdiff_t>(t + receiveCounts[r]));
    s += static_cast<std::size_t>(sendCounts[r]);
    t += static_cast<std::size_t>(receiveCounts[r]);
  }
  m_system->setParticleCount(m_base + appended.size(), m_base);
  for (std::size_t a = 0; a < appended.size(); ++a) {
    p.radius[m_base + a] = radius[a];
    p.mass[m_base + a] = mass[a];
    p.inertia[m_base + a] = inertia[a];
  }
  adoptGhosts(appended);
}

}  // namespace rupture
