// Pictures of a run's fields and series (engine/render) on run files written here with known
// contents: the colour map's published stops, the colours a field must produce, broken bonds drawn
// in red (and not when asked for none), the SPH selection (a tank's plate for damage, a slice of
// the fluid for pressure), the three formats, and every bad request refused naming its member.
#include <gtest/gtest.h>

#include <cmath>

#include "io/hdf5_file.hpp"
#include "render/colour_map.hpp"
#include "render/field_image.hpp"
#include "render/round_ticks.hpp"
#include "rupture/quantity_text.hpp"
#include "render/series_plot.hpp"
#include "support/png_probe.hpp"
#include "support/test_support.hpp"

namespace rupture::render {
namespace {

using rupture::testing::probePng;
using rupture::testing::ScratchDir;

/// A 2D bonded run: an n x n square grid (spacing 1 µm, radius 0.5 µm), damage 0 on the left
/// half and 1 on the right, a bond between horizontal neighbours, broken across the middle;
/// σ_xx = 1 MPa × column index at the second snapshot, half that at the first.
std::string writeBondedRun(const std::filesystem::path& dir, int n = 20) {
  const std::string path = (dir / "bonded.h5").string();
  io::Hdf5File f = io::Hdf5File::create(path);
  f.setAttribute("/", "scenario", std::string("dynamic-tension"));
  std::vector<double> position, velocity, damage, radius, stress;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      position.insert(position.end(), {i * 1e-6, j * 1e-6, 0.0});
      velocity.insert(velocity.end(), {0.0, 0.0, 0.0});
      damage.push_back(i < n / 2 ? 0.0 : 1.0);
      radius.push_back(0.5e-6);
      for (int c = 0; c < 9; ++c) stress.push_back(c == 0 ? 1e6 * i : 0.0);
    }
  std::vector<std::int32_t> bonds;
  std::vector<std::uint8_t> intact;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      bonds.insert(bonds.end(), {j * n + i, j * n + i + 1});
      intact.push_back(i == n / 2 - 1 ? 0 : 1);
    }
  const std::size_t count = static_cast<std::size_t>(n * n);
  f.writeDataset("/sample/bonds", bonds, {bonds.size() / 2, 2}, "1");
  for (const char* name : {"/snapshots/000000", "/snapshots/000001"}) {
    f.createGroup(name);
    f.setAttribute(name, "time", std::string(name).back() == '0' ? 0.0 : 1e-9);
    f.setAttribute(name, "strain", std::string(name).back() == '0' ? 0.0 : 1e-3);
    const std::string g = name;
    f.writeDataset(g + "/position", position, {count, 3}, "m");
    f.writeDataset(g + "/velocity", velocity, {count, 3}, "m/s");
    f.writeDataset(g + "/damage", damage, {count}, "1");
    f.writeDataset(g + "/radius", radius, {count}, "m");
    std::vector<double> scaled = stress;
    if (std::string(name).back() == '0')
      for (double& v : scaled) v *= 0.5;
    f.writeDataset(g + "/stress", scaled, {count, 3, 3}, "Pa");
    f.writeDataset(g + "/bond_intact", intact, {intact.size()}, "1");
  }
  std::vector<double> strain, mean, time, fraction;
  for (int k = 0; k <= 10; ++k) {
    time.push_back(k * 1e-10);
    strain.push_back(k * 1e-4);
    mean.push_back(k * 1e6);
    fraction.push_back(0.01 * k);
  }
  f.writeDataset("/series/time", time, {time.size()}, "s");
  f.writeDataset("/series/strain", strain, {strain.size()}, "1");
  f.writeDataset("/series/stress_mean", mean, {mean.size()}, "Pa");
  f.writeDataset("/series/broken_bond_fraction", fraction, {fraction.size()}, "1");
  return path;
}

