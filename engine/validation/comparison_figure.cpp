#include "validation/comparison_figure.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <vector>

#include "io/xml_escape.hpp"

namespace rupture::validation {

namespace {

using Json = nlohmann::json;

constexpr double kWidth = 640, kHeight = 400;
constexpr double kLeft = 70, kRight = 20, kTop = 30, kBottom = 50;

struct Range {
  double lo = std::numeric_limits<double>::infinity(), hi = -std::numeric_limits<double>::infinity();
  void add(double v) {
    if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
  }
  bool empty() const { return !(lo <= hi); }
};

/// Nice tick positions covering [lo, hi] (about five), and the range widened to them.
std::vector<double> ticks(Range& r) {
  if (r.empty()) r = {0, 1};
  if (r.hi - r.lo < 1e-12 * std::max(1.0, std::fabs(r.hi))) r.lo -= 0.5 * std::max(1.0, std::fabs(r.lo)) * 0.1, r.hi += 0.5 * std::max(1.0, std::fabs(r.hi)) * 0.1;
  const double raw = (r.hi - r.lo) / 5;
  const double magnitude = std::pow(10, std::floor(std::log10(raw)));
  double step = magnitude;
  for (double m : {1.0, 2.0, 2.5, 5.0, 10.0})
    if (m * magnitude >= raw) {
      step = m * magnitude;
      break;
    }
  r.lo = std::floor(r.lo / step) * step;
  r.hi = std::ceil(r.hi / step) * step;
  std::vector<double> out;
  for (double t = r.lo; t <= r.hi + step * 1e-6; t += step) out.push_back(std::fabs(t) < step * 1e-9 ? 0.0 : t);
  return out;
}

std::string number(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4g", v);
  return buffer;
}

class Canvas {
public:
  Canvas(Range x, Range y, const std::string& title, const std::string& xLabel, const std::string& yLabel)
      : m_xTicks(ticks(x)), m_yTicks(ticks(y)), m_x(x), m_y(y) {
    m_svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << kWidth << "\" height=\"" << kHeight
          << "\" viewBox=\"0 0 " << kWidth << ' ' << kHeight << "\" font-family=\"sans-serif\" font-size=\"12\">\n"
          << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
          << "<text x=\"" << kWidth / 2 << "\" y=\"18\" text-anchor=\"middle\" font-size=\"13\">" << io::xmlEscape(title)
          << "</text>\n";
    for (double t : m_xTicks)
      m_svg << "<line x1=\"" << px(t) << "\" y1=\"" << kTop << "\" x2=\"" << px(t) << "\" y2=\"" << kHeight - kBottom
            << "\" stroke=\"#e4e4e4\"/><text x=\"" << px(t) << "\" y=\"" << kHeight - kBottom + 16
            << "\" text-anchor=\"middle\">" << number(t) << "</text>\n";
    for (double t : m_yTicks)
      m_svg << "<line x1=\"" << kLeft << "\" y1=\"" << py(t) << "\" x2=\"" << kWidth - kRight << "\" y2=\"" << py(t)
            << "\" stroke=\"#e4e4e4\"/><text x=\"" << kLeft - 6 << "\" y=\"" << py(t) + 4 << "\" text-anchor=\"end\">"
            << number(t) << "</text>\n";
    m_svg << "<rect x=\"" << kLeft << "\" y=\"" << kTop << "\" width=\"" << kWidth - kLeft - kRight << "\" height=\""
          << kHeight - kTop - kBottom << "\" fill=\"none\" stroke=\"#444\"/>\n"
          << "<text x=\"" << (kLeft + kWidth - kRight) / 2 << "\" y=\"" << kHeight - 12 << "\" text-anchor=\"middle\">"
          << io::xmlEscape(xLabel) << "</text>\n"
          << "<text transform=\"translate(16 " << (kTop + kHeight - kBottom) / 2 << ") rotate(-90)\" text-anchor=\"middle\">"
          << io::xmlEscape(yLabel) << "</text>\n";
  }
  double px(double x) const { return kLeft + (x - m_x.lo) / (m_x.hi - m_x.lo) * (kWidth - kLeft - kRight); }
  double py(double y) const { return kHeight - kBottom - (y - m_y.lo) / (m_y.hi - m_y.lo) * (kHeight - kTop - kBottom); }
  double clampY(double y) const { return std::clamp(y, m_y.lo, m_y.hi); }
  std::ostringstream& out() { return m_svg; }
  void legend(const std::string& colour, const std::string& text, bool dashed = false) {
    // Right-aligned in the plot's top corner; about 6.5 px per character at 12 px.
    const double y = kTop + 14 + 16 * m_legendRows++;
    const double x = std::max(kLeft + 10, kWidth - kRight - 40 - 6.5 * static_cast<double>(text.size()));
    m_svg << "<line x1=\"" << x << "\" y1=\"" << y - 4 << "\" x2=\"" << x + 20 << "\" y2=\"" << y - 4 << "\" stroke=\""
          << colour << "\" stroke-width=\"2\"" << (dashed ? " stroke-dasharray=\"6 3\"" : "") << "/><text x=\"" << x + 25
          << "\" y=\"" << y << "\">" << io::xmlEscape(text) << "</text>\n";
  }
  std::string finish() {
    m_svg << "</svg>\n";
    return m_svg.str();
  }
  const Range& xRange() const { return m_x; }
  const Range& yRange() const { return m_y; }

private:
  std::vector<double> m_xTicks, m_yTicks;
  Range m_x, m_y;
  std::ostringstream m_svg;
  int m_legendRows = 0;
};

double numberOr(const Json& j, double fallback) { return j.is_number() ? j.get<double>() : fallback; }

std::string curveFigure(const Json& result, const Json& f) {
  const Json& xs = f["ours"]["x"];
  const Json& ys = f["ours"]["y"];
  Range x, y;
  for (std::size_t k = 0; k < xs.size(); ++k) x.add(xs[k].get<double>()), y.add(ys[k].get<double>());
  for (const Json& p : f["points"]) {
    x.add(p[0].get<double>());
    y.add(p[1].get<double>() - p[2].get<double>());
    y.add(p[1].get<double>() + p[2].get<double>());
  }
  for (const Json& l : f["lines"]) y.add(numberOr(l["low"], NAN)), y.add(numberOr(l["high"], NAN));
  const Json verticals = f.value("vertical_lines", Json::array());
  for (const Json& l : verticals) x.add(numberOr(l["low"], NAN)), x.add(numberOr(l["high"], NAN));
  Canvas canvas(x, y, result.value("title", ""), f.value("x_label", ""), f.value("y_label", ""));
  auto& svg = canvas.out();
  const char* palette[] = {"#d62728", "#2ca02c", "#9467bd", "#8c564b"};
  int line = 0;
  for (const Json& l : f["lines"]) {
    const std::string colour = palette[line++ % 4];
    const double lo = numberOr(l["low"], NAN), hi = numberOr(l["high"], NAN);
    const double x0 = canvas.px(canvas.xRange().lo), x1 = canvas.px(canvas.xRange().hi);
    if (std::isfinite(lo) && std::isfinite(hi) && hi > lo)
      svg << "<rect x=\"" << x0 << "\" y=\"" << canvas.py(hi) << "\" width=\"" << x1 - x0 << "\" height=\""
          << canvas.py(lo) - canvas.py(hi) << "\" fill=\"" << colour << "\" fill-opacity=\"0.15\"/>\n";
    for (double v : {lo, hi})
      if (std::isfinite(v))
        svg << "<line x1=\"" << x0 << "\" y1=\"" << canvas.py(v) << "\" x2=\"" << x1 << "\" y2=\"" << canvas.py(v)
            << "\" stroke=\"" << colour << "\" stroke-width=\"1.5\" stroke-dasharray=\"6 3\"/>\n";
    canvas.legend(colour, "reference: " + l.value("label", ""), true);
  }
  for (const Json& l : verticals) {
    const std::string colour = palette[line++ % 4];
    const double y0 = canvas.py(canvas.yRange().lo), y1 = canvas.py(canvas.yRange().hi);
    for (double v : {numberOr(l["low"], NAN), numberOr(l["high"], NAN)})
      if (std::isfinite(v))
        svg << "<line x1=\"" << canvas.px(v) << "\" y1=\"" << y0 << "\" x2=\"" << canvas.px(v) << "\" y2=\"" << y1
            << "\" stroke=\"" << colour << "\" stroke-width=\"1.5\" stroke-dasharray=\"6 3\"/>\n";
    canvas.legend(colour, "reference: " + l.value("label", ""), true);
  }
  if (!xs.empty()) {
    svg << "<polyline fill=\"none\" stroke=\"#1f77b4\" stroke-width=\"1.5\" points=\"";
    for (std::size_t k = 0; k < xs.size(); ++k) svg << canvas.px(xs[k].get<double>()) << ',' << canvas.py(ys[k].get<double>()) << ' ';
    svg << "\"/>\n";
    canvas.legend("#1f77b4", "Rupture (this build)");
  }
  if (!f["points"].empty()) {
    for (const Json& p : f["points"]) {
      const double px = canvas.px(p[0].get<double>()), v = p[1].get<double>(), u = p[2].get<double>();
      svg << "<line x1=\"" << px << "\" y1=\"" << canvas.py(v - u) << "\" x2=\"" << px << "\" y2=\"" << canvas.py(v + u)
          << "\" stroke=\"black\"/><circle cx=\"" << px << "\" cy=\"" << canvas.py(v) << "\" r=\"4\" fill=\"white\" stroke=\"black\"/>\n";
    }
    canvas.legend("black", f.value("points_label", std::string("reference points")));
  }
  return canvas.finish();
}

/// Scalars only: each quantity's signed deviation (tolerance units) against the passing band.
std::string deviationFigure(const Json& result) {
  const Json& quantities = result["quantities"];
  Range x{0, static_cast<double>(std::max<std::size_t>(1, quantities.size())) + 1}, y{-2, 2};
  std::vector<double> values;
  for (const Json& q : quantities) {
    double d = q["deviation"].is_number() ? q["deviation"].get<double>() : (q["deviation"].is_string() ? 1e9 : NAN);
    if (q["off"].is_number() && q["off"].get<double>() < 0) d = -d;
    values.push_back(d);
    if (std::isfinite(d)) y.add(std::clamp(d, -10.0, 10.0));
  }
  Canvas canvas(x, y, result.value("title", ""), "quantity (numbered as in the table)",
                "deviation: (ours - reference) / allowed difference");
  auto& svg = canvas.out();
  svg << "<rect x=\"" << kLeft << "\" y=\"" << canvas.py(1) << "\" width=\"" << kWidth - kLeft - kRight
      << "\" height=\"" << canvas.py(-1) - canvas.py(1) << "\" fill=\"#2ca02c\" fill-opacity=\"0.15\"/>\n";
  canvas.legend("#2ca02c", "within tolerance (|deviation| <= 1)", true);
  for (std::size_t k = 0; k < values.size(); ++k) {
    const double px = canvas.px(static_cast<double>(k) + 1);
    const std::string verdict = quantities[k].value("verdict", "");
    const std::string colour = verdict == "pass" ? "#1f77b4" : verdict == "known failure" ? "#ff7f0e" : "#d62728";
    if (std::isfinite(values[k]))
      svg << "<circle cx=\"" << px << "\" cy=\"" << canvas.py(canvas.clampY(values[k])) << "\" r=\"5\" fill=\"" << colour << "\"/>\n";
    else
      svg << "<text x=\"" << px << "\" y=\"" << canvas.py(0) << "\" text-anchor=\"middle\" fill=\"#d62728\">n/a</text>\n";
    svg << "<text x=\"" << px << "\" y=\"" << kHeight - kBottom - 6 << "\" text-anchor=\"middle\" font-size=\"10\">" << k + 1 << "</text>\n";
  }
  return canvas.finish();
}

}  // namespace

std::string comparisonFigureSvg(const Json& result) {
  auto f = result.find("figure");
  if (f != result.end() && !f->at("ours").at("x").empty()) return curveFigure(result, *f);
  return deviationFigure(result);
}

}  // namespace rupture::validation
