// GET /processes, /processes/{id} and POST /processes/{id}/execution: the scenarios and submitting
// a job (validation, queue bounds, idempotent retries).
#include <algorithm>
#include <cstdio>
#include <optional>

#include <httplib.h>

#include "common/heap.hpp"
#include "common/log.hpp"
#include "core/fnv1a.hpp"
#include "http/json_body.hpp"
#include "http/request_guard.hpp"
#include "jobs/job_preview.hpp"
#include "views/preview_picture.hpp"
#include "jobs/replicates.hpp"
#include "jobs/sweep.hpp"
#include "routes/answers.hpp"
#include "routes/documents.hpp"
#include "routes/handlers.hpp"
#include "routes/request_params.hpp"
#include "rupture/run.hpp"
#include "studies/refinement.hpp"
#include "views/html_views.hpp"
#include "views/render_gate.hpp"
#include "views/submit_form.hpp"

namespace rupture::server {
namespace fs = std::filesystem;
using httplib::Request;
using httplib::Response;

namespace {

/// Queued work is bounded for the whole server, in runs (--max-queued-runs) and in stored bytes
/// of inputs (--max-queued-bytes): a job that can never fit is the client's mistake (400); one
/// that fits once the queue drains is told to come back (503).
/// A dry run (`queueNow` false) checks only the bounds no wait can lift: it queues nothing.
void requireQueueRoom(ServerContext& ctx, std::size_t runs, std::size_t inputBytes, bool queueNow) {
  struct Bound {
    std::size_t amount, queued, limit;
    const char *what, *flag, *key, *field, *title;
  };
  const Bound bounds[] = {
      {inputBytes, static_cast<std::size_t>(std::max(0LL, ctx.store->queuedInputBytes())),
       static_cast<std::size_t>(ctx.config.maxQueuedBytes), "bytes of inputs", "--max-queued-bytes", "bytes", "inputs",
       "Inputs too large"},
      {runs, static_cast<std::size_t>(std::max(0, ctx.store->queueDepth())),
       static_cast<std::size_t>(ctx.config.maxQueuedRuns), "runs", "--max-queued-runs", "runs", "sweep", "Too many runs"}};
  for (const Bound& b : bounds) {
    const std::string key = b.key, flag = b.flag;
    if (b.amount > b.limit) {
      throw ApiError(400, b.key == std::string("runs") ? problem::kTooManyRuns : problem::kPayloadTooLarge, b.title,
                     "the job has " + std::to_string(b.amount) + " " + b.what + "; unfinished jobs may hold at most " +
                         std::to_string(b.limit) + " in this server (" + flag + ")",
                     b.field, Json{{"in", "body"}, {"job_" + key, b.amount}, {"max_queued_" + key, b.limit}});
    }
    if (queueNow && b.queued + b.amount > b.limit) {
      throw ApiError(503, problem::kQueueFull, "Queue full",
                     "unfinished jobs hold " + std::to_string(b.queued) + " " + b.what + " and this server allows " +
                         std::to_string(b.limit) + " (" + flag + "); this job's " + std::to_string(b.amount) +
                         " fit once some have finished: retry later",
                     "", Json{{"queued_" + key, b.queued}, {"max_queued_" + key, b.limit}, {"retry_after_s", 60}});
    }
  }
}

/// The first control character of UTF-8 text (C0, DEL, or C1 U+0080 to U+009F), as "U+0000", or
/// nothing when it holds none.
std::optional<std::string> controlCharacterAt(const std::string& text) {
  for (std::size_t i = 0; i < text.size(); ++i) {
    const auto byte = static_cast<unsigned char>(text[i]);
    unsigned code = 0x100;
    if (byte < 0x20 || byte == 0x7f) code = byte;
    else if (byte == 0xc2 && i + 1 < text.size() && static_cast<unsigned char>(text[i + 1]) <= 0x9f &&
             static_cast<unsigned char>(text[i + 1]) >= 0x80)
      code = static_cast<unsigned char>(text[i + 1]);
    if (code < 0x100) {
      char out[8];
      std::snprintf(out, sizeof out, "U+%04X", code);
      return std::string(out) + " at byte " + std::to_string(i);
    }
  }
  return std::nullopt;
}

/// The Idempotency-Key header: 1 to 200 visible ASCII characters, or "" when absent.
std::string idempotencyKeyOf(const Request& req) {
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

/// The text a submission is identified by: the scenario and the body with keys sorted.
std::string requestText(const std::string& scenario, const Json& body) {
  return scenario + "\n" + nlohmann::json(body).dump(-1, ' ', false, Json::error_handler_t::replace);
}

/// Servers before 2026-11-27 hashed with a mistyped offset basis (a digit short of FNV's); the
/// keys they stored are still honoured, so a retry across an upgrade still replays.
bool sameRequest(const std::string& storedHash, const std::string& requestHash, const std::string& scenario,
                 const Json& body) {
  constexpr std::uint64_t kEarlierServersBasis = 1469598103934665603ull;
  return storedHash == requestHash || storedHash == fnv1aHex(requestText(scenario, body), kEarlierServersBasis);
}

/// Identifies a submission: the scenario and the body with keys sorted (FNV-1a, 64 bits, hex).
std::string requestFingerprint(const std::string& scenario, const Json& body) {
  return fnv1aHex(requestText(scenario, body));
}

/// Answers a repeated Idempotency-Key: the earlier job (201, as the first answer was), or 422
/// when the key came with a different request.
void replayJob(ServerContext& ctx, const Request& req, Response& res, const IdempotentJob& earlier,
               const std::string& requestHash, const std::string& scenario, const Json& body) {
  if (!sameRequest(earlier.requestHash, requestHash, scenario, body)) {
    throw ApiError(422, problem::kIdempotencyKeyReused, "Idempotency key reused",
                   "this Idempotency-Key was first used for a different request (job " +
                       std::to_string(earlier.id) + "); use a new key for a new submission",
                   "Idempotency-Key", Json{{"in", "header"}, {"jobID", std::to_string(earlier.id)}});
  }
  auto found = ctx.store->jobWithRuns(earlier.id);
  if (!found) throw noSuchJob(std::to_string(earlier.id));
  auto& [record, runs] = *found;
  res.set_header("Location", "/jobs/" + std::to_string(earlier.id));
  res.set_header("Idempotent-Replayed", "true");
  if (req.get_header_value("Prefer").find("respond-async") != std::string::npos) {
    res.set_header("Preference-Applied", "respond-async");
  }
  sendJson(res, statusInfo(record, &runs), 201);
}

/// A POST /processes/{id}/execution body, checked member by member: the spec's inputs for `scenario`
/// and the job's name (the sweep, replicates and refinement are read by planJob).
struct Submission {
  Json body;
  std::string name;
  const Json& inputs() const { return body.at("inputs"); }
  const Json* member(const char* key) const {
    auto it = body.find(key);
    return it == body.end() ? nullptr : &*it;
  }
};

Submission readSubmission(const std::string& text, const std::string& scenario) {
  Submission s{parseJsonBody(text), {}};
  const Json& body = s.body;
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
  if (auto n = body.find("name"); n != body.end() && !n->is_null()) {
    if (!n->is_string() || n->get<std::string>().size() > 200) {
      throw ApiError(400, problem::kInvalidRequest, "Invalid request",
                     "name must be a string of at most 200 characters", "name", Json{{"in", "body"}});
    }
    // A name is shown in pages, CSV and file names: no control characters (C0, DEL, C1).
    if (const auto at = controlCharacterAt(n->get<std::string>())) {
      throw ApiError(400, problem::kInvalidRequest, "Invalid request",
                     "name holds a control character (" + *at + "); a name is printable text", "name",
                     Json{{"in", "body"}});
    }
    s.name = n->get<std::string>();
  }
  return s;
}

/// The job a submission makes: its sweep expanded and replicated into runs, each run's spec checked
/// against the operator's limits (size, memory, queue room, runs per job), and its study (replicates,
/// refinement) recorded. With `forecasts` (a dry run) each run's estimate is kept there and the
/// queue's present fill is not checked: a preview is not refused because others are queued.
NewJob planJob(ServerContext& ctx, const std::string& scenario, const Submission& submission,
               std::vector<RunForecast>* forecasts = nullptr) {
  const Json& inputs = submission.inputs();
  const SweepPlan plan = parseSweepPlan(submission.member("sweep"), submission.member("sweep_mode"));
  const ReplicatePlan replicates = parseReplicatePlan(submission.member("replicates"), scenario, plan);
  const std::size_t maxRuns = static_cast<std::size_t>(ctx.config.maxRuns);
  const std::size_t points = runCount(plan);
  if (points <= maxRuns && points * static_cast<std::size_t>(replicates.count) > maxRuns) {
    const std::size_t total = points * static_cast<std::size_t>(replicates.count);
    throw ApiError(400, problem::kTooManyRuns, "Too many runs",
                   "the sweep's " + std::to_string(points) + " points x " +
                       std::to_string(replicates.count) + " replicates make " + std::to_string(total) +
                       " runs; this server accepts at most " + std::to_string(maxRuns) + " per job (--max-runs)",
                   "replicates.count", Json{{"in", "body"}, {"runs", total}, {"max_runs", maxRuns}});
  }
  NewJob job;
  // Every spec holds the whole inputs (a large description, many probes): each run's spec is built,
  // validated and reduced to its patch against the base before the next, so the POST holds the
  // inputs a few times over, never once per run (docs/server.md, "Security and limits").
  const Json base = jobBaseSpec(scenario, inputs);
  const ReplicateExpander replicator(replicates, scenario);
  const Executor::RankLimit rankLimit = ctx.scheduler->rankLimit();
  forEachSweepPoint(scenario, inputs, plan, maxRuns, [&](SweepPoint&& point) {
    replicator.expand(std::move(point), [&](ReplicatedPoint&& rp) {
      const rupture::RunEstimate estimate =
          validateSweepPoint(rp.point, job.runs.size(), plan, static_cast<double>(ctx.config.maxElements),
                             ctx.maxRunMemory, static_cast<double>(ctx.config.maxRunSteps), rankLimit.ranks, rankLimit.why);
      if (forecasts) forecasts->push_back({rp.point.swept, rp.replicate, estimate});
      job.runPatches.push_back(Json::diff(base, rp.point.spec).dump());
      job.runs.emplace_back(std::move(rp.point.swept), Json());
      job.replicates.push_back(rp.replicate);
    });
  });
  const std::size_t runCount = job.runs.size();
  requireQueueRoom(ctx, runCount, inputs.dump().size(), forecasts == nullptr);
  const std::optional<RefinePlan> refine =
      parseRefinePlan(submission.member("refine"), scenario, plan, replicates.count, runCount, maxRuns);

  job.processId = scenario;
  job.name = submission.name;
  job.sweepMode = toString(plan.mode);
  job.sweptPaths = Json::array();
  for (const SweepAxis& axis : plan.axes) job.sweptPaths.push_back(axis.path);
  job.inputs = inputs;
  job.request = submission.body;  // what "Submit a variant" starts from
  const Json* sweep = submission.member("sweep");
  job.sweep = sweep && sweep->is_object() ? *sweep : Json::object();
  job.provenance = buildDocument();
  job.provenance["executor"] = ctx.scheduler->name();
  job.provenance["threads_per_run"] = ctx.scheduler->threadsPerRun();
  if (replicates.requested() || refine) {
    job.study = Json::object();
    if (replicates.requested()) job.study["replicates"] = replicates.toJson();
    if (refine) {
      job.study["refine"] = refine->toJson();
      job.study["refinement"] = {{"state", "pending"}, {"rounds", 0}, {"runs_added", 0}, {"points", Json::array()}};
    }
  }
  return job;
}

/// The DryRun document's `picture` when asked (picture=true): the first run's discretisation, drawn
/// behind the render gate and kept for the page to fetch, or why there is none (jobs/preview_picture.hpp).
Json firstRunPicture(ServerContext& ctx, const std::string& scenario, const Submission& submission, const NewJob& job,
                     const std::vector<RunForecast>& forecasts) {
  const PicturePolicy policy;
  if (forecasts.empty() || job.runPatches.empty()) return Json{{"available", false}, {"reason", "the job has no run"}};
  if (std::optional<Json> refused = pictureRefusal(forecasts.front().estimate, policy)) return *refused;
  const Json spec = jobBaseSpec(scenario, submission.inputs()).patch(Json::parse(job.runPatches.front()));
  const std::string note = forecasts.size() > 1 ? "run 0, the first of the job's " + std::to_string(forecasts.size()) +
                                                      " runs (the others differ by their swept or replicated values)"
                                                : "";
  const RenderGate::Slot slot = ctx.renders->acquire();  // a build is a render's cost: bounded alike
  PreviewPicture picture = previewPicture(spec, forecasts.front().estimate, policy, note,
                                          (ctx.dataDir / "cache").string(), ctx.stopping);
  Json doc = std::move(picture.doc);
  doc["run_index"] = 0;
  doc["runs"] = forecasts.size();
  if (doc.value("available", false))
    doc["href"] = "/processes/" + scenario + "/previews/" +
                  ctx.previews->put(scenario, std::move(picture.png), doc.value("media_type", "image/png"));
  return doc;
}

}  // namespace

namespace handlers {

void getProcesses(ServerContext&, const Request& req, Response& res) {
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

void getProcess(ServerContext& ctx, const Request& req, Response& res) {
  const std::string name = req.matches[1];
  const rupture::ScenarioInfo* info = rupture::findScenario(name);
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
      {"max_runs", ctx.config.maxRuns},
      {"max_replicates", kMaxReplicates},
  };
  if (wantsHtml(req)) {
    // ?from=JOB: the form starts from that job's inputs as posted, to submit a variant of it.
    Json start = Json::object(), request;
    if (req.has_param("from")) {
      const auto id = parseIndex(req.get_param_value("from"));
      const auto job = id ? ctx.store->job(*id) : std::nullopt;
      if (!job) throw noSuchJob(req.get_param_value("from").substr(0, 40));
      if (job->processId != name)
        throw ApiError(400, problem::kInvalidParameter, "Invalid parameter",
                       "job " + std::to_string(*id) + " runs " + job->processId + ", not " + name, "from",
                       Json{{"in", "query"}});
      if (job->inputs.is_object()) start = job->inputs;
      request = submittedRequest(*job);  // its sweep, replicates and name fill the form too
    }
    return sendHtml(res, processHtml(doc, start, request));
  }
  sendJson(res, doc);
}

namespace {

void submitJob(ServerContext& ctx, const Request& req, Response& res);

}  // namespace

void postExecution(ServerContext& ctx, const Request& req, Response& res) {
  // The plan of a large sweep frees megabytes that glibc would keep: give them back, so the
  // server's resident memory returns to where it was (docs/server.md, "Security and limits").
  struct ReturnHeap {
    ~ReturnHeap() { returnFreeHeapToSystem(); }
  } returnHeap;
  submitJob(ctx, req, res);
}

namespace {

void submitJob(ServerContext& ctx, const Request& req, Response& res) {
  requireToken(ctx, req);
  const bool dryRun = choiceParam(req, "dry_run", {"true", "false"}).value_or("false") == "true";
  const bool picture = choiceParam(req, "picture", {"true", "false"}).value_or("false") == "true";
  if (picture && !dryRun) {
    throw ApiError(400, problem::kInvalidParameter, "Invalid parameter",
                   "picture=true draws the preview's sample: it goes with dry_run=true (a submission is not drawn)",
                   "picture", Json{{"in", "query"}, {"value", "true"}, {"allowed", Json::array({"false"})}});
  }
  if (ctx.stopping) {
    throw ApiError(503, problem::kShuttingDown, "Service Unavailable",
                   "the server is stopping; submit again once it is back");
  }
  const std::string scenario = req.matches[1];
  if (!knownScenario(scenario)) throw noSuchProcess(scenario);
  const Submission submission = readSubmission(req.body, scenario);
  if (dryRun) {  // checked as the real submission below; nothing is stored or queued
    std::vector<RunForecast> forecasts;
    const NewJob job = planJob(ctx, scenario, submission, &forecasts);
    const PreviewContext where{ctx.scheduler->threadsPerRun(), ctx.scheduler->workers(), ctx.maxRunMemory,
                               std::max(0, ctx.store->queueDepth()), ctx.config.maxQueuedRuns};
    Json doc = jobPreview(scenario, job, forecasts, where);
    if (picture) doc["picture"] = firstRunPicture(ctx, scenario, submission, job, forecasts);
    return sendJson(res, doc);
  }

  // Idempotency-Key: a retry of a POST whose answer was lost gets the job the first one made.
  const std::string idempotencyKey = idempotencyKeyOf(req);
  const std::string requestHash =
      idempotencyKey.empty() ? std::string() : requestFingerprint(scenario, submission.body);
  if (!idempotencyKey.empty()) {
    if (auto earlier = ctx.store->jobForIdempotencyKey(idempotencyKey)) {
      replayJob(ctx, req, res, *earlier, requestHash, scenario, submission.body);
      return;
    }
  }
  NewJob job = planJob(ctx, scenario, submission);
  job.idempotencyKey = idempotencyKey;
  job.requestHash = requestHash;
  const CreatedJob created = ctx.store->createJobOnce(job);
  if (!created.created) {  // a concurrent request with the same key won the race
    replayJob(ctx, req, res, IdempotentJob{created.id, created.requestHash}, requestHash, scenario, submission.body);
    return;
  }
  const std::int64_t id = created.id;
  const int runCount = static_cast<int>(job.runs.size());
  ctx.scheduler->enqueue(id, runCount);
  logLine("job " + std::to_string(id) + " accepted: " + scenario + ", " + std::to_string(runCount) + " run(s)" +
          (job.name.empty() ? "" : ", \"" + job.name + "\""));

  auto [record, runs] = ctx.store->jobWithRuns(id).value();
  res.set_header("Location", "/jobs/" + std::to_string(id));
  if (req.get_header_value("Prefer").find("respond-async") != std::string::npos) {
    res.set_header("Preference-Applied", "respond-async");
  }
  sendJson(res, statusInfo(record, &runs), 201);
}

}  // namespace

}  // namespace handlers

}  // namespace rupture::server
