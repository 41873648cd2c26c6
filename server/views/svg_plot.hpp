#pragma once
// A self-contained SVG plot of one summary column against another, fit for a paper: one series per
// combination of the other swept parameters (with a legend), human axis labels with units from the
// scenario's declared result fields, SI units scaled to engineering prefixes chosen from the data
// (Pa -> MPa, s -> µs) or a common power of ten, one tick format per axis (decades as 10⁵ on log
// axes), text x values as categories (markers, not joined), per-point error bars, wrapped titles.
// plot_png.hpp rasterises the same SVG.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "studies/summary.hpp"

namespace rupture::server {

enum class AxisScale { Auto, Linear, Log };

struct PlotRequest {
  std::string x;  ///< column on the x axis (swept path or scalar); may be categorical (strings)
  std::string y;  ///< numeric column on the y axis
  AxisScale xScale = AxisScale::Auto;
  AxisScale yScale = AxisScale::Auto;
  std::string title;  ///< shown above the plot (wrapped to two lines, then shortened); empty = "<y> vs <x>"
  /// Optional column holding each point's y error (symmetric half-width in y's unit, e.g. a 95 %
  /// confidence half-width or a standard deviation): drawn as a vertical error bar with caps.
  /// Empty: no error bars; a row whose error value is null or not finite gets none.
  std::string yError;
  int width = 800;   ///< picture size in px (kMinWidth..kMaxWidth)
  int height = 500;  ///< (kMinHeight..kMaxHeight)
  int fontSize = 12; ///< px of the tick labels and legend (kMinFontSize..kMaxFontSize); the title,
                     ///< axis titles and margins scale with it
  std::optional<double> yMin, yMax;  ///< y range in y's SI unit; unset = from the data
};

constexpr int kMinWidth = 320, kMaxWidth = 4000, kMinHeight = 240, kMaxHeight = 3000;
constexpr int kMinFontSize = 6, kMaxFontSize = 32;

/// Auto scale rule: log when every value is > 0 and they span at least a decade, unless they are
/// spaced more evenly on a linear axis than on a log one (1, 2, ..., 10 stays linear).
bool prefersLogScale(const std::vector<double>& values);

/// How an axis shows values of an SI unit: value_shown = value_SI / factor, with `unit` the unit
/// as displayed ("MPa", "µs") or, for units without a prefix, a "×10ⁿ" factor ("×10³ 1/s").
struct DisplayUnit {
  double factor = 1;
  std::string unit;  ///< "" for a dimensionless or text column shown as plain numbers
};
/// Picks the prefix (p..T; seconds up to s) or power of ten (multiples of 3) that brings the
/// largest |value| into [1, 1000). Units that take a prefix: Pa, s, m, J, N, W and products or
/// quotients starting with one ("J/m", "N s", "m/s"); "1" and other units get a power of ten
/// when |value| >= 1e4 or < 1e-2.
DisplayUnit displayUnit(const std::string& siUnit, double maxAbs);

/// "Peak stress [MPa]" (label, then the display unit in brackets; none when it is empty).
std::string axisTitle(const std::string& label, const DisplayUnit& unit);

/// Renders the plot. Throws ApiError(400) naming `x`, `y`, `ymin`/`ymax` or `xscale`/`yscale`
/// when a column is unknown, y is not numeric, a range is empty or a log scale meets values <= 0.
std::string summarySvg(const SummaryTable& table, const PlotRequest& request);

}  // namespace rupture::server
