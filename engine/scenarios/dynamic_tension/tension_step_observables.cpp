#include "scenarios/dynamic_tension/tension_step_observables.hpp"

#include <algorithm>
#include <array>
#include <limits>

namespace rupture {

TensionStepObservables::TensionStepObservables(const TensionLoading& loading, const Subdomain* part)
    : m_loading(loading), m_part(part) {
  if (!part) return;
  const TensionGeometry& g = loading.geometry();
  auto ownedHere = [part](std::int32_t whole) {
    const std::int32_t k = part->localOf(whole);
    return k >= 0 && part->owns(static_cast<std::size_t>(k)) ? k : -1;
  };
  for (int face = 0; face < 2; ++face)
    for (std::int32_t whole : face == 0 ? g.xmin : g.xmax)
      if (const std::int32_t k = ownedHere(whole); k >= 0) {
        m_facesHere.push_back(k);
        m_facesWhole.push_back(whole);
        m_faceOf.push_back(face);
      }
  m_probeHere = ownedHere(loading.probe());
  // The records a rank sends never change in number (below), so each step's gather is one collective.
  const auto mine = static_cast<std::int64_t>(3 * (m_facesHere.size() + (m_probeHere >= 0 ? 1 : 0) + 1));
  for (std::int64_t count : part->communicator().allGather(std::vector<std::int64_t>{mine}))
    m_recordCounts.push_back(static_cast<int>(count));
}

TensionStep TensionStepObservables::measure(const BondedSystem& stepped, bool cancelHere) const {
  const ParticleStore& p = stepped.particles;
  if (!m_part) return {m_loading.strain(p), m_loading.stresses(p), stepped.brokenLastStep, cancelHere};
  // Records of three numbers: (face, whole index, x-load), (2, probe, x), (3, cancel here, bonds
  // broken here).
  std::vector<double> mine;
  mine.reserve(3 * m_facesHere.size() + 6);
  for (std::size_t t = 0; t < m_facesHere.size(); ++t)
    mine.insert(mine.end(), {m_faceOf[t], static_cast<double>(m_facesWhole[t]), p.fx[m_facesHere[t]]});
  if (m_probeHere >= 0) mine.insert(mine.end(), {2.0, static_cast<double>(m_loading.probe()), p.x[m_probeHere]});
  mine.insert(mine.end(), {3.0, cancelHere ? 1.0 : 0.0, static_cast<double>(m_part->brokenLastStepHere())});
  const std::vector<double> all = m_part->communicator().allGather(mine, m_recordCounts);
  std::vector<std::array<double, 3>> records(all.size() / 3);
  for (std::size_t r = 0; r < records.size(); ++r) records[r] = {all[3 * r], all[3 * r + 1], all[3 * r + 2]};
  std::sort(records.begin(), records.end(),
            [](const auto& a, const auto& b) { return a[0] != b[0] ? a[0] < b[0] : a[1] < b[1]; });
  double load[2] = {0.0, 0.0}, probeX = std::numeric_limits<double>::quiet_NaN(), broken = 0;
  bool cancelled = false;
  for (const auto& r : records) {
    if (r[0] < 2) {
      load[static_cast<int>(r[0])] += r[2];
    } else if (r[0] == 2) {
      probeX = r[2];
    } else {
      broken += r[2];
      cancelled = cancelled || r[1] != 0;
    }
  }
  return {m_loading.strainAt(probeX), m_loading.stressesFrom(load[0], load[1]), static_cast<std::size_t>(broken),
          cancelled};
}

}  // namespace rupture