/// A 3D SPH run with a plate: a fluid block of 6 x 6 x 10 particles (body −1, spacing 1 cm,
/// pressure growing with height) above a plate of 8 x 8 nodes (body 2) at z = −1 cm.
std::string writeTankRun(const std::filesystem::path& dir) {
  const std::string path = (dir / "tank.h5").string();
  io::Hdf5File f = io::Hdf5File::create(path);
  f.setAttribute("/", "scenario", std::string("tank-impact"));
  f.createGroup("/geometry");
  f.setAttribute("/geometry", "plate_body", std::int64_t{2});
  f.setAttribute("/geometry", "spacing", 0.01);
  f.setAttribute("/geometry", "plate_spacing", 0.01);
  f.setAttribute("/geometry", "vertical_axis", std::string("z"));
  std::vector<double> position, velocity, pressure, damage, density;
  std::vector<std::int32_t> body;
  for (int k = 0; k < 10; ++k)
    for (int j = 0; j < 6; ++j)
      for (int i = 0; i < 6; ++i) {
        position.insert(position.end(), {0.01 * i, 0.01 * j, 0.01 * k});
        pressure.push_back(1e5 * k);
        body.push_back(-1);
      }
  for (int j = 0; j < 8; ++j)
    for (int i = 0; i < 8; ++i) {
      position.insert(position.end(), {0.01 * i - 0.01, 0.01 * j - 0.01, -0.01});
      pressure.push_back(0);
      body.push_back(2);
    }
  const std::size_t n = body.size();
  velocity.assign(3 * n, 0.0);
  density.assign(n, 1000.0);
  damage.assign(n, 0.0);
  f.createGroup("/snapshots/000000");
  f.setAttribute("/snapshots/000000", "time", 2e-4);
  f.writeDataset("/snapshots/000000/position", position, {n, 3}, "m");
  f.writeDataset("/snapshots/000000/velocity", velocity, {n, 3}, "m/s");
  f.writeDataset("/snapshots/000000/pressure", pressure, {n}, "Pa");
  f.writeDataset("/snapshots/000000/density", density, {n}, "kg/m^3");
  f.writeDataset("/snapshots/000000/damage", damage, {n}, "1");
  f.writeDataset("/snapshots/000000/body", body, {n}, "1");
  return path;
}

TEST(ColourMap, ViridisPassesThroughItsPublishedStops) {
  auto rgb255 = [](double t) {
    const Rgb c = viridis(t);
    return std::array<long, 3>{std::lround(255 * c.r), std::lround(255 * c.g), std::lround(255 * c.b)};
  };
  EXPECT_EQ(rgb255(0.0), (std::array<long, 3>{68, 1, 84}));     // #440154
  EXPECT_EQ(rgb255(0.5), (std::array<long, 3>{33, 145, 140}));   // #21918c
  EXPECT_EQ(rgb255(1.0), (std::array<long, 3>{253, 231, 37}));   // #fde725
  EXPECT_EQ(rgb255(-3.0), rgb255(0.0));                          // clamped
  EXPECT_EQ(rgb255(7.0), rgb255(1.0));
  // Perceptually ordered: lightness (here the channel sum) grows with t.
  double previous = -1;
  for (double t = 0; t <= 1.0001; t += 0.05) {
    const Rgb c = viridis(t);
    const double light = 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
    EXPECT_GT(light, previous) << t;
    previous = light;
  }
}

TEST(FieldImage, DamageShowsBothStatesAndTheBrokenBondsInRed) {
  ScratchDir dir;
  const io::Hdf5File file = io::Hdf5File::openReadOnly(writeBondedRun(dir.path()));
  FieldImageRequest request;  // every default: the last snapshot, the first field (damage)
  const FieldImage image = renderFieldImage(file, request);
  EXPECT_EQ(image.field, "damage");
  EXPECT_EQ(image.snapshot, 1u);
  EXPECT_EQ(image.snapshots, 2u);
  EXPECT_EQ(image.drawn, 400u);
  EXPECT_EQ(image.mediaType, "image/png");
  const auto png = probePng(image.bytes);
  ASSERT_EQ(png.width, 800);
  ASSERT_EQ(png.height, 600);
  // Half the discs are undamaged (viridis 0), half fully damaged (viridis 1), and both cover a
  // comparable area; the broken column of bonds is red.
  const std::size_t purple = png.near(68, 1, 84), yellow = png.near(253, 231, 37), red = png.near(214, 38, 41, 30);
  EXPECT_GT(purple, 20000u);
  EXPECT_GT(yellow, 20000u);
  EXPECT_LT(std::abs(static_cast<double>(purple) - static_cast<double>(yellow)) / purple, 0.25);
  EXPECT_GT(red, 200u);

  request.bonds = "none";
  EXPECT_EQ(probePng(renderFieldImage(file, request).bytes).near(214, 38, 41, 30), 0u);
}

