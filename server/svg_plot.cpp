#include "svg_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <sstream>

#include "io/xml_escape.hpp"
#include "problem.hpp"

namespace rupture::server {
namespace {

constexpr double kWidth = 800, kHeight = 500;
constexpr double kLeft = 95, kTop = 60, kBottom = 75;
constexpr const char* kPalette[] = {"#4e79a7", "#f28e2b", "#e15759", "#76b7b2", "#59a14f",
                                    "#edc948", "#b07aa1", "#ff9da7", "#9c755f", "#bab0ac"};

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", v);
  return buf;
}

/// Tick label: compact, %g-style with at most 4 significant digits.
std::string tickLabel(double v) {
  if (std::abs(v) < 1e-300) return "0";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  std::string text = buf;  // "5.2e+07" -> "5.2e7", "1e-05" -> "1e-5"
  if (auto e = text.find('e'); e != std::string::npos) {
    std::string exponent = text.substr(e + 1);
    const bool negative = exponent[0] == '-';
    if (exponent[0] == '+' || exponent[0] == '-') exponent.erase(0, 1);
    exponent.erase(0, std::min(exponent.find_first_not_of('0'), exponent.size() - 1));
    text = text.substr(0, e + 1) + (negative ? "-" : "") + exponent;
  }
  return text;
}

std::string valueText(const Json& v) { return v.is_string() ? v.get<std::string>() : v.dump(); }

std::string axisLabel(const std::string& column, const UnitLookup& unitOf) {
  std::string unit = unitOf ? unitOf(column) : knownScalarUnit(column);
  return unit.empty() ? column + " [-]" : column + " [" + unit + "]";
}

struct Axis {
  bool log = false;
  bool categorical = false;
  double lo = 0, hi = 1;  // in data units (log10 of data when log)
  std::vector<std::pair<double, std::string>> ticks;  // position in axis units, label (may hold SVG markup)
  std::vector<std::string> categories;

  double toAxis(double v) const { return log ? std::log10(v) : v; }
  /// 0..1 along the axis.
  double frac(double v) const { return hi > lo ? (toAxis(v) - lo) / (hi - lo) : 0.5; }
};

double niceStep(double span, int target) {
  const double raw = span / target;
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 2.5, 5.0, 10.0}) {
    if (raw <= m * mag) return m * mag;
  }
  return 10 * mag;
}

Axis numericAxis(const std::vector<double>& values, AxisScale scale, const std::string& column) {
  Axis axis;
  double mn = *std::min_element(values.begin(), values.end());
  double mx = *std::max_element(values.begin(), values.end());
  axis.log = scale == AxisScale::Log || (scale == AxisScale::Auto && prefersLogScale(values));
  if (axis.log) {
    if (!(mn > 0)) {
      throw ApiError(400, problem::kInvalidParameter, "Invalid parameter",
                     "a log scale needs values > 0, but '" + column + "' has " + tickLabel(mn), column,
                     Json{{"in", "query"}});
    }
    const double a = std::log10(mn), b = std::log10(mx);
    const double pad = std::max(0.05 * (b - a), 0.15);
    axis.lo = a - pad;
    axis.hi = b + pad;
    const int first = static_cast<int>(std::ceil(axis.lo)), last = static_cast<int>(std::floor(axis.hi));
    const bool fewDecades = last - first < 2;
    for (int d = first - 1; d <= last; ++d) {
      if (d >= axis.lo && d <= axis.hi) {
        axis.ticks.push_back({double(d), "10<tspan dy=\"-7\" font-size=\"10\">" + std::to_string(d) + "</tspan>"});
      }
      if (fewDecades) {
        for (double m : {2.0, 5.0}) {
          const double p = d + std::log10(m);
          if (p >= axis.lo && p <= axis.hi) axis.ticks.push_back({p, tickLabel(m * std::pow(10.0, d))});
        }
      }
    }
    return axis;
  }
  if (mx - mn <= 0) {
    const double pad = mn == 0 ? 1 : std::abs(mn) * 0.1;
    mn -= pad;
    mx += pad;
  } else {
    const double pad = 0.04 * (mx - mn);
    mn -= pad;
    mx += pad;
  }
  const double step = niceStep(mx - mn, 6);
  axis.lo = std::floor(mn / step) * step;
  axis.hi = std::ceil(mx / step) * step;
  for (double t = axis.lo; t <= axis.hi + step * 1e-9; t += step) {
    axis.ticks.push_back({t, tickLabel(std::abs(t) < step * 1e-9 ? 0.0 : t)});
  }
  return axis;
}

