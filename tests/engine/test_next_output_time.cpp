// nextOutputTime (scenarios/run_support.hpp): the output clock of the time loops, which must give
// the old `while (next <= t) next += interval` values bit for bit when a few rows behind, and end
// in a bounded number of rounds when that loop would not (issue 56: a 5e-26 s interval at 1e-8 s).
#include <gtest/gtest.h>

#include <cmath>

#include "scenarios/run_support.hpp"

using rupture::nextOutputTime;

TEST(NextOutputTime, AFewRowsBehindIsTheAdditionLoopBitForBit) {
  const double interval = 1.7e-11;
  for (const double reached : {0.0, 1e-12, 3.3e-10, 1.0879e-9}) {
    double want = 0.0;
    while (want <= reached) want += interval;
    EXPECT_EQ(nextOutputTime(0.0, reached, interval), want) << reached;
  }
}

TEST(NextOutputTime, FarBehindIsTheFirstTimeAboveTheClock) {
  const double next = nextOutputTime(0.0, 1.0, 1e-9);  // a billion rows behind
  EXPECT_GT(next, 1.0);
  EXPECT_LE(next - 1.0, 1e-9 * (1 + 1e-6));
}

TEST(NextOutputTime, AnIntervalBelowTheClocksPrecisionStillPassesIt) {
  const double reached = 1e-8;
  const double next = nextOutputTime(reached, reached, 5e-26);  // next + interval == next
  EXPECT_GT(next, reached);
  EXPECT_EQ(next, std::nextafter(reached, INFINITY));
}
