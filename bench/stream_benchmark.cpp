#include "stream_benchmark.hpp"

#include <omp.h>
#include <unistd.h>

#include <immintrin.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace rupture::bench {

namespace {

// Uninitialised storage, so that each page is first touched by the thread that will stream it
// (a std::vector would zero it all on the master thread and place every page on its node).
struct DoubleArray {
  std::unique_ptr<double[]> data;
  explicit DoubleArray(std::size_t n) : data(new double[n]) {}
  double* get() const { return data.get(); }
};

/// The last-level cache's size (bytes; 0 when unknown): sysfs first, since in this machine kind's
/// virtual machines sysconf reports the host's 320 MiB where the processor has 32 MiB (lscpu, sysfs).
long lastLevelCacheBytes() {
  for (int index = 3; index >= 0; --index) {
    const std::string dir = "/sys/devices/system/cpu/cpu0/cache/index" + std::to_string(index) + "/";
    std::ifstream levelFile(dir + "level"), sizeFile(dir + "size");
    int level = 0;
    std::string size;
    if (!(levelFile >> level) || level != 3 || !(sizeFile >> size) || size.empty()) continue;
    const long value = std::strtol(size.c_str(), nullptr, 10);
    const char unit = size.back();
    return unit == 'K' ? value << 10 : unit == 'M' ? value << 20 : value;
  }
  const long fromLibc = sysconf(_SC_LEVEL3_CACHE_SIZE);
  return fromLibc > 0 ? fromLibc : 0;
}

double now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// The widest vector of doubles the host's instructions take (GCC's vector extension): 8 with
// AVX-512, 4 with AVX. The kernels below issue operations of that width as written, whatever the
// auto-vectoriser would have made of a plain loop. (8 doubles on an AVX2 host would be two
// registers an operand: the 8 chains and their constants no longer fit the 16 registers, and the
// spills, not the FMA pipes, would be timed: 4 GFLOP/s where the pipes give about 50.)
#if defined(__AVX512F__)
constexpr int kVectorLanes = 8;
#elif defined(__AVX__)
constexpr int kVectorLanes = 4;
#else
constexpr int kVectorLanes = 2;
#endif
typedef double Vec __attribute__((vector_size(8 * kVectorLanes)));

[[gnu::always_inline]] inline Vec squareRoot(Vec a) {
#if defined(__AVX512F__)
  // The masked form with every lane set: the plain one's undefined source trips GCC 12's
  // -Wmaybe-uninitialized.
  const __m512d v = reinterpret_cast<__m512d>(a);
  return reinterpret_cast<Vec>(_mm512_mask_sqrt_pd(v, 0xFF, v));
#elif defined(__AVX__)
  return reinterpret_cast<Vec>(_mm256_sqrt_pd(reinterpret_cast<__m256d>(a)));
#else
  for (int l = 0; l < kVectorLanes; ++l) a[l] = std::sqrt(a[l]);
  return a;
#endif
}

/// Arithmetic throughput of one thread, per second: multiply-adds (a = a·m + c, 2 flops, which GCC
/// contracts into one FMA), divisions (a = c/a) and square roots (a = √a) over 8 independent
/// vectors of kVectorLanes doubles, enough to cover each instruction's latency, so throughput and
/// not latency is timed.
/// Best of 5 runs of some 10-40 ms each. Returns {flops, divisions, roots} per second.
std::array<double, 3> arithmeticRates() {
  constexpr int kChains = 8;
  std::array<double, 3> best{0.0, 0.0, 0.0};
  volatile double sink = 0.0;  // keeps the chains' results alive
  for (int kernel = 0; kernel < 3; ++kernel) {
    const long rounds = kernel == 0 ? 4000000 : 200000;
    for (int run = 0; run < 5; ++run) {
      Vec lane{};
      for (int l = 0; l < kVectorLanes; ++l) lane[l] = l;
      Vec a[kChains];
      for (int c = 0; c < kChains; ++c) a[c] = 1.0 + 0.01 * (lane + static_cast<double>(kVectorLanes) * c);
      // m < 1 and c small: a·m + c converges to c/(1 − m), no overflow, no subnormals.
      const Vec m = Vec{} + 0.999999, add = Vec{} + 1e-6, num = Vec{} + 2.0;
      const double t0 = now();
      for (long r = 0; r < rounds; ++r) {
        for (int c = 0; c < kChains; ++c) {
          if (kernel == 0) a[c] = a[c] * m + add;
          else if (kernel == 1) a[c] = num / a[c];  // alternates between a and 2/a
          else a[c] = squareRoot(a[c]);
        }
      }
      const double seconds = now() - t0;
      double s = 0.0;
      for (int c = 0; c < kChains; ++c)
        for (int l = 0; l < kVectorLanes; ++l) s += a[c][l];
      sink = sink + s;
      const double operations = static_cast<double>(rounds) * kChains * kVectorLanes * (kernel == 0 ? 2 : 1);
      best[kernel] = std::max(best[kernel], operations / seconds);
    }
  }
  return best;
}

}  // namespace

