#include "routes.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <memory>
#include <regex>

#include <httplib.h>

#include "byte_range.hpp"
#include "files.hpp"
#include "html_views.hpp"
#include "json_body.hpp"
#include "log.hpp"
#include "problem.hpp"
#include "progress_info.hpp"
#include "public_message.hpp"
#include "request_guard.hpp"
#include "results.hpp"
#include "rupture/run.hpp"
#include "job_comparison.hpp"
#include "rate_dependence.hpp"
#include "refinement.hpp"
#include "replicate_statistics.hpp"
#include "replicates.hpp"
#include "summary.hpp"
#include "plot_png.hpp"
#include "render_gate.hpp"
#include "svg_plot.hpp"
#include "tar_archive.hpp"
#include "io/xdmf_writer.hpp"
#include "sweep.hpp"
#include "utf8.hpp"

#ifndef RUPTURE_VERSION
#define RUPTURE_VERSION "0.0.0"
#endif

namespace rupture::server {
namespace fs = std::filesystem;
using httplib::Request;
using httplib::Response;

const std::string& openApiYaml() {
  static const std::string text =
#include "openapi_yaml.inc"
      ;
  return text;
}

namespace {

constexpr const char* kJsonType = "application/json";
constexpr const char* kHdf5Type = "application/x-hdf5";
constexpr const char* kCsvType = "text/csv; charset=utf-8";
constexpr const char* kOgcRel = "http://www.opengis.net/def/rel/ogc/1.0/";

// ---------------------------------------------------------------------------------------------
// Small helpers

void sendJson(Response& res, const Json& doc, int status = 200) {
  res.status = status;
  res.set_content(dumpJson(doc), kJsonType);
}

void sendProblem(const Request& req, Response& res, const ApiError& error) {
  res.status = error.status();
  if (error.status() == 401) res.set_header("WWW-Authenticate", "Bearer realm=\"rupture\"");
  // Try-again answers say when: the problem's retry_after_s, else a few seconds.
  if (error.status() == 503 || error.status() == 507) {
    const Json& after = error.extra().contains("retry_after_s") ? error.extra()["retry_after_s"] : Json(5);
    res.set_header("Retry-After", after.is_number_integer() ? after.dump() : "5");
  }
  if (error.status() == 416 && error.extra().contains("size")) {
    res.set_header("Content-Range", "bytes */" + error.extra()["size"].dump());
  }
  res.set_content(dumpJson(problemDocument(error, req.path)), kProblemContentType);
}

/// The last resort for an exception at the HTTP boundary: a 500 problem that names no server
/// detail, and nothing thrown from here (a second failure leaves a bare 500).
void sendInternalError(const Request& req, Response& res, const std::string& what) noexcept {
  try {
    logLine("internal error on " + req.method + " " + toValidUtf8(req.path) + ": " + toValidUtf8(what));
    sendProblem(req, res, ApiError(500, problem::kInternal, "Internal Server Error",
                                   "internal error: " + publicMessage(what)));
  } catch (...) {
    res.status = 500;
    res.body.clear();
  }
}

Json link(const std::string& href, const std::string& rel, const std::string& type = kJsonType,
          const std::string& title = {}) {
  Json l = Json::object();
  l["href"] = href;
  l["rel"] = rel;
  if (!type.empty()) l["type"] = type;
  if (!title.empty()) l["title"] = title;
  return l;
}

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

bool wantsCsv(const Request& req) {
  if (req.has_param("format")) {
    const std::string f = req.get_param_value("format");
    if (f == "csv") return true;
    if (f == "json") return false;
    throw ApiError(400, problem::kInvalidParameter, "Invalid parameter",
                   "format must be 'json' or 'csv', got '" + f + "'", "format",
                   Json{{"in", "query"}, {"value", f}, {"allowed", Json::array({"json", "csv"})}});
  }
  const std::string accept = req.get_header_value("Accept");
  return accept.find("text/csv") != std::string::npos && accept.find("application/json") == std::string::npos;
}

/// OGC API style: ?f=html, or a browser's Accept (text/html) when ?f is absent; ?f=json is JSON.
bool wantsHtml(const Request& req) {
  if (req.has_param("f")) {
    const std::string f = req.get_param_value("f");
    if (f == "html") return true;
    if (f == "json") return false;
    throw ApiError(400, problem::kInvalidParameter, "Invalid parameter", "f must be 'html' or 'json', got '" + f + "'",
                   "f", Json{{"in", "query"}, {"value", f}, {"allowed", Json::array({"html", "json"})}});
  }
  return req.get_header_value("Accept").find("text/html") != std::string::npos;
}

void sendHtml(Response& res, const HtmlPage& page) {
  res.set_header("Content-Security-Policy", page.csp());
  res.set_header("X-Frame-Options", "DENY");
  res.set_content(page.body, "text/html; charset=utf-8");
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

/// Streams a file through a content provider (never the whole file in memory), or the one byte
/// range the request asks for (206; 416 past the end).
void sendFile(const Request& req, Response& res, const fs::path& path, const std::string& downloadName) {
  auto size = regularFileSize(path);
  auto stream = std::make_shared<std::ifstream>(path, std::ios::binary);
  if (!size || !*stream) {
    throw ApiError(404, problem::kNoResults, "No results", "the result file is missing on the server");
  }
  const std::uint64_t total = *size;
  const std::optional<ByteRange> range = parseByteRange(req.get_header_value("Range"), total);
  const std::uint64_t first = range ? range->offset : 0;
  const std::uint64_t length = range ? range->length : total;
  res.set_header("Content-Disposition", "attachment; filename=\"" + downloadName + "\"");
  res.set_header("Accept-Ranges", "bytes");
  if (range) {
    res.status = 206;
    res.set_header("Content-Range", "bytes " + std::to_string(first) + "-" + std::to_string(first + length - 1) +
                                        "/" + std::to_string(total));
  }
  res.set_content_provider(
      static_cast<std::size_t>(length), kHdf5Type,
      [stream, first, length](std::size_t offset, std::size_t want, httplib::DataSink& sink) {
        if (offset >= length) return false;
        std::vector<char> buffer(std::min<std::size_t>({want, length - offset, 64 * 1024}));
        stream->clear();
        stream->seekg(static_cast<std::streamoff>(first + offset));
        stream->read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
        const std::streamsize n = stream->gcount();
        if (n <= 0) return false;
        return sink.write(buffer.data(), static_cast<std::size_t>(n));
      });
}

bool knownScenario(const std::string& name) {
  for (const auto& s : rupture::listScenarios()) {
    if (s.name == name) return true;
  }
  return false;
}

int percent(double fraction) { return static_cast<int>(std::floor(std::clamp(fraction, 0.0, 1.0) * 100.0 + 1e-9)); }

// ---------------------------------------------------------------------------------------------
// Documents

Json runDocument(const JobRecord& job, const RunRecord& run) {
  Json doc = Json::object();
  doc["index"] = run.key.index;
  Json swept = Json::object();
  for (std::size_t i = 0; i < job.sweptPaths.size() && i < run.swept.size(); ++i) {
    swept[job.sweptPaths[i].get<std::string>()] = run.swept[i];
  }
  doc["swept"] = swept;
  doc["status"] = toString(run.status);
  doc["progress"] = run.status == Status::Successful ? 100 : percent(run.progress);
  if (!run.started.empty()) doc["started"] = run.started;
  if (!run.finished.empty()) doc["finished"] = run.finished;
  if (run.attempts > 1) doc["attempts"] = run.attempts;
  if (job.study.is_object() && job.study.contains("replicates")) doc["replicate"] = run.replicate;
  if (run.summary.is_object()) doc["summary"] = run.summary;
  if (!run.error.empty()) doc["error"] = publicMessage(run.error);
  addRunProgress(doc, run, utcNow());
  const std::string base = "/jobs/" + std::to_string(job.id) + "/runs/" + std::to_string(run.key.index);
  Json links = Json::array({link(base, "self")});
  if (run.status == Status::Successful) {
    links.push_back(link(base + "/results", "enclosure", kHdf5Type, "this run's HDF5 file"));
    links.push_back(link(base + "/series", "related", kJsonType, "time series (JSON or CSV)"));
    links.push_back(link(base + "/results.xdmf", "describedby", "application/xml", "ParaView sidecar (XDMF 2)"));
    links.push_back(link(base + "/bundle", "enclosure", "application/x-tar", "HDF5 file and ParaView sidecar (tar)"));
  }
  doc["links"] = links;
  return doc;
}

Json statusInfo(const JobRecord& job, const std::vector<RunRecord>* runs) {
  Json doc = Json::object();
  const std::string id = std::to_string(job.id);
  doc["jobID"] = id;
  doc["type"] = "process";
  doc["processID"] = job.processId;
  if (!job.name.empty()) doc["name"] = job.name;
  doc["status"] = toString(job.status);
  doc["message"] = publicMessage(job.message);
  doc["progress"] = percent(job.progress);
  doc["created"] = job.created;
  if (!job.started.empty()) doc["started"] = job.started;
  if (!job.finished.empty()) doc["finished"] = job.finished;
  addJobProgress(doc, job, runs, utcNow());
  doc["sweep_mode"] = job.sweepMode;
  doc["swept"] = job.sweptPaths;
  doc["runs_total"] = job.runsTotal;
  doc["runs_by_status"] = {{"accepted", job.runsAccepted},     {"running", job.runsRunning},
                           {"successful", job.runsSuccessful}, {"failed", job.runsFailed},
                           {"dismissed", job.runsDismissed}};
  if (job.study.is_object()) {  // replicates, refine (the plan) and refinement (what it added, and why)
    for (const char* key : {"replicates", "refine", "refinement"}) {
      if (job.study.contains(key)) doc[key] = job.study[key];
    }
  }
  if (runs) {
    Json list = Json::array();
    for (const RunRecord& r : *runs) list.push_back(runDocument(job, r));
    doc["runs"] = list;
  }
  const std::string base = "/jobs/" + id;
  doc["links"] = Json::array({
      link(base, "self", kJsonType, "this job's status"),
      link(base + "/results", std::string(kOgcRel) + "results", kHdf5Type, "all runs in one HDF5 file"),
      link(base + "/summary", "related", kJsonType, "summary table"),
      link(base + "/summary?format=csv", "alternate", "text/csv", "summary table as CSV"),
      link(base + "/summary.svg", "related", "image/svg+xml", "summary plot"),
  });
  if (job.study.is_object() && job.study.contains("replicates")) {
    doc["links"].push_back(link(base + "/summary?aggregate=replicates", "related", kJsonType,
                                "mean, sd, 95 % confidence interval and n per sweep point"));
  }
  return doc;
}

Json processSummary(const rupture::ScenarioInfo& info) {
  Json doc = Json::object();
  doc["id"] = info.name;
  doc["title"] = info.title;
  doc["description"] = info.description;
  doc["version"] = RUPTURE_VERSION;
  doc["jobControlOptions"] = Json::array({"async-execute"});
  doc["outputTransmission"] = Json::array({"reference"});
  doc["links"] = Json::array({
      link("/processes/" + info.name, "self", kJsonType, "process description"),
      link("/processes/" + info.name + "/execution", std::string(kOgcRel) + "execute", kJsonType,
           "execute (POST)"),
  });
  return doc;
}

// ---------------------------------------------------------------------------------------------

class Api {
public:
  explicit Api(ServerContext& ctx) : m_ctx(ctx) {}

  void landing(const Request& req, Response& res) {
    Json doc = Json::object();
    doc["title"] = "Rupture";
    doc["description"] =
        "Particle-method fracture simulations served as parameter sweeps (OGC API - Processes). "
        "POST /processes/{scenario}/execution with inputs and a sweep; follow the job.";
    doc["version"] = RUPTURE_VERSION;
    doc["links"] = Json::array({
        link("/", "self", kJsonType, "this document"),
        link("/openapi.yaml", "service-desc", "application/vnd.oai.openapi;version=3.0", "the API definition"),
        link("/conformance", std::string(kOgcRel) + "conformance", kJsonType, "conformance classes"),
        link("/processes", std::string(kOgcRel) + "processes", kJsonType, "the scenarios"),
        link("/jobs", std::string(kOgcRel) + "job-list", kJsonType, "jobs"),
        link("/health", "status", kJsonType, "server health"),
    });
    if (wantsHtml(req)) return sendHtml(res, landingHtml(doc));
    sendJson(res, doc);
  }

  void health(const Request&, Response& res) {
    Json doc = Json::object();
    doc["status"] = m_ctx.stopping ? "stopping" : "ok";
    doc["version"] = RUPTURE_VERSION;
    doc["executor"] = m_ctx.scheduler->name();
    doc["workers"] = m_ctx.scheduler->workers();
    doc["threads_per_run"] = m_ctx.scheduler->threadsPerRun();
    doc["running"] = m_ctx.store->runningCount();  // the store's view, as GET /jobs shows it
    doc["queue_depth"] = m_ctx.store->queueDepth();
    doc["waiting_for_disk"] = m_ctx.scheduler->waitingForDisk();          // below --min-free-bytes
    doc["unrecorded_outcomes"] = m_ctx.scheduler->unrecordedOutcomes();   // finished on disk, store retrying
    doc["uptime_s"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - m_ctx.startedAt).count();
    Json scenarios = Json::array();
    for (const auto& s : rupture::listScenarios()) scenarios.push_back(s.name);
    doc["scenarios"] = scenarios;
    sendJson(res, doc);
  }

  void openapi(const Request&, Response& res) {
    res.set_content(openApiYaml(), "application/vnd.oai.openapi;version=3.0");
  }

  void conformance(const Request&, Response& res) {
    const std::string base = "http://www.opengis.net/spec/ogcapi-processes-1/1.0/conf/";
    sendJson(res, Json{{"conformsTo", Json::array({base + "core", base + "json", base + "job-list",
                                                   base + "dismiss", base + "ogc-process-description",
                                                   base + "oas30"})}});
  }

  void processes(const Request& req, Response& res) {
    Json list = Json::array();
    for (const auto& s : rupture::listScenarios()) list.push_back(processSummary(s));
    const Json doc{{"processes", list}, {"links", Json::array({link("/processes", "self")})}};
    if (wantsHtml(req)) {
      Json schemas = Json::object();
      for (const auto& s : rupture::listScenarios()) schemas[s.name] = Json(rupture::scenarioSchema(s.name));
      return sendHtml(res, processesHtml(doc, schemas));
    }
    sendJson(res, doc);
  }

  void process(const Request& req, Response& res) {
    const std::string name = req.matches[1];
    const rupture::ScenarioInfo* info = nullptr;
    auto all = rupture::listScenarios();
    for (const auto& s : all) {
      if (s.name == name) info = &s;
    }
    if (!info) throw noSuchProcess(name);
    Json doc = processSummary(*info);
    Json schema = Json(rupture::scenarioSchema(name));
    Json inputs = Json::object();
    if (schema.contains("properties")) {
      for (const auto& [key, sub] : schema["properties"].items()) {
        if (key == "scenario") continue;
        Json input = Json::object();
        input["title"] = sub.value("title", key);
        if (sub.contains("description")) input["description"] = sub["description"];
        input["schema"] = sub;
        inputs[key] = input;
      }
    }
    doc["inputs"] = inputs;
    doc["outputs"] = {
        {"results", {{"title", "one HDF5 file per run, and one merged file per job"},
                     {"schema", {{"type", "string"}, {"contentMediaType", kHdf5Type}}}}},
        {"summary", {{"title", "summary scalars per run (JSON, CSV, SVG plot)"},
                     {"schema", {{"type", "object"}}}}},
    };
    doc["inputsSchema"] = schema;
    doc["sweep"] = {
        {"description",
         "POST body: {\"inputs\": {...spec without scenario...}, \"sweep\": {\"dotted.path\": [values]}, "
         "\"sweep_mode\": \"grid\"|\"zip\", \"name\": \"...\", \"replicates\": {\"count\": N, \"vary\": \"sample.seed\"}, "
         "\"refine\": {\"path\": \"loading.strain_rate\", \"quantity\": \"peak_stress\", \"max_runs\": N, "
         "\"tolerance\": 0.1}} (docs/server.md, Studies)"},
        {"modes", Json::array({"grid", "zip"})},
        {"max_runs", m_ctx.config.maxRuns},
        {"max_replicates", kMaxReplicates},
    };
    if (wantsHtml(req)) return sendHtml(res, processHtml(doc));
    sendJson(res, doc);
  }

  void execute(const Request& req, Response& res) {
    requireToken(req);
    if (m_ctx.stopping) {
      throw ApiError(503, problem::kShuttingDown, "Service Unavailable",
                     "the server is stopping; submit again once it is back");
    }
    const std::string scenario = req.matches[1];
    if (!knownScenario(scenario)) throw noSuchProcess(scenario);

    const Json body = parseJsonBody(req.body);
    if (!body.is_object()) {
      throw ApiError(400, problem::kInvalidRequest, "Invalid request",
                     "the request body must be a JSON object with \"inputs\"", "", Json{{"in", "body"}});
    }
    static const std::vector<std::string> allowedKeys = {"inputs",  "sweep",    "sweep_mode", "name",      "replicates",
                                                         "refine",  "outputs",  "response",   "subscriber"};
    for (const auto& [key, value] : body.items()) {
      if (std::find(allowedKeys.begin(), allowedKeys.end(), key) == allowedKeys.end()) {
        throw ApiError(400, problem::kInvalidRequest, "Invalid request",
                       "unknown member '" + key +
                           "' in the request body; allowed: inputs, sweep, sweep_mode, name, replicates, refine",
                       key, Json{{"in", "body"}});
      }
    }
    auto inputsIt = body.find("inputs");
    if (inputsIt == body.end() || !inputsIt->is_object()) {
      throw ApiError(400, problem::kInvalidRequest, "Invalid request",
                     "\"inputs\" is required and must be an object: the spec without \"scenario\"", "inputs",
                     Json{{"in", "body"}});
    }
    const Json& inputs = *inputsIt;
    if (const std::string empty = findEmptyKey(inputs, ""); !empty.empty()) {
      throw ApiError(400, problem::kInvalidSpec, "Invalid spec",
                     "inputs has a member whose name is the empty string (at " + empty +
                         "); every field needs a name",
                     empty, Json{{"in", "inputs"}});
    }
    if (auto sc = inputs.find("scenario"); sc != inputs.end() && *sc != scenario) {
      throw ApiError(400, problem::kInvalidSpec, "Invalid spec",
                     "inputs.scenario is " + sc->dump() + " but the URL names '" + scenario +
                         "'; leave it out, the URL decides",
                     "scenario", Json{{"in", "inputs"}, {"value", *sc}, {"allowed", Json::array({scenario})}});
    }
    std::string name;
    if (auto n = body.find("name"); n != body.end() && !n->is_null()) {
      if (!n->is_string() || n->get<std::string>().size() > 200) {
        throw ApiError(400, problem::kInvalidRequest, "Invalid request",
                       "name must be a string of at most 200 characters", "name", Json{{"in", "body"}});
      }
      name = n->get<std::string>();
    }
    auto member = [&](const char* key) -> const Json* {
      auto it = body.find(key);
      return it == body.end() ? nullptr : &*it;
    };
    // Idempotency-Key: a retry of a POST whose answer was lost gets the job the first one made.
    const std::string idempotencyKey = idempotencyKeyOf(req);
    const std::string requestHash = idempotencyKey.empty() ? std::string() : requestFingerprint(scenario, body);
    if (!idempotencyKey.empty()) {
      if (auto earlier = m_ctx.store->jobForIdempotencyKey(idempotencyKey)) {
        replayJob(req, res, *earlier, requestHash);
        return;
      }
    }
    const SweepPlan plan = parseSweepPlan(member("sweep"), member("sweep_mode"));
    const ReplicatePlan replicates = parseReplicatePlan(member("replicates"), scenario, plan);
    const std::size_t maxRuns = static_cast<std::size_t>(m_ctx.config.maxRuns);
    std::vector<SweepPoint> sweepPoints = expandSweep(scenario, inputs, plan, maxRuns);
    if (sweepPoints.size() * static_cast<std::size_t>(replicates.count) > maxRuns) {
      const std::size_t total = sweepPoints.size() * static_cast<std::size_t>(replicates.count);
      throw ApiError(400, problem::kTooManyRuns, "Too many runs",
                     "the sweep's " + std::to_string(sweepPoints.size()) + " points x " +
                         std::to_string(replicates.count) + " replicates make " + std::to_string(total) +
                         " runs; this server accepts at most " + std::to_string(maxRuns) + " per job (--max-runs)",
                     "replicates.count", Json{{"in", "body"}, {"runs", total}, {"max_runs", maxRuns}});
    }
    // Every spec holds the whole inputs (a large description, many probes): moved, never copied.
    std::vector<ReplicatedPoint> replicated = expandReplicates(std::move(sweepPoints), replicates, scenario);
    std::vector<SweepPoint> points;
    std::vector<int> replicateIndex;
    points.reserve(replicated.size());
    for (ReplicatedPoint& rp : replicated) {
      points.push_back(std::move(rp.point));
      replicateIndex.push_back(rp.replicate);
    }
    replicated.clear();
    const std::size_t runCount = points.size();
    validateSweepPoints(points, plan, static_cast<double>(m_ctx.config.maxElements), m_ctx.maxRunMemory);
    requireQueueRoom(runCount, inputs.dump().size());
    const std::optional<RefinePlan> refine =
        parseRefinePlan(member("refine"), scenario, plan, replicates.count, runCount, maxRuns);

    NewJob job;
    job.processId = scenario;
    job.name = name;
    job.sweepMode = toString(plan.mode);
    job.sweptPaths = Json::array();
    for (const SweepAxis& axis : plan.axes) job.sweptPaths.push_back(axis.path);
    job.inputs = inputs;
    job.sweep = body.contains("sweep") && body["sweep"].is_object() ? body["sweep"] : Json::object();
    job.runs.reserve(runCount);
    for (std::size_t k = 0; k < runCount; ++k) {
      job.runs.emplace_back(std::move(points[k].swept), std::move(points[k].spec));
      job.replicates.push_back(replicateIndex[k]);
    }
    points.clear();
    if (replicates.requested() || refine) {
      job.study = Json::object();
      if (replicates.requested()) job.study["replicates"] = replicates.toJson();
      if (refine) {
        job.study["refine"] = refine->toJson();
        job.study["refinement"] = {{"state", "pending"}, {"rounds", 0}, {"runs_added", 0}, {"points", Json::array()}};
      }
    }
    job.idempotencyKey = idempotencyKey;
    job.requestHash = requestHash;
    const CreatedJob created = m_ctx.store->createJobOnce(job);
    if (!created.created) {  // a concurrent request with the same key won the race
      replayJob(req, res, IdempotentJob{created.id, created.requestHash}, requestHash);
      return;
    }
    const std::int64_t id = created.id;
    m_ctx.scheduler->enqueue(id, static_cast<int>(runCount));
    logLine("job " + std::to_string(id) + " accepted: " + scenario + ", " + std::to_string(runCount) +
            " run(s)" + (name.empty() ? "" : ", \"" + name + "\""));

    auto record = m_ctx.store->job(id);
    auto runs = m_ctx.store->runs(id);
    res.set_header("Location", "/jobs/" + std::to_string(id));
    if (req.get_header_value("Prefer").find("respond-async") != std::string::npos) {
      res.set_header("Preference-Applied", "respond-async");
    }
    sendJson(res, statusInfo(*record, &runs), 201);
  }

  void jobs(const Request& req, Response& res) {
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
    std::int64_t total = 0;
    auto list = m_ctx.store->listJobs(filter, total);
    Json jobs = Json::array();
    for (const JobRecord& j : list) jobs.push_back(statusInfo(j, nullptr));
    Json doc = Json::object();
    doc["jobs"] = jobs;
    doc["numberMatched"] = total;
    doc["numberReturned"] = jobs.size();
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
    if (filter.offset + static_cast<std::int64_t>(list.size()) < total) {
      links.push_back(link(page(filter.offset + filter.limit), "next"));
    }
    if (filter.offset > 0) links.push_back(link(page(std::max<std::int64_t>(0, filter.offset - filter.limit)), "prev"));
    doc["links"] = links;
    if (wantsHtml(req)) {
      Json current = {{"name", filter.nameContains}, {"processID", filter.processId},
                      {"status", filter.statuses.size() == 1 ? toString(filter.statuses[0]) : ""}};
      Json scenarios = Json::array();
      for (const auto& s : rupture::listScenarios()) scenarios.push_back(s.name);
      return sendHtml(res, jobsHtml(doc, current, scenarios));
    }
    sendJson(res, doc);
  }

  void job(const Request& req, Response& res) {
    const JobRecord job = loadJob(req);
    auto runs = m_ctx.store->runs(job.id);
    if (wantsHtml(req)) {
      Json summary;  // once every run has ended
      std::string plot;
      if (job.runsAccepted + job.runsRunning == 0 && job.runsSuccessful > 0) {
        const SummaryTable table = buildSummary(job, runs);
        summary = summaryJson(table);
        if (!table.sweptPaths.empty() && !table.scalarNames.empty()) {
          const bool peak = std::find(table.scalarNames.begin(), table.scalarNames.end(), "peak_stress") != table.scalarNames.end();
          plot = "/jobs/" + std::to_string(job.id) + "/summary.svg?x=" +
                 httplib::detail::encode_query_param(table.sweptPaths.front()) +
                 "&y=" + httplib::detail::encode_query_param(peak ? "peak_stress" : table.scalarNames.front());
        }
      }
      return sendHtml(res, jobHtml(statusInfo(job, &runs), summary, plot));
    }
    sendJson(res, statusInfo(job, &runs));
  }

  void dismiss(const Request& req, Response& res) {
    requireToken(req);
    const std::int64_t id = jobIdFrom(req);
    auto job = m_ctx.scheduler->dismiss(id);
    if (!job) throw noSuchJob(std::to_string(id));
    logLine("job " + std::to_string(id) + " dismiss requested; status " + toString(job->status));
    auto runs = m_ctx.store->runs(id);
    sendJson(res, statusInfo(*job, &runs));
  }

  void retry(const Request& req, Response& res) {
    requireToken(req);
    const std::int64_t id = jobIdFrom(req);
    if (!m_ctx.store->job(id)) throw noSuchJob(std::to_string(id));
    const std::vector<int> indices = m_ctx.store->retryFailedRuns(id);
    if (indices.empty()) {
      const JobRecord job = *m_ctx.store->job(id);
      throw ApiError(409, problem::kNothingToRetry, "Nothing to retry",
                     "job " + std::to_string(id) + " has no failed run to retry (" + toString(job.status) + ": " +
                         publicMessage(job.message) + ")",
                     "", Json{{"jobStatus", toString(job.status)}});
    }
    m_ctx.scheduler->resubmit(id, indices);
    logLine("job " + std::to_string(id) + ": " + std::to_string(indices.size()) + " failed run(s) re-submitted");
    auto job = m_ctx.store->job(id);
    auto runs = m_ctx.store->runs(id);
    Json doc = statusInfo(*job, &runs);
    doc["retried_runs"] = indices;
    sendJson(res, doc);
  }

  void jobResults(const Request& req, Response& res) {
    const JobRecord job = loadJob(req);
    // A job whose refinement is pending gets more runs: its merged file waits for the last round.
    const bool refining = job.study.is_object() && job.study.contains("refinement") &&
                          job.study["refinement"].value("state", "") == "pending";
    if (job.runsAccepted + job.runsRunning > 0 || refining) {
      throw ApiError(409, problem::kResultNotReady, "Result not ready",
                     "job " + std::to_string(job.id) + " is " + toString(job.status) + " (" +
                         std::to_string(job.runsTotal - job.runsAccepted - job.runsRunning) + " of " +
                         std::to_string(job.runsTotal) +
                         " runs finished" + (refining ? ", refinement pending" : "") +
                         "); its results file is ready when every run has finished",
                     "", Json{{"jobStatus", toString(job.status)}});
    }
    if (job.runsSuccessful == 0) {
      throw ApiError(404, problem::kNoResults, "No results",
                     "job " + std::to_string(job.id) + " has no successful run (" + publicMessage(job.message) + ")");
    }
    const fs::path path = mergedResults(job, m_ctx.store->runs(job.id), m_ctx.resultsDir);
    sendFile(req, res, path, "rupture-job-" + std::to_string(job.id) + ".h5");
  }

  void runsList(const Request& req, Response& res) {
    const JobRecord job = loadJob(req);
    Json list = Json::array();
    for (const RunRecord& r : m_ctx.store->runs(job.id)) list.push_back(runDocument(job, r));
    sendJson(res, Json{{"jobID", std::to_string(job.id)}, {"runs", list}});
  }

  void run(const Request& req, Response& res) {
    const JobRecord job = loadJob(req);
    const RunRecord run = loadRun(req, job);
    Json doc = runDocument(job, run);
    doc["spec"] = run.spec;
    sendJson(res, doc);
  }

  void runResults(const Request& req, Response& res) {
    const JobRecord job = loadJob(req);
    const RunRecord run = finishedRun(req, job);
    sendFile(req, res, m_ctx.resultsDir / run.resultPath,
             "rupture-job-" + std::to_string(job.id) + "-run-" + std::to_string(run.key.index) + ".h5");
  }

  // -- ParaView: the sidecar names the HDF5 file by its download name, so the two work side by side.

  static std::string runFileStem(const JobRecord& job, const RunRecord& run) {
    return "rupture-job-" + std::to_string(job.id) + "-run-" + std::to_string(run.key.index);
  }

  std::string runSidecar(const JobRecord& job, const RunRecord& run) {
    const std::string file = (m_ctx.resultsDir / run.resultPath).string();
    if (rupture::io::runGroupsWithSnapshots(file) != std::vector<std::string>{""}) {
      throw ApiError(404, problem::kNoResults, "No results",
                     "run " + std::to_string(run.key.index) + " of job " + std::to_string(job.id) +
                         " has no snapshots for ParaView (" + job.processId + " writes none)");
    }
    return rupture::io::xdmfDocument(file, runFileStem(job, run) + ".h5");
  }

  void runXdmf(const Request& req, Response& res) {
    const JobRecord job = loadJob(req);
    const RunRecord run = finishedRun(req, job);
    const std::string xml = runSidecar(job, run);
    // .xdmf2: ParaView 5.11 opens *.xdmf with its broken Xdmf3 readers (docs/paraview.md).
    res.set_header("Content-Disposition", "attachment; filename=\"" + runFileStem(job, run) + ".xdmf2\"");
    res.set_content(xml, "application/xml");
  }

  void runBundle(const Request& req, Response& res) {
    const JobRecord job = loadJob(req);
    const RunRecord run = finishedRun(req, job);
    const std::string stem = runFileStem(job, run);
    const fs::path h5 = m_ctx.resultsDir / run.resultPath;
    const std::string xml = runSidecar(job, run);
    std::error_code ec;
    const auto written = fs::last_write_time(h5, ec);
    const std::int64_t mtime =
        ec ? 0
           : std::chrono::duration_cast<std::chrono::seconds>(
                 std::chrono::file_clock::to_sys(written).time_since_epoch()).count();
    auto tar = std::make_shared<TarArchive>();
    tar->addFile(stem + "/" + stem + ".h5", h5, mtime);
    tar->addText(stem + "/" + stem + ".xdmf2", xml, mtime);
    res.set_header("Content-Disposition", "attachment; filename=\"" + stem + ".tar\"");
    res.set_content_provider(static_cast<std::size_t>(tar->size()), "application/x-tar",
                             [tar](std::size_t offset, std::size_t want, httplib::DataSink& sink) {
                               std::vector<char> buffer(std::min<std::size_t>(want, 64 * 1024));
                               const std::size_t n = tar->read(offset, buffer.data(), buffer.size());
                               if (n == 0) return false;
                               return sink.write(buffer.data(), n);
                             });
  }

  void series(const Request& req, Response& res) {
    const JobRecord job = loadJob(req);
    const RunRecord run = finishedRun(req, job);
    const bool csv = wantsCsv(req);
    SeriesTable table = readSeries(m_ctx.resultsDir / run.resultPath, paramList(req, "names"));
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

  void summary(const Request& req, Response& res) {
    const JobRecord job = loadJob(req);
    const SummaryTable table = buildSummary(job, m_ctx.store->runs(job.id));
    const bool aggregate = aggregateParam(req);
    const bool csv = wantsCsv(req);
    if (csv) {
      res.set_content(aggregate ? aggregateCsv(table, aggregateReplicates(table)) : summaryCsv(table), kCsvType);
      return;
    }
    const std::vector<PointAggregate> points = aggregateReplicates(table);
    Json doc = aggregate ? aggregateJson(table, points) : summaryJson(table);
    doc["status"] = toString(job.status);
    if (Json rates = rateDependence(table, points); !rates.is_null()) doc["rate_dependence"] = rates;
    sendJson(res, doc);
  }

  /// GET /summary?jobs=3,5,7: the rows (or, with aggregate=replicates, the points) of several jobs.
  void compareSummary(const Request& req, Response& res) {
    const std::vector<ComparedJob> jobs = loadComparedJobs(req);
    const bool aggregate = aggregateParam(req);
    if (wantsCsv(req)) {
      res.set_content(comparisonCsv(jobs, aggregate), kCsvType);
      return;
    }
    sendJson(res, comparisonJson(jobs, aggregate));
  }

  /// GET /plot?jobs=3,5,7: one series per job (point means, 95 % intervals as error bars).
  void comparePlot(const Request& req, Response& res) {
    const std::vector<ComparedJob> jobs = loadComparedJobs(req);
    const SummaryTable table = comparisonPlotTable(jobs);
    PlotRequest plot;
    plot.x = req.has_param("x") ? req.get_param_value("x") : (table.sweptPaths.size() > 1 ? table.sweptPaths[1] : "");
    plot.y = req.has_param("y") ? req.get_param_value("y") : "peak_stress";
    if (plot.x.empty()) {
      throw ApiError(400, problem::kInvalidParameter, "Invalid parameter",
                     "these jobs sweep nothing; name the x column with ?x=", "x", Json{{"in", "query"}});
    }
    // Each point is a mean: its 95 % interval is the error bar unless ?yerror= names another column.
    if (table.hasColumn(ciHalfWidthColumn(plot.y))) plot.yError = ciHalfWidthColumn(plot.y);
    readPlotOptions(req, table, plot);
    std::string ids;
    for (const ComparedJob& j : jobs) ids += (ids.empty() ? "" : ", ") + std::to_string(j.job.id);
    plot.title = columnLabel(table, plot.y) + " vs " + columnLabel(table, plot.x) + " - jobs " + ids + " - mean, 95 % CI";
    sendPlot(req, res, table, plot, *m_ctx.renders);
  }

  void summarySvg(const Request& req, Response& res) {
    const JobRecord job = loadJob(req);
    SummaryTable table = buildSummary(job, m_ctx.store->runs(job.id));
    PlotRequest plot;
    plot.x = req.has_param("x") ? req.get_param_value("x")
                                : (table.sweptPaths.empty() ? std::string() : table.sweptPaths.front());
    plot.y = req.has_param("y") ? req.get_param_value("y") : "peak_stress";
    if (plot.x.empty()) {
      throw ApiError(400, problem::kInvalidParameter, "Invalid parameter",
                     "this job sweeps nothing; name the x column with ?x=", "x", Json{{"in", "query"}});
    }
    const bool replicated = table.replicated && table.hasColumn(plot.y);
    if (replicated) {
      // Replicates: one point per sweep point, at the mean, with its 95 % interval as the error bar
      // (unless ?yerror= names another column, e.g. peak_stress.sd).
      table = meansTable(table, aggregateReplicates(table));
      if (table.hasColumn(ciHalfWidthColumn(plot.y))) plot.yError = ciHalfWidthColumn(plot.y);
    }
    readPlotOptions(req, table, plot);
    plot.title = columnLabel(table, plot.y) + " vs " + columnLabel(table, plot.x) + " - job " + std::to_string(job.id) +
                 (job.name.empty() ? "" : " (" + job.name + ")") + (replicated ? " - mean, 95 % CI" : "");
    sendPlot(req, res, table, plot, *m_ctx.renders);
  }

  // -- shared checks ---------------------------------------------------------------------------

  void requireToken(const Request& req) const {
    const std::string& token = m_ctx.config.token;
    if (token.empty()) return;
    const std::string header = req.get_header_value("Authorization");
    if (!bearerMatches(header, token)) {
      throw ApiError(401, problem::kUnauthorized, "Unauthorized",
                     header.empty() ? "this server needs 'Authorization: Bearer <token>' for POST and DELETE"
                                    : "the bearer token is wrong");
    }
  }

private:
  /// Queued work is bounded for the whole server, in runs (--max-queued-runs) and in stored bytes
  /// of inputs (--max-queued-bytes): a job that can never fit is the client's mistake (400); one
  /// that fits once the queue drains is told to come back (503).
  void requireQueueRoom(std::size_t runs, std::size_t inputBytes) {
    struct Bound {
      std::size_t amount, queued, limit;
      const char *what, *flag, *key, *field, *title;
    };
    const Bound bounds[] = {
        {inputBytes, static_cast<std::size_t>(std::max(0LL, m_ctx.store->queuedInputBytes())),
         static_cast<std::size_t>(m_ctx.config.maxQueuedBytes), "bytes of inputs", "--max-queued-bytes", "bytes", "inputs",
         "Inputs too large"},
        {runs, static_cast<std::size_t>(std::max(0, m_ctx.store->queueDepth())),
         static_cast<std::size_t>(m_ctx.config.maxQueuedRuns), "runs", "--max-queued-runs", "runs", "sweep", "Too many runs"}};
    for (const Bound& b : bounds) {
      const std::string key = b.key, flag = b.flag;
      if (b.amount > b.limit) {
        throw ApiError(400, b.key == std::string("runs") ? problem::kTooManyRuns : problem::kPayloadTooLarge, b.title,
                       "the job has " + std::to_string(b.amount) + " " + b.what + "; unfinished jobs may hold at most " +
                           std::to_string(b.limit) + " in this server (" + flag + ")",
                       b.field, Json{{"in", "body"}, {"job_" + key, b.amount}, {"max_queued_" + key, b.limit}});
      }
      if (b.queued + b.amount > b.limit) {
        throw ApiError(503, problem::kQueueFull, "Queue full",
                       "unfinished jobs hold " + std::to_string(b.queued) + " " + b.what + " and this server allows " +
                           std::to_string(b.limit) + " (" + flag + "); this job's " + std::to_string(b.amount) +
                           " fit once some have finished: retry later",
                       "", Json{{"queued_" + key, b.queued}, {"max_queued_" + key, b.limit}, {"retry_after_s", 60}});
      }
    }
  }

  /// The Idempotency-Key header: 1 to 200 visible ASCII characters, or "" when absent.
  static std::string idempotencyKeyOf(const Request& req) {
    if (!req.has_header("Idempotency-Key")) return "";
    const std::string key = req.get_header_value("Idempotency-Key");
    const bool visible = std::all_of(key.begin(), key.end(), [](char c) { return c > 0x20 && c < 0x7F; });
    if (key.empty() || key.size() > 200 || !visible) {
      throw ApiError(400, problem::kInvalidRequest, "Invalid request",
                     "Idempotency-Key must be 1 to 200 visible ASCII characters (a UUID is a good choice)",
                     "Idempotency-Key", Json{{"in", "header"}});
    }
    return key;
  }

  /// Identifies a submission: the scenario and the body with keys sorted (FNV-1a, 64 bits, hex).
  static std::string requestFingerprint(const std::string& scenario, const Json& body) {
    const std::string text = scenario + "\n" + nlohmann::json(body).dump(-1, ' ', false, Json::error_handler_t::replace);
    std::uint64_t hash = 1469598103934665603ull;
    for (unsigned char c : text) {
      hash ^= c;
      hash *= 1099511628211ull;
    }
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(hash));
    return hex;
  }

  /// Answers a repeated Idempotency-Key: the earlier job (201, as the first answer was), or 422
  /// when the key came with a different request.
  void replayJob(const Request& req, Response& res, const IdempotentJob& earlier, const std::string& requestHash) {
    if (earlier.requestHash != requestHash) {
      throw ApiError(422, problem::kIdempotencyKeyReused, "Idempotency key reused",
                     "this Idempotency-Key was first used for a different request (job " +
                         std::to_string(earlier.id) + "); use a new key for a new submission",
                     "Idempotency-Key", Json{{"in", "header"}, {"jobID", std::to_string(earlier.id)}});
    }
    auto record = m_ctx.store->job(earlier.id);
    if (!record) throw noSuchJob(std::to_string(earlier.id));
    auto runs = m_ctx.store->runs(earlier.id);
    res.set_header("Location", "/jobs/" + std::to_string(earlier.id));
    res.set_header("Idempotent-Replayed", "true");
    if (req.get_header_value("Prefer").find("respond-async") != std::string::npos) {
      res.set_header("Preference-Applied", "respond-async");
    }
    sendJson(res, statusInfo(*record, &runs), 201);
  }

  static ApiError noSuchProcess(const std::string& name) {
    Json allowed = Json::array();
    for (const auto& s : rupture::listScenarios()) allowed.push_back(s.name);
    return ApiError(404, problem::kNoSuchProcess, "No such process",
                    "no scenario '" + name + "'; available: " + allowed.dump(), "processID",
                    Json{{"in", "path"}, {"allowed", allowed}});
  }

  static std::int64_t intParam(const Request& req, const char* name, std::int64_t fallback, std::int64_t lo,
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
  static bool aggregateParam(const Request& req) {
    if (!req.has_param("aggregate")) return false;
    const std::string v = req.get_param_value("aggregate");
    if (v == "replicates") return true;
    if (v == "none") return false;
    throw ApiError(400, problem::kInvalidParameter, "Invalid parameter",
                   "aggregate must be 'replicates' or 'none', got '" + v + "'", "aggregate",
                   Json{{"in", "query"}, {"value", v}, {"allowed", Json::array({"replicates", "none"})}});
  }

  /// The jobs of ?jobs=3,5,7 with their summary tables: 400 when the list is missing, malformed,
  /// repeats a job or is longer than kMaxComparedJobs; 404 naming the first unknown job.
  std::vector<ComparedJob> loadComparedJobs(const Request& req) {
    const std::vector<std::string> ids = paramList(req, "jobs");
    if (ids.empty()) {
      throw ApiError(400, problem::kInvalidParameter, "Invalid parameter",
                     "jobs is required: a comma-separated list of job ids, e.g. ?jobs=3,5", "jobs", Json{{"in", "query"}});
    }
    if (ids.size() > kMaxComparedJobs) {
      throw ApiError(400, problem::kInvalidParameter, "Invalid parameter",
                     "jobs lists " + std::to_string(ids.size()) + " jobs; at most " + std::to_string(kMaxComparedJobs) +
                         " can be compared at once",
                     "jobs", Json{{"in", "query"}, {"value", ids.size()}, {"maximum", kMaxComparedJobs}});
    }
    std::vector<ComparedJob> jobs;
    for (const std::string& text : ids) {
      auto id = parseIndex(text);
      if (!id || *id < 1) {
        throw ApiError(400, problem::kInvalidParameter, "Invalid parameter",
                       "jobs holds '" + text + "', which is not a job id (a positive integer)", "jobs",
                       Json{{"in", "query"}, {"value", text}});
      }
      for (const ComparedJob& j : jobs) {
        if (j.job.id == *id) {
          throw ApiError(400, problem::kInvalidParameter, "Invalid parameter",
                         "jobs lists job " + text + " twice", "jobs", Json{{"in", "query"}, {"value", text}});
        }
      }
      auto job = m_ctx.store->job(*id);
      if (!job) {
        throw ApiError(404, problem::kNoSuchJob, "No such job",
                       "no job '" + text + "' (named in the jobs list; GET /jobs lists them)", "jobs",
                       Json{{"in", "query"}, {"value", text}});
      }
      jobs.push_back({*job, buildSummary(*job, m_ctx.store->runs(*id))});
    }
    return jobs;
  }

  static std::string columnLabel(const SummaryTable& table, const std::string& column) {
    return table.hasColumn(column) ? table.columnInfo(column).label : column;
  }

  /// The plot query options shared by summary.svg and /plot: xscale, yscale, width, height, ymin,
  /// ymax and yerror (a column of `table` holding each point's error half-width).
  static void readPlotOptions(const Request& req, const SummaryTable& table, PlotRequest& plot) {
    plot.xScale = scaleParam(req, "xscale");
    plot.yScale = scaleParam(req, "yscale");
    plot.width = static_cast<int>(intParam(req, "width", 800, kMinWidth, kMaxWidth));
    plot.height = static_cast<int>(intParam(req, "height", 500, kMinHeight, kMaxHeight));
    plot.yMin = numberParam(req, "ymin");
    plot.yMax = numberParam(req, "ymax");
    if (req.has_param("yerror")) plot.yError = req.get_param_value("yerror");
    if (!plot.yError.empty() && !table.hasColumn(plot.yError)) {
      throw ApiError(400, problem::kInvalidParameter, "Invalid parameter",
                     "yerror='" + plot.yError + "' is not a column of this summary", "yerror",
                     Json{{"in", "query"}, {"value", plot.yError}});
    }
  }

  /// A PNG of width x height x scale² pixels at most the cap (--max-render-pixels): the
  /// parameter that makes it larger is named.
  static void requireRenderable(const PlotRequest& plot, int scale, long long maxPixels) {
    const long long pixels = static_cast<long long>(plot.width) * plot.height * scale * scale;
    if (pixels <= maxPixels) return;
    const char* field = scale > 1 ? "scale" : "width";
    throw ApiError(400, problem::kInvalidParameter, "Invalid parameter",
                   "a PNG of " + std::to_string(plot.width * scale) + " x " + std::to_string(plot.height * scale) +
                       " pixels (width x height x scale) is larger than this server renders (" +
                       std::to_string(maxPixels) + " pixels, --max-render-pixels); lower " + field +
                       ", or ask for SVG (format=svg), which has no size limit",
                   field, Json{{"in", "query"}, {"pixels", pixels}, {"max_pixels", maxPixels}});
  }

  /// The plot as SVG, or with ?format=png&scale=1..4 as PNG.
  static void sendPlot(const Request& req, Response& res, const SummaryTable& table, const PlotRequest& plot,
                       RenderGate& gate) {
    const std::string format = req.has_param("format") ? req.get_param_value("format") : "svg";
    if (format != "svg" && format != "png") {
      throw ApiError(400, problem::kInvalidParameter, "Invalid parameter",
                     "format must be 'svg' or 'png', got '" + format + "'", "format",
                     Json{{"in", "query"}, {"value", format}, {"allowed", Json::array({"svg", "png"})}});
    }
    const int scale = static_cast<int>(intParam(req, "scale", 1, 1, 4));
    if (format == "png") requireRenderable(plot, scale, gate.maxPixels());
    const std::string svg = rupture::server::summarySvg(table, plot);
    if (format == "png") {
      const RenderGate::Slot slot = gate.acquire();
      res.set_content(renderPng(svg, plot.width * scale, plot.height * scale), "image/png");
    } else {
      res.set_content(svg, "image/svg+xml");
    }
  }

  static std::optional<double> numberParam(const Request& req, const char* name) {
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

  static AxisScale scaleParam(const Request& req, const char* name) {
    if (!req.has_param(name)) return AxisScale::Auto;
    const std::string v = req.get_param_value(name);
    if (v == "auto") return AxisScale::Auto;
    if (v == "linear") return AxisScale::Linear;
    if (v == "log") return AxisScale::Log;
    throw ApiError(400, problem::kInvalidParameter, "Invalid parameter",
                   std::string(name) + " must be auto, linear or log, got '" + v + "'", name,
                   Json{{"in", "query"}, {"value", v}, {"allowed", Json::array({"auto", "linear", "log"})}});
  }

  JobRecord loadJob(const Request& req) {
    const std::int64_t id = jobIdFrom(req);
    auto job = m_ctx.store->job(id);
    if (!job) throw noSuchJob(req.matches[1]);
    return *job;
  }

  RunRecord loadRun(const Request& req, const JobRecord& job) {
    auto run = m_ctx.store->run({job.id, runIndexFrom(req, job)});
    if (!run) throw noSuchJob(req.matches[1]);
    return *run;
  }

  /// The run, which must be successful with its file in place.
  RunRecord finishedRun(const Request& req, const JobRecord& job) {
    RunRecord run = loadRun(req, job);
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

  ServerContext& m_ctx;
};

struct Route {
  std::string pattern;
  std::vector<std::string> methods;  // GET, POST, DELETE
};

}  // namespace

void registerRoutes(HttpFrontend& http, ServerContext& context) {
  auto api = std::make_shared<Api>(context);
  // cpp-httplib would apply Range headers to every response, error documents included, and gets
  // ranges past the end wrong: downloads serve them (sendFile), everything else ignores them.
  http.setRequestSetup([](Request& req) { req.ranges.clear(); });
  auto wrap = [api](void (Api::*method)(const Request&, Response&)) {
    return [api, method](const Request& req, Response& res) {
      try {
        ((*api).*method)(req, res);
      } catch (const ApiError& e) {
        sendProblem(req, res, e);
      } catch (const rupture::SpecError& e) {
        sendProblem(req, res,
                    ApiError(400, problem::kInvalidSpec, "Invalid spec", e.what(), e.field(),
                             Json{{"value", e.value()}, {"allowed", e.allowed()}}));
      } catch (const nlohmann::json::exception& e) {
        // JSON type and range errors come from what the client sent (the server's own documents
        // are built from checked values).
        sendProblem(req, res, ApiError(400, problem::kInvalidRequest, "Invalid request",
                                       "the request holds a value the server cannot use: " +
                                           truncateUtf8(e.what(), 300)));
      } catch (const std::bad_alloc&) {
        // Not the client's mistake and not a bug: the machine is short of memory right now.
        logLine("out of memory answering " + req.method + " " + toValidUtf8(req.path));
        sendProblem(req, res, ApiError(503, problem::kUnavailable, "Service Unavailable",
                                       "the server could not get the memory this request needs right now; "
                                       "retry later (other requests or runs are using it)",
                                       "", Json{{"retry_after_s", 30}}));
      } catch (const std::exception& e) {
        sendInternalError(req, res, e.what());
      } catch (...) {
        sendInternalError(req, res, "non-standard exception");
      }
    };
  };

  const std::string id = "([^/]+)";
  http.Get("/", wrap(&Api::landing));
  http.Get("/health", wrap(&Api::health));
  http.Get("/openapi.yaml", wrap(&Api::openapi));
  http.Get("/api", wrap(&Api::openapi));
  http.Get("/conformance", wrap(&Api::conformance));
  http.Get("/processes", wrap(&Api::processes));
  http.Get("/processes/" + id, wrap(&Api::process));
  http.Post("/processes/" + id + "/execution", wrap(&Api::execute));
  http.Get("/jobs", wrap(&Api::jobs));
  http.Get("/jobs/" + id, wrap(&Api::job));
  http.Delete("/jobs/" + id, wrap(&Api::dismiss));
  http.Post("/jobs/" + id + "/retry", wrap(&Api::retry));
  http.Get("/jobs/" + id + "/results", wrap(&Api::jobResults));
  http.Get("/jobs/" + id + "/runs", wrap(&Api::runsList));
  http.Get("/jobs/" + id + "/runs/" + id, wrap(&Api::run));
  http.Get("/jobs/" + id + "/runs/" + id + "/results", wrap(&Api::runResults));
  http.Get("/jobs/" + id + "/runs/" + id + "/series", wrap(&Api::series));
  http.Get(R"(/jobs/([^/]+)/runs/([^/]+)/results\.xdmf)", wrap(&Api::runXdmf));
  http.Get("/jobs/" + id + "/runs/" + id + "/bundle", wrap(&Api::runBundle));
  http.Get("/jobs/" + id + "/summary", wrap(&Api::summary));
  http.Get(R"(/jobs/([^/]+)/summary\.svg)", wrap(&Api::summarySvg));
  http.Get("/summary", wrap(&Api::compareSummary));
  http.Get("/plot", wrap(&Api::comparePlot));

  // 405 (with Allow) for the other methods on every known path; OPTIONS answers with Allow.
  const std::vector<Route> routes = {
      {"/", {"GET"}},
      {"/health", {"GET"}},
      {"/openapi\\.yaml", {"GET"}},
      {"/api", {"GET"}},
      {"/conformance", {"GET"}},
      {"/processes", {"GET"}},
      {"/processes/" + id, {"GET"}},
      {"/processes/" + id + "/execution", {"POST"}},
      {"/jobs", {"GET"}},
      {"/jobs/" + id, {"GET", "DELETE"}},
      {"/jobs/" + id + "/results", {"GET"}},
      {"/jobs/" + id + "/retry", {"POST"}},
      {"/jobs/" + id + "/runs", {"GET"}},
      {"/jobs/" + id + "/runs/" + id, {"GET"}},
      {"/jobs/" + id + "/runs/" + id + "/results", {"GET"}},
      {"/jobs/" + id + "/runs/" + id + "/series", {"GET"}},
      {R"(/jobs/([^/]+)/runs/([^/]+)/results\.xdmf)", {"GET"}},
      {"/jobs/" + id + "/runs/" + id + "/bundle", {"GET"}},
      {"/jobs/" + id + "/summary", {"GET"}},
      {R"(/jobs/([^/]+)/summary\.svg)", {"GET"}},
      {"/summary", {"GET"}},
      {"/plot", {"GET"}},
  };
  for (const Route& route : routes) {
    std::string allow;
    for (const auto& m : route.methods) allow += (allow.empty() ? "" : ", ") + m;
    if (std::find(route.methods.begin(), route.methods.end(), "GET") != route.methods.end()) allow += ", HEAD";
    allow += ", OPTIONS";
    auto notAllowed = [allow](const Request& req, Response& res) {
      res.set_header("Allow", allow);
      sendProblem(req, res,
                  ApiError(405, problem::kMethodNotAllowed, "Method Not Allowed",
                           req.method + " is not allowed on " + req.path + "; allowed: " + allow));
    };
    auto has = [&](const char* m) {
      return std::find(route.methods.begin(), route.methods.end(), m) != route.methods.end();
    };
    if (!has("GET")) http.Get(route.pattern, notAllowed);
    if (!has("POST")) http.Post(route.pattern, httplib::Server::Handler(notAllowed));
    if (!has("DELETE")) http.Delete(route.pattern, httplib::Server::Handler(notAllowed));
    http.Put(route.pattern, httplib::Server::Handler(notAllowed));
    http.Patch(route.pattern, httplib::Server::Handler(notAllowed));
    http.Options(route.pattern, [allow](const Request&, Response& res) {
      res.status = 204;
      res.set_header("Allow", allow);
    });
  }

  // Before the body is read: the request guard (UTF-8, Host, read token, Origin, Content-Type), then
  // bodies without a length: chunked uploads escape cpp-httplib 0.11.4's body-size limit, and a POST
  // without Content-Length has no body by HTTP's framing rules (both 411).
  http.set_pre_routing_handler([&context](const Request& req, Response& res) {
    try {
      if (auto error = checkRequest(req, context.config)) {
        sendProblem(req, res, *error);
        return httplib::Server::HandlerResponse::Handled;
      }
      if (req.has_header("Transfer-Encoding")) {
        res.set_header("Connection", "close");
        sendProblem(req, res, problemForStatus(411));
        return httplib::Server::HandlerResponse::Handled;
      }
      if (req.method == "POST" && !req.has_header("Content-Length")) {
        sendProblem(req, res, problemForStatus(411, "a POST needs a Content-Length header (the body's size in bytes)"));
        return httplib::Server::HandlerResponse::Handled;
      }
    } catch (const std::exception& e) {
      sendInternalError(req, res, e.what());
      return httplib::Server::HandlerResponse::Handled;
    }
    return httplib::Server::HandlerResponse::Unhandled;
  });

  // Statuses produced by the HTTP layer itself (404 without a route, 413, 400 bad request line, ...)
  // get a problem document too. Nothing may throw out of here: cpp-httplib calls it outside its
  // try block, and an exception would end the process.
  http.set_error_handler(httplib::Server::HandlerWithResponse([](const Request& req, Response& res) {
    if (!res.body.empty() || res.content_length_ > 0) return httplib::Server::HandlerResponse::Unhandled;
    try {
      sendProblem(req, res, problemForStatus(res.status));
    } catch (const std::exception& e) {
      sendInternalError(req, res, e.what());
    }
    return httplib::Server::HandlerResponse::Handled;
  }));
  http.set_exception_handler([](const Request& req, Response& res, std::exception_ptr ep) {
    std::string what = "unknown exception";
    try {
      if (ep) std::rethrow_exception(ep);
    } catch (const std::bad_alloc&) {
      try {
        sendProblem(req, res, ApiError(503, problem::kUnavailable, "Service Unavailable",
                                       "the server could not get the memory this request needs right now; retry later",
                                       "", Json{{"retry_after_s", 30}}));
        return;
      } catch (...) {
        what = "out of memory";
      }
    } catch (const std::exception& e) {
      what = e.what();
    } catch (...) {
    }
    sendInternalError(req, res, what);
  });
  http.set_post_routing_handler([](const Request&, Response& res) {
    res.set_header("X-Content-Type-Options", "nosniff");
    if (!res.has_header("Cache-Control")) res.set_header("Cache-Control", "no-store");
  });
  if (context.config.logRequests) {
    http.set_logger([](const Request& req, const Response& res) {
      logLine(req.remote_addr + " \"" + req.method + " " + req.target + "\" " + std::to_string(res.status));
    });
  }
}

}  // namespace rupture::server
