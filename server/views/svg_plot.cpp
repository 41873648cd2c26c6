#include "views/svg_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

#include "rupture/quantity_text.hpp"
#include "io/xml_escape.hpp"
#include "common/problem.hpp"

namespace rupture::server {
namespace {

constexpr double kLeft = 95, kTop = 60, kBottom = 75;
constexpr const char* kPalette[] = {"#4e79a7", "#f28e2b", "#e15759", "#76b7b2", "#59a14f",
                                    "#edc948", "#b07aa1", "#ff9da7", "#9c755f", "#bab0ac"};

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", v);
  return buf;
}

ApiError badParameter(const std::string& name, const std::string& detail) {
  return ApiError(400, problem::kInvalidParameter, "Invalid parameter", detail, name, Json{{"in", "query"}});
}

/// "⁻¹²" for -12: exponents as Unicode superscripts, so every renderer shows them the same way.
std::string superscript(int n) {
  static const char* digits[] = {"⁰", "¹", "²", "³", "⁴", "⁵", "⁶", "⁷", "⁸", "⁹"};
  std::string out = n < 0 ? "⁻" : "";
  for (char c : std::to_string(std::abs(n))) out += digits[c - '0'];
  return out;
}

std::string powerOfTen(int n) { return "10" + superscript(n); }

/// A value in a tooltip or message: 4 significant digits, exponent without '+' and leading zeros ("2.5e7").
std::string shortNumber(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  std::string text = buf;
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

/// A marker's hover text as people read it: "run 2: Strain rate 1e7 /s, Peak stress 51.1 MPa", or
/// for a mean "mean of 3 runs: ... 51.1 MPa ± 2.3 MPa" (declared labels, engineering units,
/// rupture::formatQuantity).
std::string pointTitle(const std::string& who, const ColumnInfo& x, const Json& xValue, const ColumnInfo& y,
                       double yValue, double error) {
  const std::string xText = xValue.is_number() ? formatQuantity(xValue.get<double>(), x.unit) : valueText(xValue);
  return who + ": " + x.label + " " + xText + ", " + y.label + " " +
         formatQuantity(yValue, y.unit) + (error > 0 ? " ± " + formatQuantity(error, y.unit) : std::string());
}

/// A legend value: text as is; a number with 4 significant digits, powers of ten as 10⁷ or
/// 2.5×10⁷ beyond 10⁴, and its unit ("10⁷ 1/s").
std::string legendValue(const Json& v, const std::string& unit) {
  if (!v.is_number()) return valueText(v);
  const double x = v.get<double>();
  std::string text;
  const int e = x == 0 ? 0 : static_cast<int>(std::floor(std::log10(std::abs(x)) + 1e-12));
  if (std::abs(e) >= 4) {
    const double m = x / std::pow(10.0, e);
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4g", m);
    text = (std::string(buf) == "1" ? std::string() : std::string(buf) + "×") + "10" + superscript(e);
  } else {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4g", x);
    text = buf;
  }
  return unit.empty() || unit == "1" ? text : text + " " + unit;
}

struct Axis {
  bool log = false;
  bool categorical = false;
  DisplayUnit unit;
  double lo = 0, hi = 1;  // in displayed units (log10 of SI values when log)
  std::vector<std::pair<double, std::string>> ticks;  // position in axis units, label text

  double toAxis(double si) const { return log ? std::log10(si) : si / unit.factor; }
  double frac(double si) const { return hi > lo ? (toAxis(si) - lo) / (hi - lo) : 0.5; }
  double fracOfAxis(double t) const { return hi > lo ? (t - lo) / (hi - lo) : 0.5; }
};

double niceStep(double span, int target) {
  const double raw = span / target;
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 2.5, 5.0, 10.0}) {
    if (raw <= m * mag) return m * mag;
  }
  return 10 * mag;
}