// The visible title must fit the picture: bold 15 px DejaVu Sans is about 9.5 px per character.
std::string fitTitle(const std::string& title) {
  const std::size_t maxChars = static_cast<std::size_t>((kWidth - 20) / 9.5);
  if (title.size() <= maxChars) return title;
  std::size_t cut = maxChars - 3;
  while (cut > 0 && (static_cast<unsigned char>(title[cut]) & 0xC0) == 0x80) --cut;  // whole UTF-8 characters
  return title.substr(0, cut) + "...";
}

}  // namespace

bool prefersLogScale(const std::vector<double>& values) {
  if (values.empty()) return false;
  for (double v : values) {
    if (!(v > 0) || !std::isfinite(v)) return false;
  }
  std::vector<double> v(values);
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  const double ratio = v.back() / v.front();
  if (ratio < 10) return false;
  if (v.size() <= 2 || ratio >= 1000) return true;
  // Compare how evenly the values sit on each axis: the mean absolute deviation of the gaps.
  auto unevenness = [](const std::vector<double>& p) {
    std::vector<double> gaps;
    for (std::size_t i = 1; i < p.size(); ++i) gaps.push_back(p[i] - p[i - 1]);
    double mean = 0;
    for (double g : gaps) mean += g;
    mean /= gaps.size();
    double dev = 0;
    for (double g : gaps) dev += std::abs(g - mean);
    return dev / gaps.size() / mean;
  };
  std::vector<double> logs;
  for (double x : v) logs.push_back(std::log10(x));
  return unevenness(logs) <= unevenness(v);
}

