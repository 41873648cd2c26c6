#include "render/canvas.hpp"

#include <cairo-pdf.h>
#include <cairo-svg.h>

#include <chrono>
#include <stdexcept>

namespace rupture::render {
namespace {

cairo_status_t appendBytes(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

/// Where the PNG encoder writes: the bytes, unless the drawing is stopped (the encoder then ends
/// at its next write; an 8-megapixel PNG takes about a second to encode).
struct PngSink {
  std::string* bytes;
  const StopCheck* stop;
};

cairo_status_t appendPngBytes(void* closure, const unsigned char* data, unsigned int length) {
  auto* sink = static_cast<PngSink*>(closure);
  if (*sink->stop && (*sink->stop)()) return CAIRO_STATUS_WRITE_ERROR;
  sink->bytes->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

std::timed_mutex& drawingMutex() {
  static std::timed_mutex mutex;
  return mutex;
}

}  // namespace

const char* mediaTypeOf(ImageFormat format) {
  switch (format) {
    case ImageFormat::Png: return "image/png";
    case ImageFormat::Svg: return "image/svg+xml";
    case ImageFormat::Pdf: return "application/pdf";
  }
  return "application/octet-stream";
}

Canvas::Canvas(ImageFormat format, int width, int height, StopCheck stop)
    : m_stop(std::move(stop)), m_lock(drawingMutex(), std::defer_lock), m_format(format) {
  // The turn is waited for in short steps, so that a stop reaches a drawing that has not begun.
  while (!m_lock.try_lock_for(std::chrono::milliseconds(20))) checkStop();
  checkStop();
  switch (format) {
    case ImageFormat::Png: m_surface = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, width, height); break;
    case ImageFormat::Svg: m_surface = cairo_svg_surface_create_for_stream(&appendBytes, &m_bytes, width, height); break;
    case ImageFormat::Pdf: m_surface = cairo_pdf_surface_create_for_stream(&appendBytes, &m_bytes, width, height); break;
  }
  if (cairo_surface_status(m_surface) != CAIRO_STATUS_SUCCESS) {
    const std::string why = cairo_status_to_string(cairo_surface_status(m_surface));
    cairo_surface_destroy(m_surface);
    throw std::runtime_error("cannot create the picture: " + why);
  }
  m_context = cairo_create(m_surface);
  cairo_set_source_rgb(m_context, 1, 1, 1);
  cairo_paint(m_context);
}

Canvas::~Canvas() {
  if (m_context) cairo_destroy(m_context);
  if (m_surface) cairo_surface_destroy(m_surface);
}

void Canvas::checkStop() const {
  if (m_stop && m_stop()) throw RenderStopped();
}

std::string Canvas::finish() {
  checkStop();
  cairo_destroy(m_context);
  m_context = nullptr;
  if (m_format == ImageFormat::Png) {
    cairo_surface_flush(m_surface);
    PngSink sink{&m_bytes, &m_stop};
    if (cairo_surface_write_to_png_stream(m_surface, &appendPngBytes, &sink) != CAIRO_STATUS_SUCCESS) {
      checkStop();
      throw std::runtime_error("cannot encode the picture as PNG");
    }
  } else {
    cairo_surface_finish(m_surface);  // flushes the SVG or PDF into m_bytes
  }
  cairo_surface_destroy(m_surface);
  m_surface = nullptr;
  m_lock.unlock();
  return std::move(m_bytes);
}

}  // namespace rupture::render