Axis numericAxis(const std::vector<double>& values, AxisScale scale, const std::string& unit, const char* param,
                 std::optional<double> lo, std::optional<double> hi, int targetTicks) {
  Axis axis;
  double mn = lo ? *lo : *std::min_element(values.begin(), values.end());
  double mx = hi ? *hi : *std::max_element(values.begin(), values.end());
  if (lo && !hi) mx = std::max(mx, mn);
  if (hi && !lo) mn = std::min(mn, mx);
  axis.log = scale == AxisScale::Log || (scale == AxisScale::Auto && !lo && !hi && prefersLogScale(values));
  if (axis.log) {
    if (!(mn > 0)) {
      throw badParameter(param, std::string("a log scale needs values > 0, but the ") + (lo ? "range" : "data") +
                                    " reaches " + shortNumber(mn));
    }
    axis.unit = {1, unit == "1" ? "" : unit};
    const double a = std::log10(mn), b = std::log10(mx);
    const double pad = (lo || hi) ? 0 : std::max(0.05 * (b - a), 0.15);
    axis.lo = a - (lo ? 0 : pad);
    axis.hi = b + (hi ? 0 : pad);
    if (axis.hi <= axis.lo) axis.hi = axis.lo + 0.3;
    const int first = static_cast<int>(std::ceil(axis.lo - 1e-9)), last = static_cast<int>(std::floor(axis.hi + 1e-9));
    const bool fewDecades = last - first < 2;
    for (int d = first - 1; d <= last; ++d) {
      if (d >= axis.lo - 1e-9 && d <= axis.hi + 1e-9) axis.ticks.push_back({double(d), powerOfTen(d)});
      if (fewDecades) {
        for (int m : {2, 5}) {
          const double p = d + std::log10(double(m));
          if (p >= axis.lo && p <= axis.hi) axis.ticks.push_back({p, std::to_string(m) + "×" + powerOfTen(d)});
        }
      }
    }
    return axis;
  }
  axis.unit = displayUnit(unit, std::max(std::abs(mn), std::abs(mx)));
  mn /= axis.unit.factor;
  mx /= axis.unit.factor;
  if (mx - mn <= 0) {
    const double pad = mn == 0 ? 1 : std::abs(mn) * 0.1;
    if (!lo) mn -= pad;
    if (!hi) mx += pad;
    if (mx <= mn) mx = mn + 2 * pad;
  } else {
    const double pad = 0.04 * (mx - mn);
    if (!lo) mn -= pad;
    if (!hi) mx += pad;
  }
  const double step = niceStep(mx - mn, targetTicks);
  axis.lo = lo ? mn : std::floor(mn / step) * step;
  axis.hi = hi ? mx : std::ceil(mx / step) * step;
  for (double t = std::ceil(axis.lo / step - 1e-9) * step; t <= axis.hi + step * 1e-9; t += step) {
    axis.ticks.push_back({t, tickText(t, step)});  // as the field pictures label theirs
  }
  return axis;
}

std::size_t utf8Length(const std::string& s) {
  std::size_t n = 0;
  for (unsigned char c : s) n += (c & 0xC0) != 0x80;
  return n;
}

/// At most maxChars characters (UTF-8), ending in "…" when cut.
std::string shortenText(const std::string& s, std::size_t maxChars) {
  if (utf8Length(s) <= maxChars) return s;
  std::size_t keep = 0, chars = 0;
  while (keep < s.size() && chars + 1 < maxChars) {
    ++keep;
    while (keep < s.size() && (static_cast<unsigned char>(s[keep]) & 0xC0) == 0x80) ++keep;
    ++chars;
  }
  return s.substr(0, keep) + "…";
}

/// Splits a title into at most two lines of at most maxChars characters (at a space), shortening
/// the second with "…" when needed.
std::vector<std::string> wrapTitle(const std::string& title, std::size_t maxChars) {
  if (utf8Length(title) <= maxChars) return {title};
  std::size_t cut = std::string::npos;
  for (std::size_t i = 0, chars = 0; i < title.size(); ++i) {
    if ((static_cast<unsigned char>(title[i]) & 0xC0) != 0x80) ++chars;
    if (chars > maxChars) break;
    if (title[i] == ' ') cut = i;
  }
  if (cut == std::string::npos || cut == 0) return {shortenText(title, maxChars)};
  return {title.substr(0, cut), shortenText(title.substr(cut + 1), maxChars)};
}

