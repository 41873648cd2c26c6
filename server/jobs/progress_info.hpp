#pragma once
// The live-progress members of the job and run documents: stage, elapsed_s, eta_s and updated,
// from the stored timestamps and progress, with the ETA from the estimator the CLI uses
// (rupture/progress.hpp).
#include <string>
#include <vector>

#include "jobs/job_store.hpp"

namespace rupture::server {

/// Seconds from one of the store's UTC timestamps ("2026-01-02T03:04:05.678Z") to another; negative
/// when either does not parse.
double secondsBetween(const std::string& from, const std::string& to);

/// Adds stage, elapsed_s, eta_s (null when unknown) and updated to a run's document.
void addRunProgress(Json& doc, const RunRecord& run, const std::string& now);

/// Adds stage, elapsed_s, eta_s and updated (the latest change of the job or any of its runs) to a
/// job's status document; `runs` (may be null) lets the stage name what the running runs do and,
/// for a running job, weighs its progress by cost (jobProgress).
void addJobProgress(Json& doc, const JobRecord& job, const std::vector<RunRecord>* runs, const std::string& now);

/// A running job's fraction done with each run weighted by its cost in seconds: what a finished run
/// took, what a running one will have taken (elapsed + ETA), and for the others the mean of those
/// known (all equal while none is); a run dismissed before it started weighs nothing. In a sweep
/// over strain rates a run at 1e5 /s weighs a hundred times one at 1e7 /s, as its work does.
double jobProgress(const std::vector<RunRecord>& runs, const std::string& now);

}  // namespace rupture::server
