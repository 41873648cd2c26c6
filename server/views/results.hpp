#pragma once
// Run and job result files: the merged, self-contained HDF5 file of a job (one group per run, deep
// copies, no external links) and the time series inside a run file (/series/<name>).
#include <filesystem>
#include <mutex>
#include <string>
#include <vector>

#include "jobs/job_store.hpp"

namespace rupture::server {

/// Builds <data-dir>/jobs/<id>/results.h5 from the job's successful runs if it is not there yet,
/// and returns its path. Call only for a job whose runs have all finished: the file is then final
/// and is built once (written as .part, then renamed). Group per run: /run-<k>, holding a copy of
/// every object of run-<k>.h5, the run file's root attributes, and attributes sweep.run_index,
/// sweep.values (JSON) and sweep.<path> for each swept value (with sweep.<path>_unit when it has
/// one). Root attributes describe the job. /summary holds the job's summary table: one dataset per
/// column (run, status, swept values, result scalars), one row per run, each with "unit", "label"
/// and "description" attributes.
std::filesystem::path mergedResults(const JobRecord& job, const std::vector<RunRecord>& runs,
                                    const std::filesystem::path& dataDir);

struct SeriesTable {
  std::vector<std::string> names;
  std::vector<std::string> units;                ///< "unit" attribute of each dataset, "" if none
  std::vector<std::vector<double>> columns;
};

/// Names of the 1-D datasets in /series of a run file, sorted.
std::vector<std::string> seriesNames(const std::filesystem::path& runFile);

/// Reads the named series (all of them when `names` is empty). Throws ApiError(400) naming an
/// unknown series and listing the available ones.
SeriesTable readSeries(const std::filesystem::path& runFile, const std::vector<std::string>& names);

/// CSV with one column per series (RFC 4180, header line of "name [unit]", as the summary CSV).
std::string seriesCsv(const SeriesTable& table);

}  // namespace rupture::server
