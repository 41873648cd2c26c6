#include "views/run_page.hpp"

#include <algorithm>

#include "io/hdf5_file.hpp"
#include "io/xml_escape.hpp"
#include "render/series_plot.hpp"
#include "render/snapshot_field.hpp"
#include "rupture/quantity_text.hpp"

namespace rupture::server {

using rupture::io::xmlEscape;
using namespace html;

namespace {

std::string option(const std::string& value, const std::string& text, bool selected) {
  return "<option value=\"" + xmlEscape(value) + "\"" + (selected ? " selected" : "") + ">" + xmlEscape(text) +
         "</option>";
}

/// "a=1&b=2" from the non-empty pairs, each value escaped for a URL.
std::string query(const std::vector<std::pair<std::string, std::string>>& pairs) {
  std::string out;
  for (const auto& [name, value] : pairs) {
    if (value.empty()) continue;
    std::string encoded;
    for (unsigned char c : value) {
      if (std::isalnum(c) || c == '-' || c == '_' || c == '.') {
        encoded += static_cast<char>(c);
      } else {
        static const char* digits = "0123456789ABCDEF";
        encoded += '%';
        encoded += digits[c >> 4];
        encoded += digits[c & 15];
      }
    }
    out += (out.empty() ? "" : "&") + name + "=" + encoded;
  }
  return out;
}

std::string snapshotText(const Json& s) {
  std::string text = "t = " + formatQuantity(s.value("time", 0.0), "s");
  if (s.contains("strain") && s["strain"].is_number()) text += ", strain " + formatQuantity(s["strain"].get<double>(), "1");
  return text;
}

}  // namespace

Json runProvenance(const std::filesystem::path& path) {
  const io::Hdf5File file = io::Hdf5File::openReadOnly(path.string());
  Json out = Json::object();
  constexpr const char* kGroup = "/provenance";
  if (!file.exists(kGroup)) return out;
  for (const char* name : {"rupture_version", "git_commit", "compiler", "compile_flags", "build_type", "host_processor",
                           "started_utc", "finished_utc", "spec_sha256", "seeds"})
    if (file.hasAttribute(kGroup, name)) out[name] = file.readAttributeString(kGroup, name);
  if (file.hasAttribute(kGroup, "threads")) out["threads"] = file.readAttributeInt(kGroup, "threads");
  return out;
}

Json runPictures(const std::filesystem::path& path, const ScenarioInfo* scenario) {
  const io::Hdf5File file = io::Hdf5File::openReadOnly(path.string());
  Json pictures = {{"fields", Json::array()}, {"snapshots", Json::array()}, {"series", Json::array()}};
  const std::vector<render::SnapshotRef> snapshots = render::listSnapshots(file, "");
  for (std::size_t i = 0; i < snapshots.size(); ++i) {
    Json s = {{"index", i}, {"time", snapshots[i].time}};
    if (snapshots[i].strain) s["strain"] = *snapshots[i].strain;
    pictures["snapshots"].push_back(s);
  }
  if (!snapshots.empty()) pictures["fields"] = render::fieldsOf(file, snapshots.back().group);
  const std::vector<std::string> series = render::seriesOf(file, "");
  auto has = [&](const std::string& n) { return std::find(series.begin(), series.end(), n) != series.end(); };
  const std::string x = has("strain") ? "strain" : "time";
  pictures["x"] = x;
  if (scenario && has(x)) {
    for (const ResultField& f : scenario->series) {
      if (f.name == x || f.name == "time" || !has(f.name)) continue;
      pictures["series"].push_back({{"name", f.name}, {"label", f.label}});
      if (pictures["series"].size() == 8) break;
    }
  }
  return pictures;
}

HtmlPage runHtml(const Json& data) {
  const Json& job = data["job"];
  const Json& run = data["run"];
  const std::string id = job.value("jobID", "");
  const std::string k = std::to_string(run.value("index", 0));
  const std::string base = "/jobs/" + id + "/runs/" + k;
  const std::string status = run.value("status", "");

  std::string c = "<p><a href=\"" + href("/jobs/" + id + "?f=html") + "\">Job " + xmlEscape(id) +
                  (job.contains("name") ? ": " + esc(job["name"]) : "") + "</a>, scenario " + esc(job["processID"]) +
                  ". Status <b id=\"status\">" + xmlEscape(status) + "</b> <progress id=\"bar\" max=\"100\" value=\"" +
                  esc(run["progress"]) + "\"></progress> <span id=\"progress\">" + esc(run["progress"]) +
                  "</span> %, <span id=\"stage\">" +
                  (run.value("stage", Json("")).is_string() ? xmlEscape(roundNumbersInText(run.value("stage", ""))) : "") +
                  "</span></p>\n";
  if (run.contains("error")) c += "<p class=\"error\" id=\"reason\">Why: " + esc(run["error"]) + "</p>\n";
  if (run.contains("resumes"))  // docs/checkpoints.md
    c += "<p id=\"resumed\">Continued from its checkpoint " + esc(run["resumes"]) +
         (run["resumes"] == 1 ? " time" : " times") + ", last from step " + esc(run.value("resumed_from_step", Json(0))) +
         " (after a stop, a crash or a time limit; the result is the same as an uninterrupted run's).</p>\n";
  // What made the file (its /provenance; docs/provenance.md).
  if (const Json p = data.value("provenance", Json::object()); !p.empty()) {
    c += "<p id=\"provenance\" class=\"hint\">Made by Rupture " + esc(p.value("rupture_version", Json(""))) +
         ", commit <code>" + esc(p.value("git_commit", Json(""))) + "</code>, " + esc(p.value("compiler", Json(""))) +
         " (<code>" + esc(p.value("compile_flags", Json(""))) + "</code>), on " + esc(p.value("host_processor", Json(""))) +
         " with " + esc(p.value("threads", Json(""))) + " thread(s), from " + esc(p.value("started_utc", Json(""))) +
         " to " + esc(p.value("finished_utc", Json(""))) + "; spec SHA-256 <code>" +
         esc(p.value("spec_sha256", Json(""))) + "</code>, seeds <code>" + esc(p.value("seeds", Json(""))) + "</code>.</p>\n";
  }
  if (!run.value("swept", Json::object()).empty()) {
    c += "<table id=\"swept\"><tr><th>Swept</th><th>Value</th></tr>";
    const Json described = data.value("swept_fields", Json::object());
    for (const auto& [path, value] : run["swept"].items()) {
      const Json about = described.value(path, Json::object());
      c += "<tr><td title=\"" + xmlEscape(path) + "\">" + xmlEscape(about.value("label", path)) + "</td>" +
           quantityCell(value, about.value("unit", "")) + "</tr>";
    }
    c += "</table>\n";
  }

  if (data.contains("pictures")) {
    const Json& pictures = data["pictures"];
    const Json& chosen = data.value("chosen", Json::object());
    const Json fields = pictures.value("fields", Json::array());
    const Json snapshots = pictures.value("snapshots", Json::array());
    if (!fields.empty() && !snapshots.empty()) {
      const std::string field = chosen.value("field", fields[0].get<std::string>());
      const long count = static_cast<long>(snapshots.size());
      long snapshot = chosen.value("snapshot", -1L);
      if (snapshot < 0) snapshot += count;
      snapshot = std::clamp(snapshot, 0L, count - 1);
      const std::string view = chosen.value("view", ""), bonds = chosen.value("bonds", "");
      const std::string range = chosen.value("range", "");
      // The colour range: as asked (both bounds, or one with the other from the default), else
      // the field's range over every snapshot of the run, the same on each picture of the page.
      auto bound = [&](const char* name) {
        return chosen.contains(name) && chosen[name].is_number() ? chosen[name].dump() : "";  // shortest exact text
      };
      const std::string minText = bound("min"), maxText = bound("max");
      const std::vector<std::pair<std::string, std::string>> colours = {
          {"min", minText}, {"max", maxText}, {"range", range}};
      std::vector<std::pair<std::string, std::string>> picture = {
          {"field", field}, {"snapshot", std::to_string(snapshot)}, {"view", view}, {"bonds", bonds}};
      picture.insert(picture.end(), colours.begin(), colours.end());
      c += "<h2>Field</h2><form method=\"get\" action=\"" + href(base) + "\" id=\"picture-form\">"
           "<input type=\"hidden\" name=\"f\" value=\"html\"> Field <select name=\"field\">";
      for (const auto& f : fields) c += option(f.get<std::string>(), f.get<std::string>(), f == field);
      c += "</select> Snapshot <select name=\"snapshot\" title=\"numbered from 0\">";
      for (const auto& s : snapshots) {
        const long index = s.value("index", 0L);
        c += option(std::to_string(index), std::to_string(index) + ": " + snapshotText(s), index == snapshot);
      }
      c += "</select> View <select name=\"view\">" + option("", "auto", view.empty());
      for (const char* v : {"xy", "xz", "yz"}) c += option(v, v, view == v);
      c += "</select> Bonds <select name=\"bonds\">" + option("", "auto", bonds.empty());
      for (const char* b : {"broken", "all", "none"}) c += option(b, b, bonds == b);
      c += "</select><br><span id=\"colour-range\">Colours from <input type=\"number\" step=\"any\" name=\"min\" "
           "size=\"10\" aria-label=\"colour range minimum\" value=\"" + xmlEscape(minText) + "\"> to "
           "<input type=\"number\" step=\"any\" name=\"max\" size=\"10\" aria-label=\"colour range maximum\" value=\"" +
           xmlEscape(maxText) + "\"> (SI unit of the field: Pa, m/s, kg/m^3; empty: the default) "
           "default <select name=\"range\">" + option("", "all snapshots", range.empty() || range == "run") +
           option("snapshot", "this snapshot", range == "snapshot") + "</select></span> <button>Show</button></form>\n";
      const std::string q = query(picture);
      c += "<p><img id=\"field\" alt=\"" + xmlEscape(field) + " at snapshot " + std::to_string(snapshot) +
           " (numbered from 0)\" width=\"900\" height=\"600\" src=\"" +
           href(base + "/field?" + q + "&width=900&height=600") + "\"></p>"
           "<p>This picture as <a href=\"" + href(base + "/field?" + q + "&width=1600&height=1200") + "\">PNG</a>, <a href=\"" +
           href(base + "/field?" + q + "&format=svg") + "\">SVG</a> or <a href=\"" + href(base + "/field?" + q + "&format=pdf") +
           "\">PDF</a>. Snapshots are numbered from 0; the colours span " +
           (!minText.empty() || !maxText.empty() ? "the range asked for"
            : range == "snapshot"                ? "this snapshot's range"
                                                 : "the field's range over every snapshot, so the pictures below compare by colour") +
           ".</p>\n";
      // Over time: up to six snapshots spread over the run, in the same colour range.
      c += "<h3>Over time</h3><p id=\"strip\">";
      const long shown = std::min(count, 6L);
      for (long i = 0; i < shown; ++i) {
        const long index = shown == 1 ? 0 : i * (count - 1) / (shown - 1);
        std::vector<std::pair<std::string, std::string>> small = {
            {"field", field}, {"snapshot", std::to_string(index)}, {"view", view}};
        small.insert(small.end(), colours.begin(), colours.end());
        const std::string smallQuery = query(small);
        c += "<a href=\"" + href(base + "?f=html&" + smallQuery) + "\"><img alt=\"snapshot " + std::to_string(index) +
             "\" title=\"snapshot " + std::to_string(index) + ": " +
             xmlEscape(snapshotText(snapshots[static_cast<std::size_t>(index)])) +
             "\" width=\"200\" height=\"150\" src=\"" + href(base + "/field?" + smallQuery + "&thumbnail=1") + "\"></a> ";
      }
      c += "</p>\n";
    }
    const Json series = pictures.value("series", Json::array());
    if (!series.empty()) {
      c += "<h2>Series</h2><p id=\"series\">";
      for (const auto& s : series) {
        const std::string q = query({{"x", pictures.value("x", "")}, {"y", s.value("name", "")}});
        c += "<img alt=\"" + esc(s["label"]) + "\" width=\"560\" height=\"350\" src=\"" +
             href(base + "/series?format=svg&width=560&height=350&" + q) + "\"> ";
      }
      c += "</p>\n";
    }
  }

  if (run.contains("summary") && run["summary"].is_object()) {
    c += "<h2>Summary</h2><table id=\"summary\"><tr><th>Result</th><th>Value</th></tr>";
    std::vector<std::string> done;
    for (const auto& f : data.value("summary_fields", Json::array())) {
      const std::string name = f.value("name", "");
      if (!run["summary"].contains(name)) continue;
      done.push_back(name);
      c += "<tr><td title=\"" + xmlEscape(name) + "\">" + esc(f["label"]) + "</td>" +
           quantityCell(run["summary"][name], f.value("unit", ""), whyEmpty(run), isFlag(f)) + "</tr>";
    }
    for (const auto& [name, value] : run["summary"].items())
      if (std::find(done.begin(), done.end(), name) == done.end())
        c += "<tr><td>" + xmlEscape(name) + "</td>" + cell(value, whyEmpty(run)) + "</tr>";
    c += "</table>\n";
  }
  if (status == "successful") {
    c += "<h2>Files</h2><ul><li><a href=\"" + href(base + "/results") + "\">HDF5 file</a></li><li><a href=\"" +
         href(base + "/bundle") + "\">ParaView bundle</a> (HDF5 and XDMF sidecar, tar)</li><li><a href=\"" +
         href(base + "/series?format=csv") + "\">series (CSV)</a></li></ul>\n";
  }
  if (run.contains("spec"))
    c += "<h2>Spec</h2><details><summary>The run's spec (JSON)</summary><pre id=\"spec\">" +
         xmlEscape(run["spec"].dump(2, ' ', false, Json::error_handler_t::replace)) + "</pre></details>\n";

  // While the run runs: poll its JSON, reload when it ends (for its pictures and summary).
  std::string script;
  if (status == "accepted" || status == "running")
    script = numberScript() + "const final=['successful','failed','dismissed'];"
             "function put(id,v){const e=document.getElementById(id);if(e)e.textContent=v===null||v===undefined?'':v;}"
             "async function poll(){try{const r=await fetch('" + base + "',{headers:{Accept:'application/json'}});"
             "const d=await r.json();put('status',d.status);put('progress',d.progress);put('stage',r3(d.stage));"
             "document.getElementById('bar').value=d.progress;if(final.includes(d.status)){location.reload();return;}}"
             "catch(e){}setTimeout(poll,2000);}setTimeout(poll,2000);";
  return page("Job " + id + ", run " + k, c, script);
}

}  // namespace rupture::server
