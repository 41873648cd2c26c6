#include "views/ro_crate.hpp"

#include <chrono>
#include <string>
#include <system_error>

#include "common/problem.hpp"
#include "common/public_message.hpp"
#include "common/utc_time.hpp"
#include "io/provenance.hpp"
#include "studies/summary.hpp"

namespace rupture::server {

namespace {

namespace fs = std::filesystem;

constexpr const char* kCrate = "https://w3id.org/ro/crate/1.1";
constexpr const char* kProcessRun = "https://w3id.org/ro/wfrun/process/0.5";
constexpr const char* kWorkflowRun = "https://w3id.org/ro/wfrun/workflow/0.5";
constexpr const char* kWorkflowCrate = "https://w3id.org/workflowhub/workflow-ro-crate/1.0";

Json idRef(const std::string& id) { return Json{{"@id", id}}; }

std::int64_t modified(const fs::path& path) {
  std::error_code ec;
  const auto t = fs::last_write_time(path, ec);
  if (ec) return 0;
  return std::chrono::duration_cast<std::chrono::seconds>(std::chrono::file_clock::to_sys(t).time_since_epoch()).count();
}

const char* actionStatus(Status status) {
  switch (status) {
    case Status::Successful: return "http://schema.org/CompletedActionStatus";
    case Status::Failed: return "http://schema.org/FailedActionStatus";
    case Status::Running: return "http://schema.org/ActiveActionStatus";
    default: return "http://schema.org/PotentialActionStatus";  // accepted or dismissed: never ran
  }
}

/// The crate's files as they are added: the archive and the metadata's data entities together.
class CrateBuilder {
public:
  explicit CrateBuilder(std::int64_t mtime) : m_mtime(mtime) {}

