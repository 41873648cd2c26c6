#include "views/plot_png.hpp"

#include <cairo-pdf.h>
#include <cairo.h>
#include <librsvg/rsvg.h>

#include <memory>
#include <mutex>
#include <stdexcept>

namespace rupture::server {
namespace {

cairo_status_t appendToString(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

/// The PNG encoder's output, ended at its next write once the render is stopped.
struct PngSink {
  std::string* bytes;
  const render::StopCheck* stop;
};

cairo_status_t appendPngBytes(void* closure, const unsigned char* data, unsigned int length) {
  auto* sink = static_cast<PngSink*>(closure);
  if (*sink->stop && (*sink->stop)()) return CAIRO_STATUS_WRITE_ERROR;
  sink->bytes->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

void checkStop(const render::StopCheck& stop) {
  if (stop && stop()) throw render::RenderStopped();
}

std::string takeMessage(GError* error) {
  std::string message = error && error->message ? error->message : "unknown librsvg error";
  if (error) g_error_free(error);
  return message;
}

}  // namespace

namespace {

/// Draws the SVG onto a cairo surface filling width x height (one drawing at a time: font lookup
/// through fontconfig and pango is shared process state).
void drawSvg(const std::string& svg, cairo_surface_t* surface, int width, int height, const render::StopCheck& stop) {
  static std::mutex mutex;
  std::lock_guard lock(mutex);
  checkStop(stop);  // stopped while another drawing had the turn
  GError* error = nullptr;
  std::unique_ptr<RsvgHandle, decltype(&g_object_unref)> handle(
      rsvg_handle_new_from_data(reinterpret_cast<const guint8*>(svg.data()), svg.size(), &error), &g_object_unref);
  if (!handle) throw std::runtime_error("cannot read the plot's SVG: " + takeMessage(error));
  std::unique_ptr<cairo_t, decltype(&cairo_destroy)> cr(cairo_create(surface), &cairo_destroy);
  const RsvgRectangle viewport{0, 0, static_cast<double>(width), static_cast<double>(height)};
  if (!rsvg_handle_render_document(handle.get(), cr.get(), &viewport, &error)) {
    throw std::runtime_error("cannot render the plot: " + takeMessage(error));
  }
}

}  // namespace

std::string renderPng(const std::string& svg, int widthPx, int heightPx, const render::StopCheck& stop) {
  checkStop(stop);
  std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)> surface(
      cairo_image_surface_create(CAIRO_FORMAT_ARGB32, widthPx, heightPx), &cairo_surface_destroy);
  drawSvg(svg, surface.get(), widthPx, heightPx, stop);
  cairo_surface_flush(surface.get());
  std::string png;
  PngSink sink{&png, &stop};
  if (cairo_surface_write_to_png_stream(surface.get(), &appendPngBytes, &sink) != CAIRO_STATUS_SUCCESS) {
    checkStop(stop);
    throw std::runtime_error("cannot encode the plot as PNG");
  }
  return png;
}

std::string renderPdf(const std::string& svg, int widthPt, int heightPt, const render::StopCheck& stop) {
  checkStop(stop);
  std::string pdf;
  {
    std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)> surface(
        cairo_pdf_surface_create_for_stream(&appendToString, &pdf, widthPt, heightPt), &cairo_surface_destroy);
    drawSvg(svg, surface.get(), widthPt, heightPt, stop);
    cairo_surface_finish(surface.get());  // writes the document into pdf
  }
  if (pdf.rfind("%PDF", 0) != 0) throw std::runtime_error("cannot write the plot as PDF");
  return pdf;
}

}  // namespace rupture::server
