#pragma once
// A cairo drawing that ends as the bytes of a PNG, an SVG or a PDF: the one place the output
// formats of the pictures are made (vector formats stay vector).
#include <memory>
#include <mutex>
#include <string>

#include <cairo.h>

namespace rupture::render {

enum class ImageFormat { Png, Svg, Pdf };

/// "image/png", "image/svg+xml" or "application/pdf".
const char* mediaTypeOf(ImageFormat format);

/// One canvas is drawn at a time in the process: text goes through fontconfig, whose state is
/// shared; a canvas holds the lock from construction to finish() (or destruction).
class Canvas {
public:
  /// A white canvas of width x height px (pt for PDF). Throws std::runtime_error when cairo cannot
  /// create it (out of memory).
  Canvas(ImageFormat format, int width, int height);
  ~Canvas();
  Canvas(const Canvas&) = delete;
  Canvas& operator=(const Canvas&) = delete;

  cairo_t* context() { return m_context; }
  /// Ends the drawing and returns the file's bytes; the canvas is not drawn on afterwards.
  std::string finish();

private:
  std::unique_lock<std::mutex> m_lock;
  ImageFormat m_format;
  std::string m_bytes;  // SVG and PDF stream into it while drawing
  cairo_surface_t* m_surface = nullptr;
  cairo_t* m_context = nullptr;
};

}  // namespace rupture::render
