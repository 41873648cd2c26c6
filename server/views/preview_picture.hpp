#pragma once
// The picture of a submission's discretised sample, plate or tank (POST .../execution?dry_run=true
// &picture=true): the first run's spec built by rupture::buildSamplePreview (the builders its run
// starts with) and drawn by render::renderSamplePicture, within bounds, since a build costs what a
// run's first stage costs: a spec estimated above `maxElements` elements (or particles) or
// `maxMemoryBytes` is refused before anything is built, and a build and drawing that take longer
// than `maxSeconds` (or that a stopping server ends) are stopped; each refusal is a `reason`, never
// an error (docs/server.md, "Preview and cost").
#include <atomic>
#include <optional>
#include <string>

#include "jobs/job_store.hpp"
#include "rupture/run.hpp"

namespace rupture::server {

struct PicturePolicy {
  double maxElements = 200'000;     ///< estimated elements or particles a picture is built for
  double maxMemoryBytes = 1 << 30;  ///< B: the run's memory estimate a picture is built for
  double maxSeconds = 20;           ///< s: the build and the drawing together
  int width = 900, height = 600;    ///< px
};

struct PreviewPicture {
  Json doc;         ///< the DryRun document's `picture` (api/openapi.yaml), less its href
  std::string png;  ///< the picture's bytes; empty when not available
};

/// Why `estimate` gets no picture under `policy` (the DryRun document's `picture`), or nullopt
/// when it may be built: asked before anything is built or waited for.
std::optional<Json> pictureRefusal(const rupture::RunEstimate& estimate, const PicturePolicy& policy);

/// The picture of `spec` (whose estimate is `estimate`), or why there is none. `note` says which
/// run it shows ("run 0, the first of 6"); `cacheDirectory`: the runs' sample cache; `stopping`:
/// the server is stopping (the build ends at once).
PreviewPicture previewPicture(const Json& spec, const rupture::RunEstimate& estimate, const PicturePolicy& policy,
                              const std::string& note, const std::string& cacheDirectory,
                              const std::atomic<bool>& stopping);

}  // namespace rupture::server
