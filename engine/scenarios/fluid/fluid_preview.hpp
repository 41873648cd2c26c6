#pragma once
// The preview of an SPH lattice once built (rupture/sample_preview.hpp): a side view in the
// vertical plane through the axis (2-D: the whole plane; 3-D: the lattice layer nearest the middle
// of the depth axis, so the wall shows as its section), the fluid and each body in its own group,
// and the counts the run's summary reports (`particles`, fluid and boundary).
#include <string>

#include "rupture/sample_preview.hpp"
#include "sph/sph_system.hpp"

namespace rupture {

/// The view is x across, the vertical (y in 2-D, z in 3-D) up; in 3-D the layer of sites nearest
/// y = `depthMiddle` (on its upper side where two lie alike) is drawn.
SamplePreview fluidLatticePreview(const sph::SphSystem& s, int dimension, double spacing, double depthMiddle,
                                  const std::string& title);

/// The fluid particles' extent (m) along x, y, z.
std::array<double, 3> fluidExtent(const sph::SphSystem& s);

}  // namespace rupture
