#include "render/series_plot.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

#include "render/colour_map.hpp"
#include "render/round_ticks.hpp"
#include "rupture/quantity_text.hpp"
#include "rupture/run.hpp"

namespace rupture::render {
namespace {

std::string stringAttribute(const io::Hdf5File& file, const std::string& path, const std::string& name) {
  if (!file.exists(path) || !file.hasAttribute(path, name)) return "";
  try {
    return file.readAttributeString(path, name);
  } catch (const std::exception&) {
    return "";
  }
}

}  // namespace

std::vector<std::string> seriesOf(const io::Hdf5File& file, const std::string& root) {
  std::vector<std::string> out;
  if (!file.exists(root + "/series")) return out;
  for (const std::string& name : file.listGroup(root + "/series"))
    if (file.datasetDims(root + "/series/" + name).size() == 1) out.push_back(name);
  std::sort(out.begin(), out.end());
  return out;
}

SeriesPlot renderSeriesPlot(const io::Hdf5File& file, const SeriesPlotRequest& request, const StopCheck& stop) {
  for (const auto& [side, name] : {std::pair{request.width, "width"}, std::pair{request.height, "height"}})
    if (side < kMinImageSide || side > kMaxImageSide)
      throw FieldImageError(name, std::string(name) + " " + std::to_string(side) + "; allowed: " +
                                      std::to_string(kMinImageSide) + " to " + std::to_string(kMaxImageSide));
  const std::vector<std::string> names = seriesOf(file, request.root);
  if (names.empty()) throw FieldImageError("series", "this run has no time series");
  std::string list;
  for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
  auto has = [&](const std::string& n) { return std::find(names.begin(), names.end(), n) != names.end(); };

  const ScenarioInfo* scenario = findScenario(stringAttribute(file, request.root.empty() ? "/" : request.root, "scenario"));
  if (!scenario) scenario = findScenario(stringAttribute(file, "/", "scenario"));
  SeriesPlot out;
  out.x = !request.x.empty() ? request.x : has("strain") ? "strain" : "time";
  if (!has(out.x)) throw FieldImageError("x", "series '" + out.x + "' is not in this run; allowed: " + list);
  out.y = request.y;
  if (out.y.empty()) {
    if (scenario)
      for (const ResultField& f : scenario->series)
        if (f.name != out.x && f.name != "time" && f.name != "strain" && has(f.name)) {
          out.y.push_back(f.name);
          break;
        }
    if (out.y.empty())
      for (const std::string& n : names)
        if (n != out.x && n != "time") {
          out.y.push_back(n);
          break;
        }
  }
  if (out.y.empty()) throw FieldImageError("y", "this run has no series to plot against " + out.x);
  for (const std::string& y : out.y)
    if (!has(y)) throw FieldImageError("y", "series '" + y + "' is not in this run; allowed: " + list);

  auto unitOf = [&](const std::string& n) { return stringAttribute(file, request.root + "/series/" + n, "unit"); };
  auto labelOf = [&](const std::string& n) {
    const ResultField* f = scenario ? findResultField(scenario->series, n) : nullptr;
    return f ? f->label : n;
  };
  const std::string xUnit = unitOf(out.x), yUnit = unitOf(out.y.front());
  for (const std::string& y : out.y)
    if (unitOf(y) != yUnit)
      throw FieldImageError("y", "'" + out.y.front() + "' [" + yUnit + "] and '" + y + "' [" + unitOf(y) +
                                     "] have different units: plot them apart");
  const std::vector<double> xs = file.readDatasetDouble(request.root + "/series/" + out.x);
  std::vector<std::vector<double>> ys;
  double xlo = 1e300, xhi = -1e300, ylo = 1e300, yhi = -1e300;
  for (double v : xs)
    if (std::isfinite(v)) xlo = std::min(xlo, v), xhi = std::max(xhi, v);
  for (const std::string& y : out.y) {
    ys.push_back(file.readDatasetDouble(request.root + "/series/" + y));
    for (double v : ys.back())
      if (std::isfinite(v)) ylo = std::min(ylo, v), yhi = std::max(yhi, v);
  }
  if (xlo > xhi) xlo = 0, xhi = 1;
  if (ylo > yhi) ylo = 0, yhi = 1;
  if (xhi - xlo <= 0) xlo -= 0.5, xhi += 0.5;
  if (yhi - ylo <= 0) ylo -= std::max(0.5, 0.01 * std::abs(ylo)), yhi += std::max(0.5, 0.01 * std::abs(yhi));
  const double ypad = 0.04 * (yhi - ylo);
  ylo -= ypad, yhi += ypad;

  const double W = request.width, H = request.height;
  const double left = 90, right = 20, top = 36, bottom = 56;
  const double plotW = std::max(W - left - right, 10.0), plotH = std::max(H - top - bottom, 10.0);
  auto X = [&](double v) { return left + plotW * (v - xlo) / (xhi - xlo); };
  auto Y = [&](double v) { return top + plotH * (1 - (v - ylo) / (yhi - ylo)); };

  Canvas canvas(request.format, request.width, request.height, stop);
  {
    cairo_t* cr = canvas.context();
    cairo_select_font_face(cr, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, 11);
    cairo_set_line_width(cr, 1);
    cairo_text_extents_t e;
    for (double t : roundTicks(xlo, xhi).values) {
      cairo_set_source_rgb(cr, 0.9, 0.9, 0.9);
      cairo_move_to(cr, X(t), top);
      cairo_line_to(cr, X(t), top + plotH);
      cairo_stroke(cr);
      const std::string text = formatQuantity(t, xUnit);
      cairo_text_extents(cr, text.c_str(), &e);
      cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
      cairo_move_to(cr, X(t) - 0.5 * e.width, top + plotH + 16);
      cairo_show_text(cr, text.c_str());
    }
    for (double t : roundTicks(ylo, yhi).values) {
      cairo_set_source_rgb(cr, 0.9, 0.9, 0.9);
      cairo_move_to(cr, left, Y(t));
      cairo_line_to(cr, left + plotW, Y(t));
      cairo_stroke(cr);
      const std::string text = formatQuantity(t, yUnit);
      cairo_text_extents(cr, text.c_str(), &e);
      cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
      cairo_move_to(cr, left - 6 - e.width, Y(t) + 4);
      cairo_show_text(cr, text.c_str());
    }
    cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
    cairo_rectangle(cr, left, top, plotW, plotH);
    cairo_stroke(cr);
    cairo_set_font_size(cr, 13);
    const std::string xTitle = labelOf(out.x);
    cairo_text_extents(cr, xTitle.c_str(), &e);
    cairo_move_to(cr, left + 0.5 * (plotW - e.width), H - 14);
    cairo_show_text(cr, xTitle.c_str());
    std::string title;
    for (const std::string& y : out.y) title += (title.empty() ? "" : ", ") + labelOf(y);
    title += " vs " + xTitle;
    cairo_set_font_size(cr, 14);
    cairo_move_to(cr, left, 22);
    cairo_show_text(cr, title.c_str());

    cairo_save(cr);
    cairo_rectangle(cr, left, top, plotW, plotH);
    cairo_clip(cr);
    cairo_set_line_width(cr, 1.8);
    for (std::size_t s = 0; s < ys.size(); ++s) {
      const Rgb c = viridis(ys.size() == 1 ? 0.25 : 0.85 * static_cast<double>(s) / static_cast<double>(ys.size() - 1));
      cairo_set_source_rgb(cr, c.r, c.g, c.b);
      bool pen = false;
      for (std::size_t k = 0; k < std::min(xs.size(), ys[s].size()); ++k) {
        if (!std::isfinite(xs[k]) || !std::isfinite(ys[s][k])) {
          pen = false;
          continue;
        }
        if (pen) cairo_line_to(cr, X(xs[k]), Y(ys[s][k]));
        else cairo_move_to(cr, X(xs[k]), Y(ys[s][k]));
        pen = true;
      }
      cairo_stroke(cr);
      if (ys.size() > 1) {  // legend, top left inside the frame
        cairo_set_font_size(cr, 11);
        cairo_move_to(cr, left + 10, top + 16 + 16.0 * static_cast<double>(s));
        cairo_line_to(cr, left + 30, top + 16 + 16.0 * static_cast<double>(s));
        cairo_stroke(cr);
        cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
        cairo_move_to(cr, left + 36, top + 20 + 16.0 * static_cast<double>(s));
        cairo_show_text(cr, labelOf(out.y[s]).c_str());
      }
    }
    cairo_restore(cr);
  }
  out.bytes = canvas.finish();
  out.mediaType = mediaTypeOf(request.format);
  return out;
}

}  // namespace rupture::render
