#pragma once
// Viridis (van der Walt & Smith, matplotlib 2015): a perceptually uniform, colour-blind safe map
// that prints readably in grey, for every field picture.
#include <array>

namespace rupture::render {

struct Rgb {
  double r, g, b;  ///< each in [0, 1]
};

/// The colour of t in [0, 1] (clamped; NaN gives grey), interpolated linearly between the map's
/// eleven published stops (t = 0, 0.1, ..., 1).
Rgb viridis(double t);

}  // namespace rupture::render
