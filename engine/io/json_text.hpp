#pragma once
// The one way a spec's JSON text becomes a value, for every door (CLI files, HTTP bodies).
// nlohmann::json alone is not enough at a trust boundary: it reports "1e400" as an out_of_range
// error without saying where, and dumping or copying a value nested tens of thousands of levels
// deep recurses until the stack overflows. This reader parses through a SAX handler that knows
// the dotted path of the value being read, so both become a SpecError naming the field.
#include <string_view>

#include <nlohmann/json.hpp>

namespace rupture::io {

/// Deepest nesting of arrays and objects accepted in a spec or request body.
constexpr int kMaxJsonNesting = 64;

/// Parses a whole JSON text (every byte, NUL bytes included, is part of it).
/// Throws SpecError naming the field for a number outside the double range or nesting deeper
/// than kMaxJsonNesting, and nlohmann::json::parse_error for anything that is not JSON.
nlohmann::json parseJsonText(std::string_view text);

}  // namespace rupture::io
