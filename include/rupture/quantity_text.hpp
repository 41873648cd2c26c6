#pragma once
// Numbers as people read them: a value in SI units written with an engineering prefix and a fixed
// number of significant digits (58.4 MPa, 3.63 ns, 1e7 /s), for tables, pages and terminals. The
// machine formats (JSON, CSV, HDF5) keep full precision; this text is for reading only.
#include <string>

namespace rupture {

/// Significant digits of formatQuantity unless told otherwise.
inline constexpr int kReadableDigits = 3;

/// `value` (in `siUnit`, as the result declarations give it: "Pa", "m/s", "1/s", "J/m", "1" or ""
/// for none) as text:
/// - units whose leading symbol is Pa, s, m, J, N or W take an engineering prefix (p to T; seconds
///   stop at s): 51075064.86 Pa -> "51.1 MPa", 3.6348e-9 s -> "3.63 ns", 85.7 m/s -> "85.7 m/s";
///   beyond the prefixes, a power of ten of the base unit (1e-20 J, 1e6 s, 1e300 Pa);
/// - other units and dimensionless values are written plainly between 0.001 and 100000 (0.321,
///   1234) and as a short power of ten outside (1e7, 3.2e-4), with the unit after a space; a unit
///   "1/x" is written "/x" (1e7 /s);
/// - dimensionless integers below 1e15 (counts) are written whole: 21284 bonds, 590928;
/// - zero is "0" with its unit, NaN "n/a", infinities "inf" and "-inf";
/// - a number keeps all its integer digits even when they are more than `significantDigits`
///   (1221 s, 51 MPa at one digit): rounding never drops digits before the point.
std::string formatQuantity(double value, const std::string& siUnit, int significantDigits = kReadableDigits);

}  // namespace rupture
