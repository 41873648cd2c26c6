#pragma once
// Reads a PNG back (through cairo, as the pictures are written) for tests: its size, how many
// colours it holds and how many pixels lie near a given colour.
#include <cairo.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <set>
#include <string>
#include <vector>

namespace rupture::testing {

struct PngProbe {
  int width = 0, height = 0;           ///< 0 when the bytes are not a PNG
  std::vector<std::uint32_t> pixels;   ///< 0xRRGGBB, row by row
  std::size_t colours = 0;             ///< distinct RGB values

  /// Pixels within `tolerance` (per channel, 0..255) of r, g, b.
  std::size_t near(int r, int g, int b, int tolerance = 12) const {
    std::size_t n = 0;
    for (std::uint32_t p : pixels) {
      const int R = static_cast<int>(p >> 16 & 255), G = static_cast<int>(p >> 8 & 255), B = static_cast<int>(p & 255);
      n += std::abs(R - r) <= tolerance && std::abs(G - g) <= tolerance && std::abs(B - b) <= tolerance;
    }
    return n;
  }
};

namespace detail {
struct PngReader {
  const std::string* bytes;
  std::size_t offset = 0;
};
inline cairo_status_t readPngChunk(void* closure, unsigned char* data, unsigned int length) {
  auto* r = static_cast<PngReader*>(closure);
  if (r->offset + length > r->bytes->size()) return CAIRO_STATUS_READ_ERROR;
  std::memcpy(data, r->bytes->data() + r->offset, length);
  r->offset += length;
  return CAIRO_STATUS_SUCCESS;
}
}  // namespace detail

inline PngProbe probePng(const std::string& bytes) {
  PngProbe probe;
  detail::PngReader reader{&bytes};
  cairo_surface_t* s = cairo_image_surface_create_from_png_stream(&detail::readPngChunk, &reader);
  if (cairo_surface_status(s) == CAIRO_STATUS_SUCCESS) {
    probe.width = cairo_image_surface_get_width(s);
    probe.height = cairo_image_surface_get_height(s);
    const unsigned char* data = cairo_image_surface_get_data(s);
    const int stride = cairo_image_surface_get_stride(s);
    std::set<std::uint32_t> seen;
    for (int y = 0; y < probe.height; ++y)
      for (int x = 0; x < probe.width; ++x) {
        std::uint32_t p;
        std::memcpy(&p, data + y * stride + 4 * x, 4);
        probe.pixels.push_back(p & 0xFFFFFF);
        seen.insert(p & 0xFFFFFF);
      }
    probe.colours = seen.size();
  }
  cairo_surface_destroy(s);
  return probe;
}

}  // namespace rupture::testing
