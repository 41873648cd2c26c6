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

std::string unitOfSchema(const Json& node) {
  for (const char* key : {"x-unit", "unit"})
    if (node.contains(key) && node[key].is_string()) return node[key].get<std::string>();
  return "";
}

/// Rows of one schema's inputs, dotted paths for nested objects.
void inputRows(const Json& schema, const std::string& prefix, std::string& out, int depth = 0) {
  if (!schema.is_object() || !schema.contains("properties") || depth > 4) return;
  for (const auto& [key, sub] : schema["properties"].items()) {
    if (key == "scenario") continue;
    const std::string path = prefix.empty() ? key : prefix + "." + key;
    std::string type = sub.contains("type") ? esc(sub["type"]) : (sub.contains("enum") ? "one of" : "");
    if (sub.contains("enum")) type += " " + esc(sub["enum"]);
    const bool required = schema.contains("required") && schema["required"].is_array() &&
                          std::find(schema["required"].begin(), schema["required"].end(), key) != schema["required"].end();
    out += "<tr><td><code>" + xmlEscape(path) + "</code>" + (required ? " *" : "") + "</td><td>" + type +
           "</td><td>" + xmlEscape(unitOfSchema(sub)) + "</td><td>" + esc(sub.value("description", Json(""))) +
           "</td></tr>\n";
    inputRows(sub, path, out, depth + 1);
  }
}

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

HtmlPage processHtml(const Json& process) {
  std::string rows;
  inputRows(process.value("inputsSchema", Json::object()), "", rows);
  std::string c = "<p>" + esc(process.value("description", Json(""))) + "</p>"
                  "<p>Submit with <code>POST /processes/" + esc(process.value("id", Json(""))) +
                  "/execution</code> and <code>{\"inputs\": {...}, \"sweep\": {\"dotted.path\": [values]}}</code>.</p>"
                  "<table><tr><th>Field (* required)</th><th>Type</th><th>Unit</th><th>Description</th></tr>" +
                  rows + "</table>";
  return page(process.value("id", "") + ": " + process.value("title", ""), c);
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
       " job(s), newest first.</p><table id=\"jobs\"><tr><th>Job</th><th>Name</th><th>Scenario</th><th>Status</th>"
       "<th>Progress</th><th>Runs</th><th>Created</th></tr>\n";
  for (const auto& j : jobList.value("jobs", Json::array())) {
    const std::string id = j.value("jobID", "");
    c += "<tr><td><a href=\"" + href("/jobs/" + id + "?f=html") + "\">" + xmlEscape(id) + "</a></td>" +
         cell(j.value("name", Json(""))) + cell(j["processID"]) + cell(j["status"]) + cell(j["progress"]) +
         cell(j["runs_total"]) + cell(j["created"]) + "</tr>\n";
  }
  c += "</table>";
  for (const auto& l : jobList.value("links", Json::array())) {
    const std::string rel = l.value("rel", "");
    if (rel == "next" || rel == "prev") c += "<a href=\"" + href(l.value("href", "") + "&f=html") + "\">" + xmlEscape(rel) + "</a> ";
  }
  return page("Jobs", c);
}