/// Every line of `text` broken at spaces to at most maxChars characters (a longer word stays whole
/// on its own line): a legend entry is wrapped, never cut.
std::vector<std::string> wrapWords(const std::string& text, std::size_t maxChars) {
  std::vector<std::string> lines;
  std::string line;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t space = text.find(' ', start);
    const std::string word = text.substr(start, space == std::string::npos ? std::string::npos : space - start);
    if (!line.empty() && utf8Length(line) + 1 + utf8Length(word) > maxChars) {
      lines.push_back(line);
      line.clear();
    }
    if (!line.empty()) line += ' ';
    line += word;
    if (space == std::string::npos) break;
    start = space + 1;
  }
  if (!line.empty() || lines.empty()) lines.push_back(line);
  return lines;
}

}  // namespace

DisplayUnit displayUnit(const std::string& siUnit, double maxAbs) {
  if (!(maxAbs > 0) || !std::isfinite(maxAbs)) return {1, siUnit == "1" ? "" : siUnit};
  const int exponent = static_cast<int>(std::floor(std::log10(maxAbs) / 3.0 + 1e-9)) * 3;
  // The leading symbol (up to a space or '/') takes the prefix when it is a base unit without a power.
  const std::size_t end = siUnit.find_first_of(" /");
  const std::string head = siUnit.substr(0, end);
  static const char* prefixable[] = {"Pa", "s", "m", "J", "N", "W"};
  const bool takesPrefix = std::find(std::begin(prefixable), std::end(prefixable), head) != std::end(prefixable);
  if (takesPrefix) {  // the prefix every number a person reads takes (rupture::formatQuantity)
    const ScaledUnit scaled = scaledUnit(maxAbs, siUnit);
    return {scaled.factor, scaled.unit};
  }
  const std::string shown = siUnit == "1" ? "" : siUnit;
  if (maxAbs >= 1e4 || maxAbs < 1e-2) {
    return {std::pow(10.0, exponent), "×" + powerOfTen(exponent) + (shown.empty() ? "" : " " + shown)};
  }
  return {1, shown};
}

std::string axisTitle(const std::string& label, const DisplayUnit& unit) {
  return unit.unit.empty() ? label : label + " [" + unit.unit + "]";
}

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

