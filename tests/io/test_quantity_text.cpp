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
      // s: prefixes down to ps, never ks.
      {3.6348609732528563e-09, "s", "3.63 ns"},
      {4.5e-4, "s", "450 µs"},
      {1220.708, "s", "1221 s"},
      {2e-15, "s", "2e-15 s"},  // below the smallest prefix: a power of ten of the base unit
      {1e6, "s", "1e6 s"},        // seconds take no kilo
      {1e300, "Pa", "1e300 Pa"},  // above the largest prefix
      // m, J, and a unit with a denominator that keeps its head's prefix.
      {2.5e-3, "m", "2.5 mm"},
      {3.3e-9, "m", "3.3 nm"},
      {1e-20, "J", "1e-20 J"},
      {inf, "J", "inf"},
      {-inf, "J", "-inf"},
      {85.7, "m/s", "85.7 m/s"},
      {0.004, "m/s", "4 mm/s"},
      // 1/s: the strain rates of a sweep.
      {1e7, "1/s", "1e7 /s"},
      {1e5, "1/s", "1e5 /s"},
      {4e6, "1/s", "4e6 /s"},
      {500.0, "1/s", "500 /s"},
      // Units without a prefix.
      {6060.0, "kg/m^3", "6060 kg/m^3"},
      {300000.0, "kg", "3e5 kg"},
      {12.34567, "kg", "12.3 kg"},
      {0.5, "m^2", "0.5 m^2"},
      // Dimensionless: plain between 0.001 and 100000, powers of ten outside, counts whole.
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
