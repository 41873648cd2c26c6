#pragma once
// A self-contained SVG line plot of one summary column against another: one series per combination
// of the other swept parameters (with a legend), log axes when values span decades, axis labels
// with units.
#include <string>
#include <utility>
#include <vector>

#include "summary.hpp"

namespace rupture::server {

enum class AxisScale { Auto, Linear, Log };

struct PlotRequest {
  std::string x;  ///< column on the x axis (swept path or scalar); may be categorical (strings)
  std::string y;  ///< numeric column on the y axis
  AxisScale xScale = AxisScale::Auto;
  AxisScale yScale = AxisScale::Auto;
  std::string title;  ///< shown above the plot; empty = "<y> vs <x>"
  /// Optional error bars (replicates' 95 % intervals): (low, high) of y per table row, aligned with
  /// SummaryTable::rows; empty, or NaN for a row without one.
  std::vector<std::pair<double, double>> yIntervals;
};

/// Auto scale rule: log when every value is > 0 and they span at least a decade, unless they are
/// spaced more evenly on a linear axis than on a log one (1, 2, ..., 10 stays linear).
bool prefersLogScale(const std::vector<double>& values);

/// Renders the plot. Throws ApiError(400) naming `x` or `y` when a column is unknown, when y is not
/// numeric, or when a log scale is asked for values <= 0.
std::string summarySvg(const SummaryTable& table, const PlotRequest& request, const UnitLookup& unitOf);

}  // namespace rupture::server
