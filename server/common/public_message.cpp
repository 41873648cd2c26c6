#include "common/public_message.hpp"

#include <cctype>

#include "common/utf8.hpp"

namespace rupture::server {
namespace {

bool pathChar(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '/' || c == '.' || c == '_' || c == '-' ||
         c == '+' || c == '~' || c == '@' || c == '%' || c == '=' || c == ',';
}

bool startsAbsolutePath(const std::string& text, std::size_t i) {
  if (text[i] != '/') return false;
  // A path starts after a space, quote, bracket or the start; "1/s" or "and/or" are not paths.
  if (i > 0) {
    const char before = text[i - 1];
    if (std::isalnum(static_cast<unsigned char>(before)) || before == '.' || before == '_' || before == '-') return false;
  }
  // At least two components: "/x/y" (a lone "/s" is a unit, not a path).
  const std::size_t second = text.find('/', i + 1);
  if (second == std::string::npos || second == i + 1) return false;
  for (std::size_t k = i + 1; k < second; ++k) {
    if (!pathChar(text[k])) return false;
  }
  return second + 1 < text.size() && pathChar(text[second + 1]);
}

}  // namespace

std::string publicMessage(const std::string& message) {
  const std::string text = toValidUtf8(message);
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size();) {
    if (startsAbsolutePath(text, i)) {
      std::size_t end = i;
      while (end < text.size() && pathChar(text[end])) ++end;
      std::string path = text.substr(i, end - i);
      while (path.size() > 1 && (path.back() == '.' || path.back() == ',' || path.back() == '/')) {
        path.pop_back();
        --end;
      }
      out += path.substr(path.find_last_of('/') + 1);
      i = end;
      continue;
    }
    if (text[i] == '0' && i + 1 < text.size() && (text[i + 1] == 'x' || text[i + 1] == 'X') &&
        (i == 0 || !std::isalnum(static_cast<unsigned char>(text[i - 1])))) {
      std::size_t end = i + 2;
      while (end < text.size() && std::isxdigit(static_cast<unsigned char>(text[end]))) ++end;
      if (end - i - 2 >= 6) {
        out += "0x...";
        i = end;
        continue;
      }
    }
    out += text[i++];
  }
  return out;
}

}  // namespace rupture::server
