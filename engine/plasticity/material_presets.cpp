#include "plasticity/material_presets.hpp"

#include "rupture/spec_error.hpp"

namespace rupture {

MaterialPreset materialPreset(const std::string& name, const std::string& field) {
  if (name == "au4g_2024_t351") return au4g2024T351();
  if (name == "au4g_2024_t351_seed") return au4g2024T351Seed();
  if (name == "steel_4340") return steel4340();
  throw SpecError(field, "\"" + name + "\"", "\"au4g_2024_t351\", \"au4g_2024_t351_seed\" or \"steel_4340\"");
}

}  // namespace rupture
