#pragma once
// The picture of a spec's discretisation before its run (rupture/sample_preview.hpp): each panel's
// points as discs coloured by their group (element, loaded face, fluid, wall, plate node, ...; the
// Okabe-Ito colours, told apart with colour blindness), the notches and pre-cracks in red, holes,
// projectiles and loaded regions outlined, a scale bar of a round length under each panel, a
// legend, and a caption with the counts and sizes in engineering units. Drawn with cairo as PNG or
// SVG; the server's submission preview shows it (docs/server.md, "Preview and cost").
#include <cstddef>
#include <string>

#include "render/canvas.hpp"
#include "rupture/sample_preview.hpp"

namespace rupture::render {

struct SamplePictureRequest {
  int width = 900, height = 600;  ///< px
  std::string note;               ///< a line under the title ("the first of 6 runs"); "" for none
  ImageFormat format = ImageFormat::Png;
};

struct SamplePicture {
  std::string bytes;
  std::string mediaType;
  std::size_t drawn = 0;  ///< points drawn over every panel
};

/// Draws the preview; RenderStopped when `stop` says so (asked every few thousand points).
SamplePicture renderSamplePicture(const SamplePreview& preview, const SamplePictureRequest& request,
                                  const StopCheck& stop = {});

}  // namespace rupture::render
