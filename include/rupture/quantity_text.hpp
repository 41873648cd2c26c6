#pragma once
// Numbers as people read them: a value in SI units written with an engineering prefix and a fixed
// number of significant digits (58.4 MPa, 3.63 ns, 1e7 /s), for tables, pages, pictures and
// terminals: the one formatter of every number a person reads. The machine formats (JSON, CSV,
// HDF5) keep full precision; this text is for reading only.
#include <string>

namespace rupture {

/// Significant digits of formatQuantity unless told otherwise.
inline constexpr int kReadableDigits = 3;

/// `value` (in `siUnit`, as the result declarations give it: "Pa", "m/s", "1/s", "J/m", "1" or ""
/// for none) as text:
/// - units whose leading symbol is Pa, s, m, J, N or W take an engineering prefix (a to T; seconds
///   stop at s): 51075064.86 Pa -> "51.1 MPa", 3.6348e-9 s -> "3.63 ns", 1.58e-13 s -> "158 fs",
///   1.35e-15 J -> "1.35 fJ", 85.7 m/s -> "85.7 m/s"; beyond the prefixes, a power of ten of the
///   base unit (1e-20 J, 1e6 s, 1e300 Pa);
/// - other units and dimensionless values are written plainly from 0.001 to below 10000 (0.321,
///   1234) and as a short power of ten outside (1e4, 1e7, 3.2e-4), with the unit after a space; a
///   unit "1/x" is written "/x" (1e4 /s and 1e5 /s alike, never 10000 /s beside 1e5 /s);
/// - dimensionless integers below 1e15 (counts) are written whole: 21284 bonds, 590928;
/// - zero is "0" with its unit, NaN "n/a", infinities "inf" and "-inf";
/// - a number keeps all its integer digits even when they are more than `significantDigits`
///   (1221 s, 51 MPa at one digit): rounding never drops digits before the point.
std::string formatQuantity(double value, const std::string& siUnit, int significantDigits = kReadableDigits);

/// A yes/no value as a word: "yes" or "no" (never 1/0 or true/false where a person reads it).
std::string formatFlag(bool value);

/// `text` (a run's stage, a log line) with every long decimal number in it rounded to
/// `significantDigits` as formatQuantity writes a dimensionless value: "1.1244494114900343 x the
/// plateau" -> "1.12 x the plateau". Integers and numbers already short are left as written.
std::string roundNumbersInText(const std::string& text, int significantDigits = kReadableDigits);

/// The unit an axis or a colour bar labels its ticks in, so that the ticks are plain numbers:
/// the engineering prefix formatQuantity would give `magnitude` (2e-5 m -> {1e-6, "µm"}), or
/// {1, siUnit as written} for a unit without prefixes. `unit` is "" for a dimensionless value.
struct ScaledUnit {
  double factor = 1;  ///< a value in the SI unit divided by this reads in `unit`
  std::string unit;
};
ScaledUnit scaledUnit(double magnitude, const std::string& siUnit);

/// A tick's number without unit, after dividing by a ScaledUnit's factor: plain decimal text with
/// no more decimals than `step` needs (0, 0.5, 1, 1.5 for step 0.5; 0, 50, 100 for step 50).
std::string tickText(double value, double step);

}  // namespace rupture
