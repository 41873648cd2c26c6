#pragma once
// The preview of a bonded sample once built (rupture/sample_preview.hpp): its elements as discs in
// the x-y plane (in 3-D the elements the mid-depth section cuts, at their cut radius, so pores and
// notches show as in a polished section), the notches as segments, and the counts and sizes the
// caption states. Each bonded scenario marks its own loading over it.
#include <cstdint>
#include <string>
#include <vector>

#include "bonded/bonded_system.hpp"
#include "bonded/sample_spec.hpp"
#include "rupture/sample_preview.hpp"
#include "samples/sample_builder.hpp"

namespace rupture {

/// `group` gives each element its index in `groups` (empty: every element in group 0, "element").
SamplePreview bondedSamplePreview(const BondedSystem& system, const SampleSpec& sample, const SampleReport& report,
                                  const std::vector<std::uint8_t>& group = {},
                                  std::vector<std::string> groups = {"element"});

/// "2 mm x 1 mm" (x 0.5 mm in 3-D): the sample's box in engineering units.
std::string boxText(const std::array<double, 3>& size, int dimension);

}  // namespace rupture
