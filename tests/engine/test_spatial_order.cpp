// Spatial numbering of packed samples (samples/spatial_order.hpp): the renumbered sample is the same
// sample (every bond still describes its two ends in their rest state, in the sense i -> j), the
// bonds are in (i, j) order as the incidence lists assume, and neighbours in space got neighbouring
// indices (the point of it). Over several sample seeds, 2D and 3D, as packRandomSample makes them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <vector>

#include "samples/sample_builder.hpp"
#include "sample_test_support.hpp"

using namespace rupture;
using rupture::testing::ceramic;
using rupture::testing::porousSpec;

namespace {

struct Case {
  int dimension;
  std::uint64_t seed;
};

class SpatialOrder : public ::testing::TestWithParam<Case> {};

TEST_P(SpatialOrder, BondsDescribeTheirEndsAndNeighboursAreNumberedClose) {
  BondedSystem system;
  buildSample(porousSpec(GetParam().dimension, GetParam().seed), ceramic(), system);
  const ParticleStore& p = system.particles;
  const BondStore& b = system.bonds;
  ASSERT_GT(b.size(), 1000u);
  std::vector<std::int64_t> gaps;
  for (std::size_t k = 0; k < b.size(); ++k) {
    const std::int32_t i = b.i[k], j = b.j[k];
    ASSERT_LT(i, j) << "bond " << k;
    if (k > 0) {
      ASSERT_TRUE(b.i[k - 1] < i || (b.i[k - 1] == i && b.j[k - 1] < j)) << "bond " << k << " out of (i, j) order";
    }
    // The rest state is the built configuration: the bond's length and its sense i -> j.
    const double dx = p.x[j] - p.x[i], dy = p.y[j] - p.y[i], dz = p.z[j] - p.z[i];
    const double length = std::sqrt(dx * dx + dy * dy + dz * dz);
    ASSERT_NEAR(b.restLength[k], length, 1e-12 * length) << "bond " << k;
    ASSERT_NEAR(b.n0x[k], dx / length, 1e-12) << "bond " << k;
    ASSERT_NEAR(b.n0y[k], dy / length, 1e-12) << "bond " << k;
    ASSERT_NEAR(b.n0z[k], dz / length, 1e-12) << "bond " << k;
    gaps.push_back(j - i);
  }
  // Packed in random order the median index gap of a bond is about a third of the elements; in
  // strips 8 radii wide it is about a strip's population. A tenth is well above the latter.
  std::nth_element(gaps.begin(), gaps.begin() + gaps.size() / 2, gaps.end());
  EXPECT_LT(gaps[gaps.size() / 2], static_cast<std::int64_t>(p.size() / 10)) << p.size() << " elements";
}

INSTANTIATE_TEST_SUITE_P(PackedSamples, SpatialOrder,
                         ::testing::Values(Case{2, 1}, Case{2, 2}, Case{2, 3}, Case{3, 1}, Case{3, 2}));

}  // namespace
