#include "render/field_image.hpp"

#include <algorithm>
#include <cstdlib>
#include <cmath>
#include <memory>
#include <numeric>
#include <set>
#include <tuple>

#include "io/xml_escape.hpp"
#include "render/colour_map.hpp"
#include "render/loading_marks.hpp"
#include "render/round_ticks.hpp"
#include "rupture/quantity_text.hpp"

namespace rupture::render {
namespace {

std::string axisName(int a) { return std::string(1, static_cast<char>('x' + a)); }

/// The snapshot the request names: by time (nearest), by index (negative from the end), or the last.
std::size_t chooseSnapshot(const std::vector<SnapshotRef>& snapshots, const FieldImageRequest& request) {
  const long count = static_cast<long>(snapshots.size());
  if (request.time) {
    if (!std::isfinite(*request.time))
      throw FieldImageError("time", "time must be a finite number of seconds");
    std::size_t best = 0;
    for (std::size_t k = 1; k < snapshots.size(); ++k)
      if (std::abs(snapshots[k].time - *request.time) < std::abs(snapshots[best].time - *request.time)) best = k;
    return best;
  }
  const long index = request.snapshot.value_or(-1);
  const long resolved = index < 0 ? count + index : index;
  if (resolved < 0 || resolved >= count) {
    throw FieldImageError("snapshot", "snapshot " + std::to_string(index) + " is out of range; allowed: 0 to " +
                                          std::to_string(count - 1) + ", or -1 to -" + std::to_string(count) +
                                          " from the end");
  }
  return static_cast<std::size_t>(resolved);
}

/// The body filter: the request's, else from the run's kind (the plate for a tank's damage).
std::string bodyChoice(const SnapshotField& s, const std::string& field, const std::string& body) {
  if (!body.empty()) return body;
  if (s.body.empty()) return "all";
  if (field == "damage" && s.plateBody) return std::to_string(*s.plateBody);
  return "fluid";
}

/// Which particles to draw: a body filter from the request or the run's kind.
std::vector<std::size_t> selectParticles(const SnapshotField& s, const std::string& field, const std::string& body,
                                         std::string& note) {
  const std::size_t n = s.position.size();
  const std::string choice = bodyChoice(s, field, body);
  std::vector<std::size_t> out;
  if (choice == "all") {
    out.resize(n);
    std::iota(out.begin(), out.end(), std::size_t{0});
    return out;
  }
  if (s.body.size() != n) throw FieldImageError("body", "body '" + body + "': this run records no bodies; allowed: all");
  int wanted = -1;
  if (choice != "fluid") {
    std::size_t used = 0;
    try {
      wanted = std::stoi(choice, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != choice.size() || wanted < 0)
      throw FieldImageError("body", "body '" + body + "'; allowed: all, fluid, or a body index (an integer >= 0)");
  }
  for (std::size_t k = 0; k < n; ++k)
    if (choice == "fluid" ? s.body[k] < 0 : s.body[k] == wanted) out.push_back(k);
  // A body asked for by name that no particle belongs to would be an empty picture: say which exist.
  if (out.empty() && !body.empty()) {
    std::set<int> present(s.body.begin(), s.body.end());
    std::string allowed = "all";
    if (present.count(-1)) allowed += ", fluid";
    for (int b : present)
      if (b >= 0) allowed += ", " + std::to_string(b);
    throw FieldImageError("body", "body '" + body + "': no particle of this run belongs to it; allowed: " + allowed);
  }
  note = choice == "fluid" ? "fluid" : (s.plateBody && wanted == *s.plateBody ? "plate" : "body " + choice);
  return out;
}

struct Plane {
  int u = 0, v = 1, depth = 2;
};

Plane choosePlane(const std::string& view, const SnapshotField& s, const std::vector<std::size_t>& drawn,
                  bool plateOnly) {
  if (!view.empty()) {
    if (view == "xy") return {0, 1, 2};
    if (view == "xz") return {0, 2, 1};
    if (view == "yz") return {1, 2, 0};
    throw FieldImageError("view", "view '" + view + "'; allowed: xy, xz, yz");
  }
  std::array<double, 3> lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  for (std::size_t k : drawn)
    for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], s.position[k][a]), hi[a] = std::max(hi[a], s.position[k][a]);
  std::array<double, 3> extent{};
  for (int a = 0; a < 3; ++a) extent[a] = drawn.empty() ? 0 : hi[a] - lo[a];
  auto planeWithout = [](int depth) {
    Plane p;
    p.depth = depth;
    p.u = depth == 0 ? 1 : 0;
    p.v = depth == 2 ? 1 : 2;
    return p;
  };
  if (s.verticalAxis) {
    const int up = *s.verticalAxis;
    if (plateOnly) return planeWithout(up);  // the plate seen from above
    // A vertical section through the wider horizontal axis.
    int other = -1;
    for (int a = 0; a < 3; ++a)
      if (a != up && (other < 0 || extent[a] > extent[other])) other = a;
    Plane p;
    p.u = other;
    p.v = up;
    p.depth = 3 - up - other;
    return p;
  }
  int depth = 2;  // the smallest extent (z first: a 2D run's)
  for (int a : {1, 0})
    if (extent[a] < extent[depth]) depth = a;
  return planeWithout(depth);
}


/// The field's range over every snapshot of the run, for the particles of the chosen body (all,
/// "fluid" or an index): the default colour range, so that one colour is one value on every
/// snapshot of a run. The slice is not applied: a slice moves with the view, the range does not.
std::pair<double, double> runRange(const io::Hdf5File& file, const std::vector<SnapshotRef>& snapshots,
                                   const std::string& field, const std::string& choice, const StopCheck& stop) {
  double lo = 1e300, hi = -1e300;
  const bool fluid = choice == "fluid", all = choice == "all";
  const int wanted = fluid || all ? -1 : std::atoi(choice.c_str());
  for (const SnapshotRef& snapshot : snapshots) {
    if (stop && stop()) throw RenderStopped();
    const FieldValues f = readFieldValues(file, snapshot, field);
    const bool filtered = !all && f.body.size() == f.value.size();
    for (std::size_t k = 0; k < f.value.size(); ++k) {
      if (filtered && (fluid ? f.body[k] >= 0 : f.body[k] != wanted)) continue;
      if (std::isfinite(f.value[k])) lo = std::min(lo, f.value[k]), hi = std::max(hi, f.value[k]);
    }
  }
  return {lo, hi};
}

/// An arrow from (x0, y0) to (x1, y1) with a filled head at the end.
void arrow(cairo_t* cr, double x0, double y0, double x1, double y1) {
  const double angle = std::atan2(y1 - y0, x1 - x0), head = 9, spread = 0.45;
  cairo_move_to(cr, x0, y0);
  cairo_line_to(cr, x1 - 0.8 * head * std::cos(angle), y1 - 0.8 * head * std::sin(angle));
  cairo_stroke(cr);
  cairo_move_to(cr, x1, y1);
  cairo_line_to(cr, x1 - head * std::cos(angle - spread), y1 - head * std::sin(angle - spread));
  cairo_line_to(cr, x1 - head * std::cos(angle + spread), y1 - head * std::sin(angle + spread));
  cairo_close_path(cr);
  cairo_fill(cr);
}

/// Text on a white ground, so that it reads over particles of any colour.
void label(cairo_t* cr, double x, double y, const std::string& text) {
  cairo_text_extents_t e;
  cairo_text_extents(cr, text.c_str(), &e);
  cairo_save(cr);
  cairo_set_source_rgba(cr, 1, 1, 1, 0.8);
  cairo_rectangle(cr, x - 2, y + e.y_bearing - 2, e.x_advance + 4, e.height + 4);
  cairo_fill(cr);
  cairo_restore(cr);
  cairo_move_to(cr, x, y);
  cairo_show_text(cr, text.c_str());
}

std::string directionName(int axis, double sign) { return std::string(sign < 0 ? "−" : "+") + axisName(axis); }

/// cairo writes text as glyph outlines; a <title> and a <desc> say in words what the picture
/// shows (its axes, colour range and loading), for screen readers and for checks of the picture.
std::string describeSvg(std::string svg, const std::string& title, const std::string& description) {
  const std::size_t open = svg.find("<svg");
  const std::size_t end = open == std::string::npos ? open : svg.find('>', open);
  if (end == std::string::npos) return svg;
  svg.insert(end + 1, "\n<title>" + io::xmlEscape(title) + "</title>\n<desc id=\"picture-description\">" +
                          io::xmlEscape(description) + "</desc>");
  return svg;
}

}  // namespace

