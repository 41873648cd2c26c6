#include "views/html_page.hpp"

#include <algorithm>
#include <cctype>
#include <random>
#include <vector>

#include "io/xml_escape.hpp"
#include "rupture/quantity_text.hpp"

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
           ".hint{color:#666;font-size:.9em}.bad{outline:2px solid #a40000}button{margin-right:.5em}</style></head><body>"
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


std::string summaryTable(const Json& summary, const std::string& id, std::size_t shownResults) {
  struct Column {
    std::string name, unit, label;
    bool swept;
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
      if (jobFirst) h += cell(row.value("job", Json()));
      for (const std::string& name : lead) h += cell(row.value(name, Json()));
      for (const Column* k : shown)
        if (!(jobFirst && k == &columns.front())) h += quantityCell(row.value(k->name, Json()), k->unit);
      h += "</tr>\n";
    }
    return h + "</table>";
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
