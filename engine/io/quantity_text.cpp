#include "rupture/quantity_text.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string_view>

namespace rupture {

namespace {

/// The SI prefix of a power of ten that is a multiple of 3 in [-12, 12].
const char* prefixOf(int exponent) {
  static constexpr std::array<const char*, 9> kPrefixes = {"p", "n", "µ", "m", "", "k", "M", "G", "T"};
  return kPrefixes[static_cast<std::size_t>(exponent / 3 + 4)];
}

/// Whether the unit's leading symbol (up to a space or '/') is a base unit that takes a prefix.
bool takesPrefix(std::string_view unit) {
  const std::string_view head = unit.substr(0, unit.find_first_of(" /"));
  for (std::string_view base : {"Pa", "s", "m", "J", "N", "W"})
    if (head == base) return true;
  return false;
}

/// The unit as it follows a number: " Pa", " /s" for "1/s", nothing for "1" or "".
std::string unitSuffix(const std::string& unit) {
  if (unit.empty() || unit == "1") return "";
  std::string suffix = " ";
  return unit.rfind("1/", 0) == 0 ? suffix.append(unit, 1) : suffix.append(unit);
}

/// |value| = m × 10^e with 1 <= m < 10 after rounding to `digits` significant digits.
int decimalExponent(double value, int digits) {
  int e = static_cast<int>(std::floor(std::log10(std::fabs(value))));
  const double scale = std::pow(10.0, digits - 1 - e);
  if (std::round(std::fabs(value) * scale) >= std::pow(10.0, digits)) ++e;  // 9.996 -> 10.0
  return e;
}

/// A positive `magnitude` with `digits` significant digits and never a power of ten: "51.1",
/// "0.00321", "1221" (all the integer digits when there are more than `digits`).
std::string plainText(double magnitude, int digits) {
  const int decimals = std::max(0, digits - 1 - decimalExponent(magnitude, digits));
  char buf[400];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, magnitude);
  std::string text = buf;
  if (text.find('.') != std::string::npos) {
    text.erase(text.find_last_not_of('0') + 1);
    if (text.back() == '.') text.pop_back();
  }
  return text;
}

}  // namespace

std::string formatQuantity(double value, const std::string& siUnit, int significantDigits) {
  const int digits = std::clamp(significantDigits, 1, 17);
  if (std::isnan(value)) return "n/a";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  if (value == 0) return std::string("0").append(unitSuffix(siUnit));
  const std::string sign = value < 0 ? "-" : "";
  const double magnitude = std::fabs(value);
  const int e = decimalExponent(magnitude, digits);

  if (takesPrefix(siUnit)) {
    const std::string_view head = std::string_view(siUnit).substr(0, siUnit.find_first_of(" /"));
    const int engineering = std::clamp(static_cast<int>(std::floor(e / 3.0)) * 3, -12, head == "s" ? 0 : 12);
    // Beyond the prefixes (below p, above T, seconds above 99999 s): a power of ten of the base unit.
    if (e >= engineering && e < engineering + 5)
      return std::string(sign).append(plainText(magnitude / std::pow(10.0, engineering), digits))
          .append(" ").append(prefixOf(engineering)).append(siUnit);
  }
  const bool count = siUnit.empty() || siUnit == "1";
  if (count && magnitude < 1e15 && magnitude == std::floor(magnitude)) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.0f", magnitude);
    return std::string(sign).append(buf);
  }
  if (e >= -3 && e < 5) return std::string(sign).append(plainText(magnitude, digits)).append(unitSuffix(siUnit));
  return std::string(sign)
      .append(plainText(magnitude / std::pow(10.0, e), digits))
      .append("e")
      .append(std::to_string(e))
      .append(unitSuffix(siUnit));
}

}  // namespace rupture
