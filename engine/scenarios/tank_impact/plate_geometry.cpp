#include "scenarios/tank_impact/plate_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "core/format_number.hpp"
#include "rupture/spec_error.hpp"

namespace rupture {

namespace {

constexpr double kClearance = 0.1;  ///< nodes kept this many spacings off a crack line
constexpr double kMaxPlateNodes = 1e6;

using Point = std::array<double, 2>;

/// The node spacing of the plate's rings: R / round(R / Δ) for a spot face clamped at its rim; with
/// a thick bottom, R / (m + ½) so that the step r = R falls midway between ring m and the next (each
/// node then lies wholly on one side of it).
double resolvedSpacing(const PlateSpec& plate) {
  const double R = 0.5 * plate.diameter;
  if (plate.bottom) return R / (std::max(1.0, std::round(R / plate.spacing - 0.5)) + 0.5);
  return R / std::max(1.0, std::round(R / plate.spacing));
}

/// The radius of the held ring: the clamp diameter's, rounded to a whole number of spacings.
double clampRadius(const PlateSpec& plate) {
  if (!plate.bottom) return 0.5 * plate.diameter;
  const double d = resolvedSpacing(plate);
  return d * std::round(0.5 * plate.bottom->clampDiameter / d);
}

/// Fine rings on each side of the step: the band reaches two plate spacings from it.
int stepBandRings(const PlateSpec& plate) {
  return static_cast<int>(std::ceil(2.0 * resolvedSpacing(plate) / plate.bottom->stepSpacing - 1e-9));
}

/// The ring radii of a plate refined about its step, out to the clamp.
std::vector<double> refinedRadii(const PlateSpec& plate) {
  return refinedRingRadii(clampRadius(plate), resolvedSpacing(plate), plate.bottom->stepSpacing, 0.5 * plate.diameter,
                          stepBandRings(plate));
}

/// Sideways shift δ ∈ [−Δ/2, Δ/2] of the segment [a, b] (along its left normal) that keeps every
/// node whose projection falls on the segment (± Δ) at least kClearance Δ off it, the smallest such
/// |δ|; where none does, the one with the largest clearance.
double crackShift(const ShellNodes& nodes, const Point& a, const Point& b) {
  const double d = nodes.spacing;
  const double ex = b[0] - a[0], ey = b[1] - a[1], len = std::hypot(ex, ey);
  const double tx = ex / len, ty = ey / len, nx = -ty, ny = tx;
  std::vector<double> offsets;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const double px = nodes.x[i] - a[0], py = nodes.y[i] - a[1];
    const double along = px * tx + py * ty, across = px * nx + py * ny;
    if (along >= -d && along <= len + d && std::fabs(across) <= d) offsets.push_back(across);
  }
  auto clearance = [&](double delta) {
    double c = std::numeric_limits<double>::infinity();
    for (double o : offsets) c = std::min(c, std::fabs(o - delta));
    return c;
  };
  // Candidates: no shift, the window's ends and the midpoints between neighbouring offsets.
  std::vector<double> candidates = {0.0, -0.5 * d, 0.5 * d};
  std::vector<double> sorted = offsets;
  std::sort(sorted.begin(), sorted.end());
  for (std::size_t k = 1; k < sorted.size(); ++k) {
    const double mid = 0.5 * (sorted[k - 1] + sorted[k]);
    if (std::fabs(mid) <= 0.5 * d) candidates.push_back(mid);
  }
  std::sort(candidates.begin(), candidates.end(), [](double u, double v) { return std::fabs(u) < std::fabs(v); });
  double best = 0.0, bestClearance = -1.0;
  for (double delta : candidates) {
    const double c = clearance(delta);
    if (c >= kClearance * d) return delta;
    if (c > bestClearance) { best = delta; bestClearance = c; }
  }
  return best;
}

/// The segment [a, b] moved by its shift.
PlateSegment shifted(const ShellNodes& nodes, const Point& a, const Point& b) {
  const double delta = crackShift(nodes, a, b);
  const double len = std::hypot(b[0] - a[0], b[1] - a[1]);
  const double nx = -(b[1] - a[1]) / len, ny = (b[0] - a[0]) / len;
  return {{a[0] + delta * nx, a[1] + delta * ny}, {b[0] + delta * nx, b[1] + delta * ny}};
}

/// Removes the nodes inside the hole (r < r_h) and gives the innermost ring kept the part of its
/// annulus outside the hole.
void cutHole(ShellNodes& nodes, double holeRadius) {
  const double d = nodes.spacing, pi = std::numbers::pi;
  ShellNodes kept;
  kept.spacing = d;
  double innermost = std::numeric_limits<double>::infinity(), innermostSpacing = d;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const double r = std::hypot(nodes.x[i], nodes.y[i]);
    if (r < holeRadius * (1.0 - 1e-12)) continue;
    const double spacing = nodes.nodeSpacing.empty() ? d : nodes.nodeSpacing[i];
    if (r < innermost - 1e-6 * spacing) innermost = r, innermostSpacing = spacing;
    kept.x.push_back(nodes.x[i]);
    kept.y.push_back(nodes.y[i]);
    kept.kernelVolume.push_back(nodes.kernelVolume[i]);
    kept.integrationArea.push_back(nodes.integrationArea[i]);
    kept.clamped.push_back(nodes.clamped[i]);
    if (!nodes.thickness.empty()) kept.thickness.push_back(nodes.thickness[i]);
    if (!nodes.nodeSpacing.empty()) kept.nodeSpacing.push_back(spacing);
  }
  // The innermost ring kept: the nodes within a millionth of its spacing of its radius.
  auto onInnermost = [&](std::size_t i) { return std::fabs(std::hypot(kept.x[i], kept.y[i]) - innermost) < 1e-6 * innermostSpacing; };
  std::size_t ringSize = 0;
  for (std::size_t i = 0; i < kept.size(); ++i)
    if (onInnermost(i)) ++ringSize;
  const double outer = innermost + 0.5 * innermostSpacing;
  const double area = pi * (outer * outer - holeRadius * holeRadius) / static_cast<double>(ringSize);
  for (std::size_t i = 0; i < kept.size(); ++i)
    if (onInnermost(i)) kept.integrationArea[i] = area;
  nodes = std::move(kept);
}