FieldImage renderFieldImage(const io::Hdf5File& file, const FieldImageRequest& request, const StopCheck& stop) {
  if (request.width < kMinImageSide || request.width > kMaxImageSide)
    throw FieldImageError("width", "width " + std::to_string(request.width) + "; allowed: " +
                                       std::to_string(kMinImageSide) + " to " + std::to_string(kMaxImageSide));
  if (request.height < kMinImageSide || request.height > kMaxImageSide)
    throw FieldImageError("height", "height " + std::to_string(request.height) + "; allowed: " +
                                        std::to_string(kMinImageSide) + " to " + std::to_string(kMaxImageSide));
  if (!request.bonds.empty() && request.bonds != "broken" && request.bonds != "all" && request.bonds != "none")
    throw FieldImageError("bonds", "bonds '" + request.bonds + "'; allowed: broken, all, none");
  if (request.slice && !(*request.slice >= 0 && std::isfinite(*request.slice)))
    throw FieldImageError("slice", "slice must be a distance >= 0 (m); 0 draws every particle");
  for (const auto& [bound, name] : {std::pair{request.min, "min"}, std::pair{request.max, "max"}})
    if (bound && !std::isfinite(*bound)) throw FieldImageError(name, std::string(name) + " must be a finite number");
  if (request.min && request.max && !(*request.max > *request.min))
    throw FieldImageError("max", "max must be greater than min");
  if (!request.range.empty() && request.range != "run" && request.range != "snapshot")
    throw FieldImageError("range", "range '" + request.range + "'; allowed: run, snapshot");

  const std::vector<SnapshotRef> snapshots = listSnapshots(file, request.root);
  if (snapshots.empty())
    throw FieldImageError("snapshot", "this run has no snapshots (no particle field was recorded)");
  const std::size_t index = chooseSnapshot(snapshots, request);
  const SnapshotRef& snapshot = snapshots[index];
  std::string field = request.field;
  if (field.empty()) {
    const std::vector<std::string> available = fieldsOf(file, snapshot.group);
    if (available.empty()) throw FieldImageError("field", "this run's snapshots hold no field a picture can show");
    field = available.front();
  } else if (!findFieldDeclaration(field)) {
    std::string allowed;
    for (const FieldDeclaration& f : fieldDeclarations()) allowed += (allowed.empty() ? "" : ", ") + std::string(f.name);
    throw FieldImageError("field", "field '" + field + "'; allowed: " + allowed);
  }
  const FieldDeclaration& declaration = *findFieldDeclaration(field);
  const SnapshotField s = readSnapshotField(file, request.root, snapshot, field);
  if (stop && stop()) throw RenderStopped();  // reading a large snapshot takes a while

  // Bonds drawn: as asked, else the broken ones where a particle has a few bonds; a peridynamic
  // family (tens per particle) would paint a crack solid red over the damage that shows it.
  const double bondsPerParticle =
      s.position.empty() ? 0 : static_cast<double>(s.brokenBonds.size() + s.intactBonds.size()) / s.position.size();
  const std::string bonds = !request.bonds.empty() ? request.bonds : bondsPerParticle > 6 ? "none" : "broken";

  std::string bodyNote;
  std::vector<std::size_t> drawn = selectParticles(s, field, request.body, bodyNote);
  const bool plateOnly = bodyNote == "plate";
  const Plane plane = choosePlane(request.view, s, drawn, plateOnly);

  // A slab through the middle of the depth axis, so a 3D fluid shows its section, not its skin.
  double meanRadius = 0;
  for (std::size_t k : drawn) meanRadius += s.radius[k];
  meanRadius = drawn.empty() ? 0 : meanRadius / static_cast<double>(drawn.size());
  double lo = 1e300, hi = -1e300;
  for (std::size_t k : drawn) lo = std::min(lo, s.position[k][plane.depth]), hi = std::max(hi, s.position[k][plane.depth]);
  const bool thick = !drawn.empty() && hi - lo > 8 * meanRadius;
  const double slice = request.slice.value_or(thick && !s.body.empty() && !plateOnly ? 2 * meanRadius : 0);
  std::string sliceNote;
  if (slice > 0 && !drawn.empty()) {
    double middle = 0.5 * (lo + hi);
    if (std::abs(middle) < 1e-3 * (hi - lo)) middle = 0;  // a centred domain's middle reads 0, not 2.5 µm
    std::vector<std::size_t> kept;
    for (std::size_t k : drawn)
      if (std::abs(s.position[k][plane.depth] - middle) <= slice) kept.push_back(k);
    drawn.swap(kept);
    sliceNote = "slice |";  // appended piecewise: GCC 12 misreads "..." + std::string&& (-Wrestrict)
    sliceNote += axisName(plane.depth);
    sliceNote += " - " + formatQuantity(middle, "m") + "| <= " + formatQuantity(slice, "m");
  }
  // Far to near along the depth axis: the nearest particles are drawn last.
  std::stable_sort(drawn.begin(), drawn.end(),
                   [&](std::size_t a, std::size_t b) { return s.position[a][plane.depth] < s.position[b][plane.depth]; });

  // The colour range: damage 0..1; else by default the field's range over the run's snapshots.
  std::string rangeSource = field == "damage" ? "fixed" : request.range == "snapshot" ? "snapshot" : "run";
  double vmin = field == "damage" ? 0 : 1e300, vmax = field == "damage" ? 1 : -1e300;
  if (field != "damage" && !(request.min && request.max)) {
    if (rangeSource == "run") {
      std::tie(vmin, vmax) = runRange(file, snapshots, field, bodyChoice(s, field, request.body), stop);
    } else {
      for (std::size_t k : drawn)
        if (std::isfinite(s.value[k])) vmin = std::min(vmin, s.value[k]), vmax = std::max(vmax, s.value[k]);
    }
    if (vmin > vmax) vmin = 0, vmax = 1;
    if (vmax - vmin <= 1e-12 * std::max(std::abs(vmin), std::abs(vmax))) {
      const double pad = vmin == 0 ? 1 : 0.01 * std::abs(vmin);
      vmin -= pad, vmax += pad;
    }
  }
  if (request.min) vmin = *request.min;
  if (request.max) vmax = *request.max;
  if (request.min && request.max) rangeSource = "asked";
  if (!(vmax > vmin)) throw FieldImageError(request.max ? "max" : "min", "the colour range is empty: min must be below max");

  // Layout: the title above, the colour bar on the right, axes left and below, the particles
  // fitted with equal scales and, where the run is loaded, room around them for the arrows.
  const double W = request.width, H = request.height;
  const bool text = !request.thumbnail;
  const bool axes = text && request.axes;
  const std::vector<LoadingMark> marks = axes ? loadingMarks(file, request.root) : std::vector<LoadingMark>{};
  const double top = text ? 34 : 2, bottom = axes ? 44 : text ? 10 : 2, left = axes ? 64 : text ? 10 : 2,
               right = text ? 120 : 2;
  const double pad = marks.empty() ? 0 : 46;  // px between the body and its axes: the arrows and their labels
  double ulo = 1e300, uhi = -1e300, vlo = 1e300, vhi = -1e300;
  for (std::size_t k : drawn) {
    const double r = s.radius[k];
    ulo = std::min(ulo, s.position[k][plane.u] - r), uhi = std::max(uhi, s.position[k][plane.u] + r);
    vlo = std::min(vlo, s.position[k][plane.v] - r), vhi = std::max(vhi, s.position[k][plane.v] + r);
  }
  if (drawn.empty()) ulo = vlo = 0, uhi = vhi = 1;
  const double boxW = std::max(W - left - right - 2 * pad, 1.0), boxH = std::max(H - top - bottom - 2 * pad, 1.0);
  const double scale = std::min(boxW / std::max(uhi - ulo, 1e-300), boxH / std::max(vhi - vlo, 1e-300));
  const double offU = left + pad + 0.5 * (boxW - scale * (uhi - ulo)),
               offV = top + pad + 0.5 * (boxH - scale * (vhi - vlo));
  auto X = [&](double u) { return offU + scale * (u - ulo); };
  auto Y = [&](double v) { return offV + scale * (vhi - v); };  // v up
  auto px = [&](std::size_t k) { return X(s.position[k][plane.u]); };
  auto py = [&](std::size_t k) { return Y(s.position[k][plane.v]); };

  FieldImage out;
  // Colour bar ticks at round values, labelled as plain numbers under one unit (0, 50, 100 MPa).
  const RoundTicks colourTicks = roundTicks(vmin, vmax, 5);
  const ScaledUnit colourUnit = scaledUnit(std::max(std::abs(vmin), std::abs(vmax)), declaration.unit);
  out.colourTicks = colourTicks.values;
  out.colourUnit = colourUnit.unit;
  // Both axes in one unit (equal scales), from the larger coordinate: µm for a 1 µm sample.
  const ScaledUnit lengthUnit =
      scaledUnit(std::max({std::abs(ulo), std::abs(uhi), std::abs(vlo), std::abs(vhi), uhi - ulo, vhi - vlo}), "m");
  // Ticks about every 90 px across and 70 px up, three intervals at least (a narrow column still
  // reads); a round value within 2 % beyond the drawn extent (a sample from 17.8 pm to 0.99999 µm)
  // still gets its tick, the axis line reaching it.
  auto axisTicks = [](double lo, double hi, double pixels, double every) {
    const double margin = 0.02 * (hi - lo);
    return roundTicks(lo - margin, hi + margin, std::max(3, static_cast<int>(pixels / every)));
  };
  const RoundTicks uTicks = axisTicks(ulo, uhi, scale * (uhi - ulo), 90);
  const RoundTicks vTicks = axisTicks(vlo, vhi, scale * (vhi - vlo), 70);
  if (axes) {
    out.axes.push_back({axisName(plane.u), lengthUnit.unit, ulo, uhi, uTicks.values});
    out.axes.push_back({axisName(plane.v), lengthUnit.unit, vlo, vhi, vTicks.values});
  }

  Canvas canvas(request.format, request.width, request.height, stop);
  std::string title, detail;
  {
    cairo_t* cr = canvas.context();
    std::size_t painted = 0;
    for (std::size_t k : drawn) {
      if (++painted % 4096 == 0) canvas.checkStop();
      const Rgb c = viridis((s.value[k] - vmin) / (vmax - vmin));
      cairo_set_source_rgb(cr, c.r, c.g, c.b);
      // Discs under two pixels are squares: anti-aliased dots would leave the background between them.
      const double r = std::max(0.75, scale * s.radius[k]);
      if (r < 2) cairo_rectangle(cr, px(k) - r, py(k) - r, 2 * r, 2 * r);
      else cairo_arc(cr, px(k), py(k), r, 0, 2 * M_PI);
      cairo_fill(cr);
    }
    // Bonds between drawn particles only (a slice or body filter hides the others' bonds).
    std::vector<char> shown(s.position.size(), 0);
    for (std::size_t k : drawn) shown[k] = 1;
    auto strokeBonds = [&](const std::vector<std::array<std::size_t, 2>>& pairs) {
      for (const auto& [i, j] : pairs) {
        if (!shown[i] || !shown[j]) continue;
        cairo_move_to(cr, px(i), py(i));
        cairo_line_to(cr, px(j), py(j));
      }
      cairo_stroke(cr);
    };
    canvas.checkStop();
    if (bonds == "all" && !s.intactBonds.empty()) {
      cairo_set_source_rgba(cr, 0.35, 0.35, 0.35, 0.6);
      cairo_set_line_width(cr, std::max(0.4, 0.15 * scale * meanRadius));
      strokeBonds(s.intactBonds);
    }
    if (bonds != "none" && !s.brokenBonds.empty()) {
      cairo_set_source_rgb(cr, 0.84, 0.15, 0.16);  // red: visible on every viridis colour
      cairo_set_line_width(cr, std::max(1.0, 0.5 * scale * meanRadius));
      cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
      strokeBonds(s.brokenBonds);
    }
    cairo_set_line_cap(cr, CAIRO_LINE_CAP_BUTT);

    if (text) {
      cairo_select_font_face(cr, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
      // Title: what, when, which (snapshots numbered from 0, as the request's index).
      title = std::string(declaration.label) + ", t = " + formatQuantity(snapshot.time, "s");
      if (snapshot.strain) title += ", strain " + formatQuantity(*snapshot.strain, "1");
      title += " (snapshot " + std::to_string(index) + " of 0 to " + std::to_string(snapshots.size() - 1) + ")";
      detail = "view " + axisName(plane.u) + axisName(plane.v);
      if (!bodyNote.empty()) detail += ", " + bodyNote;
      if (!sliceNote.empty()) detail += ", " + sliceNote;
      if (!s.brokenBonds.empty() && bonds != "none")
        detail += ", " + std::to_string(s.brokenBonds.size()) + " broken bonds in red";
      cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
      cairo_set_font_size(cr, 14);
      cairo_move_to(cr, 10, 17);
      cairo_show_text(cr, title.c_str());
      cairo_set_font_size(cr, 11);
      cairo_set_source_rgb(cr, 0.35, 0.35, 0.35);
      cairo_move_to(cr, 10, 30);
      cairo_show_text(cr, detail.c_str());

      // Colour bar with ticks at round values; the range's source under it.
      const double barX = W - right + 18, barW = 14, barTop = top + 18, barH = std::max(H - top - bottom - 46, 20.0);
      cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
      cairo_set_font_size(cr, 11);
      const std::string barTitle =
          std::string(declaration.label) + (colourUnit.unit.empty() ? "" : " (" + colourUnit.unit + ")");
      cairo_text_extents_t e;
      cairo_text_extents(cr, barTitle.c_str(), &e);
      cairo_move_to(cr, std::min(barX - 4, W - 4 - e.x_advance), top + 10);
      cairo_show_text(cr, barTitle.c_str());
      const int steps = 64;
      for (int i = 0; i < steps; ++i) {
        const Rgb c = viridis(1.0 - (i + 0.5) / steps);
        cairo_set_source_rgb(cr, c.r, c.g, c.b);
        cairo_rectangle(cr, barX, barTop + barH * i / steps, barW, barH / steps + 0.5);
        cairo_fill(cr);
      }
      cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
      cairo_set_line_width(cr, 1);
      cairo_rectangle(cr, barX, barTop, barW, barH);
      cairo_stroke(cr);
      for (double t : colourTicks.values) {
        const double y = barTop + barH * (1.0 - (t - vmin) / (vmax - vmin));
        cairo_move_to(cr, barX + barW, y);
        cairo_line_to(cr, barX + barW + 4, y);
        cairo_stroke(cr);
        const std::string tick = tickText(t / colourUnit.factor, colourTicks.step / colourUnit.factor);
        cairo_move_to(cr, barX + barW + 6, y + 4);
        cairo_show_text(cr, tick.c_str());
      }
      const std::string source = rangeSource == "run"        ? "range: all snapshots"
                                 : rangeSource == "snapshot" ? "range: this snapshot"
                                 : rangeSource == "asked"    ? "range: as asked"
                                                             : "range: 0 to 1";
      cairo_set_font_size(cr, 9);
      cairo_set_source_rgb(cr, 0.35, 0.35, 0.35);
      cairo_move_to(cr, barX - 4, barTop + barH + 14);
      cairo_show_text(cr, source.c_str());
      if (rangeSource != "fixed") {  // the ends the ticks fall between
        cairo_move_to(cr, barX - 4, barTop + barH + 25);
        cairo_show_text(cr, (formatQuantity(vmin, declaration.unit) + " to").c_str());
        cairo_move_to(cr, barX - 4, barTop + barH + 36);
        cairo_show_text(cr, formatQuantity(vmax, declaration.unit).c_str());
      }
    }

    if (request.thumbnail && !drawn.empty()) {
      // A scale bar instead of axes: the longest round length (1, 2 or 5 × 10^k) within a quarter
      // of the drawn width, at the lower left on a white ground.
      const double length = scaleBarLength(uhi - ulo);
      const std::string text = formatQuantity(length, "m");
      cairo_select_font_face(cr, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
      cairo_set_font_size(cr, 9);
      cairo_text_extents_t e;
      cairo_text_extents(cr, text.c_str(), &e);
      const double x0 = 4, y0 = H - 5, bar = scale * length;
      cairo_set_source_rgba(cr, 1, 1, 1, 0.85);
      cairo_rectangle(cr, x0 - 2, y0 - 15, std::max(bar, e.x_advance) + 4, 18);
      cairo_fill(cr);
      cairo_set_source_rgb(cr, 0.05, 0.05, 0.05);
      cairo_rectangle(cr, x0, y0 - 2, bar, 2.5);
      cairo_fill(cr);
      cairo_move_to(cr, x0, y0 - 5);
      cairo_show_text(cr, text.c_str());
      out.scaleBar = length;
    }

    if (axes) {
      // Axes along the drawn extent, ticks at round values in one unit, 4 px off the particles.
      cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
      cairo_set_line_width(cr, 1);
      cairo_set_font_size(cr, 11);
      cairo_text_extents_t e;
      // The axes stand off the body by the arrows' room, so that no arrow crosses them.
      const double axisY = Y(vlo) + 4 + pad, axisX = X(ulo) - 4 - pad;
      auto reach = [](const RoundTicks& t, double lo, double hi) {
        return t.values.empty() ? std::pair{lo, hi} : std::pair{std::min(lo, t.values.front()), std::max(hi, t.values.back())};
      };
      const auto [u0, u1] = reach(uTicks, ulo, uhi);
      const auto [v0, v1] = reach(vTicks, vlo, vhi);
      cairo_move_to(cr, X(u0), axisY);
      cairo_line_to(cr, X(u1), axisY);
      cairo_move_to(cr, axisX, Y(v0));
      cairo_line_to(cr, axisX, Y(v1));
      cairo_stroke(cr);
      for (double t : uTicks.values) {
        cairo_move_to(cr, X(t), axisY);
        cairo_line_to(cr, X(t), axisY + 4);
        cairo_stroke(cr);
        const std::string tick = tickText(t / lengthUnit.factor, uTicks.step / lengthUnit.factor);
        cairo_text_extents(cr, tick.c_str(), &e);
        cairo_move_to(cr, X(t) - 0.5 * e.x_advance, axisY + 16);
        cairo_show_text(cr, tick.c_str());
      }
      for (double t : vTicks.values) {
        cairo_move_to(cr, axisX, Y(t));
        cairo_line_to(cr, axisX - 4, Y(t));
        cairo_stroke(cr);
        const std::string tick = tickText(t / lengthUnit.factor, vTicks.step / lengthUnit.factor);
        cairo_text_extents(cr, tick.c_str(), &e);
        cairo_move_to(cr, axisX - 7 - e.x_advance, Y(t) + 4);
        cairo_show_text(cr, tick.c_str());
      }
      const std::string uTitle = axisName(plane.u) + " (" + lengthUnit.unit + ")";
      const std::string vTitle = axisName(plane.v) + " (" + lengthUnit.unit + ")";
      cairo_text_extents(cr, uTitle.c_str(), &e);
      cairo_move_to(cr, 0.5 * (X(ulo) + X(uhi)) - 0.5 * e.x_advance, axisY + 31);
      cairo_show_text(cr, uTitle.c_str());
      cairo_text_extents(cr, vTitle.c_str(), &e);
      cairo_save(cr);
      cairo_move_to(cr, std::max(12.0, axisX - 44), 0.5 * (Y(vlo) + Y(vhi)) + 0.5 * e.x_advance);
      cairo_rotate(cr, -M_PI / 2);
      cairo_show_text(cr, vTitle.c_str());
      cairo_restore(cr);

      // The loading: arrows at the loaded faces and regions, a hatched line where a face is held,
      // ⊙ or ⊗ in the corner for a load across the view.
      const double length = 36, gap = 5;
      const int handedness = plane.depth == 1 ? -1 : 1;  // u × v along +depth (xy, yz) or −depth (xz)
      double cornerY = offV - pad + 14;
      cairo_set_font_size(cr, 11);
      for (const LoadingMark& m : marks) {
        const double du = m.direction[static_cast<std::size_t>(plane.u)];
        const double dv = m.direction[static_cast<std::size_t>(plane.v)];
        const double dn = m.direction[static_cast<std::size_t>(plane.depth)];
        const bool across = m.kind != LoadingMark::Kind::FaceHeld && std::hypot(du, dv) < 0.3;
        const bool faceInView = m.axis == plane.u || m.axis == plane.v;
        cairo_set_source_rgb(cr, 0.05, 0.05, 0.05);
        cairo_set_line_width(cr, 2);
        if (across || (m.kind != LoadingMark::Kind::BoxArrow && !faceInView)) {
          if (m.kind == LoadingMark::Kind::FaceHeld) continue;  // a held face seen flat: nothing to mark
          // Towards the viewer (⊙) or away (⊗).
          const bool towards = dn * handedness > 0;
          const double cx = offU - pad + 10, cy = cornerY;
          cairo_arc(cr, cx, cy, 7, 0, 2 * M_PI);
          cairo_stroke(cr);
          if (towards) {
            cairo_arc(cr, cx, cy, 2, 0, 2 * M_PI);
            cairo_fill(cr);
          } else {
            cairo_move_to(cr, cx - 5, cy - 5), cairo_line_to(cr, cx + 5, cy + 5);
            cairo_move_to(cr, cx + 5, cy - 5), cairo_line_to(cr, cx - 5, cy + 5);
            cairo_stroke(cr);
          }
          const std::string what = m.label + ", along " + directionName(plane.depth, dn) +
                                   (towards ? " (out of the page)" : " (into the page)");
          label(cr, cx + 12, cy + 4, what);
          out.loading.push_back(what);
          cornerY += 20;
          continue;
        }
        if (m.kind == LoadingMark::Kind::BoxArrow) {
          // The arrow starts at the region (or the projectile) and points the way it is driven: drawn
          // over the body rather than across the axes beside it.
          const double cu = 0.5 * (m.lo[static_cast<std::size_t>(plane.u)] + m.hi[static_cast<std::size_t>(plane.u)]);
          const double cv = 0.5 * (m.lo[static_cast<std::size_t>(plane.v)] + m.hi[static_cast<std::size_t>(plane.v)]);
          const double n = std::hypot(du, dv);
          const double x0 = X(cu), y0 = Y(cv), x1 = x0 + length * du / n, y1 = y0 - length * dv / n;
          arrow(cr, x0, y0, x1, y1);
          // The label beside the head of an arrow up or down, above the shaft of one across.
          if (std::abs(dv) > std::abs(du)) label(cr, std::min(x1 + 8, W - 150), dv > 0 ? y1 + 10 : y1, m.label);
          else label(cr, std::max(2.0, std::min(std::min(x0, x1), W - 150)), y0 - 8, m.label);
          out.loading.push_back(m.label + ", along " + directionName(std::abs(du) >= std::abs(dv) ? plane.u : plane.v,
                                                                      std::abs(du) >= std::abs(dv) ? du : dv));
          continue;
        }
        // A face of the drawn body: the side's extent along its axis, in the picture.
        const bool horizontal = m.axis == plane.u;  // the face is a vertical line
        const double face = horizontal ? X(m.side > 0 ? uhi : ulo) : Y(m.side > 0 ? vhi : vlo);
        const double outward = horizontal ? m.side : -m.side;  // in pixels
        const double a0 = horizontal ? Y(vhi) : X(ulo), a1 = horizontal ? Y(vlo) : X(uhi);
        const std::string where = std::string(m.side > 0 ? "the largest " : "the smallest ") + axisName(m.axis) + " face";
        if (m.kind == LoadingMark::Kind::FaceHeld) {
          const double at = face + outward * gap;
          if (horizontal) cairo_move_to(cr, at, a0), cairo_line_to(cr, at, a1);
          else cairo_move_to(cr, a0, at), cairo_line_to(cr, a1, at);
          cairo_stroke(cr);
          cairo_set_line_width(cr, 1);
          for (double t = a0; t <= a1; t += 8) {
            if (horizontal) cairo_move_to(cr, at, t), cairo_line_to(cr, at + outward * 6, t + 6);
            else cairo_move_to(cr, t, at), cairo_line_to(cr, t + 6, at + outward * 6);
          }
          cairo_stroke(cr);
          if (horizontal) label(cr, std::max(2.0, at + (outward > 0 ? 8 : -8 - 30)), a0 - 6, m.label);
          else label(cr, a1 + 6, at + 4, m.label);
          out.loading.push_back(m.label + " at " + where);
          continue;
        }
        // Arrows spread along the face: out of it when the load points outward, into it otherwise.
        const double along = horizontal ? du : -dv;  // the direction's outward-axis part, in pixels
        const double n = std::hypot(du, dv);
        const double pu = du / n, pv = -dv / n;  // pixel direction
        for (double f : {0.2, 0.5, 0.8}) {
          const double t = a0 + f * (a1 - a0);
          const double bx = horizontal ? face + outward * gap : t, by = horizontal ? t : face + outward * gap;
          if (along * outward >= 0) arrow(cr, bx, by, bx + pu * length, by + pv * length);
          else arrow(cr, bx - pu * length, by - pv * length, bx, by);  // pushing onto the face
        }
        const double lx = horizontal ? face + outward * gap + (outward > 0 ? 0 : -length) : a1 + 6;
        const double ly = horizontal ? a0 - 6 : face + outward * (gap + length) + 4;
        label(cr, std::max(2.0, std::min(lx, W - 150)), ly, m.label);
        out.loading.push_back(m.label + ", along " + directionName(m.axis, m.direction[static_cast<std::size_t>(m.axis)]) +
                              " at " + where);
      }
    }
  }
  out.bytes = canvas.finish();
  if (request.format == ImageFormat::Svg && text) {
    std::string description;
    for (const FieldImage::Axis& axis : out.axes) {
      description += axis.name + " axis (" + axis.unit + "): " + formatQuantity(axis.lo, "m") + " to " +
                     formatQuantity(axis.hi, "m") + ", ticks";
      for (double t : axis.ticks) description.append(" ").append(formatQuantity(t, "m"));
      description += "; ";
    }
    description += std::string("colour bar: ") + declaration.label +
                   (out.colourUnit.empty() ? "" : " (" + out.colourUnit + ")") + ", " +
                   formatQuantity(vmin, declaration.unit) + " to " + formatQuantity(vmax, declaration.unit) + " (" +
                   (rangeSource == "run" ? "the range over every snapshot of the run" : rangeSource == "snapshot"
                        ? "this snapshot's range" : rangeSource == "asked" ? "the range asked for" : "damage's range") +
                   "), ticks";
    for (double t : out.colourTicks) description.append(" ").append(formatQuantity(t, declaration.unit));
    for (const std::string& m : out.loading) description += "; loading: " + m;
    out.bytes = describeSvg(std::move(out.bytes), title + "; " + detail, description);
  }
  out.mediaType = mediaTypeOf(request.format);
  out.field = field;
  out.label = declaration.label;
  out.unit = declaration.unit;
  out.snapshot = index;
  out.snapshots = snapshots.size();
  out.time = snapshot.time;
  out.min = vmin;
  out.max = vmax;
  out.range = rangeSource;
  out.drawn = drawn.size();
  return out;
}

}  // namespace rupture::render
