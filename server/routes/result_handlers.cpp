// The result files: the job's merged HDF5 file and RO-Crate, a run's file, its series, its
// ParaView sidecar and bundle.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>

#include <httplib.h>

#include "common/public_message.hpp"
#include "io/xdmf_writer.hpp"
#include "routes/answers.hpp"
#include "routes/handlers.hpp"
#include "routes/request_params.hpp"
#include "rupture/result_fields.hpp"
#include "rupture/run.hpp"
#include "views/results.hpp"
#include "views/ro_crate.hpp"
#include "views/tar_archive.hpp"
#include "views/zip_archive.hpp"

namespace rupture::server {
namespace fs = std::filesystem;
using httplib::Request;
using httplib::Response;

namespace {

// -- ParaView: the sidecar names the HDF5 file by its download name, so the two work side by side.

std::string runFileStem(const JobRecord& job, const RunRecord& run) {
  return "rupture-job-" + std::to_string(job.id) + "-run-" + std::to_string(run.key.index);
}

std::string runSidecar(const ServerContext& ctx, const JobRecord& job, const RunRecord& run) {
  const std::string file = (ctx.resultsDir / run.resultPath).string();
  if (rupture::io::runGroupsWithSnapshots(file) != std::vector<std::string>{""}) {
    throw ApiError(404, problem::kNoResults, "No results",
                   "run " + std::to_string(run.key.index) + " of job " + std::to_string(job.id) +
                       " has no snapshots for ParaView (" + job.processId + " writes none)");
  }
  return rupture::io::xdmfDocument(file, runFileStem(job, run) + ".h5");
}

/// A job's whole downloads (the merged file, the crate) wait for its last run, and for the last
/// round of a pending refinement, which adds runs.
void requireEveryRunFinished(const JobRecord& job, const std::string& what) {
  const bool refining = job.study.is_object() && job.study.contains("refinement") &&
                        job.study["refinement"].value("state", "") == "pending";
  if (job.runsAccepted + job.runsRunning > 0 || refining) {
    throw ApiError(409, problem::kResultNotReady, "Result not ready",
                   "job " + std::to_string(job.id) + " is " + toString(job.status) + " (" +
                       std::to_string(job.runsTotal - job.runsAccepted - job.runsRunning) + " of " +
                       std::to_string(job.runsTotal) +
                       " runs finished" + (refining ? ", refinement pending" : "") +
                       "); its " + what + " is ready when every run has finished",
                   "", Json{{"jobStatus", toString(job.status)}});
  }
}

/// Streams an archive (TarArchive, ZipArchive) as the response body, 64 KiB at a time.
template <class Archive>
void sendArchive(Response& res, std::shared_ptr<Archive> archive, const std::string& type, const std::string& filename) {
  res.set_header("Content-Disposition", "attachment; filename=\"" + filename + "\"");
  res.set_content_provider(static_cast<std::size_t>(archive->size()), type,
                           [archive](std::size_t offset, std::size_t want, httplib::DataSink& sink) {
                             std::vector<char> buffer(std::min<std::size_t>(want, 64 * 1024));
                             const std::size_t n = archive->read(offset, buffer.data(), buffer.size());
                             if (n == 0) return false;
                             return sink.write(buffer.data(), n);
                           });
}

}  // namespace

namespace handlers {

void getJobResults(ServerContext& ctx, const Request& req, Response& res) {
  const auto [job, runs] = loadJobWithRuns(ctx, req);
  requireEveryRunFinished(job, "results file");
  if (job.runsSuccessful == 0) {
    throw ApiError(404, problem::kNoResults, "No results",
                   "job " + std::to_string(job.id) + " has no successful run (" + publicMessage(job.message) + ")");
  }
  const fs::path path = mergedResults(job, runs, ctx.resultsDir);
  sendFile(req, res, path, "rupture-job-" + std::to_string(job.id) + ".h5");
}

void getJobCrate(ServerContext& ctx, const Request& req, Response& res) {
  const auto [job, runs] = loadJobWithRuns(ctx, req);
  requireEveryRunFinished(job, "RO-Crate");
  std::shared_ptr<ZipArchive> crate;
  try {
    crate = jobCrate(job, runs, ctx.resultsDir);
  } catch (const std::length_error&) {
    throw ApiError(409, problem::kCrateTooLarge, "Crate too large",
                   "job " + std::to_string(job.id) + "'s RO-Crate would be 4 GiB or larger (a ZIP without ZIP64): "
                   "download its runs' files one by one from /jobs/" + std::to_string(job.id) + "/runs/{k}/results");
  }
  sendArchive(res, crate, "application/zip", "rupture-job-" + std::to_string(job.id) + "-crate.zip");
}

void getRunResults(ServerContext& ctx, const Request& req, Response& res) {
  const JobRecord job = loadJob(ctx, req);
  const RunRecord run = finishedRun(ctx, req, job);
  sendFile(req, res, ctx.resultsDir / run.resultPath,
           "rupture-job-" + std::to_string(job.id) + "-run-" + std::to_string(run.key.index) + ".h5");
}

void getRunXdmf(ServerContext& ctx, const Request& req, Response& res) {
  const JobRecord job = loadJob(ctx, req);
  const RunRecord run = finishedRun(ctx, req, job);
  const std::string xml = runSidecar(ctx, job, run);
  // .xdmf2: ParaView 5.11 opens *.xdmf with its broken Xdmf3 readers (docs/paraview.md).
  res.set_header("Content-Disposition", "attachment; filename=\"" + runFileStem(job, run) + ".xdmf2\"");
  res.set_content(xml, "application/xml");
}

void getRunBundle(ServerContext& ctx, const Request& req, Response& res) {
  const JobRecord job = loadJob(ctx, req);
  const RunRecord run = finishedRun(ctx, req, job);
  const std::string stem = runFileStem(job, run);
  const fs::path h5 = ctx.resultsDir / run.resultPath;
  const std::string xml = runSidecar(ctx, job, run);
  std::error_code ec;
  const auto written = fs::last_write_time(h5, ec);
  const std::int64_t mtime =
      ec ? 0
         : std::chrono::duration_cast<std::chrono::seconds>(
               std::chrono::file_clock::to_sys(written).time_since_epoch()).count();
  auto tar = std::make_shared<TarArchive>();
  tar->addFile(stem + "/" + stem + ".h5", h5, mtime);
  tar->addText(stem + "/" + stem + ".xdmf2", xml, mtime);
  sendArchive(res, tar, "application/x-tar", stem + ".tar");
}

void getRunSeries(ServerContext& ctx, const Request& req, Response& res) {
  const std::string format = choiceParam(req, "format", {"json", "csv", "svg", "png", "pdf"}).value_or("json");
  if (format == "svg" || format == "png" || format == "pdf") return getRunSeriesPlot(ctx, req, res);
  const JobRecord job = loadJob(ctx, req);
  const RunRecord run = finishedRun(ctx, req, job);
  const bool csv = wantsCsv(req);
  SeriesTable table = readSeries(ctx.resultsDir / run.resultPath, paramList(req, "names"));
  if (csv) {
    res.set_content(seriesCsv(table), kCsvType);
    return;
  }
  Json doc = Json::object();
  doc["jobID"] = std::to_string(job.id);
  doc["run"] = run.key.index;
  doc["names"] = table.names;
  Json units = Json::object(), series = Json::object();
  std::size_t length = 0;
  for (std::size_t i = 0; i < table.names.size(); ++i) {
    units[table.names[i]] = table.units[i];
    Json values = Json::array();
    for (double v : table.columns[i]) values.push_back(std::isfinite(v) ? Json(v) : Json());
    series[table.names[i]] = std::move(values);
    length = std::max(length, table.columns[i].size());
  }
  doc["units"] = units;
  Json labels = Json::object();
  const rupture::ScenarioInfo* scenario = rupture::findScenario(job.processId);
  for (const std::string& name : table.names) {
    const rupture::ResultField* f = scenario ? rupture::findResultField(scenario->series, name) : nullptr;
    labels[name] = f ? f->label : name;
  }
  doc["labels"] = labels;
  doc["length"] = length;
  doc["series"] = series;
  sendJson(res, doc);
}

}  // namespace handlers

}  // namespace rupture::server