TEST(FieldImage, StressAndSnapshotsByIndexOrTime) {
  ScratchDir dir;
  const io::Hdf5File file = io::Hdf5File::openReadOnly(writeBondedRun(dir.path()));
  FieldImageRequest request;
  request.field = "stress_xx";
  request.thumbnail = true;
  request.width = 200;
  request.height = 150;
  const FieldImage image = renderFieldImage(file, request);
  EXPECT_DOUBLE_EQ(image.min, 0.0);
  EXPECT_DOUBLE_EQ(image.max, 19e6);  // σ_xx = 1 MPa × column index, 0 to 19
  EXPECT_GT(probePng(image.bytes).colours, 15u);  // a gradient, not one colour
  request.time = 1e-10;  // nearer the first snapshot (0 s) than the second (1 ns)
  EXPECT_EQ(renderFieldImage(file, request).snapshot, 0u);
  request.time.reset();
  request.snapshot = -2;
  EXPECT_EQ(renderFieldImage(file, request).snapshot, 0u);
  request.snapshot.reset();
  request.min = 0;
  request.max = 38e6;
  EXPECT_DOUBLE_EQ(renderFieldImage(file, request).max, 38e6);
}

TEST(FieldImage, SvgAndPdfAreVectorFiles) {
  ScratchDir dir;
  const io::Hdf5File file = io::Hdf5File::openReadOnly(writeBondedRun(dir.path(), 6));
  FieldImageRequest request;
  request.format = ImageFormat::Svg;
  const FieldImage svg = renderFieldImage(file, request);
  EXPECT_EQ(svg.mediaType, "image/svg+xml");
  EXPECT_NE(svg.bytes.find("<svg"), std::string::npos);
  request.format = ImageFormat::Pdf;
  const FieldImage pdf = renderFieldImage(file, request);
  EXPECT_EQ(pdf.mediaType, "application/pdf");
  EXPECT_EQ(pdf.bytes.rfind("%PDF", 0), 0u);
}

TEST(FieldImage, ATanksDamageIsItsPlateAndItsPressureASliceOfTheFluid) {
  ScratchDir dir;
  const io::Hdf5File file = io::Hdf5File::openReadOnly(writeTankRun(dir.path()));
  FieldImageRequest request;
  EXPECT_EQ(renderFieldImage(file, request).drawn, 64u);  // damage: the plate's 8 x 8 nodes, from above
  request.field = "pressure";
  // The fluid in a vertical section: x–z through the middle of y (y from 0 to 5 cm, middle 2.5 cm)
  // within one spacing (1 cm): the layers y = 2 and 3 cm, 6 x 10 particles each.
  const FieldImage section = renderFieldImage(file, request);
  EXPECT_EQ(section.drawn, 120u);
  EXPECT_DOUBLE_EQ(section.min, 0.0);
  EXPECT_DOUBLE_EQ(section.max, 9e5);
  request.slice = 0;  // every fluid particle
  EXPECT_EQ(renderFieldImage(file, request).drawn, 360u);
  request.body = "all";
  EXPECT_EQ(renderFieldImage(file, request).drawn, 424u);
  request.body = "2";
  request.view = "xy";
  EXPECT_EQ(renderFieldImage(file, request).drawn, 64u);
  // A body no particle belongs to is refused with the bodies there are, not drawn empty.
  request.body = "999";
  try {
    renderFieldImage(file, request);
    ADD_FAILURE() << "body 999 was drawn";
  } catch (const FieldImageError& e) {
    EXPECT_EQ(e.member(), "body");
    EXPECT_NE(std::string(e.what()).find("allowed: all, fluid, 2"), std::string::npos) << e.what();
  }
}

