#pragma once
// A cairo drawing that ends as the bytes of a PNG, an SVG or a PDF: the one place the output
// formats of the pictures are made (vector formats stay vector).
#include <functional>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>

#include <cairo.h>

namespace rupture::render {

enum class ImageFormat { Png, Svg, Pdf };

/// Asked between the stages of a drawing (waiting for the canvas, every few thousand particles,
/// while the PNG is encoded): true ends the drawing with RenderStopped. A server that is stopping
/// passes one, so that a render in flight does not hold its shutdown; empty: never stop.
using StopCheck = std::function<bool()>;

/// A drawing ended early because its StopCheck said so.
class RenderStopped : public std::runtime_error {
public:
  RenderStopped() : std::runtime_error("the drawing was stopped") {}
};

/// "image/png", "image/svg+xml" or "application/pdf".
const char* mediaTypeOf(ImageFormat format);

/// One canvas is drawn at a time in the process: text goes through fontconfig, whose state is
/// shared; a canvas holds the lock from construction to finish() (or destruction).
class Canvas {
public:
  /// A white canvas of width x height px (pt for PDF). Throws std::runtime_error when cairo cannot
  /// create it (out of memory), RenderStopped when `stop` says so while it waits for its turn.
  Canvas(ImageFormat format, int width, int height, StopCheck stop = {});
  ~Canvas();
  Canvas(const Canvas&) = delete;
  Canvas& operator=(const Canvas&) = delete;

  cairo_t* context() { return m_context; }
  /// Throws RenderStopped when the canvas's StopCheck says so; drawing loops call it now and then.
  void checkStop() const;
  /// Ends the drawing and returns the file's bytes; the canvas is not drawn on afterwards.
  /// Throws RenderStopped when stopped while the PNG is encoded.
  std::string finish();

private:
  StopCheck m_stop;
  std::unique_lock<std::timed_mutex> m_lock;
  ImageFormat m_format;
  std::string m_bytes;  // SVG and PDF stream into it while drawing
  cairo_surface_t* m_surface = nullptr;
  cairo_t* m_context = nullptr;
};

}  // namespace rupture::render
