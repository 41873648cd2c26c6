#pragma once
// When a loop is worth forking threads for. An OpenMP fork/join costs microseconds; a step of a
// small sample (a few thousand elements) is done in about as long, so small loops run serially.
#include <cstddef>

namespace rupture {

inline constexpr std::size_t kMinParallelItems = 8192;

inline bool worthParallel(std::size_t items) { return items >= kMinParallelItems; }

}  // namespace rupture
