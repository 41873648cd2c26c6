#include "routes/documents.hpp"

#include <algorithm>
#include <cmath>

#include "common/public_message.hpp"
#include "io/provenance.hpp"
#include "jobs/progress_info.hpp"
#include "routes/answers.hpp"
#include "rupture/progress.hpp"

namespace rupture::server {
namespace fs = std::filesystem;
using httplib::Request;
using httplib::Response;

int percent(double fraction) { return static_cast<int>(std::floor(std::clamp(fraction, 0.0, 1.0) * 100.0 + 1e-9)); }

Json runDocument(const JobRecord& job, const RunRecord& run) {
  Json doc = Json::object();
  doc["index"] = run.key.index;
  Json swept = Json::object();
  for (std::size_t i = 0; i < job.sweptPaths.size() && i < run.swept.size(); ++i) {
    swept[job.sweptPaths[i].get<std::string>()] = run.swept[i];
  }
  doc["swept"] = swept;
  doc["status"] = toString(run.status);
  // 100 only once the run has finished successfully (rupture::runningFraction): a failed or
  // dismissed run shows the progress it reached.
  doc["progress"] = run.status == Status::Successful ? 100 : percent(rupture::runningFraction(run.progress));
  if (!run.started.empty()) doc["started"] = run.started;
  if (!run.finished.empty()) doc["finished"] = run.finished;
  if (run.attempts > 1) doc["attempts"] = run.attempts;
  if (run.resumes > 0) {  // continued from its checkpoint after a stop, a crash or a time limit
    doc["resumes"] = run.resumes;
    doc["resumed_from_step"] = run.resumedFromStep;
  }
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

Json buildDocument() {
  const rupture::io::BuildInfo& b = rupture::io::buildInfo();
  return {{"rupture_version", b.version}, {"git_commit", b.commit},      {"compiler", b.compiler},
          {"compile_flags", b.flags},    {"build_type", b.buildType},   {"host_processor", rupture::io::hostProcessor()}};
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
  // 100 only for a successful job; a failed or dismissed one shows how far its runs got.
  doc["progress"] = job.status == Status::Successful ? 100 : percent(rupture::runningFraction(job.progress));
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
  if (job.provenance.is_object()) doc["provenance"] = job.provenance;
  if (runs) {
    Json list = Json::array();
    for (const RunRecord& r : *runs) list.push_back(runDocument(job, r));
    doc["runs"] = list;
  }
  const std::string base = "/jobs/" + id;
  doc["links"] = Json::array({
      link(base, "self", kJsonType, "this job's status"),
      link(base + "/results", std::string(kOgcRel) + "results", kHdf5Type, "all runs in one HDF5 file"),
      link(base + "/crate", "describedby", "application/zip", "RO-Crate: request, specs, results, summary, provenance"),
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

}  // namespace rupture::server
