// The roots and inverses of the SPH pair loops (simd_lanes.hpp): √x, 1/√x and 1/x from the 14-bit
// hardware estimates and one correction of fourth order (AVX-512), or from the divider (AVX2), must
// be double precision to a few ulp over the range the loops see (r² from the 1e-300 guard up, 1/ρ,
// r² + 0.01 h²), at every width; and the width is chosen by the processor as documented.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "sph/simd_lanes.hpp"

namespace rupture::sph {
namespace {

#ifdef RUPTURE_SPH_AVX2
/// Arguments spread over [1e-300, 1e300] in log and over the mantissas, plus the ends.
std::vector<double> arguments() {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> exponent(-300.0, 300.0);
  std::vector<double> x{1e-300, 1e300, 1.0, 0.25, 4.0, 1e-4, 6.76e-4};
  while (x.size() < 200000) x.push_back(std::pow(10.0, exponent(rng)));
  return x;
}

/// The largest error of f's lanes against `exact`, in units of the exact value's ulp.
template <class L, class Refined, class Exact>
double largestUlpError(Refined refined, Exact exact) {
  const std::vector<double> x = arguments();
  double worst = 0;
  for (std::size_t k = 0; k + L::kWidth <= x.size(); k += L::kWidth) {
    alignas(64) double out[8];
#ifdef RUPTURE_SPH_AVX512
    if constexpr (L::kWidth == 8) _mm512_store_pd(out, refined(_mm512_loadu_pd(&x[k])));
    else
#endif
      _mm256_store_pd(out, refined(_mm256_loadu_pd(&x[k])));
    for (int l = 0; l < L::kWidth; ++l) {
      const long double e = exact(static_cast<long double>(x[k + l]));
      const double ulp = std::nextafter(static_cast<double>(e), INFINITY) - static_cast<double>(e);
      worst = std::max(worst, static_cast<double>(std::fabs(out[l] - e) / ulp));
    }
  }
  return worst;
}
#endif

TEST(SphSimdLanes, RefinedRootInverseRootAndInverseAreDoublePrecision) {
#ifdef RUPTURE_SPH_AVX2
  auto exactInverseSqrt = [](long double x) { return 1.0L / std::sqrt(x); };
  auto exactRoot = [](long double x) { return std::sqrt(x); };
  auto exactInverse = [](long double x) { return 1.0L / x; };
#endif
#ifdef RUPTURE_SPH_AVX512
  // √x and 1/√x from one estimate (rootAndInverse: the pair loop's r and 1/r, the wall sums' r) and
  // 1/x. Measured on the Zen 4 host: 0.93 ulp (√x), 1.14 ulp (1/√x), 1.01 ulp (1/x); a third-order
  // correction would leave about 2¹³ ulp.
  EXPECT_LE(largestUlpError<Lanes8>([](__m512d v) { return rootAndInverse<Lanes8>(v).root; }, exactRoot), 2.0);
  EXPECT_LE(largestUlpError<Lanes4>([](__m256d v) { return rootAndInverse<Lanes4>(v).root; }, exactRoot), 2.0);
  EXPECT_LE(largestUlpError<Lanes8>([](__m512d v) { return rootAndInverse<Lanes8>(v).inverse; }, exactInverseSqrt),
            2.0);
  EXPECT_LE(largestUlpError<Lanes4>([](__m256d v) { return rootAndInverse<Lanes4>(v).inverse; }, exactInverseSqrt),
            2.0);
  EXPECT_LE(largestUlpError<Lanes8>([](__m512d v) { return inverse<Lanes8>(v); }, exactInverse), 2.0);
  EXPECT_LE(largestUlpError<Lanes4>([](__m256d v) { return inverse<Lanes4>(v); }, exactInverse), 2.0);
#endif
#ifdef RUPTURE_SPH_AVX2
  // The AVX2 lanes' √ and ÷: correctly rounded (√x, 1/x), 1/√x from two roundings.
  EXPECT_LE(largestUlpError<Lanes4Avx2>([](__m256d v) { return rootAndInverse<Lanes4Avx2>(v).root; }, exactRoot),
            0.5);
  EXPECT_LE(largestUlpError<Lanes4Avx2>([](__m256d v) { return rootAndInverse<Lanes4Avx2>(v).inverse; },
                                        exactInverseSqrt),
            2.0);
  EXPECT_LE(largestUlpError<Lanes4Avx2>([](__m256d v) { return inverse<Lanes4Avx2>(v); }, exactInverse), 0.5);
#else
  GTEST_SKIP() << "built without AVX2 and FMA: the portable loops use std::sqrt and division";
#endif
}

/// The first processor's `key` in /proc/cpuinfo ("" where absent): the kernel's reading of the
/// processor, independent of the CPUID instruction that preferredLaneWidth reads.
std::string cpuinfoField(const std::string& key) {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line;
  while (std::getline(cpuinfo, line) && !line.empty()) {
    const std::size_t colon = line.find(':');
    if (colon == std::string::npos) continue;
    std::string name = line.substr(0, colon);
    name.erase(name.find_last_not_of(" \t") + 1);
    if (name == key) return colon + 2 <= line.size() ? line.substr(colon + 2) : std::string();
  }
  return "";
}

TEST(SphSimdLanes, PreferredWidthIsFourOnAmdFamily19hAndEightElsewhere) {
  const char* forced = std::getenv("RUPTURE_SPH_LANES");
  if (forced && (std::string(forced) == "1" || std::string(forced) == "4" || std::string(forced) == "8")) {
    EXPECT_EQ(preferredLaneWidth(), std::stoi(forced)) << "RUPTURE_SPH_LANES=" << forced;
    return;
  }
  const std::string vendor = cpuinfoField("vendor_id"), family = cpuinfoField("cpu family");
  if (vendor.empty() || family.empty()) GTEST_SKIP() << "/proc/cpuinfo names no vendor or family";
  const bool zen4Family = vendor == "AuthenticAMD" && family == "25";
  EXPECT_EQ(preferredLaneWidth(), zen4Family ? 4 : 8) << vendor << ", family " << family;
}

}  // namespace
}  // namespace rupture::sph
