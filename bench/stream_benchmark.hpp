#pragma once
// STREAM: the memory bandwidth the roofline of W1, W2 and W3 is drawn against (bench/README.md,
// "Roofline"). McCalpin's four kernels over double arrays far larger than the last-level cache.
#include <nlohmann/json.hpp>

namespace rupture::bench {

struct StreamOptions {
  int threads = 1;
  int megabytes = 128;  ///< size of each of the three arrays, MiB (4× a 32 MiB L3 by default)
  int repetitions = 10;
};

/// Runs copy, scale, add and triad `repetitions` times and returns one JSON object: workload,
/// threads, megabytes, elements, repetitions, {copy,scale,add,triad}_gb_per_s (best repetition,
/// bytes counted as STREAM does: 16 per element for copy and scale, 24 for add and triad),
/// {…}_best_seconds, the arithmetic ceilings of `threads` threads (gflops_mul_add: a·m + c in the widest vectors, 512-bit with AVX-512 and 256-bit with AVX,
/// g_divisions_per_s, g_square_roots_per_s: double operations per ns), l3_bytes (sysfs, else the C library; null when unknown), array_to_l3 and valid (the arrays hold the values the kernels imply).
nlohmann::json runStream(const StreamOptions& options);

}  // namespace rupture::bench