  void text(const std::string& id, const std::string& bytes, Json entity) {
    m_zip->addText(id, bytes, m_mtime);
    add(id, bytes.size(), std::move(entity));
  }
  void file(const std::string& id, const fs::path& path, Json entity) {
    m_zip->addFile(id, path, modified(path));
    add(id, fs::file_size(path), std::move(entity));
  }
  Json& graph() { return m_graph; }
  const Json& parts() const { return m_parts; }
  std::shared_ptr<ZipArchive> finish(const Json& metadata) {
    // The metadata is written last (it lists the others' sizes); readers find it by name.
    m_zip->addText("ro-crate-metadata.json", metadata.dump(2) + "\n", m_mtime);
    m_zip->finish();
    return m_zip;
  }

private:
  void add(const std::string& id, std::uint64_t size, Json entity) {
    entity["@id"] = id;
    if (!entity.contains("@type")) entity["@type"] = "File";
    entity["contentSize"] = std::to_string(size);
    m_graph.push_back(std::move(entity));
    m_parts.push_back(idRef(id));
  }
  std::shared_ptr<ZipArchive> m_zip = std::make_shared<ZipArchive>();
  std::int64_t m_mtime;
  Json m_graph = Json::array(), m_parts = Json::array();
};

}  // namespace

std::shared_ptr<ZipArchive> jobCrate(const JobRecord& job, const std::vector<RunRecord>& runs,
                                     const fs::path& resultsDir) {
  const std::int64_t now =
      std::chrono::duration_cast<std::chrono::seconds>(std::chrono::system_clock::now().time_since_epoch()).count();
  CrateBuilder crate(now);
  const std::string jobName = "job " + std::to_string(job.id) + (job.name.empty() ? "" : " (" + job.name + ")");

  crate.text("request.json", dumpJson(submittedRequest(job)),
             {{"@type", Json::array({"File", "SoftwareSourceCode", "ComputationalWorkflow"})},
              {"name", "The sweep of " + job.processId + " that made " + jobName},
              {"description", "The request as the server accepted it: POST it to /processes/" + job.processId +
                                  "/execution to run the same sweep again."},
              {"encodingFormat", "application/json"},
              {"programmingLanguage", idRef("#rupture-sweep-request")}});

  Json runActions = Json::array(), jobResults = Json::array();
  for (const RunRecord& run : runs) {
    const std::string stem = "runs/run-" + std::to_string(run.key.index);
    crate.text(stem + ".json", dumpJson(runSpec(job, run)),
               {{"name", "Spec of run " + std::to_string(run.key.index)},
                {"description", "The full scenario spec the run executed (api/schemas/" + job.processId + ".schema.json)"},
                {"encodingFormat", "application/json"}});
    Json action = {{"@id", "#run-" + std::to_string(run.key.index)},
                   {"@type", "CreateAction"},
                   {"name", "Run " + std::to_string(run.key.index) + " of " + jobName},
                   {"instrument", idRef("#rupture")},
                   {"object", Json::array({idRef(stem + ".json")})},
                   {"actionStatus", idRef(actionStatus(run.status))}};
    if (!run.started.empty()) action["startTime"] = run.started;
    if (!run.finished.empty()) action["endTime"] = run.finished;
    if (!run.error.empty()) action["error"] = publicMessage(run.error);
    if (run.status == Status::Successful && !run.resultPath.empty()) {
      crate.file(stem + ".h5", resultsDir / run.resultPath,
                 {{"name", "Result of run " + std::to_string(run.key.index)},
                  {"description", "HDF5 result file; /provenance holds its build, host, threads, spec digest, seeds and times"},
                  {"encodingFormat", "application/x-hdf5"}});
      action["result"] = Json::array({idRef(stem + ".h5")});
      jobResults.push_back(idRef(stem + ".h5"));
    }
    runActions.push_back(std::move(action));
  }
  const SummaryTable table = buildSummary(job, runs);
  crate.text("summary.json", dumpJson(summaryJson(table)),
             {{"name", "Summary of " + jobName}, {"description", "One row per run: swept values and result scalars, with units"},
              {"encodingFormat", "application/json"}});
  crate.text("summary.csv", summaryCsv(table),
             {{"name", "Summary of " + jobName + " (CSV)"}, {"encodingFormat", "text/csv"}});
  jobResults.push_back(idRef("summary.json"));
  jobResults.push_back(idRef("summary.csv"));

  const Json provenance = job.provenance.is_object() ? job.provenance : Json::object();
  const io::BuildInfo& build = io::buildInfo();
  const std::string version = provenance.value("rupture_version", build.version);
  Json jobAction = {{"@id", "#job-" + std::to_string(job.id)},
                    {"@type", "CreateAction"},
                    {"name", "Execution of " + jobName},
                    {"instrument", idRef("request.json")},
                    {"object", Json::array()},
                    {"result", jobResults},
                    {"actionStatus", idRef(actionStatus(job.status == Status::Successful ? Status::Successful
                                                      : job.status == Status::Failed ? Status::Failed
                                                                                     : Status::Accepted))}};
  for (const RunRecord& run : runs) jobAction["object"].push_back(idRef("runs/run-" + std::to_string(run.key.index) + ".json"));
  if (!job.started.empty()) jobAction["startTime"] = job.started;
  if (!job.finished.empty()) jobAction["endTime"] = job.finished;

  Json mentions = Json::array({idRef(jobAction["@id"])});
  for (const Json& a : runActions) mentions.push_back(idRef(a["@id"]));

  Json graph = Json::array();
  graph.push_back({{"@id", "ro-crate-metadata.json"},
                   {"@type", "CreativeWork"},
                   {"conformsTo", Json::array({idRef(kCrate), idRef(kWorkflowCrate)})},
                   {"about", idRef("./")}});
  graph.push_back({{"@id", "./"},
                   {"@type", "Dataset"},
                   {"name", "Rupture " + jobName + ": " + job.processId},
                   {"description", "The runs of " + jobName + " of the " + job.processId +
                                       " scenario, their specs, results and summary, as run by Rupture " + version},
                   {"datePublished", job.finished.empty() ? utcNow() : job.finished},
                   {"license", idRef("#license")},
                   {"conformsTo", Json::array({idRef(kProcessRun), idRef(kWorkflowRun), idRef(kWorkflowCrate)})},
                   {"mainEntity", idRef("request.json")},
                   {"hasPart", crate.parts()},
                   {"mentions", mentions}});
  graph.push_back({{"@id", kProcessRun}, {"@type", "CreativeWork"}, {"name", "Process Run Crate"}, {"version", "0.5"}});
  graph.push_back({{"@id", kWorkflowRun}, {"@type", "CreativeWork"}, {"name", "Workflow Run Crate"}, {"version", "0.5"}});
  graph.push_back({{"@id", kWorkflowCrate}, {"@type", "CreativeWork"}, {"name", "Workflow RO-Crate"}, {"version", "1.0"}});
  graph.push_back({{"@id", "#license"},
                   {"@type", "CreativeWork"},
                   {"name", "No license stated"},
                   {"description", "The job's submitter stated no license for these results: ask them before reuse."}});
  graph.push_back({{"@id", "#rupture-sweep-request"},
                   {"@type", "ComputerLanguage"},
                   {"name", "Rupture sweep request"},
                   {"alternateName", "the JSON body of POST /processes/{scenario}/execution (api/openapi.yaml)"},
                   {"version", version}});
  graph.push_back({{"@id", "#rupture"},
                   {"@type", "SoftwareApplication"},
                   {"name", "Rupture"},
                   {"softwareVersion", version},
                   {"description", "Built from commit " + provenance.value("git_commit", build.commit) + " with " +
                                       provenance.value("compiler", build.compiler) + " (" +
                                       provenance.value("compile_flags", build.flags) + "); runs on " +
                                       provenance.value("host_processor", io::hostProcessor()) + ", " +
                                       provenance.value("executor", std::string("local")) + " executor"}});
  graph.push_back(jobAction);
  for (Json& a : runActions) graph.push_back(std::move(a));
  for (const Json& e : crate.graph()) graph.push_back(e);
  const Json metadata = {{"@context", kCrate + std::string("/context")}, {"@graph", graph}};
  return crate.finish(metadata);
}

}  // namespace rupture::server
