// GET /jobs, /jobs/{id}, /jobs/{id}/runs[/{k}], DELETE /jobs/{id}, POST /jobs/{id}/retry.
#include <algorithm>
#include <limits>

#include <httplib.h>

#include "common/log.hpp"
#include "common/public_message.hpp"
#include "routes/answers.hpp"
#include "routes/documents.hpp"
#include "routes/handlers.hpp"
#include "routes/request_params.hpp"
#include "rupture/run.hpp"
#include "studies/summary.hpp"
#include "views/html_views.hpp"

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

void getJob(ServerContext& ctx, const Request& req, Response& res) {
  const JobRecord job = loadJob(ctx, req);
  auto runs = ctx.store->runs(job.id);
  if (wantsHtml(req)) {
    Json summary;  // once every run has ended
    std::string plot;
    if (job.runsAccepted + job.runsRunning == 0 && job.runsSuccessful > 0) {
      const SummaryTable table = buildSummary(job, runs);
      summary = summaryJson(table);
      if (const std::string y = table.headlineQuantity(); !table.sweptPaths.empty() && !y.empty()) {
        plot = "/jobs/" + std::to_string(job.id) + "/summary.svg?x=" +
               httplib::detail::encode_query_param(table.sweptPaths.front()) +
               "&y=" + httplib::detail::encode_query_param(y);
      }
    }
    return sendHtml(res, jobHtml(statusInfo(job, &runs), summary, plot));
  }
  sendJson(res, statusInfo(job, &runs));
}

void deleteJob(ServerContext& ctx, const Request& req, Response& res) {
  requireToken(ctx, req);
  const std::int64_t id = jobIdFrom(req);
  auto job = ctx.scheduler->dismiss(id);
  if (!job) throw noSuchJob(std::to_string(id));
  logLine("job " + std::to_string(id) + " dismiss requested; status " + toString(job->status));
  auto runs = ctx.store->runs(id);
  sendJson(res, statusInfo(*job, &runs));
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
  auto job = ctx.store->job(id);
  auto runs = ctx.store->runs(id);
  Json doc = statusInfo(*job, &runs);
  doc["retried_runs"] = indices;
  sendJson(res, doc);
}

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
  sendJson(res, doc);
}

}  // namespace handlers

}  // namespace rupture::server