TEST(FieldImage, AStopCheckEndsTheDrawing) {
  ScratchDir dir;
  const io::Hdf5File file = io::Hdf5File::openReadOnly(writeBondedRun(dir.path(), 4));
  const auto stopNow = [] { return true; };
  for (ImageFormat format : {ImageFormat::Png, ImageFormat::Svg}) {
    FieldImageRequest field;
    field.format = format;
    EXPECT_THROW(renderFieldImage(file, field, stopNow), RenderStopped);
    SeriesPlotRequest series;
    series.format = format;
    EXPECT_THROW(renderSeriesPlot(file, series, stopNow), RenderStopped);
  }
  // Stopped only once the PNG is being encoded: the four checks before (after reading, on the
  // canvas, before the bonds, at finish) say go on, the encoder's first write is refused.
  int asked = 0;
  const auto stopLate = [&asked] { return ++asked > 4; };
  EXPECT_THROW(renderFieldImage(file, FieldImageRequest{}, stopLate), RenderStopped);
  EXPECT_GE(asked, 5);
  // Told to go on, it draws as ever, and the canvas is free for the next drawing.
  EXPECT_EQ(renderFieldImage(file, FieldImageRequest{}, [] { return false; }).bytes.substr(1, 3), "PNG");
}

TEST(FieldImage, RefusesWhatItCannotDrawNamingTheMember) {
  ScratchDir dir;
  const io::Hdf5File file = io::Hdf5File::openReadOnly(writeBondedRun(dir.path(), 4));
  auto memberOf = [&](const std::function<void(FieldImageRequest&)>& change) {
    FieldImageRequest request;
    change(request);
    try {
      renderFieldImage(file, request);
    } catch (const FieldImageError& e) {
      EXPECT_NE(std::string(e.what()).find("allowed"), std::string::npos) << e.what();
      return e.member();
    } catch (const std::exception& e) {
      return std::string("other: ") + e.what();
    }
    return std::string("accepted");
  };
  EXPECT_EQ(memberOf([](auto& r) { r.field = "pressure"; }), "field");  // not recorded in this run
  EXPECT_EQ(memberOf([](auto& r) { r.field = "temperature"; }), "field");
  EXPECT_EQ(memberOf([](auto& r) { r.snapshot = 2; }), "snapshot");
  EXPECT_EQ(memberOf([](auto& r) { r.snapshot = -3; }), "snapshot");
  EXPECT_EQ(memberOf([](auto& r) { r.view = "zz"; }), "view");
  EXPECT_EQ(memberOf([](auto& r) { r.bonds = "some"; }), "bonds");
  EXPECT_EQ(memberOf([](auto& r) { r.body = "fluid"; }), "body");  // no bodies in a bonded run
  EXPECT_EQ(memberOf([](auto& r) { r.width = 10; }), "width");
  EXPECT_EQ(memberOf([](auto& r) { r.height = 100000; }), "height");
  FieldImageRequest request;
  request.min = 2;
  request.max = 1;
  EXPECT_THROW(renderFieldImage(file, request), FieldImageError);
  request.max.reset();
  request.min.reset();
  request.slice = -1;
  EXPECT_THROW(renderFieldImage(file, request), FieldImageError);
}

