#include "render/sample_picture.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "render/colour_map.hpp"
#include "render/round_ticks.hpp"
#include "rupture/quantity_text.hpp"

namespace rupture::render {

namespace {

/// Okabe & Ito (2008): eight colours told apart with every common colour blindness.
Rgb groupColour(std::size_t group) {
  static const Rgb palette[] = {{0.00, 0.45, 0.70}, {0.90, 0.62, 0.00}, {0.84, 0.37, 0.00}, {0.00, 0.62, 0.45},
                                {0.80, 0.47, 0.65}, {0.34, 0.71, 0.91}, {0.50, 0.50, 0.50}, {0.94, 0.89, 0.26}};
  return palette[group % (sizeof palette / sizeof palette[0])];
}

void text(cairo_t* cr, double x, double y, const std::string& s, double size, bool bold = false) {
  cairo_select_font_face(cr, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL,
                         bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, size);
  cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
  cairo_move_to(cr, x, y);
  cairo_show_text(cr, s.c_str());
}

struct Frame {
  double left, top, width, height;
};

/// The panel's points and marks in `frame`, u across and v up at one scale (m to px).
std::size_t drawPanel(cairo_t* cr, const PreviewPanel& panel, const Frame& frame, const Canvas& canvas) {
  double lo[2] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  double hi[2] = {-lo[0], -lo[1]};
  for (std::size_t k = 0; k < panel.u.size(); ++k) {
    lo[0] = std::min(lo[0], panel.u[k] - panel.radius[k]), hi[0] = std::max(hi[0], panel.u[k] + panel.radius[k]);
    lo[1] = std::min(lo[1], panel.v[k] - panel.radius[k]), hi[1] = std::max(hi[1], panel.v[k] + panel.radius[k]);
  }
  for (const auto& c : panel.circles) {
    lo[0] = std::min(lo[0], c.at[0] - c.at[2]), hi[0] = std::max(hi[0], c.at[0] + c.at[2]);
    lo[1] = std::min(lo[1], c.at[1] - c.at[2]), hi[1] = std::max(hi[1], c.at[1] + c.at[2]);
  }
  for (const auto& b : panel.boxes) {
    lo[0] = std::min(lo[0], b.at[0]), hi[0] = std::max(hi[0], b.at[2]);
    lo[1] = std::min(lo[1], b.at[1]), hi[1] = std::max(hi[1], b.at[3]);
  }
  text(cr, frame.left, frame.top + 13, panel.title, 12, true);
  if (!(hi[0] > lo[0]) || !(hi[1] > lo[1])) {
    text(cr, frame.left, frame.top + 40, "no points in this view", 12);
    return 0;
  }
  const double top = frame.top + 22, bottom = frame.top + frame.height - 34;  // title above, scale bar below
  const double scale = std::min(frame.width / (hi[0] - lo[0]), (bottom - top) / (hi[1] - lo[1]));
  const double x0 = frame.left + 0.5 * (frame.width - scale * (hi[0] - lo[0]));
  const double y0 = bottom - 0.5 * ((bottom - top) - scale * (hi[1] - lo[1]));
  auto px = [&](double u) { return x0 + scale * (u - lo[0]); };
  auto py = [&](double v) { return y0 - scale * (v - lo[1]); };

  std::size_t drawn = 0;
  for (std::size_t k = 0; k < panel.u.size(); ++k) {
    if ((k & 4095) == 4095) canvas.checkStop();
    const Rgb c = groupColour(panel.group[k]);
    cairo_set_source_rgb(cr, c.r, c.g, c.b);
    const double r = scale * panel.radius[k];
    if (r < 0.7) cairo_rectangle(cr, px(panel.u[k]) - 0.5, py(panel.v[k]) - 0.5, 1, 1);  // below a pixel: a dot
    else cairo_arc(cr, px(panel.u[k]), py(panel.v[k]), r, 0, 2 * M_PI);
    cairo_fill(cr);
    ++drawn;
  }
  cairo_set_line_width(cr, 2);
  for (const auto& s : panel.segments) {
    cairo_set_source_rgb(cr, 0.85, 0.1, 0.1);
    cairo_move_to(cr, px(s.at[0]), py(s.at[1]));
    cairo_line_to(cr, px(s.at[2]), py(s.at[3]));
    cairo_stroke(cr);
  }
  for (const auto& c : panel.circles) {
    cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
    cairo_new_path(cr);  // a label's text leaves a current point the arc would join with a line
    cairo_arc(cr, px(c.at[0]), py(c.at[1]), scale * c.at[2], 0, 2 * M_PI);
    cairo_stroke(cr);
    text(cr, px(c.at[0] + c.at[2]) + 3, py(c.at[1]), c.label, 10);
  }
  for (const auto& b : panel.boxes) {
    cairo_set_source_rgb(cr, 0.55, 0.0, 0.55);
    const double dash = 5;
    cairo_set_dash(cr, &dash, 1, 0);
    cairo_new_path(cr);
    cairo_rectangle(cr, px(b.at[0]), py(b.at[3]), scale * (b.at[2] - b.at[0]), scale * (b.at[3] - b.at[1]));
    cairo_stroke(cr);
    cairo_set_dash(cr, nullptr, 0, 0);
    text(cr, px(b.at[0]), py(b.at[3]) - 3, b.label, 10);
  }
  // The scale bar: a round length under the panel's left edge.
  const double length = scaleBarLength(hi[0] - lo[0]);
  const double barY = frame.top + frame.height - 18;
  cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
  cairo_set_line_width(cr, 3);
  cairo_move_to(cr, x0, barY);
  cairo_line_to(cr, x0 + scale * length, barY);
  cairo_stroke(cr);
  text(cr, x0 + scale * length + 6, barY + 4, formatQuantity(length, "m") + "   (" + panel.uAxis + " across, " +
                                                   panel.vAxis + " up)",
       11);
  return drawn;
}

}  // namespace

SamplePicture renderSamplePicture(const SamplePreview& preview, const SamplePictureRequest& request,
                                  const StopCheck& stop) {
  Canvas canvas(request.format, request.width, request.height, stop);
  cairo_t* cr = canvas.context();
  const double margin = 12, w = request.width, h = request.height;
  double y = margin + 14;
  text(cr, margin, y, preview.scenario + ": the discretisation the run starts from", 15, true);
  const std::string note = request.note;
  if (!note.empty()) text(cr, margin, y += 17, note, 11);
  for (const std::string& fact : preview.facts) text(cr, margin, y += 16, fact, 12);

  // The legend, one line at the foot: the groups that some panel draws.
  std::vector<bool> used(preview.groups.size(), false);
  for (const PreviewPanel& p : preview.panels)
    for (std::uint8_t g : p.group)
      if (g < used.size()) used[g] = true;
  double x = margin;
  const double legendY = h - margin;
  for (std::size_t g = 0; g < preview.groups.size(); ++g) {
    if (!used[g]) continue;
    const Rgb c = groupColour(g);
    cairo_set_source_rgb(cr, c.r, c.g, c.b);
    cairo_arc(cr, x + 5, legendY - 4, 5, 0, 2 * M_PI);
    cairo_fill(cr);
    text(cr, x + 14, legendY, preview.groups[g], 11);
    cairo_text_extents_t extents;
    cairo_text_extents(cr, preview.groups[g].c_str(), &extents);
    x += 14 + extents.x_advance + 16;
  }

  SamplePicture out;
  const double panelsTop = y + 12, panelsHeight = legendY - 18 - panelsTop;
  const auto count = static_cast<double>(std::max<std::size_t>(preview.panels.size(), 1));
  const double panelWidth = (w - margin * (count + 1)) / count;
  for (std::size_t k = 0; k < preview.panels.size(); ++k)
    out.drawn += drawPanel(cr, preview.panels[k],
                           {margin + static_cast<double>(k) * (panelWidth + margin), panelsTop, panelWidth, panelsHeight},
                           canvas);
  out.bytes = canvas.finish();
  out.mediaType = mediaTypeOf(request.format);
  return out;
}

}  // namespace rupture::render
