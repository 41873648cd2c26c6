// formatQuantity: numbers as people read them, against the strings a reader expects: engineering
// prefixes on Pa, s, m, J, N, W; plain or short powers of ten elsewhere; counts whole; tiny, huge,
// negative, zero, NaN and infinities.
#include "rupture/quantity_text.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

namespace {

struct Case {
  double value;
  const char* unit;
  const char* expected;
};

TEST(QuantityText, ReadsAsPeopleWriteQuantities) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const Case cases[] = {
      // Pa: the seed's strengths and moduli.
      {51075064.859861486, "Pa", "51.1 MPa"},
      {58.4e6, "Pa", "58.4 MPa"},
      {160e9, "Pa", "160 GPa"},
      {7372909623.974194, "Pa", "7.37 GPa"},
      {999.96e6, "Pa", "1 GPa"},  // rounds up into the next prefix
      {-58.4e6, "Pa", "-58.4 MPa"},
      {0.0, "Pa", "0 Pa"},
      {nan, "Pa", "n/a"},
      // s: prefixes down to as, never ks.
      {3.6348609732528563e-09, "s", "3.63 ns"},
      {4.5e-4, "s", "450 µs"},
      {1220.708, "s", "1221 s"},
      {2e-15, "s", "2 fs"},
      {1.58e-13, "s", "158 fs"},     // a bonded run's time step beside its 1.05 ps critical step
      {1.05e-12, "s", "1.05 ps"},
      {2e-21, "s", "2e-21 s"},  // below the smallest prefix: a power of ten of the base unit
      {1e6, "s", "1e6 s"},        // seconds take no kilo
      {1e300, "Pa", "1e300 Pa"},  // above the largest prefix
      // m, J, and a unit with a denominator that keeps its head's prefix.
      {2.5e-3, "m", "2.5 mm"},
      {3.3e-9, "m", "3.3 nm"},
      {1e-20, "J", "1e-20 J"},
      {1.35e-15, "J", "1.35 fJ"},
      {3.2e-17, "J", "32 aJ"},
      {inf, "J", "inf"},
      {-inf, "J", "-inf"},
      {85.7, "m/s", "85.7 m/s"},
      {0.004, "m/s", "4 mm/s"},
      // 1/s: the strain rates of a sweep.
      {1e7, "1/s", "1e7 /s"},
      {1e5, "1/s", "1e5 /s"},
      {4e6, "1/s", "4e6 /s"},
      {500.0, "1/s", "500 /s"},
      {10000.0, "1/s", "1e4 /s"},  // as 1e5 /s beside it in one sweep, never 10000 /s
      {25000.0, "1/s", "2.5e4 /s"},
      {5000.0, "1/s", "5000 /s"},
      // Units without a prefix.
      {6060.0, "kg/m^3", "6060 kg/m^3"},
      {300000.0, "kg", "3e5 kg"},
      {12.34567, "kg", "12.3 kg"},
      {0.5, "m^2", "0.5 m^2"},
      // Dimensionless: plain from 0.001 to below 10000, powers of ten outside, counts whole.
      {0.321, "1", "0.321"},
      {3.2e-4, "1", "3.2e-4"},
      {4.5e-4, "", "4.5e-4"},
      {0.11, "1", "0.11"},
      {0.999996, "1", "1"},
      {-1e-7, "1", "-1e-7"},
      {21284.0, "1", "21284"},
      {590928.0, "1", "590928"},
      {1e30, "1", "1e30"},
      {45.0, "", "45"},
      {12345.6, "1", "1.23e4"},
  };
  for (const Case& c : cases) {
    EXPECT_EQ(rupture::formatQuantity(c.value, c.unit), c.expected) << c.value << " " << c.unit;
  }
}

TEST(QuantityText, SignificantDigitsAreAChoice) {
  EXPECT_EQ(rupture::formatQuantity(51075064.859861486, "Pa", 5), "51.075 MPa");
  EXPECT_EQ(rupture::formatQuantity(51075064.859861486, "Pa", 1), "51 MPa") << "integer digits are never dropped";
  EXPECT_EQ(rupture::formatQuantity(0.000321, "1", 2), "3.2e-4");
}

}  // namespace

TEST(QuantityText, FlagsAreWords) {
  EXPECT_EQ(rupture::formatFlag(true), "yes");
  EXPECT_EQ(rupture::formatFlag(false), "no");
}

TEST(QuantityText, LongDecimalsInTextAreRounded) {
  struct TextCase {
    const char* text;
    const char* expected;
  };
  const TextCase cases[] = {
      {"1.1244494114900343 x the plateau", "1.12 x the plateau"},
      {"separated at strain 0.000543219876", "separated at strain 5.43e-4"},
      {"time step 1.5800000000000001e-13 s", "time step 1.58e-13 s"},
      {"step 14683 of 20000, strain 0.0023", "step 14683 of 20000, strain 0.0023"},  // counts, short values
      {"mean -58412345.678 Pa", "mean -5.84e7 Pa"},
      {"run v1.2.3456789 x2.75", "run v1.2.3456789 x2.75"},  // part of a word: left as written
      {"", ""},
  };
  for (const TextCase& c : cases) EXPECT_EQ(rupture::roundNumbersInText(c.text), c.expected) << c.text;
}

TEST(QuantityText, AxesReadInOnePrefixedUnit) {
  const rupture::ScaledUnit micro = rupture::scaledUnit(2e-5, "m");
  EXPECT_DOUBLE_EQ(micro.factor, 1e-6);
  EXPECT_EQ(micro.unit, "µm");
  EXPECT_EQ(rupture::scaledUnit(211e6, "Pa").unit, "MPa");
  EXPECT_EQ(rupture::scaledUnit(0.5, "1").unit, "");
  EXPECT_EQ(rupture::scaledUnit(1000, "kg/m^3").unit, "kg/m^3");
  EXPECT_EQ(rupture::scaledUnit(1e6, "1/s").unit, "/s");
  EXPECT_EQ(rupture::scaledUnit(5000, "s").unit, "s") << "seconds take no kilo";
}