[[noreturn]] void refuse(const std::string& field, double value, const std::string& allowed) {
  throw SpecError("plate." + field, formatNumber(value), allowed);
}

}  // namespace

bool plateRefinedAtStep(const PlateSpec& plate) {
  return plate.bottom && plate.bottom->stepSpacing > 0.0 && plate.bottom->stepSpacing < resolvedSpacing(plate) * (1.0 - 1e-9);
}

void validatePlateGeometry(const PlateSpec& plate) {
  const double R = 0.5 * plate.diameter, t = plate.shell.thickness;
  if (!(plate.diameter > 0.0)) refuse("diameter", plate.diameter, "a diameter > 0 (m)");
  if (!(plate.spacing > 0.0 && plate.spacing <= R / 4.0))
    refuse("spacing", plate.spacing, "a node spacing in (0, " + formatNumber(R / 4.0) + "] m: at least 4 rings of nodes across the radius");
  if (plate.spacing < t / 20.0)
    refuse("spacing", plate.spacing,
           "a node spacing >= plate.thickness / 20 = " + formatNumber(t / 20.0) +
               " m: a shell node stands for the whole thickness, a finer spacing resolves nothing the shell can represent");
  if (std::numbers::pi * R * R / (plate.spacing * plate.spacing) > kMaxPlateNodes)
    refuse("spacing", plate.spacing, "a node spacing giving at most 1e6 plate nodes (>= " +
                                         formatNumber(R * std::sqrt(std::numbers::pi / kMaxPlateNodes)) + " m)");
  if (t > R) refuse("thickness", t, "a thickness <= the spot-face radius " + formatNumber(R) + " m (a shell)");
  if (plate.bottom) {
    const PlateBottomSpec& b = *plate.bottom;
    const double d = resolvedSpacing(plate);
    const double Rc = 0.5 * b.clampDiameter;
    if (!(b.thickness >= t && b.thickness <= Rc))
      refuse("bottom.thickness", b.thickness,
             "a thickness in [plate.thickness, clamp radius] = [" + formatNumber(t) + ", " + formatNumber(Rc) +
                 "] m (the step goes up from the spot face; a shell)");
    if (!(b.clampDiameter >= plate.diameter + 4.0 * d))
      refuse("bottom.clamp_diameter", b.clampDiameter,
             "a diameter >= plate.diameter + 4 spacings = " + formatNumber(plate.diameter + 4.0 * d) +
                 " m: at least two rings of the thick bottom between the step and the clamp");
    if (std::numbers::pi * Rc * Rc / (d * d) > kMaxPlateNodes)
      refuse("spacing", plate.spacing, "a node spacing giving at most 1e6 plate nodes out to the clamp (>= " +
                                           formatNumber(Rc * std::sqrt(std::numbers::pi / kMaxPlateNodes)) + " m)");
    const double f = b.stepSpacing;
    if (f != 0.0 && !(f >= t / 20.0 && f <= plate.spacing * (1.0 + 1e-12)))
      refuse("bottom.step_spacing", f,
             "a node spacing in [plate.thickness / 20, plate.spacing] = [" + formatNumber(t / 20.0) + ", " + formatNumber(plate.spacing) +
                 "] m (a shell node stands for the whole thickness; plate.spacing itself: no refinement)");
    if (plateRefinedAtStep(plate)) {
      std::vector<double> radii;
      try {
        radii = refinedRadii(plate);
      } catch (const std::invalid_argument&) {
        refuse("bottom.step_spacing", f,
               "a refinement whose band (two plate spacings each side of the step) and grading fit between the centre and the clamp");
      }
      const double nodes = static_cast<double>(ringDiskNodeCount(radii));
      if (nodes > kMaxPlateNodes)
        refuse("bottom.step_spacing", f, "a node spacing giving at most 1e6 plate nodes (this one gives " + formatNumber(nodes) + ")");
    }
  }

  const PrecrackSpec& c = plate.precrack;
  const double d = resolvedSpacing(plate), room = R - 2.0 * d;  // 2 spacings of plate before the clamp
  const std::string resolve = " (at least 2 node spacings; plate.spacing resolves to " + formatNumber(d) + " m)";
  const bool hole = c.shape == PrecrackShape::Hole || c.shape == PrecrackShape::HoleAndCracks;
  if (hole) {
    if (c.holeDiameter < 2.0 * d) refuse("precrack.hole_diameter", c.holeDiameter, ">= " + formatNumber(2.0 * d) + " m" + resolve);
    if (0.5 * c.holeDiameter > room)
      refuse("precrack.hole_diameter", c.holeDiameter,
             "a hole smaller than the plate: <= plate.diameter − 4 spacings = " + formatNumber(2.0 * room) + " m");
  }
  if (c.shape == PrecrackShape::None || c.shape == PrecrackShape::Hole) return;
  if (c.length < 2.0 * d) refuse("precrack.length", c.length, ">= " + formatNumber(2.0 * d) + " m" + resolve);
  switch (c.shape) {
    case PrecrackShape::U:
      if (c.width < 2.0 * d) refuse("precrack.width", c.width, ">= " + formatNumber(2.0 * d) + " m" + resolve);
      if (std::hypot(0.5 * c.length, 0.5 * c.width) > room)
        refuse("precrack.length", c.length,
               "a U whose corners lie inside the plate, 2 spacings off the clamp: sqrt((length/2)^2 + (width/2)^2) <= " +
                   formatNumber(room) + " m with width " + formatNumber(c.width) + " m");
      break;
    case PrecrackShape::X:
    case PrecrackShape::I:
      if (0.5 * c.length > room)
        refuse("precrack.length", c.length, "a centred crack inside the plate, 2 spacings off the clamp: <= " + formatNumber(2.0 * room) + " m");
      break;
    case PrecrackShape::HoleAndCracks:
      if (0.5 * c.holeDiameter + c.length > room)
        refuse("precrack.length", c.length,
               "radial cracks ending inside the plate, 2 spacings off the clamp: <= " + formatNumber(room - 0.5 * c.holeDiameter) +
                   " m from the hole's edge");
      if (c.crackCount < 1 || c.crackCount > 8)
        throw SpecError("plate.precrack.crack_count", std::to_string(c.crackCount), "an integer in [1, 8]");
      break;
    default: break;
  }
}

