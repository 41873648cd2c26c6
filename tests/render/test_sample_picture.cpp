// The preview picture of a discretisation (engine/render/sample_picture.hpp) on a preview built
// here with known contents: each group in its own colour over comparable areas, a notch in red, the
// scale bar's round lengths, and a stop check that ends the drawing.
#include <gtest/gtest.h>

#include "render/round_ticks.hpp"
#include "render/sample_picture.hpp"
#include "support/png_probe.hpp"

namespace rupture::render {
namespace {

using rupture::testing::probePng;

/// A 20 x 10 grid of discs (spacing 1 µm): the left half group 0, the right half group 1, and a
/// notch across the middle.
SamplePreview twoHalves() {
  SamplePreview preview;
  preview.scenario = "dynamic-tension";
  preview.groups = {"element", "face X_max (pulled)"};
  preview.facts = {"200 elements", "sample 20 µm x 10 µm"};
  PreviewPanel panel;
  panel.title = "sample";
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 10; ++j) {
      panel.u.push_back(1e-6 * (i + 0.5));
      panel.v.push_back(1e-6 * (j + 0.5));
      panel.radius.push_back(0.5e-6);
      panel.group.push_back(i < 10 ? 0 : 1);
    }
  panel.segments.push_back({{0, 5e-6, 8e-6, 5e-6}, "notch"});
  preview.panels.push_back(panel);
  return preview;
}

TEST(SamplePicture, EachGroupInItsColourAndTheNotchInRed) {
  const SamplePicture picture = renderSamplePicture(twoHalves(), {});
  EXPECT_EQ(picture.drawn, 200u);
  EXPECT_EQ(picture.mediaType, "image/png");
  const auto png = probePng(picture.bytes);
  ASSERT_EQ(png.width, 900);
  ASSERT_EQ(png.height, 600);
  // Okabe-Ito blue (0, 115, 178) and orange (230, 158, 0): the two halves, of equal area.
  const std::size_t blue = png.near(0, 115, 178), orange = png.near(230, 158, 0);
  EXPECT_GT(blue, 20000u);
  EXPECT_GT(orange, 20000u);
  EXPECT_LT(std::abs(static_cast<double>(blue) - static_cast<double>(orange)) / blue, 0.1);
  EXPECT_GT(png.near(217, 26, 26, 30), 100u) << "the notch";
}

TEST(SamplePicture, ScaleBarsAreRoundLengths) {
  EXPECT_DOUBLE_EQ(scaleBarLength(1.0), 0.2);
  EXPECT_DOUBLE_EQ(scaleBarLength(0.08), 0.02);
  EXPECT_NEAR(scaleBarLength(975e-9), 2e-7, 1e-20);
  EXPECT_NEAR(scaleBarLength(3e-5), 5e-6, 1e-20);
  EXPECT_EQ(scaleBarLength(0), 0);
}

TEST(SamplePicture, AStopCheckEndsTheDrawing) {
  EXPECT_THROW(renderSamplePicture(twoHalves(), {}, [] { return true; }), RenderStopped);
}

}  // namespace
}  // namespace rupture::render
