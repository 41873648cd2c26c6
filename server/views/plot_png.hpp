#pragma once
// PNG output of the summary plot: the SVG of svg_plot.hpp rasterised by librsvg (through cairo),
// so both formats show the same drawing.
#include <string>

namespace rupture::server {

/// Renders an SVG document to a PNG of widthPx x heightPx pixels (the SVG is scaled to fill it).
/// Throws std::runtime_error with librsvg's message when the SVG cannot be rendered.
std::string renderPng(const std::string& svg, int widthPx, int heightPx);

}  // namespace rupture::server