/// Whether every tick is a whole multiple of a 1-2-5 step, and the steps between ticks are equal.
::testing::AssertionResult roundTicksOf(const std::vector<double>& ticks) {
  if (ticks.size() < 2) return ::testing::AssertionFailure() << ticks.size() << " ticks";
  const double step = ticks[1] - ticks[0];
  const double mantissa = step / std::pow(10.0, std::floor(std::log10(step)));
  if (std::abs(mantissa - 1) > 1e-9 && std::abs(mantissa - 2) > 1e-9 && std::abs(mantissa - 5) > 1e-9)
    return ::testing::AssertionFailure() << "step " << step << " is not 1, 2 or 5 x 10^k";
  for (double t : ticks)
    if (std::abs(t / step - std::round(t / step)) > 1e-6)
      return ::testing::AssertionFailure() << "tick " << t << " is not a multiple of " << step;
  return ::testing::AssertionSuccess();
}

TEST(RoundTicks, FallOnOneTwoFiveSteps) {
  const RoundTicks stress = roundTicks(0, 211e6, 5);  // the issue's 70.5, 141, 211 MPa
  EXPECT_DOUBLE_EQ(stress.step, 50e6);
  EXPECT_EQ(stress.values, (std::vector<double>{0, 50e6, 100e6, 150e6, 200e6}));
  const RoundTicks small = roundTicks(0.1, 0.7, 6);
  EXPECT_DOUBLE_EQ(small.step, 0.1);
  ASSERT_EQ(small.values.size(), 7u);
  EXPECT_EQ(small.values[2], 3 * 0.1) << "multiples by index, no drift";
  EXPECT_TRUE(roundTicksOf(roundTicks(-3.3e-6, 17.2e-6, 4).values));
  EXPECT_TRUE(roundTicks(1, 1, 5).values.empty());
  EXPECT_EQ(tickText(150e6 / 1e6, 50e6 / 1e6), "150");
  EXPECT_EQ(tickText(0.30000000000000004, 0.1), "0.3");
  EXPECT_EQ(tickText(2.5, 2.5), "2.5");
  EXPECT_EQ(tickText(-1e-17, 0.5), "0");
}

TEST(FieldImage, AxesInEngineeringUnitsAndRoundColourTicks) {
  ScratchDir dir;
  const io::Hdf5File file = io::Hdf5File::openReadOnly(writeBondedRun(dir.path()));
  FieldImageRequest request;
  request.field = "stress_xx";
  const FieldImage image = renderFieldImage(file, request);
  // The 20 x 20 µm grid: both axes in µm, at round ticks over the drawn extent (-0.5 to 19.5 µm).
  ASSERT_EQ(image.axes.size(), 2u);
  EXPECT_EQ(image.axes[0].name, "x");
  EXPECT_EQ(image.axes[1].name, "y");
  for (const FieldImage::Axis& axis : image.axes) {
    EXPECT_EQ(axis.unit, "µm");
    EXPECT_NEAR(axis.lo, -0.5e-6, 1e-12);
    EXPECT_NEAR(axis.hi, 19.5e-6, 1e-12);
    EXPECT_TRUE(roundTicksOf(axis.ticks));
    EXPECT_GE(axis.ticks.size(), 3u);
  }
  // σ_xx from 0 to 19 MPa: the colour bar's ticks at 0, 5, 10, 15 MPa, labelled in MPa.
  EXPECT_EQ(image.colourUnit, "MPa");
  EXPECT_EQ(image.colourTicks, (std::vector<double>{0, 5e6, 10e6, 15e6}));
  // The axes are drawn: dark pixels in the band under the particles where the x axis runs.
  const auto png = probePng(image.bytes);
  std::size_t dark = 0;
  for (int y = png.height - 50; y < png.height; ++y)
    for (int x = 0; x < png.width - 130; ++x) {
      const std::uint32_t p = png.pixels[static_cast<std::size_t>(y * png.width + x)];
      dark += (p >> 16 & 255) < 90 && (p >> 8 & 255) < 90 && (p & 255) < 90;
    }
  EXPECT_GT(dark, 150u) << "axis line, ticks and labels below the picture";
  // The SVG says in words what its glyphs show: the axes with their unit, the colour ticks.
  request.format = ImageFormat::Svg;
  const std::string svg = renderFieldImage(file, request).bytes;
  const std::size_t desc = svg.find("<desc id=\"picture-description\">");
  ASSERT_NE(desc, std::string::npos);
  const std::string text = svg.substr(desc, svg.find("</desc>", desc) - desc);
  EXPECT_NE(text.find("x axis (µm)"), std::string::npos) << text;
  EXPECT_NE(text.find("y axis (µm)"), std::string::npos) << text;
  EXPECT_NE(text.find("ticks 0 Pa 5 MPa 10 MPa 15 MPa"), std::string::npos) << text;
  EXPECT_NE(svg.find("<title>Stress xx, t = 1 ns, strain 0.001 (snapshot 1 of 0 to 1)"), std::string::npos);
  // A thumbnail has no room for axes: a scale bar of a round length instead, a quarter of the
  // 20 µm width at most (5 µm).
  request.thumbnail = true;
  request.format = ImageFormat::Png;
  request.width = 200;
  request.height = 150;
  const FieldImage thumbnail = renderFieldImage(file, request);
  EXPECT_TRUE(thumbnail.axes.empty());
  EXPECT_DOUBLE_EQ(thumbnail.scaleBar, 5e-6);
  const auto small = probePng(thumbnail.bytes);
  std::size_t bar = 0;  // the bar's dark pixels at the lower left
  for (int y = small.height - 10; y < small.height; ++y)
    for (int x = 0; x < 60; ++x) bar += (small.pixels[static_cast<std::size_t>(y * small.width + x)] & 0xFFFFFF) < 0x202020;
  EXPECT_GT(bar, 40u);
  EXPECT_EQ(renderFieldImage(file, FieldImageRequest{}).scaleBar, 0.0) << "the full picture has axes instead";
}

