#pragma once
// UTF-8 at the HTTP boundary: everything a response echoes (paths, query values, body strings,
// parser excerpts) may hold arbitrary bytes; JSON documents must be valid UTF-8.
#include <cstddef>
#include <string>
#include <string_view>

namespace rupture::server {

/// True when `text` is well-formed UTF-8 (RFC 3629: no overlongs, no surrogates, <= U+10FFFF).
bool isValidUtf8(std::string_view text);

/// Byte offset of the first ill-formed sequence, or npos when `text` is valid.
std::size_t firstInvalidUtf8(std::string_view text);

/// `text` with every ill-formed sequence replaced by U+FFFD.
std::string toValidUtf8(std::string_view text);

/// At most `maxBytes` of valid UTF-8 from the start of `text`, never cut inside a character;
/// "..." is appended when something was cut.
std::string truncateUtf8(std::string_view text, std::size_t maxBytes);

}  // namespace rupture::server
