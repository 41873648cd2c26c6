#include "views/results.hpp"

#include <algorithm>
#include <limits>
#include <optional>
#include <sstream>

#include "common/files.hpp"
#include "common/public_message.hpp"
#include "io/hdf5_file.hpp"
#include "rupture/result_fields.hpp"
#include "studies/summary.hpp"

namespace rupture::server {
namespace fs = std::filesystem;
using rupture::io::Hdf5File;

namespace {

/// /summary: one dataset per column (run, status, swept values, result scalars), one row per run,
/// each with attributes unit, label and description; numbers as float64 (NaN where a run has no
/// value), anything else as UTF-8 text. The group's "columns" attribute lists them in order.
void writeSummaryTable(Hdf5File& out, const SummaryTable& table) {
  out.createGroup("/summary");
  Json columns = Json::array({"run", "status"});
  std::vector<std::int32_t> runIndex;
  std::vector<std::string> status;
  for (const SummaryRow& row : table.rows) {
    runIndex.push_back(row.run);
    status.emplace_back(toString(row.status));
  }
  auto describe = [&](const std::string& path, const std::string& label, const std::string& description) {
    out.setAttribute(path, "label", label);
    out.setAttribute(path, "description", description);
  };
  out.writeDataset("/summary/run", runIndex, {runIndex.size()}, "1");
  describe("/summary/run", "Run", "Index of the run in the job (group /run-<index> when it succeeded)");
  out.writeDataset("/summary/status", status, "");
  describe("/summary/status", "Status", "Final status of the run");
  std::vector<std::string> names = table.sweptPaths;
  names.insert(names.end(), table.inputPaths.begin(), table.inputPaths.end());
  names.insert(names.end(), table.scalarNames.begin(), table.scalarNames.end());
  for (const std::string& name : names) {
    const ColumnInfo info = table.columnInfo(name);
    bool numeric = true;
    for (const SummaryRow& row : table.rows) {
      const Json v = table.value(row, name);
      if (!v.is_null() && !v.is_number()) numeric = false;
    }
    const std::string path = "/summary/" + name;
    if (numeric) {
      std::vector<double> values;
      for (const SummaryRow& row : table.rows) {
        const Json v = table.value(row, name);
        values.push_back(v.is_number() ? v.get<double>() : std::numeric_limits<double>::quiet_NaN());
      }
      out.writeDataset(path, values, {values.size()}, info.unit);
    } else {
      std::vector<std::string> values;
      for (const SummaryRow& row : table.rows) {
        const Json v = table.value(row, name);
        values.push_back(v.is_string() ? v.get<std::string>() : v.is_null() ? "" : v.dump());
      }
      out.writeDataset(path, values, info.unit);
    }
    describe(path, info.label, info.description);
    columns.push_back(name);
  }
  out.setAttribute("/summary", "columns", columns.dump());
  out.setAttribute("/summary", "description",
                   "One row per run of the job: its swept values, sample seed and result scalars, one dataset per column "
                   "(listed in order in \"columns\"), each with its SI unit in the attribute \"unit\"");
}

}  // namespace

namespace {

/// Merged files up to this size are built in memory and written when closed: a disk that fills up
/// meanwhile fails that write, never HDF5 half way through an object copy (HDF5 1.10.8 crashed
/// there, inside H5Ocopy). Larger ones are built in place after the space check.
constexpr std::uintmax_t kInMemoryMergeBytes = 256u << 20;

ApiError noRoomForMerge(std::uintmax_t needed, std::optional<std::uintmax_t> available) {
  return ApiError(507, problem::kInsufficientStorage, "Insufficient Storage",
                  "the server's data disk has no room for this job's merged results file (it needs about " +
                      formatBytes(static_cast<double>(needed)) + ", " +
                      (available ? formatBytes(static_cast<double>(*available)) : std::string("an unknown amount")) +
                      " is free); retry once space is freed, or download the runs one by one (/jobs/{id}/runs/{k}/results)",
                  "", Json{{"needed_bytes", needed}, {"available_bytes", available ? Json(*available) : Json()}, {"retry_after_s", 60}});
}

void writeMergedFile(Hdf5File& out, const JobRecord& job, const std::vector<RunRecord>& runs, const fs::path& dataDir) {
  const SummaryTable table = buildSummary(job, runs);
  writeSummaryTable(out, table);
  for (const RunRecord& run : runs) {
    if (run.status != Status::Successful || run.resultPath.empty()) continue;
    out.copyFileInto((dataDir / run.resultPath).string(), "/run-" + std::to_string(run.key.index));
  }
  out.setAttribute("/", "job_id", std::int64_t{job.id});
  out.setAttribute("/", "process_id", job.processId);
  out.setAttribute("/", "name", job.name);
  out.setAttribute("/", "status", std::string(toString(job.status)));
  out.setAttribute("/", "sweep_mode", job.sweepMode);
  out.setAttribute("/", "swept_paths", job.sweptPaths.dump());
  out.setAttribute("/", "inputs", job.inputs.dump());
  out.setAttribute("/", "created", job.created);
  out.setAttribute("/", "runs_total", std::int64_t{job.runsTotal});
  if (job.study.is_object()) out.setAttribute("/", "study", job.study.dump());  // replicates, refinement record
  if (job.provenance.is_object()) out.setAttribute("/", "provenance", job.provenance.dump());  // each run's is in its group
  std::int64_t included = 0;
  for (const RunRecord& run : runs) {
    if (run.status != Status::Successful || run.resultPath.empty()) continue;
    const std::string group = "/run-" + std::to_string(run.key.index);
    out.setAttribute(group, "sweep.run_index", std::int64_t{run.key.index});
    out.setAttribute(group, "sweep.values", run.swept.dump());
    out.setAttribute(group, "sweep.spec", runSpec(job, run).dump());
    out.setAttribute(group, "sweep.summary", run.summary.dump());
    if (job.study.is_object() && job.study.contains("replicates"))
      out.setAttribute(group, "sweep.replicate", std::int64_t{run.replicate});
    for (std::size_t i = 0; i < job.sweptPaths.size() && i < run.swept.size(); ++i) {
      const std::string name = "sweep." + job.sweptPaths[i].get<std::string>();
      const Json& v = run.swept[i];
      if (v.is_number_integer()) out.setAttribute(group, name, v.get<std::int64_t>());
      else if (v.is_number()) out.setAttribute(group, name, v.get<double>());
      else if (v.is_string()) out.setAttribute(group, name, v.get<std::string>());
      else out.setAttribute(group, name, v.dump());
      const std::string unit = table.columnInfo(job.sweptPaths[i].get<std::string>()).unit;
      if (!unit.empty()) out.setAttribute(group, name + "_unit", unit);
    }
    ++included;
  }
  out.setAttribute("/", "runs_included", included);
}

}  // namespace

fs::path mergedResults(const JobRecord& job, const std::vector<RunRecord>& runs, const fs::path& dataDir) {
  // One builder at a time: HDF5 serialises calls anyway, and two requests for the same job must not
  // both write the file.
  static std::mutex mutex;
  std::lock_guard lock(mutex);
  const fs::path dir = dataDir / "jobs" / std::to_string(job.id);
  const fs::path target = dir / "results.h5";
  if (regularFileSize(target)) return target;
  fs::create_directories(dir);
  const fs::path part = dir / "results.h5.part";
  std::error_code ec;
  fs::remove(part, ec);
  // The merged file holds copies of the run files and a table: check the room before writing.
  std::uintmax_t inputs = 0;
  for (const RunRecord& run : runs) {
    if (run.status != Status::Successful || run.resultPath.empty()) continue;
    inputs += regularFileSize(dataDir / run.resultPath).value_or(0);
  }
  const std::uintmax_t needed = inputs + inputs / 16 + (std::uintmax_t{1} << 20);
  const std::optional<std::uintmax_t> available = availableBytes(dir);
  if (available && *available < needed) throw noRoomForMerge(needed, available);
  try {
    {
      Hdf5File out = inputs <= kInMemoryMergeBytes ? Hdf5File::createBuffered(part.string()) : Hdf5File::create(part.string());
      writeMergedFile(out, job, runs, dataDir);
      out.close();
    }
    renameDurable(part, target);
  } catch (const ApiError&) {
    fs::remove(part, ec);
    throw;
  } catch (const std::exception& e) {
    fs::remove(part, ec);
    fs::remove(target, ec);
    const std::optional<std::uintmax_t> now = availableBytes(dir);
    if (isDiskFull(e.what()) || (now && *now < needed)) throw noRoomForMerge(needed, now);
    throw ApiError(503, problem::kUnavailable, "Service Unavailable",
                   "the job's merged results file could not be built (" + publicMessage(e.what()) +
                       "); retry later, or download the runs one by one (/jobs/{id}/runs/{k}/results)",
                   "", Json{{"retry_after_s", 30}});
  }
  return target;
}

std::vector<std::string> seriesNames(const fs::path& runFile) {
  Hdf5File file = Hdf5File::openReadOnly(runFile.string());
  if (!file.exists("/series")) return {};
  return file.listGroup("/series");
}

SeriesTable readSeries(const fs::path& runFile, const std::vector<std::string>& names) {
  Hdf5File file = Hdf5File::openReadOnly(runFile.string());
  std::vector<std::string> available = file.exists("/series") ? file.listGroup("/series") : std::vector<std::string>{};
  SeriesTable table;
  table.names = names.empty() ? available : names;
  for (const std::string& name : table.names) {
    if (std::find(available.begin(), available.end(), name) == available.end()) {
      Json allowed = Json::array();
      for (const auto& a : available) allowed.push_back(a);
      throw ApiError(400, problem::kInvalidParameter, "Invalid parameter",
                     "no series '" + name + "' in this run; available: " + allowed.dump(), "names",
                     Json{{"in", "query"}, {"value", name}, {"allowed", allowed}});
    }
    const std::string path = "/series/" + name;
    table.columns.push_back(file.readDatasetDouble(path));
    table.units.push_back(file.hasAttribute(path, "unit") ? file.readAttributeString(path, "unit") : "");
  }
  return table;
}

std::string seriesCsv(const SeriesTable& table) {
  std::ostringstream out;
  std::size_t rows = 0;
  for (std::size_t i = 0; i < table.names.size(); ++i) {
    out << (i ? "," : "") << csvTextCell(rupture::nameWithUnit(table.names[i], table.units[i]));
    rows = std::max(rows, table.columns[i].size());
  }
  out << "\r\n";
  for (std::size_t r = 0; r < rows; ++r) {
    for (std::size_t i = 0; i < table.columns.size(); ++i) {
      if (i) out << ',';
      if (r < table.columns[i].size()) out << formatNumber(table.columns[i][r]);
    }
    out << "\r\n";
  }
  return out.str();
}

}  // namespace rupture::server
