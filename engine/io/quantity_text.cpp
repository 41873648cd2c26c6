#include "rupture/quantity_text.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <string_view>

namespace rupture {

namespace {

// The prefixes used: atto (a run's energies in fJ and aJ, its time steps in fs) to tera.
constexpr int kLowestPrefix = -18, kHighestPrefix = 12;

/// The SI prefix of a power of ten that is a multiple of 3 in [kLowestPrefix, kHighestPrefix].
const char* prefixOf(int exponent) {
  static constexpr std::array<const char*, 11> kPrefixes = {"a", "f", "p", "n", "µ", "m", "", "k", "M", "G", "T"};
  return kPrefixes[static_cast<std::size_t>((exponent - kLowestPrefix) / 3)];
}

/// The engineering exponent (a multiple of 3) formatQuantity writes a value of decimal exponent
/// `e` with, for a unit whose head is `head`: seconds take no kilo and above.
int engineeringExponent(int e, std::string_view head) {
  return std::clamp(static_cast<int>(std::floor(e / 3.0)) * 3, kLowestPrefix, head == "s" ? 0 : kHighestPrefix);
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
    const int engineering = engineeringExponent(e, head);
    // Beyond the prefixes (below a, above T, seconds above 99999 s): a power of ten of the base unit.
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
  // Plain below 10000: 10000 /s and 1e5 /s would otherwise sit side by side in one sweep's table.
  if (e >= -3 && e < 4) return std::string(sign).append(plainText(magnitude, digits)).append(unitSuffix(siUnit));
  return std::string(sign)
      .append(plainText(magnitude / std::pow(10.0, e), digits))
      .append("e")
      .append(std::to_string(e))
      .append(unitSuffix(siUnit));
}

std::string formatFlag(bool value) { return value ? "yes" : "no"; }

std::string roundNumbersInText(const std::string& text, int significantDigits) {
  const int digits = std::clamp(significantDigits, 1, 17);
  std::string out;
  std::size_t i = 0;
  auto isDigit = [](char c) { return c >= '0' && c <= '9'; };
  while (i < text.size()) {
    // A number starts at a digit that does not continue a word (x2, v1.2.3 stay as written).
    const bool starts = isDigit(text[i]) && (i == 0 || !(std::isalnum(static_cast<unsigned char>(text[i - 1])) ||
                                                        text[i - 1] == '.' || text[i - 1] == '_'));
    if (!starts) {
      out += text[i++];
      continue;
    }
    std::size_t end = i, significant = 0;
    bool point = false, exponent = false, leading = true;
    while (end < text.size() && (isDigit(text[end]) || (text[end] == '.' && !point && end + 1 < text.size() &&
                                                        isDigit(text[end + 1])))) {
      if (text[end] == '.') point = true;
      else if (!(leading && text[end] == '0')) leading = false, ++significant;
      ++end;
    }
    if (end + 1 < text.size() && (text[end] == 'e' || text[end] == 'E')) {
      std::size_t k = end + 1;
      if (text[k] == '+' || text[k] == '-') ++k;
      if (k < text.size() && isDigit(text[k])) {
        while (k < text.size() && isDigit(text[k])) ++k;
        end = k, exponent = true;
      }
    }
    const std::string number = text.substr(i, end - i);
    // Only long decimals and powers of ten are rewritten; counts and short values read as written.
    if ((point && significant > static_cast<std::size_t>(digits) + 1) || exponent) {
      out += formatQuantity(std::strtod(number.c_str(), nullptr), "1", digits);  // the sign stays in `out`
    } else {
      out += number;
    }
    i = end;
  }
  return out;
}

ScaledUnit scaledUnit(double magnitude, const std::string& siUnit) {
  ScaledUnit out{1, siUnit == "1" ? "" : siUnit};
  if (!(magnitude > 0) || !std::isfinite(magnitude) || !takesPrefix(siUnit)) {
    if (siUnit.rfind("1/", 0) == 0) out.unit = siUnit.substr(1);
    return out;
  }
  const std::string_view head = std::string_view(siUnit).substr(0, siUnit.find_first_of(" /"));
  const int engineering = engineeringExponent(decimalExponent(magnitude, kReadableDigits), head);
  out.factor = std::pow(10.0, engineering);
  out.unit = std::string(prefixOf(engineering)).append(siUnit);
  return out;
}

std::string tickText(double value, double step) {
  const double magnitude = std::fabs(step);
  int decimals = 0;
  if (magnitude > 0 && std::isfinite(magnitude))
    decimals = std::clamp(-static_cast<int>(std::floor(std::log10(magnitude) + 1e-9)), 0, 12);
  // A step of 2.5 or 0.25 needs one decimal more than its leading digit says.
  if (magnitude > 0 && std::fmod(magnitude * std::pow(10.0, decimals), 1.0) > 1e-6) ++decimals;
  // 0.30000000000000004 reads as the round value it stands for.
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, value);
  std::string text = buf;
  if (text.find('.') != std::string::npos) {
    text.erase(text.find_last_not_of('0') + 1);
    if (text.back() == '.') text.pop_back();
  }
  if (text == "-0") text = "0";
  return text;
}

}  // namespace rupture
