// The tank-impact plate (issue 11): hole and pre-crack geometry on the SPH shell, and the plate
// observables against fields whose answer is known.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>

#include "rupture/spec_error.hpp"
#include "scenarios/tank_impact/plate_geometry.hpp"
#include "scenarios/tank_impact/plate_observables.hpp"

namespace rupture {
namespace {

constexpr double kPi = std::numbers::pi;

PlateSpec plateWith(PrecrackShape shape, double spacing) {
  PlateSpec p;
  p.shell.plasticity = false;
  p.shell.damage = false;
  p.diameter = 0.08;
  p.spacing = spacing;
  p.precrack.shape = shape;
  switch (shape) {
    case PrecrackShape::Hole: p.precrack.holeDiameter = 0.020; break;
    case PrecrackShape::U: p.precrack.length = 0.020; p.precrack.width = 0.020; break;
    case PrecrackShape::X: p.precrack.length = 0.030; break;
    case PrecrackShape::I: p.precrack.length = 0.020; break;
    case PrecrackShape::HoleAndCracks: p.precrack.holeDiameter = 0.014; p.precrack.length = 0.003; p.precrack.crackCount = 2; break;
    case PrecrackShape::None: break;
  }
  return p;
}

double distanceToLine(const PlateSegment& s, double x, double y) {
  const double ex = s.b[0] - s.a[0], ey = s.b[1] - s.a[1];
  return std::fabs((x - s.a[0]) * ey - (y - s.a[1]) * ex) / std::hypot(ex, ey);
}

// Every pre-crack is cut through: no link crosses it. The same segment moved 3 spacings sideways
// (through intact plate) is crossed by links, so cutting did not strip the plate. Over the shapes
// and three spacings (the ring lattice places nodes differently at each).
TEST(TankPlate, PrecracksCutEveryCrossingLinkAndOnlyThose) {
  for (PrecrackShape shape : {PrecrackShape::I, PrecrackShape::X, PrecrackShape::U, PrecrackShape::HoleAndCracks}) {
    for (double spacing : {0.001, 0.0012, 0.0014}) {
      SCOPED_TRACE(toString(shape) + " at spacing " + std::to_string(spacing));
      const PlateSpec plate = plateWith(shape, spacing);
      const PlateGeometry g = plateGeometry(plate);
      const SphShell shell = buildPlate(plate, g);
      ASSERT_FALSE(g.precracks.empty());
      const double d = g.nodes.spacing;
      for (const PlateSegment& s : g.precracks) {
        EXPECT_EQ(shell.linksCrossing(s.a, s.b), 0u);
        // Nodes stay off the crack line (the shift's clearance), so no link only touches it.
        const double len = std::hypot(s.b[0] - s.a[0], s.b[1] - s.a[1]);
        for (std::size_t i = 0; i < g.nodes.size(); ++i) {
          const double along = ((g.nodes.x[i] - s.a[0]) * (s.b[0] - s.a[0]) + (g.nodes.y[i] - s.a[1]) * (s.b[1] - s.a[1])) / len;
          if (along > 0.0 && along < len) {
            EXPECT_GT(distanceToLine(s, g.nodes.x[i], g.nodes.y[i]), 1e-3 * d);
          }
        }
        // A parallel segment 3 spacings away crosses intact plate.
        const double nx = -(s.b[1] - s.a[1]) / len * 3.0 * d, ny = (s.b[0] - s.a[0]) / len * 3.0 * d;
        for (double sign : {-1.0, 1.0}) {
          const std::array<double, 2> a{s.a[0] + sign * nx, s.a[1] + sign * ny}, b{s.b[0] + sign * nx, s.b[1] + sign * ny};
          if (std::hypot(a[0], a[1]) < g.holeRadius + 3.0 * d || std::hypot(b[0], b[1]) < g.holeRadius + 3.0 * d) continue;
          EXPECT_GT(shell.linksCrossing(a, b), 0u);
        }
      }
    }
  }
}

// The thick bottom (plate.clamp "bottom"): the step r = R falls midway between two rings, the
// nodes outside it carry the bottom's thickness, the outer ring at the clamp diameter is held, the
// areas sum to the annulus inside the clamp, and the shell's step shrinks by √(t_bottom / e_p).
TEST(TankPlate, ThickBottomStepsMidwayBetweenRingsAndIsHeldAtItsClamp) {
  for (double spacing : {0.002, 0.0013}) {
    SCOPED_TRACE("spacing " + std::to_string(spacing));
    PlateSpec plate = plateWith(PrecrackShape::Hole, spacing);
    plate.shell.thickness = 0.002;
    plate.bottom = PlateBottomSpec{};
    const PlateGeometry g = plateGeometry(plate);
    const double d = g.nodes.spacing, R = 0.04, Rc = 0.5 * plate.bottom->clampDiameter;
    double area = 0.0, heldRadius = 0.0;
    for (std::size_t i = 0; i < g.nodes.size(); ++i) {
      const double r = std::hypot(g.nodes.x[i], g.nodes.y[i]);
      EXPECT_GT(std::fabs(r - R), 0.49 * d) << "node at r = " << r;
      EXPECT_EQ(g.nodes.thickness[i], r < R ? 0.002 : 0.025);
      if (g.nodes.clamped[i]) heldRadius = std::max(heldRadius, r);
      EXPECT_EQ(g.nodes.clamped[i] != 0, r > Rc - 0.5 * d) << "node at r = " << r;
      area += g.nodes.integrationArea[i];
    }
    EXPECT_NEAR(heldRadius, Rc, 0.5 * d);
    EXPECT_NEAR(area, kPi * (heldRadius * heldRadius - 0.01 * 0.01), 1e-9);
    // The same nodes all 25 mm thick: their membrane estimate sets the step (the rotation of so
    // thick a plate is slower); at the step the 2 mm nodes see it √(25/2) times faster.
    const SphShell stepped = buildPlate(plate, g);
    ShellNodes thickNodes = g.nodes;
    thickNodes.thickness.clear();
    ShellParameters thick = plate.shell;
    thick.thickness = 0.025;
    const SphShell uniform(thickNodes, thick);
    EXPECT_NEAR(uniform.stableTimeStep() / stepped.stableTimeStep(), std::sqrt(0.025 / 0.002), 1e-9);
  }
}

// plate.bottom.step_spacing: the rings within two plate spacings of the step at the fine spacing,
// the step still midway between two rings, the areas still the annulus out to the clamp, and the
// deflection observable reading the graded rings as the uniform ones.
TEST(TankPlate, ThickBottomRefinedAtTheStep) {
  PlateSpec plate = plateWith(PrecrackShape::Hole, 0.002);
  plate.shell.thickness = 0.001;
  plate.bottom = PlateBottomSpec{};
  plate.bottom->stepSpacing = 0.0005;
  ASSERT_TRUE(plateRefinedAtStep(plate));
  const PlateGeometry g = plateGeometry(plate);
  const double d = 0.04 / 20.5, f = 0.0005, R = 0.04, Rc = 0.5 * plate.bottom->clampDiameter;  // resolved spacing
  ASSERT_EQ(g.nodes.nodeSpacing.size(), g.nodes.size());
  double area = 0.0, heldRadius = 0.0, finest = 1.0;
  for (std::size_t i = 0; i < g.nodes.size(); ++i) {
    const double r = std::hypot(g.nodes.x[i], g.nodes.y[i]);
    EXPECT_GT(std::fabs(r - R), 0.49 * f) << "node at r = " << r;
    EXPECT_EQ(g.nodes.thickness[i], r < R ? 0.001 : 0.025);
    // The band's last rings border the grading: their spacing is the mean of their two gaps.
    // …and the cells square: the pitch along a ring is its radial spacing, so a cell's area is f².
    if (std::fabs(r - R) < 2.0 * d - f) {
      EXPECT_NEAR(g.nodes.nodeSpacing[i], f, 1e-12) << "node at r = " << r;
      EXPECT_NEAR(g.nodes.integrationArea[i] / (f * f), 1.0, 0.02) << "node at r = " << r;
    }
    if (r < 0.02) { EXPECT_NEAR(g.nodes.nodeSpacing[i] / d, 1.0, 0.5) << "node at r = " << r; }
    finest = std::min(finest, g.nodes.nodeSpacing[i]);
    if (g.nodes.clamped[i]) heldRadius = std::max(heldRadius, r);
    area += g.nodes.integrationArea[i];
  }
  EXPECT_NEAR(finest, f, 1e-12);
  EXPECT_NEAR(heldRadius, Rc, 0.5 * d);
  EXPECT_NEAR(area, kPi * (heldRadius * heldRadius - 0.01 * 0.01), 1e-9);

  // A paraboloid w = −c r² on the nodes: read between rings, exactly within the interpolation's
  // error c Δ_k² / 4 (linear between rings of a quadratic).
  SphShell shell = buildPlate(plate, g);
  const double c = 2.0;
  for (std::size_t i = 0; i < shell.size(); ++i) {
    const double x = g.nodes.x[i], y = g.nodes.y[i];
    shell.setNodeState(i, {x, y, -c * (x * x + y * y)}, {0.0, 0.0, 1.0}, {0.0, 0.0, 0.0});
  }
  for (double radius : {0.0235, 0.0381, 0.0405, 0.05})
    EXPECT_NEAR(deflectionAtRadius(shell, g, radius), c * radius * radius, 0.25 * c * (1.5 * d) * (1.5 * d)) << "r = " << radius;
  // Refinement past the plate's spacing, or too fine for a shell, names the field.
  plate.bottom->stepSpacing = 0.003;
  EXPECT_THROW(
      try { validatePlateGeometry(plate); } catch (const SpecError& e) {
        EXPECT_EQ(e.field(), "plate.bottom.step_spacing");
        throw;
      },
      SpecError);
  plate.bottom->stepSpacing = 0.00004;
  EXPECT_THROW(validatePlateGeometry(plate), SpecError);
}

// The crack lines are where the spec puts them, up to the documented shift of at most Δ/2.
TEST(TankPlate, PrecracksLieWithinHalfASpacingOfTheNominalLines) {
  const PlateSpec plate = plateWith(PrecrackShape::U, 0.0015);
  const PlateGeometry g = plateGeometry(plate);
  const double d = g.nodes.spacing;
  ASSERT_EQ(g.precracks.size(), 3u);
  EXPECT_NEAR(g.precracks[0].a[0], -0.010, 0.5 * d + 1e-12);  // left arm x = −W/2
  EXPECT_NEAR(g.precracks[2].a[0], 0.010, 0.5 * d + 1e-12);   // right arm x = +W/2
  EXPECT_NEAR(g.precracks[1].a[1], -0.010, 0.5 * d + 1e-12);  // base y = −L/2
  EXPECT_DOUBLE_EQ(g.hinge.a[1], 0.010);                      // hinge y = +L/2
  // The tongue: every node strictly inside the U, and it has nodes (about W L / Δ²).
  EXPECT_NEAR(static_cast<double>(g.tongueNodes.size()), 0.020 * 0.020 / (d * d), 0.25 * 0.020 * 0.020 / (d * d));
}

// The hole holds no node, the integration areas that remain sum to the annulus π(R² − r²), and
// no link bridges the hole. Over hole sizes that fall on and between node rings.
TEST(TankPlate, HoleHasNoNodesAndTheAreasSumToTheAnnulus) {
  for (double holeDiameter : {0.014, 0.020, 0.0153}) {
    for (double spacing : {0.002, 0.0013}) {
      SCOPED_TRACE(std::to_string(holeDiameter) + " at spacing " + std::to_string(spacing));
      PlateSpec plate = plateWith(PrecrackShape::Hole, spacing);
      plate.precrack.holeDiameter = holeDiameter;
      const PlateGeometry g = plateGeometry(plate);
      const double r = 0.5 * holeDiameter, R = 0.04;
      EXPECT_DOUBLE_EQ(g.holeRadius, r);
      double area = 0.0, innermost = 1.0;
      for (std::size_t i = 0; i < g.nodes.size(); ++i) {
        const double ri = std::hypot(g.nodes.x[i], g.nodes.y[i]);
        EXPECT_GE(ri, r * (1.0 - 1e-9));
        innermost = std::min(innermost, ri);
        area += g.nodes.integrationArea[i];
      }
      EXPECT_LT(innermost, r + g.nodes.spacing);  // the first ring kept is the hole's edge
      EXPECT_NEAR(area, kPi * (R * R - r * r), 1e-9 * kPi * R * R);
      const SphShell shell = buildPlate(plate, g);
      // Any chord of the hole: no link crosses it.
      for (int k = 0; k < 12; ++k) {
        const double phi = kPi * k / 12.0, c = 0.999 * r;
        EXPECT_EQ(shell.linksCrossing({-c * std::cos(phi), -c * std::sin(phi)}, {c * std::cos(phi), c * std::sin(phi)}), 0u);
      }
    }
  }
}

/// Mean deflection (m, towards −z) of the nodes at the tongue's free end (within 2Δ of the base).
double tongueEndDeflection(const SphShell& shell, const PlateGeometry& u) {
  const double base = u.precracks[1].a[1], d = u.nodes.spacing;
  double sum = 0.0;
  int count = 0;
  for (std::size_t i : u.tongueNodes)
    if (u.nodes.y[i] < base + 2.0 * d) {
      sum -= shell.deflection(i);
      ++count;
    }
  return sum / count;
}

// A U tongue under uniform pressure bends as a cantilever on top of the plate's own deflection:
// its free end goes down further than the same points of the intact plate (elastic, quasi-static
// through mass-proportional damping near critical for the plate's first mode).
TEST(TankPlate, UTongueUnderPressureDeflectsMoreThanTheIntactPlate) {
  const double spacing = 0.0025, pressure = -1.0e5;  // 1 bar, pushing towards −z (the water's side is +z)
  PlateSpec intact = plateWith(PrecrackShape::None, spacing);
  PlateSpec cut = plateWith(PrecrackShape::U, spacing);
  intact.shell.dampingRate = cut.shell.dampingRate = 4.0e4;  // ζ ≈ 1 for the 3.2 kHz first mode
  const PlateGeometry gi = plateGeometry(intact), gu = plateGeometry(cut);
  ASSERT_EQ(gi.nodes.size(), gu.nodes.size());
  SphShell si = buildPlate(intact, gi), su = buildPlate(cut, gu);
  si.setPressure(pressure);
  su.setPressure(pressure);
  const double dt = std::min(si.stableTimeStep(), su.stableTimeStep());
  const int steps = static_cast<int>(0.8e-3 / dt);  // 16 decay times c/2
  const Cancellation never;
  si.advance(steps, dt, never);
  su.advance(steps, dt, never);
  const double wIntact = tongueEndDeflection(si, gu), wCut = tongueEndDeflection(su, gu);  // same node sets
  // Intact: the clamped plate's p a⁴/(64 D) (1 − r²/a²)² at r ≈ 10 mm, 0.88 × 73 µm.
  const double D = intact.shell.material.youngModulus * std::pow(intact.shell.thickness, 3) /
                   (12.0 * (1.0 - std::pow(intact.shell.material.poissonRatio, 2)));
  const double w0 = std::fabs(pressure) * std::pow(0.04, 4) / (64.0 * D);
  EXPECT_NEAR(wIntact, w0 * std::pow(1.0 - 0.0105 * 0.0105 / 0.0016, 2), 0.15 * w0);
  // Cut: at least the cantilever's own q L⁴ / (8 E I) more (the hinge line itself sinks too).
  const double cantilever = std::fabs(pressure) * std::pow(0.020, 4) / (8.0 * D);
  EXPECT_GT(wCut, wIntact + 0.8 * cantilever) << "intact " << wIntact << " m, U " << wCut << " m";
  EXPECT_GT(tongueOpeningAngle(su, gu, cut), 0.0);
}

/// Kirchhoff deflection w(r) of an annular plate b <= r <= a under uniform pressure q, clamped at
/// r = a and free at r = b (M_r = Q_r = 0): w = q r⁴/(64 D) + C1 + C2 r² + C3 ln r + C4 r² ln r.
double annularPlateDeflection(double r, double a, double b, double q, double D, double nu) {
  const double C4 = -q * b * b / (8.0 * D);  // Q_r(b) = −D (q b/(2D) + 4 C4/b) = 0
  // w'(a) = 0 and M_r(b) = 0 for C2, C3.
  const double r1 = -(q * a * a * a / (16.0 * D) + C4 * (2.0 * a * std::log(a) + a));
  const double r2 = -((3.0 + nu) * q * b * b / (16.0 * D) + C4 * (2.0 * std::log(b) * (1.0 + nu) + 3.0 + nu));
  const double m11 = 2.0 * a, m12 = 1.0 / a, m21 = 2.0 * (1.0 + nu), m22 = (nu - 1.0) / (b * b);
  const double det = m11 * m22 - m12 * m21;
  const double C2 = (r1 * m22 - m12 * r2) / det, C3 = (m11 * r2 - m21 * r1) / det;
  const double C1 = -(q * std::pow(a, 4) / (64.0 * D) + C2 * a * a + C3 * std::log(a) + C4 * a * a * std::log(a));
  return q * std::pow(r, 4) / (64.0 * D) + C1 + C2 * r * r + C3 * std::log(r) + C4 * r * r * std::log(r);
}

// The hole's edge is a free edge: a plate with a 20 mm hole under uniform pressure deflects as
// the clamped-free annular Kirchhoff plate (elastic, quasi-static), at the hole's edge and at the
// seed's gauge radius (D_ext + d)/4. Material bridging the hole would stiffen the edge.
TEST(TankPlate, PlateWithAHoleDeflectsAsAClampedFreeAnnulus) {
  const double pressure = -1.0e5;
  PlateSpec plate = plateWith(PrecrackShape::Hole, 0.002);
  plate.shell.dampingRate = 4.0e4;
  const PlateGeometry g = plateGeometry(plate);
  SphShell shell = buildPlate(plate, g);
  shell.setPressure(pressure);
  const double dt = shell.stableTimeStep();
  shell.advance(static_cast<int>(0.8e-3 / dt), dt, Cancellation{});
  const double nu = plate.shell.material.poissonRatio;
  const double D = plate.shell.material.youngModulus * std::pow(plate.shell.thickness, 3) / (12.0 * (1.0 - nu * nu));
  const double a = 0.04, b = 0.010;
  const double wEdge = annularPlateDeflection(b, a, b, std::fabs(pressure), D, nu);
  const double wGauge = annularPlateDeflection(0.025, a, b, std::fabs(pressure), D, nu);
  EXPECT_NEAR(deflectionAtRadius(shell, g, b), wEdge, 0.1 * wEdge);
  EXPECT_NEAR(deflectionAtRadius(shell, g, 0.025), wGauge, 0.1 * wEdge);
  // The free edge sinks further than the intact plate at the same radius, p a⁴/(64 D)(1 − b²/a²)².
  EXPECT_GT(deflectionAtRadius(shell, g, b), std::fabs(pressure) * std::pow(a, 4) / (64.0 * D) * std::pow(1.0 - b * b / (a * a), 2));
}

TEST(TankPlate, BadGeometryNamesTheField) {
  auto fieldOf = [](const PlateSpec& p) {
    try {
      plateGeometry(p);
    } catch (const SpecError& e) {
      return e.field();
    }
    return std::string("(no error)");
  };
  PlateSpec x = plateWith(PrecrackShape::X, 0.002);
  x.precrack.length = 0.1;  // longer than the plate
  EXPECT_EQ(fieldOf(x), "plate.precrack.length");
  PlateSpec hole = plateWith(PrecrackShape::Hole, 0.002);
  hole.precrack.holeDiameter = 0.08;  // as large as the plate
  EXPECT_EQ(fieldOf(hole), "plate.precrack.hole_diameter");
  hole.precrack.holeDiameter = 0.002;  // one spacing: not resolved
  EXPECT_EQ(fieldOf(hole), "plate.precrack.hole_diameter");
  PlateSpec u = plateWith(PrecrackShape::U, 0.002);
  u.precrack.width = 0.07;  // corners outside the plate
  EXPECT_EQ(fieldOf(u), "plate.precrack.length");
  u.precrack.width = 0.003;  // narrower than 2 spacings
  EXPECT_EQ(fieldOf(u), "plate.precrack.width");
  PlateSpec tf = plateWith(PrecrackShape::HoleAndCracks, 0.002);  // 3 mm cracks at Δ = 2 mm
  EXPECT_EQ(fieldOf(tf), "plate.precrack.length");
  PlateSpec coarse = plateWith(PrecrackShape::None, 0.02);
  EXPECT_EQ(fieldOf(coarse), "plate.spacing");
  PlateSpec thick = plateWith(PrecrackShape::None, 0.003);
  thick.shell.thickness = 0.045;  // thicker than the radius: not a shell
  EXPECT_EQ(fieldOf(thick), "plate.thickness");
}

// ---- Observables ----------------------------------------------------------------------------

// A rigid rotation of the tongue about its hinge by a known angle is read back exactly, also when
// the hinge itself has sunk and drawn in (the plate dishes around it: FUA5's hinge sinks about
// 4.6 mm at 3 ms), and a tongue that only sinks with the plate reads 0.
TEST(TankPlateObservables, TongueOpeningAngleOfARigidRotation) {
  for (double spacing : {0.002, 0.0013}) {
    const PlateSpec plate = plateWith(PrecrackShape::U, spacing);
    const PlateGeometry g = plateGeometry(plate);
    SphShell shell = buildPlate(plate, g);
    EXPECT_NEAR(tongueOpeningAngle(shell, g, plate), 0.0, 1e-12);
    const double yh = g.hinge.a[1];
    const std::array<std::array<double, 2>, 3> hingeMoves = {{{0.0, 0.0}, {0.0, -0.0046}, {-0.0008, -0.008}}};
    for (const auto& [drawIn, sink] : hingeMoves) {
      for (double degrees : {0.0, 5.0, 28.0, 50.0, 90.0, 120.0}) {
        const double a = degrees * kPi / 180.0;
        for (std::size_t i : g.tongueNodes) {
          const double dist = yh - g.nodes.y[i];  // from the hinge into the tongue (−y)
          shell.setNodeState(i, {g.nodes.x[i], yh + drawIn - dist * std::cos(a), sink - dist * std::sin(a)},
                             {0.0, -std::sin(a), std::cos(a)}, {0.0, 0.0, 0.0});
        }
        EXPECT_NEAR(tongueOpeningAngle(shell, g, plate) * 180.0 / kPi, degrees, 1e-9)
            << "spacing " << spacing << ", hinge sunk " << -sink << " m, drawn in " << -drawIn << " m";
      }
    }
  }
  const PlateSpec x = plateWith(PrecrackShape::X, 0.002);
  const PlateGeometry gx = plateGeometry(x);
  EXPECT_EQ(tongueOpeningAngle(buildPlate(x, gx), gx, x), 0.0);
}

// The clamped plate's static deflection w(r) = w0 (1 − r²/R²)², set node by node, is read back
// at the seed's gauge radius (D_ext + d)/4 and elsewhere, with and without a hole.
TEST(TankPlateObservables, DeflectionAtRadiusOfAKnownField) {
  const double R = 0.04, w0 = 1.5e-3;
  auto w = [&](double r) { return w0 * std::pow(1.0 - r * r / (R * R), 2); };
  for (PrecrackShape shape : {PrecrackShape::None, PrecrackShape::Hole}) {
    PlateSpec plate = plateWith(shape, 0.0015);
    if (shape == PrecrackShape::Hole) plate.precrack.holeDiameter = 0.014;
    const PlateGeometry g = plateGeometry(plate);
    SphShell shell = buildPlate(plate, g);
    for (std::size_t i = 0; i < g.nodes.size(); ++i) {
      const double r = std::hypot(g.nodes.x[i], g.nodes.y[i]);
      shell.setNodeState(i, {g.nodes.x[i], g.nodes.y[i], -w(r)}, {0.0, 0.0, 1.0}, {0.0, 0.0, 0.0});
    }
    for (double r : {(0.080 + 0.014) / 4.0, 0.010, 0.031, 0.0377}) {
      SCOPED_TRACE(r);
      EXPECT_NEAR(deflectionAtRadius(shell, g, r), w(r), 0.01 * w0);
    }
    if (shape == PrecrackShape::Hole) {
      EXPECT_TRUE(std::isnan(deflectionAtRadius(shell, g, 0.002)));
    }
  }
}

// Nodes fractured along a straight band of known length add up to that length (each cell counts
// its side), over several lines through the ring lattice.
TEST(TankPlateObservables, CrackedLengthOfABandOfFracturedNodes) {
  PlateSpec plate = plateWith(PrecrackShape::None, 0.001);
  const PlateGeometry g = plateGeometry(plate);
  const double d = g.nodes.spacing, length = 0.025;
  for (double angle : {0.0, 0.4, 1.1, 2.0}) {
    for (double offset : {0.0, 0.0043}) {
      SCOPED_TRACE(std::to_string(angle) + " rad, offset " + std::to_string(offset));
      SphShell shell = buildPlate(plate, g);
      const double tx = std::cos(angle), ty = std::sin(angle);
      const double ax = -0.5 * length * tx - offset * ty, ay = -0.5 * length * ty + offset * tx;
      std::size_t count = 0;
      for (std::size_t i = 0; i < g.nodes.size(); ++i) {
        const double px = g.nodes.x[i] - ax, py = g.nodes.y[i] - ay;
        const double along = px * tx + py * ty, across = -px * ty + py * tx;
        if (along >= 0.0 && along < length && std::fabs(across) <= 0.5 * d) {
          shell.fractureNode(i);
          ++count;
        }
      }
      EXPECT_EQ(shell.fracturedCount(), count);
      EXPECT_NEAR(crackedLength(shell, g), length, 0.12 * length);
    }
  }
}

// The rim's torn fraction: the angular cover of the fractured cells near r = D/2. A ring torn all
// round covers the circumference, half a ring half of it (within a cell's width), and cracks
// away from the rim nothing.
TEST(TankPlateObservables, RimTornFractionIsTheTornShareOfTheCircumference) {
  const PlateSpec plate = plateWith(PrecrackShape::None, 0.002);
  const PlateGeometry g = plateGeometry(plate);
  const double rim = 0.5 * plate.diameter, band = 2.0 * plate.spacing;
  // The outermost ring of free nodes inside the rim.
  double ring = 0.0;
  for (std::size_t i = 0; i < g.nodes.size(); ++i)
    if (!g.nodes.clamped[i]) ring = std::max(ring, std::hypot(g.nodes.x[i], g.nodes.y[i]));
  auto onRing = [&](std::size_t i) { return std::abs(std::hypot(g.nodes.x[i], g.nodes.y[i]) - ring) < 1e-9; };
  SphShell whole = buildPlate(plate, g), half = buildPlate(plate, g), inner = buildPlate(plate, g);
  EXPECT_EQ(rimTornFraction(whole, g, rim, band), 0.0);
  std::size_t cells = 0;
  for (std::size_t i = 0; i < g.nodes.size(); ++i) {
    if (onRing(i)) {
      whole.fractureNode(i);
      ++cells;
      if (g.nodes.y[i] > 0.0) half.fractureNode(i);
    }
    if (std::hypot(g.nodes.x[i], g.nodes.y[i]) < rim - 2.0 * band && std::abs(g.nodes.y[i]) < 0.5 * plate.spacing)
      inner.fractureNode(i);  // a diameter's crack, short of the band
  }
  ASSERT_GT(cells, 50u);
  const double cell = 1.0 / static_cast<double>(cells);  // one cell's share of the circumference
  EXPECT_NEAR(rimTornFraction(whole, g, rim, band), 1.0, cell);
  EXPECT_LE(rimTornFraction(whole, g, rim, band), 1.0);
  EXPECT_NEAR(rimTornFraction(half, g, rim, band), 0.5, 1.5 * cell);
  EXPECT_GT(inner.fracturedCount(), 10u);
  EXPECT_EQ(rimTornFraction(inner, g, rim, band), 0.0);
}

// The fracture history: crackPath lists the failed nodes in the order they failed, and each
// node's fracture time is the time of the step it failed in.
TEST(TankPlateObservables, CrackPathFollowsTheFractureOrder) {
  PlateSpec plate = plateWith(PrecrackShape::None, 0.002);
  const PlateGeometry g = plateGeometry(plate);
  SphShell shell = buildPlate(plate, g);
  const std::size_t first = 40, second = 7, third = 100;
  EXPECT_TRUE(crackPath(shell, g).empty());
  EXPECT_TRUE(std::isnan(shell.fractureTime(first)));
  const double dt = shell.stableTimeStep();
  shell.fractureNode(first);
  shell.advance(3, dt, Cancellation{});
  shell.fractureNode(second);
  shell.fractureNode(second);  // already failed: not listed twice
  shell.advance(2, dt, Cancellation{});
  shell.fractureNode(third);
  const auto path = crackPath(shell, g);
  ASSERT_EQ(path.size(), 3u);
  const std::size_t order[3] = {first, second, third};
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(path[k][0], g.nodes.x[order[k]]);
    EXPECT_EQ(path[k][1], g.nodes.y[order[k]]);
  }
  EXPECT_EQ(shell.fractureTime(first), 0.0);
  EXPECT_NEAR(shell.fractureTime(second), 3 * dt, 1e-15);
  EXPECT_NEAR(shell.fractureTime(third), 5 * dt, 1e-15);
}

}  // namespace
}  // namespace rupture
