#include "sph/simd_lanes.hpp"

#include <cpuid.h>

#include <cstdlib>
#include <cstring>
#include <string_view>

namespace rupture::sph {

namespace {

/// AMD family 19h (Zen 3 and Zen 4; of these only Zen 4 has AVX-512, split into 256-bit halves).
bool isAmdFamily19h() {
  unsigned eax = 0, ebx = 0, ecx = 0, edx = 0;
  if (!__get_cpuid(0, &eax, &ebx, &ecx, &edx)) return false;
  char vendor[13] = {};
  std::memcpy(vendor, &ebx, 4);
  std::memcpy(vendor + 4, &edx, 4);
  std::memcpy(vendor + 8, &ecx, 4);
  if (std::string_view(vendor) != "AuthenticAMD") return false;
  if (!__get_cpuid(1, &eax, &ebx, &ecx, &edx)) return false;
  const unsigned base = (eax >> 8) & 0xF, extended = (eax >> 20) & 0xFF;
  return (base == 0xF ? base + extended : base) == 0x19;
}

int detectLaneWidth() {
  if (const char* forced = std::getenv("RUPTURE_SPH_LANES")) {
    const std::string_view v(forced);
    if (v == "1") return kPortableLanes;
    if (v == "4") return 4;
    if (v == "8") return 8;
  }
  return isAmdFamily19h() ? 4 : 8;
}

}  // namespace

int preferredLaneWidth() {
  static const int width = detectLaneWidth();
  return width;
}

}  // namespace rupture::sph
