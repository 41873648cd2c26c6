#pragma once
// The one way a spec's JSON text becomes a value, for every door (CLI files, HTTP bodies).
// nlohmann::json alone is not enough at a trust boundary: it reports "1e400" as an out_of_range
// error without saying where, and dumping or copying a value nested tens of thousands of levels
// deep recurses until the stack overflows. This reader parses through a SAX handler that knows
// the dotted path of the value being read, so both become a SpecError naming the field.
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "rupture/spec_error.hpp"

namespace rupture::io {

/// Deepest nesting of arrays and objects accepted in a spec or request body.
constexpr int kMaxJsonNesting = 64;

/// A JSON text that is well formed but beyond what a spec may hold, at a named field.
class JsonLimitError : public SpecError {
public:
  enum class Kind { NumberOutOfRange, TooDeep, NotFinite };
  JsonLimitError(Kind kind, std::size_t byte, std::string field, std::string value, std::string allowed)
      : SpecError(std::move(field), std::move(value), std::move(allowed)), m_kind(kind), m_byte(byte) {}
  Kind kind() const { return m_kind; }
  std::size_t byte() const { return m_byte; }  ///< offset in the text where it was noticed

private:
  Kind m_kind;
  std::size_t m_byte;
};

/// Parses a whole JSON text (every byte, NUL bytes included, is part of it).
/// Throws JsonLimitError (a SpecError naming the field) for a number outside the double range, a
/// NaN or Infinity literal (which JSON does not have), or nesting deeper than kMaxJsonNesting, and nlohmann::json::parse_error for anything that is not JSON.
nlohmann::json parseJsonText(std::string_view text);
/// The same, keeping object members in their order in the text (the server's request bodies,
/// where a sweep's first path varies slowest).
nlohmann::ordered_json parseOrderedJsonText(std::string_view text);

}  // namespace rupture::io
