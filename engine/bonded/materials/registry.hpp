#pragma once
// The registered bonded material styles, by name (registry.cpp holds one line per style).
#include <string>
#include <string_view>
#include <vector>

#include "bonded/materials/material_style.hpp"

namespace rupture {

/// Every registered style, in registration order (the order the spec's errors list them in).
const std::vector<const MaterialStyle*>& materialStyles();
/// Their names, in the same order.
std::vector<std::string> materialStyleNames();
/// The style of that name; throws std::invalid_argument for an unknown one.
const MaterialStyle& materialStyle(std::string_view name);
/// The names of the styles that pass `capability`, quoted and joined ("\"beam\"").
std::string quotedStyleNames(bool (MaterialStyle::*capability)() const);

}  // namespace rupture
