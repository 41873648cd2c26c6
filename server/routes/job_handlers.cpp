// GET /jobs, /jobs/{id}, /jobs/{id}/runs[/{k}], DELETE /jobs/{id}, POST /jobs/{id}/retry.
#include <algorithm>
#include <limits>

#include <httplib.h>

#include "common/log.hpp"
#include "io/hdf5_file.hpp"
#include "render/snapshot_field.hpp"
#include "common/public_message.hpp"
#include "routes/answers.hpp"
#include "routes/documents.hpp"
#include "routes/handlers.hpp"
#include "routes/request_params.hpp"
#include "rupture/run.hpp"
#include "studies/replicate_statistics.hpp"
#include "studies/summary.hpp"
#include "views/html_views.hpp"
#include "views/run_page.hpp"

namespace rupture::server {
namespace fs = std::filesystem;
using httplib::Request;
using httplib::Response;

namespace handlers {

namespace {

/// GET /jobs' query: ?status= (repeatable, comma lists), ?processID=, ?name=, ?limit=, ?offset=.
JobFilter jobFilterOf(const Request& req) {
  JobFilter filter;
  for (const std::string& s : paramList(req, "status")) {
    auto status = parseStatus(s);
    if (!status) {
      throw ApiError(400, problem::kInvalidParameter, "Invalid parameter",
                     "unknown status '" + s + "'", "status",
                     Json{{"in", "query"},
                          {"value", s},
                          {"allowed", Json::array({"accepted", "running", "successful", "failed", "dismissed"})}});
    }
    filter.statuses.push_back(*status);
  }
  for (const char* key : {"processID", "process_id"}) {
    if (req.has_param(key)) filter.processId = req.get_param_value(key);
  }
  if (req.has_param("name")) filter.nameContains = req.get_param_value("name");
  filter.limit = static_cast<int>(intParam(req, "limit", 50, 1, 1000));
  filter.offset = intParam(req, "offset", 0, 0, std::numeric_limits<std::int64_t>::max() / 2);
  return filter;
}

/// The self, next and prev links of a page of `returned` jobs out of `total` matching `filter`.
Json jobPageLinks(const JobFilter& filter, std::size_t returned, std::int64_t total) {
  std::string query;
  if (!filter.statuses.empty()) {
    query += "&status=";
    for (std::size_t i = 0; i < filter.statuses.size(); ++i) {
      if (i > 0) query += ',';
      query += toString(filter.statuses[i]);
    }
  }
  if (!filter.processId.empty()) query += "&processID=" + httplib::detail::encode_query_param(filter.processId);
  if (!filter.nameContains.empty()) query += "&name=" + httplib::detail::encode_query_param(filter.nameContains);
  auto page = [&](std::int64_t offset) {
    return "/jobs?limit=" + std::to_string(filter.limit) + "&offset=" + std::to_string(offset) + query;
  };
  Json links = Json::array({link(page(filter.offset), "self")});
  if (filter.offset + static_cast<std::int64_t>(returned) < total) {
    links.push_back(link(page(filter.offset + filter.limit), "next"));
  }
  if (filter.offset > 0) links.push_back(link(page(std::max<std::int64_t>(0, filter.offset - filter.limit)), "prev"));
  return links;
}

}  // namespace

void getJobs(ServerContext& ctx, const Request& req, Response& res) {
  const JobFilter filter = jobFilterOf(req);
  std::int64_t total = 0;
  auto list = ctx.store->listJobs(filter, total);
  Json jobs = Json::array();
  for (const JobRecord& j : list) jobs.push_back(statusInfo(j, nullptr));
  Json doc = Json::object();
  doc["jobs"] = jobs;
  doc["numberMatched"] = total;
  doc["numberReturned"] = jobs.size();
  doc["links"] = jobPageLinks(filter, list.size(), total);
  if (wantsHtml(req)) {
    Json current = {{"name", filter.nameContains}, {"processID", filter.processId},
                    {"status", filter.statuses.size() == 1 ? toString(filter.statuses[0]) : ""}};
    Json scenarios = Json::array();
    for (const auto& s : rupture::listScenarios()) scenarios.push_back(s.name);
    return sendHtml(res, jobsHtml(doc, current, scenarios));
  }
  sendJson(res, doc);
}

namespace {

/// The label and unit of each swept path, from the scenario's schema: {path: {label, unit}}.
Json sweptFields(const JobRecord& job) {
  Json swept = Json::object();
  if (!rupture::findScenario(job.processId)) return swept;
  const Json schema = rupture::scenarioSchema(job.processId);
  for (const auto& path : job.sweptPaths)
    swept[path.get<std::string>()] = {{"label", rupture::specFieldLabel(schema, path.get<std::string>())},
                                      {"unit", rupture::specFieldUnit(schema, path.get<std::string>())}};
  return swept;
}

/// Marks "picture": true on the status document's runs whose file holds snapshots, so the job page
/// shows a thumbnail of each (the first kMaxThumbnails: a page of a thousand runs stays light).
void markRunsWithPictures(ServerContext& ctx, const std::vector<RunRecord>& runs, Json& status) {
  constexpr int kMaxThumbnails = 60;
  int marked = 0;
  for (const RunRecord& run : runs) {
    if (run.status != Status::Successful || marked >= kMaxThumbnails) continue;
    try {
      const io::Hdf5File file = io::Hdf5File::openReadOnly((ctx.resultsDir / run.resultPath).string());
      if (render::listSnapshots(file, "").empty()) continue;
    } catch (const std::exception&) {
      continue;  // no picture for a file that cannot be read; its download says why
    }
    for (auto& r : status["runs"])
      if (r.value("index", -1) == run.key.index) r["picture"] = true;
    ++marked;
  }
}

}  // namespace

void getJob(ServerContext& ctx, const Request& req, Response& res) {
  auto [job, runs] = loadJobWithRuns(ctx, req);
  if (wantsHtml(req)) {
    Json summary, points;  // once every run has ended
    std::string plot;
    if (job.runsAccepted + job.runsRunning == 0 && job.runsSuccessful > 0) {
      const SummaryTable table = buildSummary(job, runs);
      summary = summaryJson(table);
      if (table.replicated) points = aggregateJson(table, aggregateReplicates(table));
      if (const std::string y = table.headlineQuantity(); !table.sweptPaths.empty() && !y.empty()) {
        plot = "/jobs/" + std::to_string(job.id) + "/summary.svg?x=" +
               httplib::detail::encode_query_param(table.sweptPaths.front()) +
               "&y=" + httplib::detail::encode_query_param(y);
      }
    }
    Json status = statusInfo(job, &runs);
    markRunsWithPictures(ctx, runs, status);
    status["swept_fields"] = sweptFields(job);  // for the page's headers; not in the JSON answer
    return sendHtml(res, jobHtml(status, summary, plot, points));
  }
  sendJson(res, statusInfo(job, &runs));
}

void deleteJob(ServerContext& ctx, const Request& req, Response& res) {
  requireToken(ctx, req);
  const std::int64_t id = jobIdFrom(req);
  auto job = ctx.scheduler->dismiss(id);
  if (!job) throw noSuchJob(std::to_string(id));
  logLine("job " + std::to_string(id) + " dismiss requested; status " + toString(job->status));
  auto [record, runs] = ctx.store->jobWithRuns(id).value_or(JobWithRuns{*job, {}});
  sendJson(res, statusInfo(record, &runs));
}

void postRetry(ServerContext& ctx, const Request& req, Response& res) {
  requireToken(ctx, req);
  const std::int64_t id = jobIdFrom(req);
  if (!ctx.store->job(id)) throw noSuchJob(std::to_string(id));
  const std::vector<int> indices = ctx.store->retryFailedRuns(id);
  if (indices.empty()) {
    const JobRecord job = *ctx.store->job(id);
    throw ApiError(409, problem::kNothingToRetry, "Nothing to retry",
                   "job " + std::to_string(id) + " has no failed run to retry (" + toString(job.status) + ": " +
                       publicMessage(job.message) + ")",
                   "", Json{{"jobStatus", toString(job.status)}});
  }
  ctx.scheduler->resubmit(id, indices);
  logLine("job " + std::to_string(id) + ": " + std::to_string(indices.size()) + " failed run(s) re-submitted");
  auto [job, runs] = ctx.store->jobWithRuns(id).value();
  Json doc = statusInfo(job, &runs);
  doc["retried_runs"] = indices;
  sendJson(res, doc);
}

void postResume(ServerContext& ctx, const Request& req, Response& res) {
  requireToken(ctx, req);
  const std::int64_t id = jobIdFrom(req);
  if (!ctx.store->job(id)) throw noSuchJob(std::to_string(id));
  const std::vector<int> indices = ctx.store->resumeUnfinishedRuns(id);
  if (indices.empty()) {
    const JobRecord job = *ctx.store->job(id);
    const bool ended = job.status == Status::Failed || job.status == Status::Dismissed;
    const std::string why = !ended            ? "it has not ended; cancel it first, or let it finish"
                            : job.runsRunning ? "a cancelled run is still stopping; resume again in a few seconds"
                                              : "every run is successful";
    throw ApiError(409, problem::kNothingToRetry, "Nothing to resume",
                   "job " + std::to_string(id) + " cannot be resumed (" + toString(job.status) + "): " + why, "",
                   Json{{"jobStatus", toString(job.status)}});
  }
  ctx.scheduler->resubmit(id, indices);
  logLine("job " + std::to_string(id) + ": resumed, " + std::to_string(indices.size()) + " unfinished run(s) re-queued");
  auto [job, runs] = ctx.store->jobWithRuns(id).value();
  Json doc = statusInfo(job, &runs);
  doc["resumed_runs"] = indices;
  sendJson(res, doc);
}

namespace {

/// What the run page shows: the run, its declared summary fields, the pictures its file can give,
/// and the picture the query chose (each choice checked: a 400 names a bad one).
Json runPageData(ServerContext& ctx, const Request& req, const JobRecord& job, const RunRecord& run, Json doc) {
  Json data;
  data["job"] = {{"jobID", std::to_string(job.id)}, {"processID", job.processId}};
  if (!job.name.empty()) data["job"]["name"] = job.name;
  const rupture::ScenarioInfo* scenario = rupture::findScenario(job.processId);
  Json fields = Json::array();
  if (scenario) {
    const int dimension = rupture::specDimension(rupture::scenarioSchema(scenario->name), run.spec);
    for (const rupture::ResultField& f : scenario->summary)
      fields.push_back({{"name", f.name}, {"label", f.label}, {"unit", f.unitFor(dimension)}, {"description", f.description}});
  }
  data["summary_fields"] = fields;
  data["swept_fields"] = sweptFields(job);
  Json chosen = Json::object();
  if (run.status == Status::Successful) {
    data["pictures"] = runPictures(ctx.resultsDir / run.resultPath, scenario);
    data["provenance"] = runProvenance(ctx.resultsDir / run.resultPath);
    const Json& available = data["pictures"]["fields"];
    if (req.has_param("field")) {
      const std::string field = req.get_param_value("field");
      if (std::find(available.begin(), available.end(), field) == available.end())
        throw ApiError(400, problem::kInvalidParameter, "Invalid parameter",
                       "field '" + field.substr(0, 64) + "' is not recorded in this run; allowed: " + available.dump(),
                       "field", Json{{"in", "query"}});
      chosen["field"] = field;
    }
    if (req.has_param("snapshot")) {
      const std::int64_t count = static_cast<std::int64_t>(data["pictures"]["snapshots"].size());
      chosen["snapshot"] = intParam(req, "snapshot", 0, 0, std::max<std::int64_t>(count - 1, 0));
    }
    if (auto view = choiceParam(req, "view", {"", "xy", "xz", "yz"})) chosen["view"] = *view;
    if (auto bonds = choiceParam(req, "bonds", {"", "broken", "all", "none"})) chosen["bonds"] = *bonds;
    // The colour range (empty fields of the page's form: the default) and its default's source.
    for (const char* bound : {"min", "max"})
      if (req.has_param(bound) && !req.get_param_value(bound).empty())
        if (auto value = numberParam(req, bound)) chosen[bound] = *value;
    if (auto range = choiceParam(req, "range", {"", "run", "snapshot"}); range && !range->empty()) chosen["range"] = *range;
    if (chosen.contains("min") && chosen.contains("max") && !(chosen["max"].get<double>() > chosen["min"].get<double>()))
      throw ApiError(400, problem::kInvalidParameter, "Invalid parameter", "max must be greater than min", "max",
                     Json{{"in", "query"}});
  }
  data["chosen"] = chosen;
  data["run"] = std::move(doc);
  return data;
}

}  // namespace

void getRuns(ServerContext& ctx, const Request& req, Response& res) {
  const JobRecord job = loadJob(ctx, req);
  Json list = Json::array();
  for (const RunRecord& r : ctx.store->runs(job.id)) list.push_back(runDocument(job, r));
  sendJson(res, Json{{"jobID", std::to_string(job.id)}, {"runs", list}});
}

void getRun(ServerContext& ctx, const Request& req, Response& res) {
  const JobRecord job = loadJob(ctx, req);
  const RunRecord run = loadRun(ctx, req, job);
  Json doc = runDocument(job, run);
  doc["spec"] = run.spec;
  if (wantsHtml(req)) return sendHtml(res, runHtml(runPageData(ctx, req, job, run, std::move(doc))));
  sendJson(res, doc);
}

}  // namespace handlers

}  // namespace rupture::server