std::string summarySvg(const SummaryTable& table, const PlotRequest& request, const UnitLookup& unitOf) {
  for (const auto& [name, col] : {std::pair{"x", &request.x}, std::pair{"y", &request.y}}) {
    if (!table.hasColumn(*col) && !isKnownScalar(*col)) {
      Json allowed = Json::array();
      for (const auto& p : table.sweptPaths) allowed.push_back(p);
      for (const auto& s : table.scalarNames) allowed.push_back(s);
      throw ApiError(400, problem::kInvalidParameter, "Invalid parameter",
                     std::string("query parameter ") + name + "='" + *col +
                         "' is not a column of this job's summary (swept paths and result scalars: " +
                         allowed.dump() + ")",
                     name, Json{{"in", "query"}, {"value", *col}, {"allowed", allowed}});
    }
  }

  // Series: one per combination of the other swept parameters.
  std::vector<std::string> others;
  for (const auto& p : table.sweptPaths) {
    if (p != request.x && p != request.y) others.push_back(p);
  }
  struct Point { double x; Json xRaw; double y; int run; double lo = NAN, hi = NAN; };
  std::vector<std::string> seriesOrder;
  std::map<std::string, std::vector<Point>> series;
  bool categorical = false;
  for (const SummaryRow& row : table.rows) {
    Json xv = table.value(row, request.x);
    if (!xv.is_null() && !xv.is_number()) categorical = true;
  }
  std::vector<std::string> categories;
  std::vector<double> xs, ys;
  for (std::size_t r = 0; r < table.rows.size(); ++r) {
    const SummaryRow& row = table.rows[r];
    Json xv = table.value(row, request.x), yv = table.value(row, request.y);
    if (xv.is_null() || yv.is_null()) continue;
    if (!yv.is_number()) {
      throw ApiError(400, problem::kInvalidParameter, "Invalid parameter",
                     "query parameter y='" + request.y + "' is not numeric (" + yv.dump() + ")", "y",
                     Json{{"in", "query"}, {"value", request.y}});
    }
    double x = 0;
    if (categorical) {
      const std::string label = valueText(xv);
      auto it = std::find(categories.begin(), categories.end(), label);
      if (it == categories.end()) { categories.push_back(label); it = categories.end() - 1; }
      x = static_cast<double>(it - categories.begin());
    } else {
      x = xv.get<double>();
    }
    std::string key;
    for (const auto& p : others) {
      key += (key.empty() ? "" : ", ") + (others.size() > 1 ? p + "=" : std::string()) +
             valueText(table.value(row, p));
    }
    if (!series.count(key)) seriesOrder.push_back(key);
    series[key].push_back({x, xv, yv.get<double>(), row.run});
    xs.push_back(x);
    ys.push_back(yv.get<double>());
    if (r < request.yIntervals.size() && std::isfinite(request.yIntervals[r].first) &&
        std::isfinite(request.yIntervals[r].second)) {  // error bar: the axis must hold it
      series[key].back().lo = request.yIntervals[r].first;
      series[key].back().hi = request.yIntervals[r].second;
      // A low end <= 0 would turn an all-positive (log) axis linear: it is drawn clipped instead.
      if (request.yIntervals[r].first > 0 || yv.get<double>() <= 0) ys.push_back(request.yIntervals[r].first);
      ys.push_back(request.yIntervals[r].second);
    }
  }

  const bool legend = !others.empty() && !seriesOrder.empty();
  const double right = legend ? 215 : 30;
  const double plotW = kWidth - kLeft - right, plotH = kHeight - kTop - kBottom;
  const std::string title =
      request.title.empty() ? request.y + " vs " + request.x : request.title;

  std::ostringstream svg;
  svg << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << kWidth << "\" height=\"" << kHeight
      << "\" viewBox=\"0 0 " << kWidth << ' ' << kHeight
      << "\" font-family=\"DejaVu Sans, Helvetica, Arial, sans-serif\" font-size=\"12\">\n"
      << "<title>" << io::xmlEscape(title) << "</title>\n"
      << "<rect x=\"0\" y=\"0\" width=\"" << kWidth << "\" height=\"" << kHeight << "\" fill=\"white\"/>\n"
      << "<text x=\"" << num(kWidth / 2) << "\" y=\"28\" text-anchor=\"middle\" font-size=\"15\" "
      << "font-weight=\"bold\">" << io::xmlEscape(fitTitle(title)) << "</text>\n";

  if (xs.empty()) {
    svg << "<rect x=\"" << kLeft << "\" y=\"" << kTop << "\" width=\"" << num(plotW) << "\" height=\""
        << num(plotH) << "\" fill=\"none\" stroke=\"#333\"/>\n"
        << "<text x=\"" << num(kLeft + plotW / 2) << "\" y=\"" << num(kTop + plotH / 2)
        << "\" text-anchor=\"middle\" fill=\"#666\">no finished runs with " << io::xmlEscape(request.y)
        << " yet</text>\n</svg>\n";
    return svg.str();
  }

  Axis xAxis, yAxis = numericAxis(ys, request.yScale, request.y);
  if (categorical) {
    if (request.xScale == AxisScale::Log) {
      throw ApiError(400, problem::kInvalidParameter, "Invalid parameter",
                     "x='" + request.x + "' holds text values; a log scale is not possible", "xscale",
                     Json{{"in", "query"}});
    }
    xAxis.categorical = true;
    xAxis.lo = -0.5;
    xAxis.hi = static_cast<double>(categories.size()) - 0.5;
    for (std::size_t i = 0; i < categories.size(); ++i) xAxis.ticks.push_back({double(i), io::xmlEscape(categories[i])});
  } else {
    xAxis = numericAxis(xs, request.xScale, request.x);
  }
  auto px = [&](double x) { return kLeft + xAxis.frac(x) * plotW; };
  auto py = [&](double y) { return kTop + plotH - yAxis.frac(y) * plotH; };

  // Grid and ticks.
  svg << "<g stroke=\"#e3e3e3\" stroke-width=\"1\">\n";
  for (const auto& [t, label] : xAxis.ticks) {
    const double x = kLeft + (t - xAxis.lo) / (xAxis.hi - xAxis.lo) * plotW;
    svg << "<line x1=\"" << num(x) << "\" y1=\"" << kTop << "\" x2=\"" << num(x) << "\" y2=\"" << num(kTop + plotH)
        << "\"/>\n";
  }
  for (const auto& [t, label] : yAxis.ticks) {
    const double y = kTop + plotH - (t - yAxis.lo) / (yAxis.hi - yAxis.lo) * plotH;
    svg << "<line x1=\"" << kLeft << "\" y1=\"" << num(y) << "\" x2=\"" << num(kLeft + plotW) << "\" y2=\""
        << num(y) << "\"/>\n";
  }
  svg << "</g>\n<rect x=\"" << kLeft << "\" y=\"" << kTop << "\" width=\"" << num(plotW) << "\" height=\""
      << num(plotH) << "\" fill=\"none\" stroke=\"#333\"/>\n";
  svg << "<g class=\"x-ticks\" text-anchor=\"middle\">\n";
  for (const auto& [t, label] : xAxis.ticks) {
    const double x = kLeft + (t - xAxis.lo) / (xAxis.hi - xAxis.lo) * plotW;
    svg << "<line x1=\"" << num(x) << "\" y1=\"" << num(kTop + plotH) << "\" x2=\"" << num(x) << "\" y2=\""
        << num(kTop + plotH + 5) << "\" stroke=\"#333\"/><text x=\"" << num(x) << "\" y=\""
        << num(kTop + plotH + 20) << "\">" << label << "</text>\n";
  }
  svg << "</g>\n<g class=\"y-ticks\" text-anchor=\"end\">\n";
  for (const auto& [t, label] : yAxis.ticks) {
    const double y = kTop + plotH - (t - yAxis.lo) / (yAxis.hi - yAxis.lo) * plotH;
    svg << "<line x1=\"" << num(kLeft - 5) << "\" y1=\"" << num(y) << "\" x2=\"" << kLeft << "\" y2=\"" << num(y)
        << "\" stroke=\"#333\"/><text x=\"" << num(kLeft - 8) << "\" y=\"" << num(y + 4) << "\">" << label
        << "</text>\n";
  }
  svg << "</g>\n";
  // Axis labels.
  svg << "<text class=\"x-label\" x=\"" << num(kLeft + plotW / 2) << "\" y=\"" << num(kHeight - 22)
      << "\" text-anchor=\"middle\" font-size=\"13\">" << io::xmlEscape(axisLabel(request.x, unitOf))
      << (xAxis.log ? " (log scale)" : "") << "</text>\n";
  svg << "<text class=\"y-label\" transform=\"translate(22," << num(kTop + plotH / 2)
      << ") rotate(-90)\" text-anchor=\"middle\" font-size=\"13\">" << io::xmlEscape(axisLabel(request.y, unitOf))
      << (yAxis.log ? " (log scale)" : "") << "</text>\n";

  // Series.
  for (std::size_t s = 0; s < seriesOrder.size(); ++s) {
    const std::string colour = kPalette[s % std::size(kPalette)];
    std::vector<Point> pts = series[seriesOrder[s]];
    std::stable_sort(pts.begin(), pts.end(), [](const Point& a, const Point& b) { return a.x < b.x; });
    svg << "<g class=\"series\" data-label=\"" << io::xmlEscape(seriesOrder[s]) << "\">\n";
    if (pts.size() > 1) {
      svg << "<polyline fill=\"none\" stroke=\"" << colour << "\" stroke-width=\"2\" points=\"";
      for (const Point& p : pts) svg << num(px(p.x)) << ',' << num(py(p.y)) << ' ';
      svg << "\"/>\n";
    }
    for (const Point& p : pts) {
      if (std::isfinite(p.lo) && std::isfinite(p.hi)) {
        const double cx = px(p.x);
        const double lo = yAxis.log && !(p.lo > 0) ? std::pow(10.0, yAxis.lo) : p.lo;
        svg << "<path class=\"error-bar\" stroke=\"" << colour << "\" stroke-width=\"1.5\" fill=\"none\" d=\"M"
            << num(cx) << ',' << num(py(lo)) << "V" << num(py(p.hi)) << "M" << num(cx - 4) << ',' << num(py(lo))
            << "h8M" << num(cx - 4) << ',' << num(py(p.hi)) << "h8\"><title>95 % CI " << io::xmlEscape(tickLabel(p.lo))
            << " to " << io::xmlEscape(tickLabel(p.hi)) << "</title></path>\n";
      }
      svg << "<circle cx=\"" << num(px(p.x)) << "\" cy=\"" << num(py(p.y)) << "\" r=\"4\" fill=\"" << colour
          << "\"><title>run " << p.run << ": " << io::xmlEscape(request.x) << "=" << io::xmlEscape(valueText(p.xRaw))
          << ", " << io::xmlEscape(request.y) << "=" << io::xmlEscape(tickLabel(p.y)) << "</title></circle>\n";
    }
    svg << "</g>\n";
  }

  // Legend.
  if (legend) {
    const double lx = kLeft + plotW + 20;
    double ly = kTop + 6;
    std::string heading;
    for (const auto& p : others) heading += (heading.empty() ? "" : ", ") + p;
    svg << "<g class=\"legend\">\n<text x=\"" << num(lx) << "\" y=\"" << num(ly) << "\" font-weight=\"bold\">"
        << io::xmlEscape(others.size() > 1 ? std::string("series") : heading) << "</text>\n";
    for (std::size_t s = 0; s < seriesOrder.size(); ++s) {
      ly += 20;
      const std::string colour = kPalette[s % std::size(kPalette)];
      svg << "<line x1=\"" << num(lx) << "\" y1=\"" << num(ly - 4) << "\" x2=\"" << num(lx + 22) << "\" y2=\""
          << num(ly - 4) << "\" stroke=\"" << colour << "\" stroke-width=\"2\"/><circle cx=\"" << num(lx + 11)
          << "\" cy=\"" << num(ly - 4) << "\" r=\"4\" fill=\"" << colour << "\"/><text x=\"" << num(lx + 30)
          << "\" y=\"" << num(ly) << "\">" << io::xmlEscape(seriesOrder[s]) << "</text>\n";
    }
    svg << "</g>\n";
  }
  svg << "</svg>\n";
  return svg.str();
}

}  // namespace rupture::server