HtmlPage jobHtml(const Json& status, const Json& summary, const std::string& plotPath) {
  const std::string id = status.value("jobID", "");
  const std::string base = "/jobs/" + id;
  std::string c = "<p>Scenario <a href=\"" + href("/processes/" + status.value("processID", "") + "?f=html") + "\">" +
                  esc(status["processID"]) + "</a>" +
                  (status.contains("name") ? ", name <b>" + esc(status["name"]) + "</b>" : "") + ", created " +
                  esc(status["created"]) + ".</p>"
                  "<p>Status <b id=\"status\">" + esc(status["status"]) + "</b> <progress id=\"bar\" max=\"100\" value=\"" +
                  esc(status["progress"]) + "\"></progress> <span id=\"progress\">" + esc(status["progress"]) +
                  "</span> %, <span id=\"stage\">" + esc(status.value("stage", Json(""))) + "</span>; elapsed <span id=\"elapsed\">" +
                  esc(status.value("elapsed_s", Json())) + "</span> s, ETA <span id=\"eta\">" +
                  esc(status.value("eta_s", Json())) + "</span> s; updated <span id=\"updated\">" + esc(status["updated"]) +
                  "</span></p>\n";
  // A job that did not succeed says why (the same message as its JSON), before anything else.
  const std::string jobStatus = status.value("status", "");
  if ((jobStatus == "failed" || jobStatus == "dismissed") && !status.value("message", "").empty())
    c += "<p class=\"error\" id=\"reason\">Why: " + esc(status["message"]) + "</p>\n";
  c += "<h2>Runs</h2><table id=\"runs\"><tr><th>Run</th>";
  const Json swept = status.value("swept", Json::array());
  std::map<std::string, std::string> sweptUnit;  // from the summary's columns, once it has them
  if (summary.is_object())
    for (const auto& col : summary.value("columns", Json::array()))
      if (col.is_object()) sweptUnit[col.value("name", "")] = col.value("unit", "");
  for (const auto& p : swept) c += "<th>" + esc(p) + "</th>";
  c += "<th>Status</th><th>Progress</th><th>Stage</th><th>Files</th><th>Picture</th></tr>\n";
  for (const auto& r : status.value("runs", Json::array())) {
    const std::string k = std::to_string(r.value("index", 0));
    const std::string runPage = base + "/runs/" + k + "?f=html";
    c += "<tr id=\"run-" + k + "\"><td><a href=\"" + href(runPage) + "\">" + k + "</a></td>";
    for (const auto& p : swept) {
      const std::string path = p.get<std::string>();
      c += quantityCell(r["swept"].value(path, Json()), sweptUnit[path]);
    }
    c += "<td class=\"st\">" + esc(r["status"]) + "</td><td class=\"num pr\">" + esc(r["progress"]) +
         "</td><td class=\"sg\">" + esc(r.value("stage", Json(""))) + "</td><td>";
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
  c += "</table>\n";
  if (summary.is_object()) {
    // Declared labels as headers (the key on hover), values with their unit and three significant
    // digits (the full value on hover; the JSON and CSV keep full precision). The table that fits a
    // laptop shows the swept inputs and the first kShownResults declared results (the declarations
    // put the headline results first); every column is one click away.
    constexpr std::size_t kShownResults = 8;
    struct Column { std::string name, unit, label; bool swept; };
    std::vector<Column> columns;
    for (const auto& col : summary.value("columns", Json::array())) {
      Column k;
      k.name = col.is_object() ? col.value("name", "") : col.get<std::string>();
      k.unit = col.is_object() ? col.value("unit", "") : "";
      if (summary.contains("units") && summary["units"].contains(k.name)) k.unit = summary["units"][k.name].get<std::string>();
      k.label = col.is_object() ? col.value("label", "") : "";
      if (k.label.empty()) k.label = k.name;
      k.swept = col.is_object() && col.value("kind", "") == "swept";
      columns.push_back(std::move(k));
    }
    auto table = [&](const std::string& id, const std::vector<const Column*>& shown) {
      std::string h = "<table id=\"" + id + "\"><tr><th>Run</th><th>Status</th>";
      for (const Column* k : shown) h += "<th title=\"" + xmlEscape(k->name) + "\">" + xmlEscape(k->label) + "</th>";
      h += "</tr>\n";
      for (const auto& row : summary.value("rows", Json::array())) {
        h += "<tr>" + cell(row.value("run", Json())) + cell(row.value("status", Json()));
        for (const Column* k : shown) h += quantityCell(row.value(k->name, Json()), k->unit);
        h += "</tr>\n";
      }
      return h + "</table>";
    };
    std::vector<const Column*> all, headline;
    std::size_t results = 0;
    for (const Column& k : columns) {
      all.push_back(&k);
      if (k.swept || results++ < kShownResults) headline.push_back(&k);
    }
    c += "<h2>Summary</h2>" + table("summary", headline);
    if (headline.size() < all.size()) {
      c += "<details><summary>All " + std::to_string(all.size()) + " columns</summary>" + table("summary-all", all) +
           "</details>";
    }
  }
  if (!plotPath.empty()) c += "<h2>Plot</h2><p><img alt=\"summary plot\" src=\"" + href(plotPath) + "\"></p>";
  // The merged file exists only once a run has succeeded: no link that would answer 404.
  const bool anySuccessful =
      status.contains("runs_by_status") && status["runs_by_status"].value("successful", 0) > 0;
  c += "<h2>Downloads</h2><ul>";
  if (anySuccessful) c += "<li><a href=\"" + href(base + "/results") + "\">every run in one HDF5 file</a></li>";
  c += "<li><a href=\"" + href(base + "/summary?format=csv") + "\">summary table (CSV)</a></li>"
       "<li><a href=\"" + href(base + "/summary") + "\">summary (JSON)</a></li>"
       "<li><a href=\"" + href(base) + "\">status (JSON)</a></li></ul>";
  // Live progress: poll the JSON while the job runs; reload once it ends (for the summary and plot).
  const std::string script =
      "const final=['successful','failed','dismissed'];let seen='" + esc(status["status"]) + "';"
      "function put(id,v){const e=document.getElementById(id);if(e)e.textContent=v===null||v===undefined?'':v;}"
      "async function poll(){if(final.includes(seen))return;"
      "try{const r=await fetch('" + base + "',{headers:{Accept:'application/json'}});const d=await r.json();"
      "put('status',d.status);put('progress',d.progress);put('stage',d.stage);put('elapsed',d.elapsed_s);"
      "put('eta',d.eta_s);put('updated',d.updated);document.getElementById('bar').value=d.progress;"
      "for(const run of d.runs||[]){const tr=document.getElementById('run-'+run.index);if(!tr)continue;"
      "tr.querySelector('.st').textContent=run.status;tr.querySelector('.pr').textContent=run.progress;"
      "tr.querySelector('.sg').textContent=run.stage||'';}"
      "if(final.includes(d.status)){location.reload();return;}seen=d.status;}catch(e){}"
      "setTimeout(poll,2000);}setTimeout(poll,2000);";
  return page("Job " + id + (status.contains("name") ? ": " + status["name"].get<std::string>() : ""), c, script);
}

}  // namespace rupture::server
