#pragma once
// Ticks at round values (1, 2 or 5 × 10^k) for every axis and colour bar of the pictures, so that
// a reader measures against 0, 50, 100, 150 MPa rather than 70.5, 141, 211.
#include <vector>

namespace rupture::render {

struct RoundTicks {
  double step = 0;             ///< 1, 2 or 5 × 10^k
  std::vector<double> values;  ///< the multiples of `step` in [lo, hi], ascending
};

/// About `intervals` steps over [lo, hi] (lo < hi, both finite); at most 20 ticks. An exact zero
/// is written 0 (not 1e-17 from the sum of steps).
RoundTicks roundTicks(double lo, double hi, int intervals = 5);

/// The longest round length (1, 2 or 5 × 10^k) within a quarter of `span` (a quarter that is itself
/// round counts): a scale bar's (thumbnails, the sample preview). 0 for a span that is not > 0.
double scaleBarLength(double span);

}  // namespace rupture::render
