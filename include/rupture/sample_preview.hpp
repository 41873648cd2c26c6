#pragma once
// The discretised sample, plate or tank of a spec, built by the very functions its run starts with
// (the bonded sample builder and its cache, the SPH lattices, the plate's node set) and stopped
// there, before any time step: what a submission form shows before the job is queued
// (docs/server.md, "Preview and cost"), drawn by engine/render/sample_picture.hpp.
#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "rupture/run.hpp"

namespace rupture {

/// One view of the discretisation, in its own plane (u across, v up), lengths in m.
struct PreviewPanel {
  std::string title;                 ///< "sample (x-y plane)", "plate, top view", ...
  std::string uAxis = "x", vAxis = "y";
  /// The points drawn: centre, radius (m; the element's, or half the particle spacing) and group
  /// (an index into SamplePreview::groups).
  std::vector<double> u, v, radius;
  std::vector<std::uint8_t> group;
  /// Outlines drawn over the points: line segments (pre-cracks, notches: u0, v0, u1, v1), circles
  /// (a hole, a projectile: u, v, r) and boxes (a loaded region: u0, v0, u1, v1), each with a label.
  struct Segment { std::array<double, 4> at; std::string label; };
  struct Circle { std::array<double, 3> at; std::string label; };
  struct Rect { std::array<double, 4> at; std::string label; };
  std::vector<Segment> segments;
  std::vector<Circle> circles;
  std::vector<Rect> boxes;
};

struct SamplePreview {
  std::string scenario;
  /// What each group of points is ("element", "loaded face X_max (pulled)", "fluid", "wall", ...).
  std::vector<std::string> groups;
  std::vector<PreviewPanel> panels;
  /// The count the run holds, as its summary reports it: a bonded run's `elements`, a fluid run's
  /// `particles` (fluid and boundary), and for tank-impact also the plate's nodes.
  std::size_t elements = 0;
  std::string elementsName = "elements";  ///< "elements" or "particles"
  std::size_t plateNodes = 0;             ///< tank-impact only
  std::size_t bonds = 0;                  ///< bonded scenarios only
  std::array<double, 3> size{0, 0, 0};    ///< the sample's (or fluid domain's) extent (m); [2] 0 in 2-D
  int dimension = 2;
  /// Lines for the caption, in engineering units: the counts, the sizes, what is marked.
  std::vector<std::string> facts;
  bool fromCache = false;                 ///< the bonded sample was read from the run's sample cache
};

/// The spec's scenario draws no discretisation (validation: its runs are whole published cases).
class PreviewNotAvailable : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

/// Builds the spec's discretisation as its run would, without stepping it. `cancel` is polled
/// through the builders (RunCancelled once set); `cacheDirectory`: the run's cache of packed
/// samples, read and filled exactly as a run with that cache does (empty: no cache). Throws
/// PreviewNotAvailable for a scenario without one, std::runtime_error where the build fails.
SamplePreview buildSamplePreview(const ParsedSpec& spec, const std::atomic<bool>& cancel,
                                 const std::string& cacheDirectory = {});

}  // namespace rupture
