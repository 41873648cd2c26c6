#include "routes/request_params.hpp"
#include <algorithm>

#include <charconv>
#include <cmath>

#include "common/public_message.hpp"
#include "http/request_guard.hpp"
#include "rupture/run.hpp"

namespace rupture::server {
namespace fs = std::filesystem;
using httplib::Request;
using httplib::Response;

/// Strict non-negative integer parse (digits only, no sign, no spaces, fits in int64).
std::optional<std::int64_t> parseIndex(const std::string& text) {
  if (text.empty() || text.size() > 18) return std::nullopt;
  std::int64_t value = 0;
  auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || ptr != text.data() + text.size() || value < 0) return std::nullopt;
  return value;
}

ApiError noSuchJob(const std::string& id) {
  return ApiError(404, problem::kNoSuchJob, "No such job",
                  "no job '" + id + "' (job ids are positive integers; GET /jobs lists them)", "jobID",
                  Json{{"in", "path"}});
}

std::int64_t jobIdFrom(const Request& req) {
  const std::string text = req.matches[1];
  auto id = parseIndex(text);
  if (!id || *id < 1) throw noSuchJob(text);
  return *id;
}

int runIndexFrom(const Request& req, const JobRecord& job) {
  const std::string text = req.matches[2];
  auto k = parseIndex(text);
  if (!k || *k >= job.runsTotal) {
    throw ApiError(404, problem::kNotFound, "No such run",
                   "job " + std::to_string(job.id) + " has no run '" + text + "' (runs are numbered 0 to " +
                       std::to_string(job.runsTotal - 1) + ")",
                   "run", Json{{"in", "path"}});
  }
  return static_cast<int>(*k);
}

std::optional<std::string> choiceParam(const Request& req, const char* name,
                                       std::initializer_list<const char*> allowed) {
  if (!req.has_param(name)) return std::nullopt;
  std::string value = req.get_param_value(name);
  std::string listed;
  Json names = Json::array();
  for (const char* a : allowed) {
    if (value == a) return value;
    listed += (listed.empty() ? "'" : names.size() + 1 == allowed.size() ? " or '" : ", '") + std::string(a) + "'";
    names.push_back(a);
  }
  throw ApiError(400, problem::kInvalidParameter, "Invalid parameter",
                 std::string(name) + " must be " + listed + ", got '" + value + "'", name,
                 Json{{"in", "query"}, {"value", value}, {"allowed", names}});
}

void refuseUnknownParams(const Request& req, const std::vector<std::string>& known) {
  for (const auto& [name, value] : req.params) {
    if (std::find(known.begin(), known.end(), name) != known.end()) continue;
    std::string allowed;
    for (const std::string& k : known) allowed += (allowed.empty() ? "" : ", ") + k;
    throw ApiError(400, problem::kInvalidParameter, "Invalid parameter",
                   "unknown parameter '" + name + "'; allowed: " + allowed, name,
                   Json{{"in", "query"}, {"allowed", known}});
  }
}

bool wantsCsv(const Request& req) {
  if (const auto f = choiceParam(req, "format", {"json", "csv"})) return *f == "csv";
  const std::string accept = req.get_header_value("Accept");
  return accept.find("text/csv") != std::string::npos && accept.find("application/json") == std::string::npos;
}

/// OGC API style: ?f=html, or a browser's Accept (text/html) when ?f is absent; ?f=json is JSON.
bool wantsHtml(const Request& req) {
  if (const auto f = choiceParam(req, "f", {"html", "json"})) return *f == "html";
  return req.get_header_value("Accept").find("text/html") != std::string::npos;
}

std::vector<std::string> splitList(const std::string& text) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (start <= text.size()) {
    std::size_t comma = text.find(',', start);
    if (comma == std::string::npos) comma = text.size();
    std::string item = text.substr(start, comma - start);
    if (!item.empty()) out.push_back(item);
    start = comma + 1;
  }
  return out;
}

/// Every value of a (possibly repeated) query parameter, comma lists split.
std::vector<std::string> paramList(const Request& req, const std::string& name) {
  std::vector<std::string> out;
  for (std::size_t i = 0; i < req.get_param_value_count(name); ++i) {
    for (auto& item : splitList(req.get_param_value(name, i))) out.push_back(item);
  }
  return out;
}

