// The SPH store's per-particle arrays (core/staggered_allocator.hpp): each starts at its own line
// offset within a page, so that a loop over many of them does not map them all to one cache set,
// also after the re-sort has passed the buffers from field to field; and the arrays behave as
// ordinary vectors (contents kept through growth, copies and permutations).
#include <gtest/gtest.h>

#include <cstdint>
#include <set>
#include <vector>

#include "core/staggered_allocator.hpp"
#include "sph/fluid_particles.hpp"

namespace rupture::sph {
namespace {

std::uintptr_t offsetInPage(const void* p) { return reinterpret_cast<std::uintptr_t>(p) % 4096; }

/// The page offsets of the double fields the integrator and the pair loop walk together.
std::vector<std::uintptr_t> fieldOffsets(const FluidParticles& p) {
  std::vector<std::uintptr_t> offsets;
  for (const ParticleArray<double>* f : {&p.x, &p.y, &p.z, &p.vx, &p.vy, &p.vz, &p.rho, &p.vxEst, &p.vyEst, &p.vzEst,
                                         &p.rhoEst, &p.pressure, &p.ax, &p.ay, &p.az, &p.drho, &p.mass})
    offsets.push_back(offsetInPage(f->data()));
  return offsets;
}

FluidParticles block(std::size_t n) {
  FluidParticles p;
  for (std::size_t k = 0; k < n; ++k)
    p.add(0.01 * static_cast<double>(k % 50), 0.01 * static_cast<double>(k / 50 % 50), 0.01 * static_cast<double>(k / 2500),
          1e-3, 1000.0 + static_cast<double>(k), k % 3 == 0 ? 0 : kFluid);
  return p;
}

TEST(ParticleArrays, FieldsOfALargeStoreStartAtDistinctCacheLinesOfThePage) {
  // From the smallest store the staggered path serves (16 KiB a field) to W3's 164,608 particles;
  // malloc would put every field of these 16 bytes into a page: one offset for all 17.
  for (std::size_t n : {2048u, 20000u, 164608u}) {
    FluidParticles p = block(n);
    std::vector<std::uintptr_t> offsets = fieldOffsets(p);
    for (std::uintptr_t offset : offsets) EXPECT_EQ(offset % 64, 0u) << n;  // 64-byte aligned
    EXPECT_EQ(std::set<std::uintptr_t>(offsets.begin(), offsets.end()).size(), offsets.size()) << n;

    // The re-sort swaps each field's buffer with one scratch buffer: still 17 distinct offsets,
    // and the contents reordered as asked.
    std::vector<std::int32_t> reverse(n);
    for (std::size_t k = 0; k < n; ++k) reverse[k] = static_cast<std::int32_t>(n - 1 - k);
    ParticleArray<double> scratch;
    ParticleArray<std::int32_t> indexScratch;
    p.permute(reverse, scratch, indexScratch);
    offsets = fieldOffsets(p);
    EXPECT_EQ(std::set<std::uintptr_t>(offsets.begin(), offsets.end()).size(), offsets.size()) << n;
    EXPECT_EQ(p.rho.front(), 1000.0 + static_cast<double>(n - 1)) << n;
    EXPECT_EQ(p.rho.back(), 1000.0) << n;
    EXPECT_EQ(p.id.front(), static_cast<std::int32_t>(n - 1)) << n;
  }
}

TEST(ParticleArrays, KeepTheirContentsThroughGrowthCopiesAndShrinking) {
  // Sizes across the small (plain operator new) and staggered paths, growth across both.
  ParticleArray<double> a;
  for (int k = 0; k < 50000; ++k) a.push_back(0.5 * k);
  for (int k = 0; k < 50000; ++k) ASSERT_EQ(a[k], 0.5 * k);
  ParticleArray<double> copy = a;
  EXPECT_EQ(copy, a);
  EXPECT_NE(copy.data(), a.data());
  a.resize(100);
  a.shrink_to_fit();  // back to the small path
  EXPECT_EQ(a.size(), 100u);
  EXPECT_EQ(a[99], 49.5);
  ParticleArray<std::int32_t> small(10, 7);
  EXPECT_EQ(small[9], 7);
  EXPECT_EQ(offsetInPage(small.data()) % 64, 0u);
}

}  // namespace
}  // namespace rupture::sph
