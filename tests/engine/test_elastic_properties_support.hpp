#pragma once
// The small beam sample the elastic-properties tests measure (560 elements, porosity 0): the seed's
// element radius and Table 3's beams on a 0.15 µm square, fast enough for a strength test in seconds.
#include <nlohmann/json.hpp>

namespace rupture::test {

inline nlohmann::json smallBeamElasticPropertiesSpec() {
  return {{"scenario", "elastic-properties"},
          {"dimension", 2},
          {"sample", {{"size", {0.15e-6, 0.15e-6}}, {"element_radius", 3.3e-9}, {"seed", 7}}},
          {"material",
           {{"model", "beam"},
            {"density", 6060.0},
            {"beam", {{"young_modulus", 2865e9}, {"poisson_ratio", 0.3}, {"radius_ratio", 0.3}, {"failure_stress", 4e9}}}}}};
}

}  // namespace rupture::test