std::string summarySvg(const SummaryTable& table, const PlotRequest& request) {
  for (const auto& [name, col] : {std::pair{"x", &request.x}, std::pair{"y", &request.y}}) {
    if (!table.hasColumn(*col) &&
        std::find(table.declaredScalars.begin(), table.declaredScalars.end(), *col) == table.declaredScalars.end()) {
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
  if (request.yMin && request.yMax && !(*request.yMin < *request.yMax)) {
    throw badParameter("ymin", "ymin (" + shortNumber(*request.yMin) + ") must be below ymax (" +
                                   shortNumber(*request.yMax) + ")");
  }
  const double width = std::clamp(request.width, kMinWidth, kMaxWidth);
  const double height = std::clamp(request.height, kMinHeight, kMaxHeight);

  // Series: one per combination of the other swept parameters.
  std::vector<std::string> others;
  for (const auto& p : table.sweptPaths) {
    if (p != request.x && p != request.y) others.push_back(p);
  }
  struct Point { double x; Json xRaw; double y; int run; double err; int n; };
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
      key += (key.empty() ? "" : ", ") + (others.size() > 1 ? table.columnInfo(p).label + " " : std::string()) +
             legendValue(table.value(row, p), table.columnInfo(p).unit);
    }
    double err = 0;
    if (!request.yError.empty()) {
      const Json ev = table.value(row, request.yError);
      if (ev.is_number() && std::isfinite(ev.get<double>())) err = std::abs(ev.get<double>());
    }
    // A table of means (replicates, comparisons) counts each point's runs in "<y>.n".
    const Json count = table.value(row, request.y + ".n");
    const int n = count.is_number_integer() ? count.get<int>() : 0;
    if (!series.count(key)) seriesOrder.push_back(key);
    series[key].push_back({x, xv, yv.get<double>(), row.run, err, n});
    xs.push_back(x);
    ys.push_back(yv.get<double>());
    if (err > 0) {  // the bars must fit in the y range (the lower end only where a log axis allows)
      ys.push_back(yv.get<double>() + err);
      if (yv.get<double>() - err > 0 || request.yScale == AxisScale::Linear) ys.push_back(yv.get<double>() - err);
    }
  }

  // Every size follows the font: fontsize=24 doubles text, margins and the legend's width.
  const double f = request.fontSize / 12.0;
  const double left = kLeft * f, bottom = kBottom * f;
  const bool legend = !others.empty() && !seriesOrder.empty();
  const double right = legend ? 215 * f : 30;
  const std::string title = request.title.empty() ? table.columnInfo(request.y).label + " vs " +
                                                        table.columnInfo(request.x).label
                                                  : request.title;
  // Bold 15 px DejaVu Sans averages about 9.5 px per character.
  const std::vector<std::string> titleLines = wrapTitle(title, static_cast<std::size_t>((width - 20) / (9.5 * f)));
  const double top = kTop * f + (titleLines.size() - 1) * 18 * f;
  const double plotW = width - left - right, plotH = height - top - bottom;

  std::ostringstream svg;
  svg << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
      << "\" viewBox=\"0 0 " << width << ' ' << height
      << "\" font-family=\"DejaVu Sans, Helvetica, Arial, sans-serif\" font-size=\"" << num(12 * f) << "\">\n"
      << "<title>" << io::xmlEscape(title) << "</title>\n"
      << "<rect x=\"0\" y=\"0\" width=\"" << width << "\" height=\"" << height << "\" fill=\"white\"/>\n";
  for (std::size_t i = 0; i < titleLines.size(); ++i) {
    svg << "<text class=\"title\" x=\"" << num(width / 2) << "\" y=\"" << num((28 + 18.0 * i) * f)
        << "\" text-anchor=\"middle\" font-size=\"" << num(15 * f) << "\" font-weight=\"bold\">" << io::xmlEscape(titleLines[i])
        << "</text>\n";
  }

  if (xs.empty()) {
    svg << "<rect x=\"" << left << "\" y=\"" << top << "\" width=\"" << num(plotW) << "\" height=\""
        << num(plotH) << "\" fill=\"none\" stroke=\"#333\"/>\n"
        << "<text x=\"" << num(left + plotW / 2) << "\" y=\"" << num(top + plotH / 2)
        << "\" text-anchor=\"middle\" fill=\"#666\">no finished runs with " << io::xmlEscape(request.y)
        << " yet</text>\n</svg>\n";
    return svg.str();
  }

  const int yTicks = std::max(3, static_cast<int>(plotH / 60));
  Axis xAxis, yAxis = numericAxis(ys, request.yScale, table.columnInfo(request.y).unit, "yscale", request.yMin,
                                  request.yMax, yTicks);
  if (categorical) {
    if (request.xScale == AxisScale::Log) {
      throw badParameter("xscale", "x='" + request.x + "' holds text values; a log scale is not possible");
    }
    xAxis.categorical = true;
    xAxis.unit = {1, table.columnInfo(request.x).unit == "1" ? "" : table.columnInfo(request.x).unit};
    xAxis.lo = -0.5;
    xAxis.hi = static_cast<double>(categories.size()) - 0.5;
    for (std::size_t i = 0; i < categories.size(); ++i) xAxis.ticks.push_back({double(i), categories[i]});
  } else {
    xAxis = numericAxis(xs, request.xScale, table.columnInfo(request.x).unit, "xscale", std::nullopt, std::nullopt,
                        std::max(3, static_cast<int>(plotW / 110)));
  }
  auto px = [&](double x) { return left + (xAxis.categorical ? xAxis.fracOfAxis(x) : xAxis.frac(x)) * plotW; };
  auto py = [&](double y) { return top + plotH - yAxis.frac(y) * plotH; };

  // Grid and ticks.
  svg << "<defs><clipPath id=\"plot-area\"><rect x=\"" << left << "\" y=\"" << num(top) << "\" width=\""
      << num(plotW) << "\" height=\"" << num(plotH) << "\"/></clipPath></defs>\n";
  svg << "<g stroke=\"#e3e3e3\" stroke-width=\"1\">\n";
  for (const auto& [t, label] : xAxis.ticks) {
    const double x = left + xAxis.fracOfAxis(t) * plotW;
    svg << "<line x1=\"" << num(x) << "\" y1=\"" << num(top) << "\" x2=\"" << num(x) << "\" y2=\"" << num(top + plotH)
        << "\"/>\n";
  }
  for (const auto& [t, label] : yAxis.ticks) {
    const double y = top + plotH - yAxis.fracOfAxis(t) * plotH;
    svg << "<line x1=\"" << left << "\" y1=\"" << num(y) << "\" x2=\"" << num(left + plotW) << "\" y2=\""
        << num(y) << "\"/>\n";
  }
  svg << "</g>\n<rect x=\"" << left << "\" y=\"" << num(top) << "\" width=\"" << num(plotW) << "\" height=\""
      << num(plotH) << "\" fill=\"none\" stroke=\"#333\"/>\n";
  svg << "<g class=\"x-ticks\" text-anchor=\"middle\">\n";
  for (const auto& [t, label] : xAxis.ticks) {
    const double x = left + xAxis.fracOfAxis(t) * plotW;
    svg << "<line x1=\"" << num(x) << "\" y1=\"" << num(top + plotH) << "\" x2=\"" << num(x) << "\" y2=\""
        << num(top + plotH + 5) << "\" stroke=\"#333\"/><text x=\"" << num(x) << "\" y=\"" << num(top + plotH + 8 + 12 * f)
        << "\">" << io::xmlEscape(label) << "</text>\n";
  }
  svg << "</g>\n<g class=\"y-ticks\" text-anchor=\"end\">\n";
  for (const auto& [t, label] : yAxis.ticks) {
    const double y = top + plotH - yAxis.fracOfAxis(t) * plotH;
    svg << "<line x1=\"" << num(left - 5) << "\" y1=\"" << num(y) << "\" x2=\"" << left << "\" y2=\"" << num(y)
        << "\" stroke=\"#333\"/><text x=\"" << num(left - 8) << "\" y=\"" << num(y + 4 * f) << "\">"
        << io::xmlEscape(label) << "</text>\n";
  }
  svg << "</g>\n";
  // Axis titles: human label and displayed unit.
  svg << "<text class=\"x-label\" x=\"" << num(left + plotW / 2) << "\" y=\"" << num(height - 22 * f)
      << "\" text-anchor=\"middle\" font-size=\"" << num(13 * f) << "\">"
      << io::xmlEscape(axisTitle(table.columnInfo(request.x).label, xAxis.unit)) << "</text>\n";
  svg << "<text class=\"y-label\" transform=\"translate(" << num(22 * f) << "," << num(top + plotH / 2)
      << ") rotate(-90)\" text-anchor=\"middle\" font-size=\"" << num(13 * f) << "\">"
      << io::xmlEscape(axisTitle(table.columnInfo(request.y).label, yAxis.unit)) << "</text>\n";

  // Series, clipped to the plot area (a y range may cut points off). Categories are not joined by
  // lines; each series is shifted a little sideways so that markers of equal values stay visible.
  const ColumnInfo xInfo = table.columnInfo(request.x), yInfo = table.columnInfo(request.y);
  svg << "<g clip-path=\"url(#plot-area)\">\n";
  for (std::size_t s = 0; s < seriesOrder.size(); ++s) {
    const std::string colour = kPalette[s % std::size(kPalette)];
    std::vector<Point> pts = series[seriesOrder[s]];
    std::stable_sort(pts.begin(), pts.end(), [](const Point& a, const Point& b) { return a.x < b.x; });
    const double dodge =
        categorical && seriesOrder.size() > 1 ? (double(s) - (seriesOrder.size() - 1) / 2.0) * std::min(0.5 / seriesOrder.size(), 0.12) : 0;
    svg << "<g class=\"series\" data-label=\"" << io::xmlEscape(seriesOrder[s]) << "\">\n";
    if (pts.size() > 1 && !categorical) {
      svg << "<polyline fill=\"none\" stroke=\"" << colour << "\" stroke-width=\"2\" points=\"";
      for (const Point& p : pts) svg << num(px(p.x)) << ',' << num(py(p.y)) << ' ';
      svg << "\"/>\n";
    }
    for (const Point& p : pts) {
      const double x = px(p.x + dodge);
      if (p.err > 0) {
        const double lo = yAxis.log && p.y - p.err <= 0 ? top + plotH : py(p.y - p.err);
        const double hi = py(p.y + p.err);
        svg << "<path class=\"error-bar\" stroke=\"" << colour << "\" stroke-width=\"1.5\" fill=\"none\" d=\"M"
            << num(x) << ',' << num(lo) << 'V' << num(hi) << 'M' << num(x - 4) << ',' << num(hi) << 'H' << num(x + 4)
            << 'M' << num(x - 4) << ',' << num(lo) << 'H' << num(x + 4) << "\"/>\n";
      }
      svg << "<circle cx=\"" << num(x) << "\" cy=\"" << num(py(p.y)) << "\" r=\"4\" fill=\"" << colour
          << "\"><title>" << io::xmlEscape(pointTitle(p.n > 1 ? "mean of " + std::to_string(p.n) + " runs" : "run " + std::to_string(p.run),
                                              xInfo, p.xRaw, yInfo, p.y, p.err)) << "</title></circle>\n";
    }
    svg << "</g>\n";
  }
  svg << "</g>\n";

  // Legend: each entry wrapped to the legend's width (about 26 characters), never cut.
  if (legend) {
    const double lx = left + plotW + 20 * f, line = 16 * f;
    double ly = top + 6 * f;
    std::string heading;
    for (const auto& p : others) heading += (heading.empty() ? "" : ", ") + table.columnInfo(p).label;
    svg << "<g class=\"legend\">\n";
    for (const std::string& text : wrapWords(others.size() > 1 ? std::string("Series") : heading, 26)) {
      svg << "<text x=\"" << num(lx) << "\" y=\"" << num(ly) << "\" font-weight=\"bold\">" << io::xmlEscape(text)
          << "</text>\n";
      ly += line;
    }
    ly += 4 * f;
    for (std::size_t s = 0; s < seriesOrder.size(); ++s) {
      const std::string colour = kPalette[s % std::size(kPalette)];
      if (!categorical) {
        svg << "<line x1=\"" << num(lx) << "\" y1=\"" << num(ly - 4 * f) << "\" x2=\"" << num(lx + 22 * f) << "\" y2=\""
            << num(ly - 4 * f) << "\" stroke=\"" << colour << "\" stroke-width=\"2\"/>";
      }
      svg << "<circle cx=\"" << num(lx + 11 * f) << "\" cy=\"" << num(ly - 4 * f) << "\" r=\"4\" fill=\"" << colour
          << "\"/>";
      for (const std::string& text : wrapWords(seriesOrder[s], 22)) {
        svg << "<text class=\"entry\" x=\"" << num(lx + 30 * f) << "\" y=\"" << num(ly) << "\">" << io::xmlEscape(text)
            << "</text>";
        ly += line;
      }
      svg << "\n";
      ly += 4 * f;
    }
    svg << "</g>\n";
  }
  svg << "</svg>\n";
  return svg.str();
}

}  // namespace rupture::server