nlohmann::json runStream(const StreamOptions& options) {
  const int threads = std::max(1, options.threads);
  omp_set_num_threads(threads);
  const std::size_t n = static_cast<std::size_t>(options.megabytes) * (std::size_t{1} << 20) / sizeof(double);
  const DoubleArray A(n), B(n), C(n);
  double* const a = A.get();
  double* const b = B.get();
  double* const c = C.get();
  const std::ptrdiff_t count = static_cast<std::ptrdiff_t>(n);

  // First touch in the kernels' own static schedule: each thread's pages are the ones it streams.
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t k = 0; k < count; ++k) {
    a[k] = 1.0;
    b[k] = 2.0;
    c[k] = 0.0;
  }

  const double scalar = 3.0;
  constexpr int kKernels = 4;
  double best[kKernels];
  std::fill(best, best + kKernels, std::numeric_limits<double>::infinity());
  const int repetitions = std::max(2, options.repetitions);
  for (int rep = 0; rep < repetitions; ++rep) {
    double t[kKernels + 1];
    t[0] = now();
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t k = 0; k < count; ++k) c[k] = a[k];
    t[1] = now();
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t k = 0; k < count; ++k) b[k] = scalar * c[k];
    t[2] = now();
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t k = 0; k < count; ++k) c[k] = a[k] + b[k];
    t[3] = now();
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t k = 0; k < count; ++k) a[k] = b[k] + scalar * c[k];
    t[4] = now();
    // STREAM skips the first repetition (page faults, cold TLB).
    if (rep > 0)
      for (int j = 0; j < kKernels; ++j) best[j] = std::min(best[j], t[j + 1] - t[j]);
  }

  // The values every element must hold after the repetitions (STREAM's check): a kernel that the
  // compiler elided or a thread that skipped its share shows here.
  double aj = 1.0, bj = 2.0, cj = 0.0;
  for (int rep = 0; rep < repetitions; ++rep) {
    cj = aj;
    bj = scalar * cj;
    cj = aj + bj;
    aj = bj + scalar * cj;
  }
  double error = 0.0;
#pragma omp parallel for schedule(static) reduction(max : error)
  for (std::ptrdiff_t k = 0; k < count; ++k)
    error = std::max({error, std::abs(a[k] - aj) / aj, std::abs(b[k] - bj) / bj, std::abs(c[k] - cj) / cj});

  // The arithmetic ceilings, each thread on its own chains at the same time (as the loops run).
  std::vector<std::array<double, 3>> rates(static_cast<std::size_t>(threads));
#pragma omp parallel num_threads(threads)
  rates[static_cast<std::size_t>(omp_get_thread_num())] = arithmeticRates();
  std::array<double, 3> total{0.0, 0.0, 0.0};
  for (const auto& r : rates)
    for (int j = 0; j < 3; ++j) total[j] += r[j];

  const double bytes[kKernels] = {16.0 * n, 16.0 * n, 24.0 * n, 24.0 * n};
  const char* names[kKernels] = {"copy", "scale", "add", "triad"};
  const long l3 = lastLevelCacheBytes();
  nlohmann::json report = {{"workload", "STREAM"},
                           {"threads", threads},
                           {"megabytes", options.megabytes},
                           {"elements", n},
                           {"repetitions", repetitions},
                           {"l3_bytes", l3 > 0 ? nlohmann::json(l3) : nlohmann::json(nullptr)},
                           {"array_to_l3", l3 > 0 ? nlohmann::json(static_cast<double>(n * sizeof(double)) / l3)
                                                  : nlohmann::json(nullptr)},
                           {"valid", error <= 1e-13}};
  report["gflops_mul_add"] = total[0] * 1e-9;
  report["g_divisions_per_s"] = total[1] * 1e-9;
  report["g_square_roots_per_s"] = total[2] * 1e-9;
  for (int j = 0; j < kKernels; ++j) {
    report[std::string(names[j]) + "_gb_per_s"] = bytes[j] / best[j] * 1e-9;
    report[std::string(names[j]) + "_best_seconds"] = best[j];
  }
  return report;
}

}  // namespace rupture::bench
