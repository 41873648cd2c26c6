// GET /, /health, /openapi.yaml, /conformance: what the service is and whether it is well.
#include <chrono>

#include <httplib.h>

#include "common/heap.hpp"
#include "routes/answers.hpp"
#include "routes/documents.hpp"
#include "routes/handlers.hpp"
#include "routes/request_params.hpp"
#include "rupture/run.hpp"
#include "views/html_views.hpp"
#include "views/render_gate.hpp"


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

namespace handlers {

void getLanding(ServerContext&, const Request& req, Response& res) {
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

void getHealth(ServerContext& ctx, const Request&, Response& res) {
  Json doc = Json::object();
  doc["status"] = ctx.stopping ? "stopping" : "ok";
  doc["version"] = RUPTURE_VERSION;
  doc["build"] = buildDocument();
  doc["executor"] = ctx.scheduler->name();
  doc["workers"] = ctx.scheduler->workers();
  doc["threads_per_run"] = ctx.scheduler->threadsPerRun();
  const Executor::RankLimit ranks = ctx.scheduler->rankLimit();
  doc["max_ranks"] = ranks.ranks;
  doc["max_ranks_reason"] = ranks.why;
  doc["running"] = ctx.store->runningCount();  // the store's view, as GET /jobs shows it
  doc["queue_depth"] = ctx.store->queueDepth();
  doc["waiting_for_disk"] = ctx.scheduler->waitingForDisk();          // below --min-free-bytes
  doc["unrecorded_outcomes"] = ctx.scheduler->unrecordedOutcomes();   // finished on disk, store retrying
  doc["resident_memory_bytes"] = residentBytes();  // the server's, so a memory leak shows from outside
  doc["renders"] = {{"running", ctx.renders->running()}, {"waiting", ctx.renders->waiting()},
                    {"max_running", ctx.renders->maxRunning()}, {"max_waiting", ctx.renders->maxWaiting()}};
  doc["uptime_s"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - ctx.startedAt).count();
  Json scenarios = Json::array();
  for (const auto& s : rupture::listScenarios()) scenarios.push_back(s.name);
  doc["scenarios"] = scenarios;
  sendJson(res, doc);
}

void getOpenApi(ServerContext&, const Request&, Response& res) {
  res.set_content(openApiYaml(), "application/vnd.oai.openapi;version=3.0");
}

void getConformance(ServerContext&, const Request&, Response& res) {
  const std::string base = "http://www.opengis.net/spec/ogcapi-processes-1/1.0/conf/";
  sendJson(res, Json{{"conformsTo", Json::array({base + "core", base + "json", base + "job-list",
                                                 base + "dismiss", base + "ogc-process-description",
                                                 base + "oas30"})}});
}

}  // namespace handlers

}  // namespace rupture::server
