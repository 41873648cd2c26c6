#pragma once
// 64-bit FNV-1a (Fowler, Noll and Vo): a fast, stable hash for cache file names, checksums of
// cached arrays and request fingerprints. Not cryptographic: every user compares the hashed text
// itself where a collision would matter.
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>

namespace rupture {

inline constexpr std::uint64_t kFnv1aOffsetBasis = 14695981039346656037ull;
inline constexpr std::uint64_t kFnv1aPrime = 1099511628211ull;

inline std::uint64_t fnv1a64(std::string_view bytes, std::uint64_t basis = kFnv1aOffsetBasis) {
  std::uint64_t h = basis;
  for (unsigned char c : bytes) {
    h ^= c;
    h *= kFnv1aPrime;
  }
  return h;
}

/// fnv1a64 as 16 lower-case hex digits.
inline std::string fnv1aHex(std::string_view bytes, std::uint64_t basis = kFnv1aOffsetBasis) {
  char buffer[17];
  std::snprintf(buffer, sizeof buffer, "%016llx", static_cast<unsigned long long>(fnv1a64(bytes, basis)));
  return buffer;
}

}  // namespace rupture
