#pragma once
// The picture of a run's field at one snapshot: every particle a disc coloured by the field with
// viridis and a labelled colour bar, and where the run has bonds its broken bonds drawn as red
// lines, so the crack network of the seeds' figures shows (Longchamp et al. 2024, Fig. 4; Ha &
// Bobaru 2010, Fig. 5). Drawn with cairo as PNG, SVG or PDF: the server's run pages and
// `rupture plot` show the same image.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "io/hdf5_file.hpp"
#include "render/canvas.hpp"
#include "render/snapshot_field.hpp"

namespace rupture::render {

/// Every member is optional; what is left empty is chosen from the run (see each member).
struct FieldImageRequest {
  std::string root;                   ///< the run's group in a job's merged file; "" for a run file
  std::string field;                  ///< a FieldDeclaration name; "": the first the run recorded
  std::optional<long> snapshot;       ///< index, negative from the end (−1 the last, the default)
  std::optional<double> time;         ///< s: the snapshot nearest this time (instead of `snapshot`)
  std::string view;                   ///< "xy", "xz" or "yz"; "": the section or plane that shows most
  std::string body;                   ///< "all", "fluid" or a body index; "": the plate for a tank's
                                      ///< damage, the fluid for other SPH fields, else all
  std::optional<double> slice;        ///< m: draw only points within this distance of the middle of
                                      ///< the depth axis (0: all); default: one particle spacing for a
                                      ///< 3D fluid, 0 otherwise
  std::string bonds;                  ///< "broken", "all" or "none"; "": broken where a particle has a
                                      ///< few bonds (discrete elements, lattices), none for a dense
                                      ///< peridynamic family (its damage field shows the crack)
  std::optional<double> min, max;     ///< colour range in the field's unit; default: see `range`
  std::string range;                  ///< the default colour range: "run" (or ""): the field's range
                                      ///< over every snapshot of the run, so that snapshots compare
                                      ///< by colour; "snapshot": this snapshot's own. Damage: 0..1
  bool axes = true;                   ///< axes in engineering units (µm, mm) at round ticks, and
                                      ///< the loading marks; a thumbnail has neither
  int width = 800, height = 600;      ///< px (pt for PDF)
  bool thumbnail = false;             ///< no title, colour bar or axes, a scale bar instead: the job
                                      ///< page's small images
  ImageFormat format = ImageFormat::Png;
};

inline constexpr int kMinImageSide = 48, kMaxImageSide = 4000;

struct FieldImage {
  std::string bytes;
  std::string mediaType;                   ///< image/png, image/svg+xml or application/pdf
  std::string field, label, unit;          ///< what was drawn
  std::size_t snapshot = 0, snapshots = 0; ///< the index drawn, of how many
  double time = 0;                         ///< s
  double min = 0, max = 0;                 ///< the colour range used
  std::string range;                       ///< where min..max came from: "run", "snapshot",
                                           ///< "fixed" (damage), "asked" (min and max given)
  std::vector<double> colourTicks;         ///< the colour bar's ticks (field unit), round values
  std::string colourUnit;                  ///< the unit its labels read in ("MPa")
  struct Axis {
    std::string name;                      ///< "x", "y" or "z"
    std::string unit;                      ///< the labels' unit ("µm")
    double lo = 0, hi = 0;                 ///< m, the drawn extent
    std::vector<double> ticks;             ///< m, round values in the unit
  };
  std::vector<Axis> axes;                  ///< horizontal, vertical; empty without axes
  std::vector<std::string> loading;        ///< the loading marks drawn, described for people
  double scaleBar = 0;                     ///< m, a thumbnail's scale bar (1, 2 or 5 × 10^k); 0: none
  std::size_t drawn = 0;                   ///< particles drawn
};

/// Snapshots are numbered from 0 wherever a person reads them (the title, the run page, the CLI),
/// as the `snapshot` index of the request and the HDF5 groups /snapshots/<k> are.

/// Renders the picture. Throws FieldImageError naming the member at fault (an unknown field, a
/// snapshot out of range, a run without snapshots: "snapshot"), std::runtime_error when the file
/// cannot be read, RenderStopped when `stop` says so (asked between stages and every few thousand
/// particles).
FieldImage renderFieldImage(const io::Hdf5File& file, const FieldImageRequest& request, const StopCheck& stop = {});

}  // namespace rupture::render
