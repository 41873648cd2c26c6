#pragma once
// The preview of a job before it is queued (POST .../execution?dry_run=true, the form's Preview):
// its runs as the submission planned and checked them, each with the estimate admission used
// (elements, memory, steps) and a time from the scenario's cost model, and the job's time on this
// server's workers (docs/server.md, "Preview and cost").
#include <string>
#include <vector>

#include "jobs/job_store.hpp"
#include "rupture/run.hpp"

namespace rupture::server {

/// One run of a planned job: where it sits and the estimate it was checked by.
struct RunForecast {
  Json swept;  ///< its swept values, aligned with NewJob::sweptPaths
  int replicate = 0;
  rupture::RunEstimate estimate;
};

/// What the preview says of the server it would run on.
struct PreviewContext {
  int threadsPerRun = 1;
  int workers = 0;            ///< runs at a time; 0 when a cluster decides (every run may start at once)
  double maxRunMemory = 0;    ///< B one run may need (inf with Slurm)
  int queuedRuns = 0;         ///< runs waiting now
  int maxQueuedRuns = 0;      ///< --max-queued-runs
};

/// The end of the last of runs taking `seconds` each, in queue order, on `workers` workers that take
/// them first come, first served, as the scheduler does (s): run k holds `slots[k]` workers (its
/// MPI ranks; 1 where `slots` is shorter, at most `workers`) and starts when that many are free,
/// never before the run ahead of it.
double queueMakespan(const std::vector<double>& seconds, int workers, const std::vector<int>& slots = {});

/// The DryRun document of api/openapi.yaml for `job` and its runs' `forecasts`.
Json jobPreview(const std::string& scenario, const NewJob& job, const std::vector<RunForecast>& forecasts,
                const PreviewContext& where);

}  // namespace rupture::server
