#pragma once
// Escaping text for XML 1.0 (XDMF sidecars, SVG plots): the five entities; characters XML 1.0
// forbids (C0 controls but tab, LF and CR; U+FFFE and U+FFFF) are dropped, and bytes that are not
// well-formed UTF-8 become U+FFFD, so any input gives a well-formed document.
#include <cstddef>
#include <string>

namespace rupture::io {

namespace detail {
/// Length of the well-formed UTF-8 sequence at text[i] (2 to 4 bytes, lead byte >= 0x80) and its
/// code point, or 0 when the bytes are not well-formed.
inline std::size_t utf8Sequence(const std::string& text, std::size_t i, char32_t& codePoint) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char lead = byte(i);
  std::size_t length = lead >= 0xF5 ? 0 : lead >= 0xF0 ? 4 : lead >= 0xE0 ? 3 : lead >= 0xC2 ? 2 : 0;
  if (length == 0 || i + length > text.size()) return 0;
  char32_t cp = lead & (0x7F >> length);
  for (std::size_t k = 1; k < length; ++k) {
    if ((byte(i + k) & 0xC0) != 0x80) return 0;
    cp = (cp << 6) | (byte(i + k) & 0x3F);
  }
  const char32_t smallest = length == 2 ? 0x80 : length == 3 ? 0x800 : 0x10000;
  if (cp < smallest || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return 0;
  codePoint = cp;
  return length;
}
}  // namespace detail

inline std::string xmlEscape(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size();) {
    const char c = text[i];
    if (static_cast<unsigned char>(c) >= 0x80) {
      char32_t cp = 0;
      const std::size_t n = detail::utf8Sequence(text, i, cp);
      if (n == 0) {
        out += "\xEF\xBF\xBD";  // U+FFFD for each byte that is not part of a character
        ++i;
        continue;
      }
      if (cp != 0xFFFE && cp != 0xFFFF) out.append(text, i, n);
      i += n;
      continue;
    }
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\n' && c != '\r') break;
        out += c;
    }
    ++i;
  }
  return out;
}

}  // namespace rupture::io