TEST(FieldImage, TheColourRangeIsTheRunsUnlessAskedOtherwise) {
  ScratchDir dir;
  const io::Hdf5File file = io::Hdf5File::openReadOnly(writeBondedRun(dir.path()));
  FieldImageRequest request;
  request.field = "stress_xx";
  request.snapshot = 0;  // σ_xx up to 9.5 MPa
  const FieldImage first = renderFieldImage(file, request);
  request.snapshot = 1;  // up to 19 MPa
  const FieldImage last = renderFieldImage(file, request);
  // By default one colour is one value on every snapshot: both span the run's 0 to 19 MPa.
  EXPECT_EQ(first.range, "run");
  EXPECT_DOUBLE_EQ(first.min, last.min);
  EXPECT_DOUBLE_EQ(first.max, last.max);
  EXPECT_DOUBLE_EQ(first.max, 19e6);
  EXPECT_EQ(first.colourTicks, last.colourTicks);
  // Asked for, each snapshot its own range.
  request.snapshot = 0;
  request.range = "snapshot";
  const FieldImage own = renderFieldImage(file, request);
  EXPECT_EQ(own.range, "snapshot");
  EXPECT_DOUBLE_EQ(own.max, 9.5e6);
  // A range given is the range drawn, ticks round within it.
  request.range.clear();
  request.min = 2e6;
  request.max = 12e6;
  const FieldImage asked = renderFieldImage(file, request);
  EXPECT_EQ(asked.range, "asked");
  EXPECT_DOUBLE_EQ(asked.min, 2e6);
  EXPECT_DOUBLE_EQ(asked.max, 12e6);
  EXPECT_EQ(asked.colourTicks, (std::vector<double>{2e6, 4e6, 6e6, 8e6, 10e6, 12e6}));
  request.min.reset();
  request.max.reset();
  request.range = "all";
  EXPECT_THROW(renderFieldImage(file, request), FieldImageError);
}

