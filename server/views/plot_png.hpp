#pragma once
// PNG and PDF output of the summary plot: the SVG of svg_plot.hpp drawn by librsvg through cairo,
// rasterised for PNG and kept vector for PDF, so every format shows the same drawing.
#include <string>

#include "render/canvas.hpp"

namespace rupture::server {

/// Renders an SVG document to a PNG of widthPx x heightPx pixels (the SVG is scaled to fill it).
/// Throws std::runtime_error with librsvg's message when the SVG cannot be rendered,
/// render::RenderStopped when `stop` says so (before drawing, and while the PNG is encoded).
std::string renderPng(const std::string& svg, int widthPx, int heightPx, const render::StopCheck& stop = {});

/// The same drawing as a one-page vector PDF of widthPt x heightPt points.
std::string renderPdf(const std::string& svg, int widthPt, int heightPt, const render::StopCheck& stop = {});

}  // namespace rupture::server