PlateGeometry plateGeometry(const PlateSpec& plate) {
  validatePlateGeometry(plate);
  PlateGeometry g;
  const double R = 0.5 * plate.diameter;
  if (plate.bottom) {
    // Rings out to the clamp; the nodes beyond the step (r > R, none lies on it) carry the bottom's thickness.
    g.nodes = plateRefinedAtStep(plate) ? ringDiskNodes(refinedRadii(plate)) : clampedDiskNodes(clampRadius(plate), resolvedSpacing(plate), 0);
    g.nodes.thickness.resize(g.nodes.size());
    for (std::size_t i = 0; i < g.nodes.size(); ++i)
      g.nodes.thickness[i] = std::hypot(g.nodes.x[i], g.nodes.y[i]) < R ? plate.shell.thickness : plate.bottom->thickness;
  } else {
    g.nodes = clampedDiskNodes(R, plate.spacing, 0);
  }
  const PrecrackSpec& c = plate.precrack;
  const double pi = std::numbers::pi;
  if (c.shape == PrecrackShape::Hole || c.shape == PrecrackShape::HoleAndCracks) {
    g.holeRadius = 0.5 * c.holeDiameter;
    cutHole(g.nodes, g.holeRadius);
  }
  const double d = g.nodes.spacing, L = c.length;
  switch (c.shape) {
    case PrecrackShape::None:
    case PrecrackShape::Hole: break;
    case PrecrackShape::I: g.precracks.push_back(shifted(g.nodes, {-0.5 * L, 0.0}, {0.5 * L, 0.0})); break;
    case PrecrackShape::X: {
      const double s = 0.5 * L / std::sqrt(2.0);  // the two cracks along the diagonals
      g.precracks.push_back(shifted(g.nodes, {-s, -s}, {s, s}));
      g.precracks.push_back(shifted(g.nodes, {-s, s}, {s, -s}));
      break;
    }
    case PrecrackShape::HoleAndCracks:
      for (int k = 0; k < c.crackCount; ++k) {
        // From the centre (no nodes in the hole: this also cuts the chords across the crack's mouth).
        const double phi = 2.0 * pi * k / c.crackCount, r = g.holeRadius + L;
        g.precracks.push_back(shifted(g.nodes, {0.0, 0.0}, {r * std::cos(phi), r * std::sin(phi)}));
      }
      break;
    case PrecrackShape::U: {
      // Centred U: arms x = ±W/2 from the base y = −L/2 to the hinge y = +L/2; the arms overrun
      // the base by Δ/20 so that the corners are closed.
      const double W = c.width, e = 0.05 * d;
      const PlateSegment left = shifted(g.nodes, {-0.5 * W, -0.5 * L}, {-0.5 * W, 0.5 * L});
      const PlateSegment right = shifted(g.nodes, {0.5 * W, -0.5 * L}, {0.5 * W, 0.5 * L});
      const PlateSegment base = shifted(g.nodes, {-0.5 * W, -0.5 * L}, {0.5 * W, -0.5 * L});
      const double xl = left.a[0], xr = right.a[0], yb = base.a[1], yh = 0.5 * L;
      g.precracks.push_back({{xl, yb - e}, {xl, yh}});
      g.precracks.push_back({{xl - e, yb}, {xr + e, yb}});
      g.precracks.push_back({{xr, yb - e}, {xr, yh}});
      g.hinge = {{xl, yh}, {xr, yh}};
      for (std::size_t i = 0; i < g.nodes.size(); ++i)
        if (g.nodes.x[i] > xl && g.nodes.x[i] < xr && g.nodes.y[i] > yb && g.nodes.y[i] < yh) g.tongueNodes.push_back(i);
      break;
    }
  }
  return g;
}

SphShell buildPlate(const PlateSpec& plate, const PlateGeometry& geometry) {
  SphShell shell(geometry.nodes, plate.shell);
  std::vector<std::array<Point, 2>> cuts;
  if (geometry.holeRadius > 0.0) {
    const double r = geometry.holeRadius * (1.0 - 1e-9), pi = std::numbers::pi;
    for (int k = 0; k < kHoleEdgeSides; ++k) {
      const double a0 = 2.0 * pi * k / kHoleEdgeSides, a1 = 2.0 * pi * (k + 1) / kHoleEdgeSides;
      cuts.push_back({Point{r * std::cos(a0), r * std::sin(a0)}, Point{r * std::cos(a1), r * std::sin(a1)}});
    }
  }
  for (const PlateSegment& s : geometry.precracks) cuts.push_back({s.a, s.b});
  shell.cutAlongSegments(cuts);
  return shell;
}

}  // namespace rupture
