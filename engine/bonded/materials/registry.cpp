#include "bonded/materials/registry.hpp"

#include <stdexcept>

namespace rupture {

// Each style's file defines its accessor; a new style is one line here and one in materialStyles().
const MaterialStyle& beamStyle();
const MaterialStyle& hookeanStyle();
const MaterialStyle& bornStyle();
const MaterialStyle& pmbStyle();

const std::vector<const MaterialStyle*>& materialStyles() {
  static const std::vector<const MaterialStyle*> styles = {
      &beamStyle(),
      &hookeanStyle(),
      &bornStyle(),
      &pmbStyle(),
  };
  return styles;
}

std::vector<std::string> materialStyleNames() {
  std::vector<std::string> names;
  for (const MaterialStyle* style : materialStyles()) names.emplace_back(style->name());
  return names;
}

const MaterialStyle& materialStyle(std::string_view name) {
  for (const MaterialStyle* style : materialStyles())
    if (style->name() == name) return *style;
  throw std::invalid_argument("unknown material model \"" + std::string(name) + "\"");
}

std::string quotedStyleNames(bool (MaterialStyle::*capability)() const) {
  std::string names;
  for (const MaterialStyle* style : materialStyles())
    if ((style->*capability)()) names += (names.empty() ? "\"" : ", \"") + std::string(style->name()) + "\"";
  return names;
}

}  // namespace rupture
