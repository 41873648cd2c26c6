#include "core/bond_store.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <tuple>
#include <utility>

namespace rupture {

std::size_t BondStore::add(const ParticleStore& p, std::size_t a, std::size_t b) {
  if (a > b) std::swap(a, b);  // order by index (= id) so both ends agree on the bond's sense
  const double dx = p.x[b] - p.x[a], dy = p.y[b] - p.y[a], dz = p.z[b] - p.z[a];
  const double length = std::sqrt(dx * dx + dy * dy + dz * dz);
  i.push_back(static_cast<std::int32_t>(a));
  j.push_back(static_cast<std::int32_t>(b));
  restLength.push_back(length);
  n0x.push_back(dx / length);
  n0y.push_back(dy / length);
  n0z.push_back(dz / length);
  intact.push_back(1.0);
  stiffness.push_back(1.0);
  threshold.push_back(std::numeric_limits<double>::infinity());
  strength.push_back(1.0);
  return i.size() - 1;
}

void BondStore::finalize(std::size_t particleCount) {
  const std::size_t n = size();
  for (auto* v : {&fjx, &fjy, &fjz, &tix, &tiy, &tiz, &tjx, &tjy, &tjz, &failureMeasure})
    v->assign(n, 0.0);
  failureThreshold.resize(n);
  for (std::size_t b = 0; b < n; ++b) failureThreshold[b] = threshold[b] * strength[b];
  incidenceStart.assign(particleCount + 1, 0);
  for (std::size_t b = 0; b < n; ++b) {
    ++incidenceStart[i[b] + 1];
    ++incidenceStart[j[b] + 1];
  }
  for (std::size_t k = 0; k < particleCount; ++k) incidenceStart[k + 1] += incidenceStart[k];
  incidence.assign(2 * n, 0);
  std::vector<std::int32_t> cursor(incidenceStart.begin(), incidenceStart.end() - 1);
  for (std::size_t b = 0; b < n; ++b) {  // ascending b: a fixed summation order per particle
    incidence[cursor[i[b]]++] = static_cast<std::int32_t>(2 * b);
    incidence[cursor[j[b]]++] = static_cast<std::int32_t>(2 * b + 1);
  }
}

void BondStore::moveBond(std::size_t from, std::size_t to) {
  forEachReferenceArray([&](std::vector<double>& v) { v[to] = v[from]; });
}

void BondStore::truncate(std::size_t m) {
  forEachReferenceArray([&](std::vector<double>& v) { v.resize(m); });
  i.resize(m);
  j.resize(m);
}

void BondStore::remap(const std::vector<std::int32_t>& newIndex) {
  std::size_t m = 0;
  for (std::size_t b = 0; b < size(); ++b) {
    const std::int32_t a = newIndex[i[b]], c = newIndex[j[b]];
    if (a < 0 || c < 0) continue;
    i[m] = a; j[m] = c;
    moveBond(b, m++);
  }
  truncate(m);
  std::size_t kept = 0;
  for (const CutPair& pair : cutPairs) {
    const std::int32_t a = newIndex[pair.i], c = newIndex[pair.j];
    if (a >= 0 && c >= 0) cutPairs[kept++] = {a, c, pair.restLength};
  }
  cutPairs.resize(kept);
}

void BondStore::renumber(const std::vector<std::int32_t>& newIndex) {
  const std::size_t m = size();
  for (std::size_t b = 0; b < m; ++b) {
    std::int32_t a = newIndex[i[b]], c = newIndex[j[b]];
    if (a > c) {  // the sense of a bond is i -> j: exact negation, no rounding
      std::swap(a, c);
      n0x[b] = -n0x[b]; n0y[b] = -n0y[b]; n0z[b] = -n0z[b];
    }
    i[b] = a;
    j[b] = c;
  }
  std::vector<std::size_t> order(m);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return std::tie(i[a], j[a], a) < std::tie(i[b], j[b], b); });
  auto reorder = [&](auto& v) {
    auto old = v;
    for (std::size_t b = 0; b < m; ++b) v[b] = old[order[b]];
  };
  reorder(i);
  reorder(j);
  forEachReferenceArray(reorder);
  for (CutPair& pair : cutPairs) {
    pair.i = newIndex[pair.i];
    pair.j = newIndex[pair.j];
  }
}

BondStore BondStore::subset(const std::vector<std::uint8_t>& keep, const std::vector<std::int32_t>& newIndex) const {
  if (keep.size() != size()) throw std::logic_error("BondStore::subset: keep flags of the wrong size");
  std::vector<std::size_t> kept;
  for (std::size_t b = 0; b < size(); ++b)
    if (keep[b] && newIndex[i[b]] >= 0 && newIndex[j[b]] >= 0) kept.push_back(b);
  BondStore out;
  out.i.reserve(kept.size());
  out.j.reserve(kept.size());
  for (std::size_t b : kept) {
    out.i.push_back(newIndex[i[b]]);
    out.j.push_back(newIndex[j[b]]);
  }
  std::vector<std::vector<double>> arrays;
  forEachReferenceArrayOf(*this, hasFibres(), [&](const std::vector<double>& v) {
    std::vector<double>& copy = arrays.emplace_back();
    copy.reserve(kept.size());
    for (std::size_t b : kept) copy.push_back(v[b]);
  });
  std::size_t next = 0;
  forEachReferenceArrayOf(out, hasFibres(), [&](std::vector<double>& v) { v = std::move(arrays[next++]); });
  for (const CutPair& pair : cutPairs) {
    const std::int32_t a = newIndex[pair.i], c = newIndex[pair.j];
    if (a >= 0 && c >= 0) out.cutPairs.push_back({a, c, pair.restLength});
  }
  return out;
}

void BondStore::filter(const std::vector<std::uint8_t>& keep) {
  std::size_t m = 0;
  for (std::size_t b = 0; b < size(); ++b) {
    if (!keep[b]) continue;
    i[m] = i[b]; j[m] = j[b];
    moveBond(b, m++);
  }
  truncate(m);
}

double BondStore::firstDamageFactor(std::size_t b) const {
  if (!hasFibres()) return 1.0;
  double left = 1.0;
  for (std::size_t c = 0; c < fibreFactor.size(); ++c) {
    if (fibreIntegrity[c][b] < left) return fibreFactor[c][b];
    left = fibreIntegrity[c][b];
  }
  return std::numeric_limits<double>::infinity();
}

std::size_t BondStore::intactCount() const {
  std::size_t n = 0;
  for (double v : intact) n += v > 0.0;
  return n;
}

std::vector<int> BondStore::coordination(std::size_t particleCount) const {
  std::vector<int> z(particleCount, 0);
  for (std::size_t b = 0; b < size(); ++b)
    if (intact[b] > 0.0) { ++z[i[b]]; ++z[j[b]]; }
  return z;
}

void BondStore::exchangeState(StateArchive& archive, bool torques) {
  StateGroup group(archive, "bonds");
  archive.expectCount("bonds", size());
  archive.array("intact", intact);
  archive.array("fjx", fjx), archive.array("fjy", fjy), archive.array("fjz", fjz);
  if (torques) {
    archive.array("tix", tix), archive.array("tiy", tiy), archive.array("tiz", tiz);
    archive.array("tjx", tjx), archive.array("tjy", tjy), archive.array("tjz", tjz);
  }
  archive.array("failure_measure", failureMeasure);
}

}  // namespace rupture
