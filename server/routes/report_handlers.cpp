// A validation job's report (docs/validation.md): the table of every case's quantities against
// their references, as HTML with each case's figure inline, JSON or CSV, made from the job's run
// files by the same functions as `rupture validate-suite`.
#include <httplib.h>

#include "io/provenance.hpp"
#include "routes/answers.hpp"
#include "routes/handlers.hpp"
#include "routes/request_params.hpp"
#include "rupture/validation.hpp"
#include "views/html_page.hpp"

namespace rupture::server {
using httplib::Request;
using httplib::Response;

namespace handlers {

void getJobReport(ServerContext& ctx, const Request& req, Response& res) {
  refuseUnknownParams(req, {"format"});
  const std::string format = choiceParam(req, "format", {"html", "json", "csv"}).value_or("html");
  const JobRecord job = loadJob(ctx, req);
  if (job.processId != "validation")
    throw ApiError(404, problem::kNoResults, "No report",
                   "job " + std::to_string(job.id) + " runs " + job.processId +
                       "; a report is made for validation jobs (POST /processes/validation/execution)");
  std::vector<nlohmann::json> results;
  std::string level;
  int pending = 0;
  for (const RunRecord& run : ctx.store->runs(job.id)) {
    const Json spec = runSpec(job, run);
    const std::string caseId = spec.value("case", ""), runLevel = spec.value("level", "full");
    if (level.empty()) level = runLevel;
    if (run.status == Status::Successful) {
      try {
        results.push_back(rupture::validation::readCaseResult((ctx.resultsDir / run.resultPath).string()));
      } catch (const std::exception& e) {
        results.push_back(rupture::validation::caseThatCouldNotRun(caseId, runLevel, e.what()));
      }
    } else if (run.status == Status::Failed || run.status == Status::Dismissed) {
      results.push_back(rupture::validation::caseThatCouldNotRun(
          caseId, runLevel, run.status == Status::Failed ? "run failed: " + run.error : "run dismissed"));
    } else {
      ++pending;
    }
  }
  const rupture::io::BuildInfo& build = rupture::io::buildInfo();
  nlohmann::json context = {{"job", job.id}, {"status", toString(job.status)},
                  {"rupture", build.version + " (" + build.commit + ")"}, {"host", rupture::io::hostProcessor()}};
  if (pending > 0) context["runs still to finish"] = pending;
  const auto report = rupture::validation::buildSuiteReport(results, level.empty() ? "full" : level, context, true);
  if (format == "json")
    res.set_content(report.json, kJsonType);
  else if (format == "csv")
    res.set_content(report.csv, kCsvType);
  else  // with the CSP and X-Frame-Options of every other page
    sendHtml(res, html::document(report.html));
}

}  // namespace handlers
}  // namespace rupture::server
