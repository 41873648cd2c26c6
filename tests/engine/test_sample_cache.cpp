// The packed-sample cache (scenarios/bonded/sample_cache.hpp): a second build of the same sample block
// reads the entry and gives the same system as a fresh build; an entry that was damaged (truncated,
// or bytes changed) is rebuilt and replaced, never used; another sample or another density gets
// the right system.
#include <gtest/gtest.h>

#include <atomic>
#include <filesystem>
#include <fstream>

#include "samples/sample_builder.hpp"
#include "scenarios/bonded/sample_cache.hpp"
#include "sample_test_support.hpp"
#include "support/test_support.hpp"

namespace rupture {
namespace {

namespace fs = std::filesystem;
using rupture::testing::ScratchDir;
using rupture::testing::ceramic;

SampleSpec porousSpec(std::uint64_t seed) {
  SampleSpec s;
  s.dimension = 2;
  s.size = {0.2e-6, 0.2e-6, 0};
  s.elementRadius = 4e-9;
  s.porosity = 0.11;
  s.poreRadius = {0.02e-6, 0.05e-6};
  s.seed = seed;
  return s;
}

/// The same elements (positions, radii, masses, inertia), bonds (pairs, rest state) and report.
void expectSameSample(const BondedSystem& a, const SampleReport& ra, const BondedSystem& b, const SampleReport& rb) {
  ASSERT_EQ(a.particles.size(), b.particles.size());
  ASSERT_EQ(a.bonds.size(), b.bonds.size());
  EXPECT_EQ(a.particles.x, b.particles.x);
  EXPECT_EQ(a.particles.y, b.particles.y);
  EXPECT_EQ(a.particles.radius, b.particles.radius);
  for (std::size_t k = 0; k < a.particles.size(); ++k) {
    ASSERT_NEAR(a.particles.mass[k], b.particles.mass[k], 1e-12 * a.particles.mass[k]);
    ASSERT_NEAR(a.particles.inertia[k], b.particles.inertia[k], 1e-12 * a.particles.inertia[k]);
  }
  EXPECT_EQ(a.bonds.i, b.bonds.i);
  EXPECT_EQ(a.bonds.j, b.bonds.j);
  EXPECT_EQ(a.bonds.restLength, b.bonds.restLength);
  EXPECT_EQ(ra.elements, rb.elements);
  EXPECT_EQ(ra.bonds, rb.bonds);
  EXPECT_DOUBLE_EQ(ra.porosity, rb.porosity);
  EXPECT_DOUBLE_EQ(ra.packingFraction, rb.packingFraction);
  EXPECT_NEAR(ra.elementDensity, rb.elementDensity, 1e-12 * ra.elementDensity);
  EXPECT_EQ(ra.pores.size(), rb.pores.size());
}

TEST(SampleCache, SecondBuildReadsTheEntryAndGivesTheSameSample) {
  ScratchDir dir;
  const std::atomic<bool> cancel{false};
  const SampleSpec spec = porousSpec(4);
  BondedSystem fresh, first, second;
  const SampleReport rFresh = buildSample(spec, ceramic(), fresh);
  SampleCacheUse use1, use2;
  const SampleReport r1 = buildSampleCached(spec, ceramic(), first, dir.path().string(), cancel, use1);
  const SampleReport r2 = buildSampleCached(spec, ceramic(), second, dir.path().string(), cancel, use2);
  EXPECT_TRUE(use1.enabled);
  EXPECT_FALSE(use1.fromCache);
  EXPECT_TRUE(use2.fromCache);
  EXPECT_EQ(use1.file, use2.file);
  EXPECT_TRUE(fs::exists(use2.file));
  expectSameSample(fresh, rFresh, first, r1);
  expectSameSample(fresh, rFresh, second, r2);

  // Another density: same entry, masses of the new density (the material is applied after loading).
  BondedSystem heavyFresh, heavyCached;
  SampleCacheUse use3;
  const SampleReport rh = buildSample(spec, ceramic(2 * 6060), heavyFresh);
  const SampleReport rc = buildSampleCached(spec, ceramic(2 * 6060), heavyCached, dir.path().string(), cancel, use3);
  EXPECT_TRUE(use3.fromCache);
  expectSameSample(heavyFresh, rh, heavyCached, rc);

  // Another sample seed: another entry.
  BondedSystem other;
  SampleCacheUse use4;
  buildSampleCached(porousSpec(5), ceramic(), other, dir.path().string(), cancel, use4);
  EXPECT_FALSE(use4.fromCache);
  EXPECT_NE(use4.file, use1.file);
}

TEST(SampleCache, DamagedEntryIsRebuiltNotUsed) {
  ScratchDir dir;
  const std::atomic<bool> cancel{false};
  const SampleSpec spec = porousSpec(6);
  BondedSystem fresh;
  const SampleReport rFresh = buildSample(spec, ceramic(), fresh);
  SampleCacheUse use;
  BondedSystem s;
  buildSampleCached(spec, ceramic(), s, dir.path().string(), cancel, use);
  const std::string file = use.file;
  const auto size = fs::file_size(file);

  // Every damage: bytes changed in the data region, the file cut in half, the file emptied.
  for (int damage = 0; damage < 3; ++damage) {
    SCOPED_TRACE(damage);
    if (damage == 0) {
      std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
      for (std::uintmax_t at = size / 2; at < size / 2 + 64; ++at) {
        f.seekp(static_cast<std::streamoff>(at));
        f.put('\x5a');
      }
    } else {
      fs::resize_file(file, damage == 1 ? size / 2 : 0);
    }
    BondedSystem rebuilt;
    SampleCacheUse again;
    const SampleReport r = buildSampleCached(spec, ceramic(), rebuilt, dir.path().string(), cancel, again);
    EXPECT_FALSE(again.fromCache);
    expectSameSample(fresh, rFresh, rebuilt, r);
    // The rebuilt entry replaced the damaged one and is used next time.
    BondedSystem reread;
    SampleCacheUse third;
    const SampleReport r3 = buildSampleCached(spec, ceramic(), reread, dir.path().string(), cancel, third);
    EXPECT_TRUE(third.fromCache);
    expectSameSample(fresh, rFresh, reread, r3);
  }
}

TEST(SampleCache, NoDirectoryMeansNoCache) {
  const std::atomic<bool> cancel{false};
  BondedSystem s;
  SampleCacheUse use;
  const SampleReport r = buildSampleCached(porousSpec(4), ceramic(), s, "", cancel, use);
  EXPECT_FALSE(use.enabled);
  EXPECT_FALSE(use.fromCache);
  EXPECT_GT(r.elements, 100u);
}

}  // namespace
}  // namespace rupture
