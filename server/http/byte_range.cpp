#include "http/byte_range.hpp"

#include <charconv>

#include "common/problem.hpp"

namespace rupture::server {
namespace {

std::optional<std::uint64_t> number(const std::string& text) {
  if (text.empty() || text.size() > 19) return std::nullopt;
  std::uint64_t v = 0;
  auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || ptr != text.data() + text.size()) return std::nullopt;
  return v;
}

std::string trimmed(const std::string& s) {
  const std::size_t b = s.find_first_not_of(" \t");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t") - b + 1);
}

[[noreturn]] void unsatisfiable(const std::string& header, std::uint64_t size) {
  throw ApiError(416, problem::kRangeNotSatisfiable, "Range Not Satisfiable",
                 "the range '" + header + "' lies outside the " + std::to_string(size) + "-byte file", "Range",
                 Json{{"in", "header"}, {"size", size}});
}

}  // namespace

std::optional<ByteRange> parseByteRange(const std::string& header, std::uint64_t size) {
  const std::string h = trimmed(header);
  if (h.rfind("bytes=", 0) != 0) return std::nullopt;
  const std::string spec = trimmed(h.substr(6));
  if (spec.find(',') != std::string::npos) return std::nullopt;
  const std::size_t dash = spec.find('-');
  if (dash == std::string::npos) return std::nullopt;
  const std::string first = trimmed(spec.substr(0, dash)), last = trimmed(spec.substr(dash + 1));
  if (first.empty()) {  // suffix: the last N bytes
    auto n = number(last);
    if (!n) return std::nullopt;
    if (*n == 0 || size == 0) unsatisfiable(h, size);
    const std::uint64_t length = std::min(*n, size);
    return ByteRange{size - length, length};
  }
  auto a = number(first);
  if (!a) return std::nullopt;
  std::optional<std::uint64_t> b;
  if (!last.empty()) {
    b = number(last);
    if (!b || *b < *a) return std::nullopt;
  }
  if (*a >= size) unsatisfiable(h, size);
  const std::uint64_t end = b ? std::min(*b, size - 1) : size - 1;
  return ByteRange{*a, end - *a + 1};
}

}  // namespace rupture::server