TEST(FieldImage, MarksTheLoadingFromTheSpec) {
  ScratchDir dir;
  const std::string path = writeBondedRun(dir.path());
  {
    io::Hdf5File f = io::Hdf5File::openReadWrite(path);
    f.createGroup("/spec");
    f.setAttribute("/spec", "json", std::string(R"({"loading": {"strain_rate": 1e6}})"));
  }
  const io::Hdf5File file = io::Hdf5File::openReadOnly(path);
  const FieldImage tension = renderFieldImage(file, FieldImageRequest{});
  ASSERT_EQ(tension.loading.size(), 2u);
  EXPECT_EQ(tension.loading[0], "held at the smallest x face");
  EXPECT_EQ(tension.loading[1], "pulled at 1e6 /s, along +x at the largest x face");
  FieldImageRequest bare;
  bare.axes = false;
  EXPECT_TRUE(renderFieldImage(file, bare).loading.empty());

  // A tank's plate seen from above is loaded across the view: the water pushes it along −z.
  const io::Hdf5File tank = [&] {
    const std::string tankPath = writeTankRun(dir.path());
    io::Hdf5File f = io::Hdf5File::openReadWrite(tankPath);
    f.createGroup("/spec");
    f.setAttribute("/spec", "json", std::string(R"({"impactor": {"mass": 245, "speed": 5}})"));
    return io::Hdf5File::openReadOnly(tankPath);
  }();
  const FieldImage plate = renderFieldImage(tank, FieldImageRequest{});  // damage: the plate from above
  ASSERT_EQ(plate.loading.size(), 1u);
  EXPECT_EQ(plate.loading[0], "piston at 5 m/s, along −z (into the page)");
  FieldImageRequest section;
  section.field = "pressure";  // a vertical section through the fluid: the piston's face at the top
  const FieldImage fluid = renderFieldImage(tank, section);
  ASSERT_EQ(fluid.loading.size(), 1u);
  EXPECT_EQ(fluid.loading[0], "piston at 5 m/s, along −z at the largest z face");
}

TEST(SnapshotField, AStrainOfZeroOnEverySnapshotIsNoStrain) {
  ScratchDir dir;
  const std::string path = writeBondedRun(dir.path(), 4);
  {
    const io::Hdf5File tension = io::Hdf5File::openReadOnly(path);
    const std::vector<SnapshotRef> snapshots = listSnapshots(tension, "");
    ASSERT_EQ(snapshots.size(), 2u);
    EXPECT_EQ(snapshots[0].strain, 0.0) << "a tension run's first snapshot is at strain 0";
    EXPECT_EQ(snapshots[1].strain, 1e-3);
  }
  {
    io::Hdf5File f = io::Hdf5File::openReadWrite(path);
    f.setAttribute("/snapshots/000001", "strain", 0.0);  // as impact writes every snapshot
  }
  const io::Hdf5File impact = io::Hdf5File::openReadOnly(path);
  for (const SnapshotRef& s : listSnapshots(impact, "")) EXPECT_FALSE(s.strain.has_value()) << s.group;
  FieldImageRequest request;
  request.format = ImageFormat::Svg;
  const std::string svg = renderFieldImage(impact, request).bytes;
  EXPECT_EQ(svg.find("strain 0"), std::string::npos) << "the title says no strain";
}

TEST(SeriesPlot, PlotsAgainstStrainByDefaultAndRefusesMixedUnits) {
  ScratchDir dir;
  const io::Hdf5File file = io::Hdf5File::openReadOnly(writeBondedRun(dir.path(), 4));
  SeriesPlotRequest request;
  const SeriesPlot plot = renderSeriesPlot(file, request);
  EXPECT_EQ(plot.x, "strain");
  ASSERT_EQ(plot.y.size(), 1u);
  const auto png = probePng(plot.bytes);
  EXPECT_EQ(png.width, 800);
  EXPECT_EQ(png.height, 500);
  EXPECT_GT(png.colours, 10u);
  request.y = {"stress_mean", "broken_bond_fraction"};
  try {
    renderSeriesPlot(file, request);
    ADD_FAILURE() << "Pa and 1 on one axis were accepted";
  } catch (const FieldImageError& e) {
    EXPECT_EQ(e.member(), "y");
  }
  request.y = {"no_such_series"};
  EXPECT_THROW(renderSeriesPlot(file, request), FieldImageError);
}

}  // namespace
}  // namespace rupture::render
