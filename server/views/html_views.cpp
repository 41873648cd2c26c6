#include "views/html_views.hpp"

#include <algorithm>
#include <map>
#include <random>

#include "io/xml_escape.hpp"
#include "rupture/quantity_text.hpp"

namespace rupture::server {
namespace {

using rupture::io::xmlEscape;

std::string esc(const Json& v) {
  if (v.is_string()) return xmlEscape(v.get<std::string>());
  if (v.is_null()) return "";
  return xmlEscape(v.dump());
}

std::string newNonce() {
  static thread_local std::mt19937_64 engine{std::random_device{}()};
  static const char* digits = "0123456789abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ";
  std::string out;
  for (int i = 0; i < 22; ++i) out += digits[engine() % 62];
  return out;
}

std::string href(const std::string& path) { return xmlEscape(path); }

/// The page frame: one inline style, navigation, the content, and an optional inline script.
HtmlPage page(const std::string& title, const std::string& content, const std::string& script = {}) {
  HtmlPage p;
  p.nonce = newNonce();
  p.body = "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
           "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">"
           "<title>" + xmlEscape(title) + " - Rupture</title>"
           "<style nonce=\"" + p.nonce + "\">"
           "body{font-family:system-ui,sans-serif;margin:1.5em auto;max-width:72em;padding:0 1em;color:#222}"
           "table{border-collapse:collapse;margin:.5em 0}td,th{border:1px solid #ccc;padding:.25em .5em;text-align:left}"
           "th{background:#f3f3f3}td.num{text-align:right;font-variant-numeric:tabular-nums;white-space:nowrap}"
           "nav a{margin-right:1em}progress{width:16em}.unit{color:#666;font-weight:normal}"
           "img{max-width:100%;border:1px solid #ddd}.error{color:#a40000}</style></head><body>"
           "<nav><a href=\"/?f=html\">Rupture</a><a href=\"/processes?f=html\">Scenarios</a>"
           "<a href=\"/jobs?f=html\">Jobs</a><a href=\"/openapi.yaml\">API</a></nav>\n<h1>" +
           xmlEscape(title) + "</h1>\n" + content;
  if (!script.empty()) p.body += "<script nonce=\"" + p.nonce + "\">" + script + "</script>";
  p.body += "</body></html>\n";
  return p;
}

std::string cell(const Json& v) {
  const bool number = v.is_number();
  return std::string(number ? "<td class=\"num\">" : "<td>") + esc(v) + "</td>";
}

/// A table cell for a value in `unit`: a number as people read it (rupture::formatQuantity), its
/// full precision in the title; anything else as cell() writes it.
std::string quantityCell(const Json& v, const std::string& unit) {
  if (!v.is_number()) return cell(v);
  return "<td class=\"num\" title=\"" + esc(v) + "\">" + xmlEscape(rupture::formatQuantity(v.get<double>(), unit)) + "</td>";
}

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

std::string HtmlPage::csp() const {
  return "default-src 'none'; img-src 'self'; connect-src 'self'; style-src 'nonce-" + nonce +
         "'; script-src 'nonce-" + nonce + "'; base-uri 'none'; form-action 'self'; frame-ancestors 'none'";
}

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
  c += "<th>Status</th><th>Progress</th><th>Stage</th><th>Files</th></tr>\n";
  for (const auto& r : status.value("runs", Json::array())) {
    const std::string k = std::to_string(r.value("index", 0));
    c += "<tr id=\"run-" + k + "\"><td>" + k + "</td>";
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
