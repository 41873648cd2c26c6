#include "views/html_views.hpp"

#include "views/html_page.hpp"

#include <algorithm>
#include <map>

#include "io/xml_escape.hpp"
#include "rupture/quantity_text.hpp"

namespace rupture::server {
namespace {

using rupture::io::xmlEscape;
using namespace html;

}  // namespace

HtmlPage landingHtml(const Json& landing) {
  std::string c = "<p>" + esc(landing.value("description", Json(""))) + "</p><ul>";
  for (const auto& l : landing.value("links", Json::array())) {
    std::string h = l.value("href", "");
    if (l.value("type", "") == "application/json") h += "?f=html";
    c += "<li><a href=\"" + href(h) + "\">" + esc(l.value("title", l.value("href", Json("")))) + "</a></li>";
  }
  c += "</ul><p>Version " + esc(landing.value("version", Json(""))) + "</p>";
  return page("Rupture job server", c);
}

HtmlPage processesHtml(const Json& processes, const Json& schemasByProcess) {
  std::string c;
  for (const auto& p : processes.value("processes", Json::array())) {
    const std::string id = p.value("id", "");
    c += "<h2><a href=\"" + href("/processes/" + id + "?f=html") + "\">" + xmlEscape(id) + "</a>: " +
         esc(p.value("title", Json(""))) + "</h2><p>" + esc(p.value("description", Json(""))) + "</p>";
    if (schemasByProcess.contains(id)) {
      std::string rows;
      inputRows(schemasByProcess[id], "", rows);
      c += "<details><summary>Inputs</summary><table><tr><th>Field (* required)</th><th>Type</th><th>Unit</th>"
           "<th>Description</th></tr>" + rows + "</table></details>";
    }
  }
  return page("Scenarios", c);
}

HtmlPage jobsHtml(const Json& jobList, const Json& query, const Json& scenarios) {
  std::string c = "<form method=\"get\" action=\"/jobs\"><input type=\"hidden\" name=\"f\" value=\"html\">"
                  "Name <input name=\"name\" value=\"" + esc(query.value("name", Json(""))) + "\"> Status <select name=\"status\">"
                  "<option value=\"\">any</option>";
  for (const char* s : {"accepted", "running", "successful", "failed", "dismissed"}) {
    c += std::string("<option") + (query.value("status", "") == s ? " selected" : "") + ">" + s + "</option>";
  }
  c += "</select> Scenario <select name=\"processID\"><option value=\"\">any</option>";
  for (const auto& s : scenarios) {
    c += "<option" + std::string(query.value("processID", "") == s.get<std::string>() ? " selected" : "") + ">" + esc(s) + "</option>";
  }
  c += "</select> <button>Filter</button></form>\n<p>" + esc(jobList.value("numberMatched", Json(0))) +
       " job(s), newest first.</p><form method=\"get\" action=\"/summary\" id=\"compare-form\">"
       "<input type=\"hidden\" name=\"f\" value=\"html\"><table id=\"jobs\"><tr><th>Compare</th><th>Job</th><th>Name</th>"
       "<th>Scenario</th><th>Status</th><th>Progress</th><th>Runs</th><th>Created</th></tr>\n";
  for (const auto& j : jobList.value("jobs", Json::array())) {
    const std::string id = j.value("jobID", "");
    c += "<tr><td><input type=\"checkbox\" name=\"jobs\" value=\"" + xmlEscape(id) + "\" aria-label=\"compare job " +
         xmlEscape(id) + "\"></td><td><a href=\"" + href("/jobs/" + id + "?f=html") + "\">" + xmlEscape(id) + "</a></td>" +
         cell(j.value("name", Json("")), "no name given") + cell(j["processID"]) + cell(j["status"]) + cell(j["progress"]) +
         cell(j["runs_total"]) + cell(j["created"]) + "</tr>\n";
  }
  c += "</table><p><button id=\"compare\">Compare the chosen jobs</button> <a href=\"/processes?f=html\">Submit a job</a>"
       "</p></form>";
  for (const auto& l : jobList.value("links", Json::array())) {
    const std::string rel = l.value("rel", "");
    if (rel == "next" || rel == "prev") c += "<a href=\"" + href(l.value("href", "") + "&f=html") + "\">" + xmlEscape(rel) + "</a> ";
  }
  return page("Jobs", c);
}

namespace {

/// A run's or a job's stage as people read it: long decimals rounded (the JSON keeps them).
std::string stageText(const Json& status) {
  const Json stage = status.value("stage", Json(""));
  return stage.is_string() ? xmlEscape(roundNumbersInText(stage.get<std::string>())) : esc(stage);
}

/// Seconds as people read them ("12.3 s", "450 ms"); nothing when not known.
std::string secondsText(const Json& seconds) {
  return seconds.is_number() ? xmlEscape(formatQuantity(seconds.get<double>(), "s")) : "";
}

/// The replicate table: per sweep point its swept values, n, and mean ± 95 % half-width of the
/// first results, in their units.
std::string replicateTable(const Json& points) {
  std::vector<Json> swept, scalars;
  for (const auto& col : points.value("columns", Json::array())) {
    if (!col.is_object()) continue;
    if (col.value("kind", "") == "swept") swept.push_back(col);
    else if (col.contains("members") && scalars.size() < 6) scalars.push_back(col);
  }
  std::string h = "<table id=\"replicates\"><tr>";
  for (const auto& col : swept) h += "<th title=\"" + esc(col["name"]) + "\">" + esc(col.value("label", col["name"])) + "</th>";
  h += "<th>n</th>";
  for (const auto& col : scalars)
    h += "<th title=\"" + esc(col["name"]) + "\">" + esc(col.value("label", col["name"])) + " (mean ± 95 %)</th>";
  h += "</tr>\n";
  for (const auto& row : points.value("rows", Json::array())) {
    h += "<tr>";
    for (const auto& col : swept) h += quantityCell(row.value(col.value("name", ""), Json()), col.value("unit", ""));
    h += cell(row.value("n_successful", Json()));
    for (const auto& col : scalars) {
      const Json stats = row.value(col.value("name", ""), Json::object());
      const std::string unit = col.value("unit", "");
      const Json mean = stats.value("mean", Json()), half = stats.value("ci95_half_width", Json());
      if (!mean.is_number()) {  // no successful run at this point
        h += cell(Json(), "no successful run at this point");
        continue;
      }
      std::string text = rupture::formatQuantity(mean.get<double>(), unit);
      if (half.is_number()) text += " ± " + rupture::formatQuantity(half.get<double>(), unit);
      h += "<td class=\"num\" title=\"" + esc(stats.dump()) + "\">" + xmlEscape(text) + "</td>";
    }
    h += "</tr>\n";
  }
  return scrolling(h + "</table>");
}

/// How many times a run was started, marked when more than once (a retry, a resume or a restart
/// after a stop) or when it continued from its checkpoint: what was asked again shows.
std::string attemptsCell(const Json& run) {
  const int attempts = run.value("attempts", run.contains("started") ? 1 : 0);
  std::string text = std::to_string(attempts), title;
  if (attempts > 1) {
    text += " <span class=\"mark\">&#x21bb; retried</span>";
    title = "started " + std::to_string(attempts) + " times: retried, resumed, or restarted after a stop";
  }
  if (const int resumes = run.value("resumes", 0); resumes > 0) {
    text += " <span class=\"mark\">continued</span>";
    title += std::string(title.empty() ? "" : "; ") + "continued from its checkpoint " + std::to_string(resumes) +
             (resumes == 1 ? " time" : " times");
  }
  return "<td class=\"num at\"" + (title.empty() ? std::string() : " title=\"" + xmlEscape(title) + "\"") + ">" +
         text + "</td>";
}

// Cancel and retry: the token (when the server has one) is kept in the browser session, sent as a
// header, never put in a URL.
constexpr const char* kActionScript =
    "const tokenBox=document.getElementById('token');if(tokenBox)tokenBox.value=sessionStorage.getItem('rupture-token')||'';"
    "for(const b of document.querySelectorAll('button[data-method]'))b.addEventListener('click',async()=>{"
    "const t=tokenBox?tokenBox.value.trim():'';if(t)sessionStorage.setItem('rupture-token',t);"
    "const h={Accept:'application/json'};if(t)h.Authorization='Bearer '+t;"
    "const o={method:b.dataset.method,headers:h};if(b.dataset.method==='POST'){h['Content-Type']='application/json';o.body='{}';}"
    "const out=document.getElementById('action-error');out.textContent='';"
    "try{const r=await fetch(b.dataset.url,o);if(r.ok){location.reload();return;}"
    "const d=await r.json().catch(()=>({}));out.textContent=d.detail||('HTTP '+r.status);}"
    "catch(e){out.textContent='no answer from the server: '+e;}});";

}  // namespace

HtmlPage jobHtml(const Json& status, const Json& summary, const std::string& plotPath, const Json& points) {
  const std::string id = status.value("jobID", "");
  const std::string base = "/jobs/" + id;
  std::string c = "<p>Scenario <a href=\"" + href("/processes/" + status.value("processID", "") + "?f=html") + "\">" +
                  esc(status["processID"]) + "</a>" +
                  (status.contains("name") ? ", name <b>" + esc(status["name"]) + "</b>" : "") + ", created " +
                  esc(status["created"]) + ".</p>"
                  "<p>Status <b id=\"status\">" + esc(status["status"]) + "</b> <progress id=\"bar\" max=\"100\" value=\"" +
                  esc(status["progress"]) + "\"></progress> <span id=\"progress\">" + esc(status["progress"]) +
                  "</span> %, <span id=\"stage\">" + stageText(status) + "</span>; elapsed <span id=\"elapsed\">" +
                  secondsText(status.value("elapsed_s", Json())) + "</span>, ETA " +
                  etaText(status.value("eta_s", Json()),
                          status.value("status", "") == "accepted" || status.value("status", "") == "running") +
                  "; updated <span id=\"updated\">" + esc(status["updated"]) + "</span></p>\n";
  // A job that did not succeed says why (the same message as its JSON), before anything else.
  const std::string jobStatus = status.value("status", "");
  if ((jobStatus == "failed" || jobStatus == "dismissed") && !status.value("message", "").empty()) {
    // The job's message counts the failures; the first runs' own reasons say what went wrong.
    std::string reasons;
    int listed = 0;
    for (const auto& r : status.value("runs", Json::array()))
      if (r.value("status", "") == "failed" && r.contains("error") && listed++ < 3)
        reasons += "<br>run " + esc(r["index"]) + ": " + esc(r["error"]);
    c += "<p class=\"error\" id=\"reason\">Why: " + esc(status["message"]) + reasons + "</p>\n";
  }
  // Actions: cancel while it runs, retry when a run failed, resume a cancelled job's unfinished runs,
  // a variant through the form.
  const bool active = jobStatus == "accepted" || jobStatus == "running";
  const Json byStatus = status.value("runs_by_status", Json::object());
  const bool anyFailed = byStatus.value("failed", 0) > 0;
  const int unfinished = byStatus.value("failed", 0) + byStatus.value("dismissed", 0);
  const bool resumable = jobStatus == "dismissed" && unfinished > 0;
  c += "<p id=\"actions\">";
  if (active) c += "<button id=\"cancel\" data-method=\"DELETE\" data-url=\"" + href(base) + "\">Cancel</button>";
  if (anyFailed && !active && !resumable)
    c += "<button id=\"retry\" data-method=\"POST\" data-url=\"" + href(base + "/retry") + "\">Retry failed runs</button>";
  if (resumable)
    c += "<button id=\"resume\" data-method=\"POST\" data-url=\"" + href(base + "/resume") + "\">Resume: run the " +
         std::to_string(unfinished) + " unfinished run" + (unfinished == 1 ? "" : "s") + " again</button>";
  c += "<a href=\"" + href("/processes/" + status.value("processID", "") + "?f=html&from=" + id) + "\">Submit a variant</a>";
  if (active || anyFailed || resumable)
    c += " Token <input id=\"token\" type=\"password\" autocomplete=\"off\" size=\"16\"> <span class=\"hint\">(only if "
         "the server has one)</span>";
  c += " <span class=\"error\" id=\"action-error\" role=\"alert\"></span></p>\n";
  c += "<h2>Runs</h2><div class=\"scroll\"><table id=\"runs\"><tr><th>Run</th>";
  const Json swept = status.value("swept", Json::array());
  // Each swept path headed by its label (the path on hover), its values in its unit.
  std::map<std::string, std::string> sweptUnit, sweptLabel;
  const Json sweptFields = status.value("swept_fields", Json::object());  // held: items() keeps a reference
  for (const auto& [path, about] : sweptFields.items()) {
    sweptUnit[path] = about.value("unit", "");
    sweptLabel[path] = about.value("label", path);
  }
  for (const auto& p : swept) {
    const std::string path = p.get<std::string>();
    const std::string label = sweptLabel.count(path) ? sweptLabel[path] : path;
    c += "<th title=\"" + xmlEscape(path) + "\">" + xmlEscape(label) + "</th>";
  }
  c += "<th>Status</th><th>Progress</th><th title=\"times the run was started\">Attempts</th><th>Stage</th>"
       "<th>Files</th><th>Picture</th></tr>\n";
  for (const auto& r : status.value("runs", Json::array())) {
    const std::string k = std::to_string(r.value("index", 0));
    const std::string runPage = base + "/runs/" + k + "?f=html";
    c += "<tr id=\"run-" + k + "\"><td><a href=\"" + href(runPage) + "\">" + k + "</a></td>";
    for (const auto& p : swept) {
      const std::string path = p.get<std::string>();
      c += quantityCell(r["swept"].value(path, Json()), sweptUnit[path]);
    }
    c += "<td class=\"st\">" + esc(r["status"]) + "</td><td class=\"num pr\">" + esc(r["progress"]) +
         "</td>" + attemptsCell(r) + "<td class=\"sg\">" + stageText(r) + "</td><td>";
    if (r["status"] == "successful") {
      const std::string rb = base + "/runs/" + k;
      c += "<a href=\"" + href(rb + "/results") + "\">HDF5</a> <a href=\"" + href(rb + "/bundle") +
           "\">ParaView bundle</a> <a href=\"" + href(rb + "/series?format=csv") + "\">series CSV</a>";
    } else if (r.contains("error")) {  // a failed run's files do not exist: its reason instead
      c += "<span class=\"error\">" + esc(r["error"]) + "</span>";
    }
    c += "</td><td>";
    if (r.value("picture", false))  // the run's field at its last snapshot, linking to its page
      c += "<a href=\"" + href(runPage) + "\"><img class=\"thumb\" alt=\"run " + k + "\" width=\"160\" height=\"120\" src=\"" +
           href(base + "/runs/" + k + "/field?thumbnail=1&width=160&height=120") + "\"></a>";
    c += "</td></tr>\n";
  }
  c += "</table></div>\n";
  if (points.is_object()) c += "<h2>Replicates</h2>" + replicateTable(points);
  if (summary.is_object()) c += "<h2>Summary</h2>" + summaryTable(summary, "summary");
  if (!plotPath.empty()) c += "<h2>Plot</h2><p><img alt=\"summary plot\" src=\"" + href(plotPath) + "\"></p>";
  // The merged file exists only once a run has succeeded: no link that would answer 404.
  const bool anySuccessful =
      status.contains("runs_by_status") && status["runs_by_status"].value("successful", 0) > 0;
  const bool finished = jobStatus == "successful" || jobStatus == "failed" || jobStatus == "dismissed";
  c += "<h2>Downloads</h2><ul>";
  // A validation job's report (docs/validation.md): its cases against their references, figures inline.
  if (status.value("processID", "") == "validation")
    c += "<li><a id=\"report\" href=\"" + href(base + "/report") +
         "\">validation report (the cases against their published references, with figures)</a>, as <a href=\"" +
         href(base + "/report?format=csv") + "\">CSV</a> or <a href=\"" + href(base + "/report?format=json") + "\">JSON</a></li>";
  if (anySuccessful) c += "<li><a href=\"" + href(base + "/results") + "\">every run in one HDF5 file</a></li>";
  // The crate waits for the last run (409 before): offered once the job has ended.
  if (finished)
    c += "<li><a id=\"crate\" href=\"" + href(base + "/crate") +
         "\">everything as an RO-Crate (ZIP: request, specs, files, summary, provenance)</a></li>";
  c += "<li><a href=\"" + href(base + "/summary?format=csv") + "\">summary table (CSV)</a></li>"
       "<li><a href=\"" + href(base + "/summary") + "\">summary (JSON)</a></li>"
       "<li><a href=\"" + href(base) + "\">status (JSON)</a></li></ul>";
  // What made it (docs/provenance.md): the build and host the job was submitted to.
  if (const Json p = status.value("provenance", Json()); p.is_object()) {
    c += "<p id=\"provenance\" class=\"hint\">Made by Rupture " + esc(p.value("rupture_version", Json(""))) +
         ", commit <code>" + esc(p.value("git_commit", Json(""))) + "</code>, " + esc(p.value("compiler", Json(""))) +
         " (" + esc(p.value("build_type", Json(""))) + ": <code>" + esc(p.value("compile_flags", Json(""))) +
         "</code>), on " + esc(p.value("host_processor", Json(""))) + ", " + esc(p.value("executor", Json(""))) +
         " executor, " + esc(p.value("threads_per_run", Json(""))) + " thread(s) per run.</p>\n";
  }
  // Live progress: poll the JSON while the job runs; reload once it ends (for the summary and plot).
  const std::string script = numberScript() +
      "const final=['successful','failed','dismissed'];let seen='" + esc(status["status"]) + "';"
      "function put(id,v){const e=document.getElementById(id);if(e)e.textContent=v===null||v===undefined?'':v;}"
      "async function poll(){if(final.includes(seen))return;"
      "try{const r=await fetch('" + base + "',{headers:{Accept:'application/json'}});const d=await r.json();"
      "put('status',d.status);put('progress',d.progress);put('stage',r3(d.stage));put('elapsed',fq(d.elapsed_s,'s'));"
      "put('eta',d.eta_s===null||d.eta_s===undefined?(final.includes(d.status)?'—':'unknown'):fq(d.eta_s,'s'));"
      "put('updated',d.updated);document.getElementById('bar').value=d.progress;"
      "for(const run of d.runs||[]){const tr=document.getElementById('run-'+run.index);if(!tr)continue;"
      "tr.querySelector('.st').textContent=run.status;tr.querySelector('.pr').textContent=run.progress;"
      "tr.querySelector('.sg').textContent=r3(run.stage);}"
      "if(final.includes(d.status)){location.reload();return;}seen=d.status;}catch(e){}"
      "setTimeout(poll,2000);}setTimeout(poll,2000);";
  return page("Job " + id + (status.contains("name") ? ": " + status["name"].get<std::string>() : ""), c,
              kActionScript + script);
}

HtmlPage comparisonHtml(const Json& comparison, const std::string& plotPath) {
  std::string ids, c = "<p>";
  for (const auto& j : comparison.value("jobs", Json::array())) {
    const std::string id = j.value("jobID", "");
    ids += (ids.empty() ? "" : ",") + id;
    c += "<a href=\"" + href("/jobs/" + id + "?f=html") + "\">Job " + xmlEscape(id) + "</a> (" + esc(j["processID"]) +
         (j.value("name", "").empty() ? "" : ", " + esc(j["name"])) + ", " + esc(j["status"]) + ") ";
  }
  c += "</p>";
  if (!plotPath.empty()) c += "<p><img id=\"compare-plot\" alt=\"comparison plot\" src=\"" + href(plotPath) + "\"></p>";
  // What was asked differently: the inputs whose values differ between the jobs (one job: none).
  const Json differing = comparison.value("differing_inputs", Json::array());
  const Json jobs = comparison.value("jobs", Json::array());
  if (jobs.size() > 1) {
    if (differing.empty()) {
      c += "<p id=\"differing\">The jobs were asked with the same inputs.</p>";
    } else {
      // One column per job: as wide as the jobs compared, so it scrolls inside the page too.
      c += "<h2>Inputs that differ</h2><div class=\"scroll\"><table id=\"differing\"><tr><th>Input</th>";
      for (const auto& j : jobs) c += "<th>Job " + esc(j["jobID"]) + "</th>";
      c += "</tr>";
      for (const auto& d : differing) {
        c += "<tr><td><code>" + esc(d["path"]) + "</code></td>";
        for (const auto& j : jobs) {
          const Json v = d["values"].value(j.value("jobID", ""), Json());
          const std::string text = v.is_null()                           ? "(default)"
                                   : v.is_object() && v.contains("swept") ? "swept: " + v["swept"].dump()
                                   : v.is_string()                        ? v.get<std::string>()
                                                                          : v.dump();
          c += "<td>" + xmlEscape(text) + "</td>";
        }
        c += "</tr>";
      }
      c += "</table></div>";
    }
  }
  c += "<h2>Rows</h2>" + summaryTable(comparison, "compare") + "<p><a href=\"" +
       href("/summary?jobs=" + ids + "&format=csv") + "\">CSV</a> <a href=\"" + href("/summary?jobs=" + ids) +
       "\">JSON</a></p>";
  return page("Compare jobs " + ids, c);
}

HtmlPage compareChoiceHtml(const std::string& detail, std::size_t maxJobs) {
  const std::string c =
      "<p id=\"choice\">Nothing to compare: tick the <em>Compare</em> box of each job you want side by side in the "
      "<a href=\"/jobs?f=html\">job list</a> (up to " + std::to_string(maxJobs) +
      "; one job alone shows its rows), then press <em>Compare the chosen jobs</em>.</p>"
      "<p class=\"hint\">" + xmlEscape(detail) + "</p>";
  return page("Compare jobs", c);
}

}  // namespace rupture::server
