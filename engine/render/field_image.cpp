#include "render/field_image.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <numeric>
#include <set>

#include "render/colour_map.hpp"
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

/// Which particles to draw: a body filter from the request or the run's kind.
std::vector<std::size_t> selectParticles(const SnapshotField& s, const std::string& field, const std::string& body,
                                         std::string& note) {
  const std::size_t n = s.position.size();
  std::string choice = body;
  if (choice.empty()) {
    if (s.body.empty()) choice = "all";
    else if (field == "damage" && s.plateBody) choice = std::to_string(*s.plateBody);
    else choice = "fluid";
  }
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

  // The colour range.
  double vmin = field == "damage" ? 0 : 1e300, vmax = field == "damage" ? 1 : -1e300;
  if (field != "damage") {
    for (std::size_t k : drawn)
      if (std::isfinite(s.value[k])) vmin = std::min(vmin, s.value[k]), vmax = std::max(vmax, s.value[k]);
    if (vmin > vmax) vmin = 0, vmax = 1;
    if (vmax - vmin <= 1e-12 * std::max(std::abs(vmin), std::abs(vmax))) {
      const double pad = vmin == 0 ? 1 : 0.01 * std::abs(vmin);
      vmin -= pad, vmax += pad;
    }
  }
  if (request.min) vmin = *request.min;
  if (request.max) vmax = *request.max;
  if (!(vmax > vmin)) throw FieldImageError(request.max ? "max" : "min", "the colour range is empty: min must be below max");

  // Layout: the title above, the colour bar on the right, the particles fitted with equal scales.
  const double W = request.width, H = request.height;
  const bool text = !request.thumbnail;
  const double top = text ? 34 : 2, bottom = text ? 10 : 2, left = text ? 10 : 2, right = text ? 110 : 2;
  double ulo = 1e300, uhi = -1e300, vlo = 1e300, vhi = -1e300;
  for (std::size_t k : drawn) {
    const double r = s.radius[k];
    ulo = std::min(ulo, s.position[k][plane.u] - r), uhi = std::max(uhi, s.position[k][plane.u] + r);
    vlo = std::min(vlo, s.position[k][plane.v] - r), vhi = std::max(vhi, s.position[k][plane.v] + r);
  }
  if (drawn.empty()) ulo = vlo = 0, uhi = vhi = 1;
  const double boxW = std::max(W - left - right, 1.0), boxH = std::max(H - top - bottom, 1.0);
  const double scale = std::min(boxW / std::max(uhi - ulo, 1e-300), boxH / std::max(vhi - vlo, 1e-300));
  const double offU = left + 0.5 * (boxW - scale * (uhi - ulo)), offV = top + 0.5 * (boxH - scale * (vhi - vlo));
  auto px = [&](std::size_t k) { return offU + scale * (s.position[k][plane.u] - ulo); };
  auto py = [&](std::size_t k) { return offV + scale * (vhi - s.position[k][plane.v]); };  // v up

  FieldImage out;
  Canvas canvas(request.format, request.width, request.height, stop);
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

    if (text) {
      cairo_select_font_face(cr, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
      // Title: what, when, which.
      std::string title = std::string(declaration.label) + ", t = " + formatQuantity(snapshot.time, "s");
      if (snapshot.strain) title += ", strain " + formatQuantity(*snapshot.strain, "1");
      title += " (snapshot " + std::to_string(index + 1) + " of " + std::to_string(snapshots.size()) + ")";
      std::string detail = "view " + axisName(plane.u) + axisName(plane.v);
      if (!bodyNote.empty()) detail += ", " + bodyNote;
      if (!sliceNote.empty()) detail += ", " + sliceNote;
      if (!s.brokenBonds.empty() && bonds != "none")
        detail += ", " + std::to_string(s.brokenBonds.size()) + " broken bonds in red";
      cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
      cairo_set_font_size(cr, 14);
      cairo_move_to(cr, left, 17);
      cairo_show_text(cr, title.c_str());
      cairo_set_font_size(cr, 11);
      cairo_set_source_rgb(cr, 0.35, 0.35, 0.35);
      cairo_move_to(cr, left, 30);
      cairo_show_text(cr, detail.c_str());

      // Colour bar with five labelled ticks.
      const double barX = W - right + 18, barW = 14, barTop = top + 18, barH = std::max(boxH - 28, 20.0);
      cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
      cairo_set_font_size(cr, 11);
      cairo_move_to(cr, barX - 4, top + 10);
      cairo_show_text(cr, declaration.label);
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
      for (int t = 0; t <= 4; ++t) {
        const double y = barTop + barH * (1.0 - t / 4.0);
        cairo_move_to(cr, barX + barW, y);
        cairo_line_to(cr, barX + barW + 4, y);
        cairo_stroke(cr);
        const std::string label = formatQuantity(vmin + (vmax - vmin) * t / 4.0, declaration.unit);
        cairo_move_to(cr, barX + barW + 6, y + 4);
        cairo_show_text(cr, label.c_str());
      }
    }
  }
  out.bytes = canvas.finish();
  out.mediaType = mediaTypeOf(request.format);
  out.field = field;
  out.label = declaration.label;
  out.unit = declaration.unit;
  out.snapshot = index;
  out.snapshots = snapshots.size();
  out.time = snapshot.time;
  out.min = vmin;
  out.max = vmax;
  out.drawn = drawn.size();
  return out;
}

}  // namespace rupture::render