bool knownScenario(const std::string& name) { return rupture::findScenario(name) != nullptr; }

void requireToken(const ServerContext& ctx, const Request& req) {
  const std::string& token = ctx.config.token;
  if (token.empty()) return;
  const std::string header = req.get_header_value("Authorization");
  if (!bearerMatches(header, token)) {
    throw ApiError(401, problem::kUnauthorized, "Unauthorized",
                   header.empty() ? "this server needs 'Authorization: Bearer <token>' for POST and DELETE"
                                  : "the bearer token is wrong");
  }
}

ApiError noSuchProcess(const std::string& name) {
  Json allowed = Json::array();
  for (const auto& s : rupture::listScenarios()) allowed.push_back(s.name);
  return ApiError(404, problem::kNoSuchProcess, "No such process",
                  "no scenario '" + name + "'; available: " + allowed.dump(), "processID",
                  Json{{"in", "path"}, {"allowed", allowed}});
}

std::int64_t intParam(const Request& req, const char* name, std::int64_t fallback, std::int64_t lo,
                             std::int64_t hi) {
  if (!req.has_param(name)) return fallback;
  const std::string text = req.get_param_value(name);
  auto v = parseIndex(text);
  if (!v || *v < lo || *v > hi) {
    throw ApiError(400, problem::kInvalidParameter, "Invalid parameter",
                   std::string(name) + " must be an integer in [" + std::to_string(lo) + ", " +
                       std::to_string(hi) + "], got '" + text + "'",
                   name, Json{{"in", "query"}, {"value", text}});
  }
  return *v;
}

/// ?aggregate=replicates (statistics per sweep point) or ?aggregate=none (the runs; default).
bool aggregateParam(const Request& req) {
  return choiceParam(req, "aggregate", {"replicates", "none"}) == "replicates";
}

std::optional<double> numberParam(const Request& req, const char* name) {
  if (!req.has_param(name)) return std::nullopt;
  const std::string text = req.get_param_value(name);
  double v = 0;
  auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (text.empty() || ec != std::errc() || ptr != text.data() + text.size() || !std::isfinite(v)) {
    throw ApiError(400, problem::kInvalidParameter, "Invalid parameter",
                   std::string(name) + " must be a finite number (in the column's SI unit), got '" + text + "'",
                   name, Json{{"in", "query"}, {"value", text}});
  }
  return v;
}

AxisScale scaleParam(const Request& req, const char* name) {
  const std::string v = choiceParam(req, name, {"auto", "linear", "log"}).value_or("auto");
  return v == "linear" ? AxisScale::Linear : v == "log" ? AxisScale::Log : AxisScale::Auto;
}

JobRecord loadJob(ServerContext& ctx, const Request& req) {
  const std::int64_t id = jobIdFrom(req);
  auto job = ctx.store->job(id);
  if (!job) throw noSuchJob(req.matches[1]);
  return *job;
}

JobWithRuns loadJobWithRuns(ServerContext& ctx, const Request& req) {
  auto found = ctx.store->jobWithRuns(jobIdFrom(req));
  if (!found) throw noSuchJob(req.matches[1]);
  return std::move(*found);
}

RunRecord loadRun(ServerContext& ctx, const Request& req, const JobRecord& job) {
  auto run = ctx.store->run({job.id, runIndexFrom(req, job)});
  if (!run) throw noSuchJob(req.matches[1]);
  return *run;
}

/// The run, which must be successful with its file in place.
RunRecord finishedRun(ServerContext& ctx, const Request& req, const JobRecord& job) {
  RunRecord run = loadRun(ctx, req, job);
  const std::string what = "run " + std::to_string(run.key.index) + " of job " + std::to_string(job.id);
  if (run.status == Status::Accepted || run.status == Status::Running) {
    throw ApiError(409, problem::kResultNotReady, "Result not ready",
                   what + " is " + toString(run.status) + "; its results are ready when it is successful",
                   "", Json{{"runStatus", toString(run.status)}});
  }
  if (run.status != Status::Successful || run.resultPath.empty()) {
    throw ApiError(404, problem::kNoResults, "No results",
                   what + " is " + toString(run.status) + " and has no results" +
                       (run.error.empty() ? std::string() : ": " + publicMessage(run.error)),
                   "", Json{{"runStatus", toString(run.status)}});
  }
  return run;
}

}  // namespace rupture::server
