#include "core/particle_store.hpp"

#include <algorithm>
#include <numbers>
#include <stdexcept>
#include <type_traits>
#include <utility>

namespace rupture {

std::size_t ParticleStore::add(double px, double py, double pz, double r) {
  x.push_back(px); y.push_back(py); z.push_back(pz);
  for (auto* v : {&vx, &vy, &vz, &fx, &fy, &fz, &qx, &qy, &qz, &wx, &wy, &wz, &tx, &ty, &tz})
    v->push_back(0.0);
  qw.push_back(1.0);
  radius.push_back(r);
  mass.push_back(0.0);
  inertia.push_back(0.0);
  volume.push_back(0.0);
  fixedDofs.push_back(0);
  return x.size() - 1;
}

std::vector<std::int32_t> ParticleStore::compact(const std::vector<std::uint8_t>& keep) {
  std::vector<std::int32_t> newIndex(size(), -1);
  std::size_t n = 0;
  for (std::size_t k = 0; k < size(); ++k)
    if (keep[k]) newIndex[k] = static_cast<std::int32_t>(n++);
  auto squeeze = [&](auto& field) {
    std::size_t m = 0;
    for (std::size_t k = 0; k < field.size(); ++k)
      if (keep[k]) field[m++] = field[k];
    field.resize(m);
  };
  forEachArray(squeeze);
  return newIndex;
}

ParticleStore ParticleStore::subset(const std::vector<std::uint8_t>& keep) const {
  const std::size_t n = size();
  if (keep.size() != n) throw std::logic_error("ParticleStore::subset: keep flags of the wrong size");
  const auto count = static_cast<std::size_t>(std::count_if(keep.begin(), keep.end(), [](std::uint8_t k) { return k != 0; }));
  // Each array's kept entries, in the list's order; then moved into the new store's arrays.
  std::vector<std::vector<double>> doubles;
  std::vector<std::uint8_t> dofs;
  forEachArrayOf(*this, [&](const auto& field) {
    std::decay_t<decltype(field)> kept;
    if (!field.empty()) {
      kept.reserve(count);
      for (std::size_t k = 0; k < n; ++k)
        if (keep[k]) kept.push_back(field[k]);
    }
    if constexpr (std::is_same_v<std::decay_t<decltype(field)>, std::vector<double>>) doubles.push_back(std::move(kept));
    else dofs = std::move(kept);
  });
  ParticleStore out;
  out.dimension = dimension;
  std::size_t next = 0;
  forEachArrayOf(out, [&](auto& field) {
    if constexpr (std::is_same_v<std::decay_t<decltype(field)>, std::vector<double>>) field = std::move(doubles[next++]);
    else field = std::move(dofs);
  });
  return out;
}

void ParticleStore::resize(std::size_t n) {
  const std::size_t before = size();
  forEachArray([&](auto& field) {
    if (field.size() == before) field.resize(n);
  });
  if (n > before) std::fill(qw.begin() + static_cast<std::ptrdiff_t>(before), qw.end(), 1.0);
}

std::vector<std::int32_t> ParticleStore::permute(const std::vector<std::size_t>& order) {
  const std::size_t n = size();
  if (order.size() != n) throw std::logic_error("ParticleStore::permute: order of the wrong size");
  std::vector<std::int32_t> newIndex(n, -1);
  for (std::size_t k = 0; k < n; ++k) newIndex[order[k]] = static_cast<std::int32_t>(k);
  forEachArray([&](auto& field) {
    if (field.empty()) return;  // not set yet (e.g. volumes before the masses)
    if (field.size() != n) throw std::logic_error("ParticleStore::permute: a per-particle array of the wrong size");
    auto old = field;
    for (std::size_t k = 0; k < n; ++k) field[k] = old[order[k]];
  });
  return newIndex;
}

void ParticleStore::setMassFromDensity(double elementDensity, double thickness2d) {
  constexpr double pi = std::numbers::pi;
  for (std::size_t k = 0; k < size(); ++k) {
    const double r = radius[k];
    if (dimension == 2) {
      volume[k] = pi * r * r * thickness2d;
      mass[k] = elementDensity * volume[k];
      inertia[k] = 0.5 * mass[k] * r * r;
    } else {
      volume[k] = 4.0 / 3.0 * pi * r * r * r;
      mass[k] = elementDensity * volume[k];
      inertia[k] = 0.4 * mass[k] * r * r;
    }
  }
}

void ParticleStore::exchangeState(StateArchive& archive) {
  StateGroup group(archive, "particles");
  archive.expectCount("particles", size());
  archive.array("x", x), archive.array("y", y), archive.array("z", z);
  archive.array("vx", vx), archive.array("vy", vy), archive.array("vz", vz);
  archive.array("fx", fx), archive.array("fy", fy), archive.array("fz", fz);
  archive.array("qw", qw), archive.array("qx", qx), archive.array("qy", qy), archive.array("qz", qz);
  archive.array("wx", wx), archive.array("wy", wy), archive.array("wz", wz);
  archive.array("tx", tx), archive.array("ty", ty), archive.array("tz", tz);
}

}  // namespace rupture
