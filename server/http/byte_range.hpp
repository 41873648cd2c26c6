#pragma once
// One byte range of a download (RFC 9110 section 14). cpp-httplib 0.11.4 applies Range headers
// itself, but a range past the end gets 206 with a wrapped Content-Length, and error documents get
// cut by the range too; so the server clears cpp-httplib's ranges and serves them here.
// A request for several ranges is answered with the whole file (200), as RFC 9110 allows.
#include <cstdint>
#include <optional>
#include <string>

namespace rupture::server {

struct ByteRange {
  std::uint64_t offset = 0;
  std::uint64_t length = 0;
};

/// The single range `header` asks for within `size` bytes; nullopt to send the whole resource
/// (no header, several ranges, another unit, or a malformed spec, which RFC 9110 says to ignore).
/// Throws ApiError 416 (with `size` for Content-Range: bytes */size) when the range lies past the end.
std::optional<ByteRange> parseByteRange(const std::string& header, std::uint64_t size);

}  // namespace rupture::server
