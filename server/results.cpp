#include "results.hpp"

#include <algorithm>
#include <sstream>

#include "files.hpp"
#include "io/hdf5_file.hpp"
#include "summary.hpp"

namespace rupture::server {
namespace fs = std::filesystem;
using rupture::io::Hdf5File;

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
  {
    Hdf5File out = Hdf5File::create(part.string());
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
    std::int64_t included = 0;
    for (const RunRecord& run : runs) {
      if (run.status != Status::Successful || run.resultPath.empty()) continue;
      const std::string group = "/run-" + std::to_string(run.key.index);
      out.setAttribute(group, "sweep.run_index", std::int64_t{run.key.index});
      out.setAttribute(group, "sweep.values", run.swept.dump());
      out.setAttribute(group, "sweep.spec", run.spec.dump());
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
      }
      ++included;
    }
    out.setAttribute("/", "runs_included", included);
    out.close();
  }
  renameDurable(part, target);
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
    out << (i ? "," : "") << csvTextCell(table.names[i]);
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
