#pragma once
// A run's time series as a line plot (y against x, each from /series), with the scenario's labels
// and engineering units on the axes: `rupture plot RUN.h5 --series strain,stress_mean`.
#include <string>
#include <vector>

#include "io/hdf5_file.hpp"
#include "render/field_image.hpp"

namespace rupture::render {

struct SeriesPlotRequest {
  std::string root;            ///< the run's group in a job's merged file; "" for a run file
  std::string x;               ///< a series name; "": strain when recorded, else time
  std::vector<std::string> y;  ///< series names (one unit); empty: the scenario's first declared one
  int width = 800, height = 500;
  ImageFormat format = ImageFormat::Png;
};

struct SeriesPlot {
  std::string bytes, mediaType;
  std::string x;
  std::vector<std::string> y;
};

/// The names of the 1-D datasets under root + "/series", sorted.
std::vector<std::string> seriesOf(const io::Hdf5File& file, const std::string& root);

/// Throws FieldImageError naming "x", "y", "width" or "height" for a request that cannot be drawn,
/// RenderStopped when `stop` says so.
SeriesPlot renderSeriesPlot(const io::Hdf5File& file, const SeriesPlotRequest& request, const StopCheck& stop = {});

}  // namespace rupture::render
