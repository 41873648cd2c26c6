#pragma once
// PNG and PDF output of the summary plot: the SVG of svg_plot.hpp drawn by librsvg through cairo,
// rasterised for PNG and kept vector for PDF, so every format shows the same drawing.
#include <string>

namespace rupture::server {

/// Renders an SVG document to a PNG of widthPx x heightPx pixels (the SVG is scaled to fill it).
/// Throws std::runtime_error with librsvg's message when the SVG cannot be rendered.
std::string renderPng(const std::string& svg, int widthPx, int heightPx);

/// The same drawing as a one-page vector PDF of widthPt x heightPt points.
std::string renderPdf(const std::string& svg, int widthPt, int heightPt);

}  // namespace rupture::server
