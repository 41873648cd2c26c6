#pragma once
// Several jobs side by side (GET /summary?jobs=3,5,7 and GET /plot?jobs=3,5,7): the rows of each
// job's summary (or, aggregated, its sweep points) with a leading "job" column, the columns being
// the union of the jobs' columns in the order they first appear. Unfinished jobs are included as
// they stand: their unfinished runs are rows with status accepted or running and no scalars.
#include <string>
#include <vector>

#include "studies/summary.hpp"

namespace rupture::server {

/// At most this many jobs in one comparison.
inline constexpr std::size_t kMaxComparedJobs = 10;

struct ComparedJob {
  JobRecord job;
  SummaryTable table;
};

/// The legend label of a job: "<id>: <name>", or "job <id>" without a name.
std::string jobLabel(const JobRecord& job);

/// {"jobs": [{jobID, name, label, processID, status, runs_total, runs_successful}], "aggregate",
///  "columns": [{name, kind, unit, label, description}], "rows": [{job, ...}],
///  "differing_inputs": differingInputs(jobs)}
Json comparisonJson(const std::vector<ComparedJob>& jobs, bool aggregate);

/// The inputs that differ between the jobs, by dotted path: [{path, values: {jobID: value}}], a
/// value null where a job leaves it to the default, {"swept": [values]} where a job sweeps it, the
/// path "replicates" for the replicate plan and "scenario" when the jobs run different scenarios.
/// Empty for one job.
Json differingInputs(const std::vector<ComparedJob>& jobs);

/// The same rows as CSV: job,job_name, then the union of the columns (statistics as
/// <scalar>.mean, ... when aggregated).
std::string comparisonCsv(const std::vector<ComparedJob>& jobs, bool aggregate);

/// A table for the plot: swept paths "job" (the label) and the union of the jobs' swept paths, one
/// row per sweep point at its mean, with the derived columns of meansTable (ciHalfWidthColumn(y)
/// is the error-bar column).
SummaryTable comparisonPlotTable(const std::vector<ComparedJob>& jobs);

}  // namespace rupture::server
