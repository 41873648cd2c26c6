#include "views/html_page.hpp"

#include <algorithm>
#include <cctype>
#include <random>
#include <vector>

#include "io/xml_escape.hpp"
#include "rupture/quantity_text.hpp"
#include "rupture/result_fields.hpp"

namespace rupture::server {

using rupture::io::xmlEscape;

namespace {

std::string newNonce() {
  static thread_local std::mt19937_64 engine{std::random_device{}()};
  static const char* digits = "0123456789abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ";
  std::string out;
  for (int i = 0; i < 22; ++i) out += digits[engine() % 62];
  return out;
}

}  // namespace

std::string HtmlPage::csp() const {
  return "default-src 'none'; img-src 'self'; connect-src 'self'; style-src 'nonce-" + nonce +
         "'; script-src 'nonce-" + nonce + "'; base-uri 'none'; form-action 'self'; frame-ancestors 'none'";
}

namespace html {

std::string esc(const Json& v) {
  if (v.is_string()) return xmlEscape(v.get<std::string>());
  if (v.is_null()) return "";
  return xmlEscape(v.dump());
}

std::string href(const std::string& path) { return xmlEscape(path); }

/// The page frame: one inline style, navigation, the content, and an optional inline script.
HtmlPage page(const std::string& title, const std::string& content, const std::string& script) {
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
           "img{max-width:100%;border:1px solid #ddd}.error{color:#a40000}"
           ".field{margin:.15em 0}.field label{display:inline-block;min-width:20em}.group{margin-left:1.5em}"
           ".hint{color:#666;font-size:.9em}.bad{outline:2px solid #a40000}button{margin-right:.5em}"
           // A wide table scrolls inside the page; its first column (the run) stays in view.
           ".scroll{overflow-x:auto;max-width:100%}.scroll table{margin:0}"
           ".scroll tr>:first-child{position:sticky;left:0;background:#fff}.scroll tr>th:first-child{background:#f3f3f3}"
           "td.none{color:#999;text-align:center}</style></head><body>"
           "<nav><a href=\"/?f=html\">Rupture</a><a href=\"/processes?f=html\">Scenarios</a>"
           "<a href=\"/jobs?f=html\">Jobs</a><a href=\"/openapi.yaml\">API</a></nav>\n<h1>" +
           xmlEscape(title) + "</h1>\n" + content;
  if (!script.empty()) p.body += "<script nonce=\"" + p.nonce + "\">" + script + "</script>";
  p.body += "</body></html>\n";
  return p;
}

HtmlPage document(std::string html) {
  HtmlPage p;
  p.nonce = newNonce();
  const std::string tag = "<style>", withNonce = "<style nonce=\"" + p.nonce + "\">";
  for (std::size_t at = html.find(tag); at != std::string::npos; at = html.find(tag, at + withNonce.size()))
    html.replace(at, tag.size(), withNonce);
  p.body = std::move(html);
  return p;
}

std::string cell(const Json& v, const std::string& whyEmpty) {
  if (v.is_null() || (v.is_string() && v.get<std::string>().empty()))
    return "<td class=\"none\" title=\"" + xmlEscape(whyEmpty) + "\">—</td>";
  if (v.is_boolean()) return "<td>" + rupture::formatFlag(v.get<bool>()) + "</td>";
  const bool number = v.is_number();
  return std::string(number ? "<td class=\"num\">" : "<td>") + esc(v) + "</td>";
}

/// A table cell for a value in `unit`: a number as people read it (rupture::formatQuantity), its
/// full precision in the title; anything else as cell() writes it.
std::string quantityCell(const Json& v, const std::string& unit, const std::string& whyEmpty, bool flag) {
  if (flag && v.is_number()) return "<td title=\"" + esc(v) + "\">" + rupture::formatFlag(v.get<double>() != 0) + "</td>";
  if (!v.is_number()) return cell(v, whyEmpty);
  return "<td class=\"num\" title=\"" + esc(v) + "\">" + xmlEscape(rupture::formatQuantity(v.get<double>(), unit)) + "</td>";
}

bool isFlag(const Json& column) {
  return column.is_object() && ResultField::describesFlag(column.value("unit", ""), column.value("description", ""));
}

std::string whyEmpty(const Json& row) {
  const std::string status = row.is_object() ? row.value("status", "") : "";
  if (status == "failed") return "run failed";
  if (status == "dismissed") return "run cancelled";
  if (status == "accepted" || status == "running") return "not finished yet";
  return "not measured by this run";
}

const std::string& numberScript() {
  static const std::string script =
      "function fq(v,u){if(v===null||v===undefined||!isFinite(v))return null;if(v===0)return u?'0 '+u:'0';"
      "const a=Math.abs(v),g=v<0?'-':'';let e=Math.floor(Math.log10(a));if(Math.round(a*Math.pow(10,2-e))>=1000)e++;"
      "const p=(m,x)=>String(+m.toFixed(Math.max(0,2-x)));"
      "if(u==='s'){const n=Math.min(0,Math.max(-18,Math.floor(e/3)*3));"
      "if(e>=n&&e<n+5)return g+p(a/Math.pow(10,n),e-n)+' '+['a','f','p','n','µ','m',''][(n+18)/3]+'s';}"
      "const t=u?' '+u:'';if(!u&&a<1e15&&a===Math.floor(a))return g+a.toFixed(0);"
      "if(e>=-3&&e<4)return g+p(a,e)+t;return g+p(a/Math.pow(10,e),0)+'e'+e+t;}"
      "function r3(s){return (s||'').replace(/(^|[^\\w.])(\\d+\\.\\d+(?:[eE][-+]?\\d+)?|\\d+[eE][-+]?\\d+)/g,"
      "(w,b,n)=>{const d=n.split(/[eE]/)[0].replace('.','').replace(/^0+/,'').length;"
      "return !/[eE]/.test(n)&&d<=4?w:b+fq(+n,'');});}";
  return script;
}

std::string etaText(const Json& etaSeconds, bool active) {
  if (etaSeconds.is_number())
    return "<span id=\"eta\">" + xmlEscape(rupture::formatQuantity(etaSeconds.get<double>(), "s")) + "</span>";
  return active ? "<span id=\"eta\" title=\"not enough of the run measured yet to estimate the time left\">unknown</span>"
                : "<span id=\"eta\" title=\"the job has ended\">—</span>";
}

std::string scrolling(const std::string& table) { return "<div class=\"scroll\">" + table + "</div>"; }


std::string summaryTable(const Json& summary, const std::string& id, std::size_t shownResults) {
  struct Column {
    std::string name, unit, label;
    bool swept;
    bool flag = false;  ///< yes/no stored as 1/0
    bool input = false;  ///< an input every run shares: under "All columns" only
  };
  std::vector<Column> columns;
  for (const auto& col : summary.value("columns", Json::array())) {
    Column k;
    k.name = col.is_object() ? col.value("name", "") : col.get<std::string>();
    k.unit = col.is_object() ? col.value("unit", "") : "";
    if (summary.contains("units") && summary["units"].contains(k.name) && summary["units"][k.name].is_string())
      k.unit = summary["units"][k.name].get<std::string>();
    k.label = col.is_object() ? col.value("label", "") : "";
    if (k.label.empty()) k.label = k.name;
    const std::string kind = col.is_object() ? col.value("kind", "") : "";
    k.swept = kind == "swept" || kind == "job";
    // An input column (the sample seed) heads the table when it tells the runs apart (replicates).
    if (kind == "input")
      for (const auto& row : summary.value("rows", Json::array()))
        k.swept = k.swept || row.value(k.name, Json()) != summary["rows"][0].value(k.name, Json());
    k.input = kind == "input" && !k.swept;
    k.flag = isFlag(col);
    columns.push_back(std::move(k));
  }
  const Json rows = summary.value("rows", Json::array());
  // A comparison's job column leads, then the run, its replicate and status.
  std::stable_partition(columns.begin(), columns.end(), [](const Column& k) { return k.name == "job"; });
  std::vector<std::string> lead;
  for (const char* name : {"run", "replicate", "status"}) {
    bool listed = false, held = false;
    for (const Column& k : columns) listed = listed || k.name == name;
    for (const auto& row : rows) held = held || row.contains(name);
    if (held && !listed) lead.push_back(name);
  }
  // The job column (a comparison's) comes first, then the run columns, then the rest.
  const bool jobFirst = !columns.empty() && columns.front().name == "job";
  auto table = [&](const std::string& tableId, const std::vector<const Column*>& shown) {
    std::string h = "<table id=\"" + tableId + "\"><tr>";
    auto header = [&](const Column* k) { h += "<th title=\"" + xmlEscape(k->name) + "\">" + xmlEscape(k->label) + "</th>"; };
    if (jobFirst) header(&columns.front());
    for (const std::string& name : lead) h += "<th>" + std::string(1, static_cast<char>(std::toupper(name[0]))) + name.substr(1) + "</th>";
    for (const Column* k : shown)
      if (!(jobFirst && k == &columns.front())) header(k);
    h += "</tr>\n";
    for (const auto& row : rows) {
      h += "<tr>";
      const std::string why = whyEmpty(row);
      if (jobFirst) h += cell(row.value("job", Json()), why);
      for (const std::string& name : lead) h += cell(row.value(name, Json()), why);
      for (const Column* k : shown)
        if (!(jobFirst && k == &columns.front())) h += quantityCell(row.value(k->name, Json()), k->unit, why, k->flag);
      h += "</tr>\n";
    }
    return scrolling(h + "</table>");
  };
  std::vector<const Column*> all, headline;
  std::size_t results = 0;
  for (const Column& k : columns) {
    all.push_back(&k);
    if (k.swept || (!k.input && results++ < shownResults)) headline.push_back(&k);
  }
  std::string out = table(id, headline);
  if (headline.size() < all.size())
    out += "<details><summary>All " + std::to_string(all.size()) + " columns</summary>" + table(id + "-all", all) +
           "</details>";
  return out;
}

std::string schemaUnit(const Json& node) {
  for (const char* key : {"x-unit", "unit"})
    if (node.contains(key) && node[key].is_string()) return node[key].get<std::string>();
  return "";
}

void inputRows(const Json& schema, const std::string& prefix, std::string& out, int depth) {
  if (!schema.is_object() || !schema.contains("properties") || depth > 4) return;
  for (const auto& [key, sub] : schema["properties"].items()) {
    if (key == "scenario") continue;
    const std::string path = prefix.empty() ? key : prefix + "." + key;
    std::string type = sub.contains("type") ? esc(sub["type"]) : (sub.contains("enum") ? "one of" : "");
    if (sub.contains("enum")) {
      type += ' ';
      type += esc(sub["enum"]);
    }
    const bool required = schema.contains("required") && schema["required"].is_array() &&
                          std::find(schema["required"].begin(), schema["required"].end(), key) != schema["required"].end();
    out += "<tr><td><code>" + xmlEscape(path) + "</code>" + (required ? " *" : "") + "</td><td>" + type +
           "</td><td>" + xmlEscape(schemaUnit(sub)) + "</td><td>" + esc(sub.value("description", Json(""))) +
           "</td></tr>\n";
    inputRows(sub, path, out, depth + 1);
  }
}

}  // namespace html
}  // namespace rupture::server
