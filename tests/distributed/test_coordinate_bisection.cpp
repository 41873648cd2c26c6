// Recursive coordinate bisection (distributed/coordinate_bisection.hpp): every part gets its share
// of the work (particles plus bond ends) to within the largest single particle's work, parts are
// bricks across the longest extent, and the partition depends only on the sample.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <numeric>

#include "distributed/coordinate_bisection.hpp"
#include "distributed_test_support.hpp"

namespace rupture {
namespace {

TEST(CoordinateBisection, EveryPartGetsItsShareOfTheWorkAndTheSameSampleGivesTheSameParts) {
  const BondedSystem s = testing::pmbBlock();
  const std::size_t n = s.particles.size();
  std::vector<double> work(n, 1.0);
  for (std::size_t b = 0; b < s.bonds.size(); ++b) {
    work[s.bonds.i[b]] += 1;
    work[s.bonds.j[b]] += 1;
  }
  const double total = std::accumulate(work.begin(), work.end(), 0.0);
  const double largest = *std::max_element(work.begin(), work.end());
  for (int parts : {1, 2, 3, 4, 5, 7, 8}) {
    const std::vector<int> owner = bisectCoordinates(s.particles, s.bonds, parts);
    std::vector<double> share(parts, 0.0);
    for (std::size_t k = 0; k < n; ++k) {
      ASSERT_GE(owner[k], 0);
      ASSERT_LT(owner[k], parts);
      share[owner[k]] += work[k];
    }
    // Each cut misses its target by at most half a particle's work, and a part is cut at most
    // log2(parts) + 1 times.
    const double levels = std::ceil(std::log2(parts)) + 1;
    for (int r = 0; r < parts; ++r) EXPECT_NEAR(share[r], total / parts, levels * largest) << parts << " parts, part " << r;
    EXPECT_EQ(owner, bisectCoordinates(s.particles, s.bonds, parts));
  }
}

TEST(CoordinateBisection, TwoPartsCutAcrossTheLongestEdge) {
  const BondedSystem s = testing::pmbBlock();  // 14 mm along x, 10 along y, 8 along z
  const std::vector<int> owner = bisectCoordinates(s.particles, s.bonds, 2);
  double leftMax = -1, rightMin = 1;
  for (std::size_t k = 0; k < s.particles.size(); ++k) {
    if (owner[k] == 0) leftMax = std::max(leftMax, s.particles.x[k]);
    else rightMin = std::min(rightMin, s.particles.x[k]);
  }
  EXPECT_LE(leftMax, rightMin);  // one plane x = const separates the parts
  EXPECT_NEAR(0.5 * (leftMax + rightMin), 7e-3, 1e-3);
}

TEST(CoordinateBisection, MorePartsThanParticlesIsRefusedNamingBoth) {
  ParticleStore p;
  p.add(0, 0, 0, 1);
  BondStore b;
  try {
    bisectCoordinates(p, b, 2);
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("2 sub-domains for 1 particles"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rupture
