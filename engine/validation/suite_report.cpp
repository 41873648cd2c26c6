// The suite's report: one table (HTML, JSON, CSV) of every quantity of every case, and a figure per
// case. The three tables are made from the same rows, so they cannot disagree.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "io/atomic_text_file.hpp"
#include "io/hdf5_file.hpp"
#include "io/xml_escape.hpp"
#include "rupture/quantity_text.hpp"
#include "rupture/validation.hpp"
#include "validation/comparison_figure.hpp"
#include "validation/validation_case.hpp"

namespace rupture::validation {

namespace {

using Json = nlohmann::json;
namespace fs = std::filesystem;

/// One row of the table: a quantity of a case, with its numbers at full precision.
Json tableRow(const Json& result, const Json& q) {
  const Json& ref = q["reference"];
  return {{"case", result["case"]},
          {"quantity", q["name"]},
          {"label", q["label"]},
          {"unit", q["unit"]},
          {"ours", q["ours"]},
          {"reference", ref.value("value", Json(nullptr))},
          {"reference_low", ref.value("low", Json(nullptr))},
          {"reference_high", ref.value("high", Json(nullptr))},
          {"reference_uncertainty", ref.value("uncertainty", 0.0)},
          {"tolerance_relative", q["tolerance"]["relative"]},
          {"tolerance_absolute", q["tolerance"]["absolute"]},
          {"deviation", q["deviation"]},
          {"off", q["off"]},
          {"verdict", q["verdict"]},
          {"known_failure", q.value("known_failure", "")}};
}

std::string csvField(const Json& v) {
  if (v.is_null()) return "";
  if (v.is_number()) {
    std::ostringstream s;
    s.precision(17);
    s << v.get<double>();
    return s.str();
  }
  std::string text = v.is_string() ? v.get<std::string>() : v.dump();
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

std::string readable(const Json& v, const std::string& unit) {
  return v.is_number() ? formatQuantity(v.get<double>(), unit) : std::string("n/a");
}

std::string referenceText(const Json& row) {
  const std::string unit = row["unit"];
  std::string text;
  if (row["reference"].is_number())
    text = readable(row["reference"], unit);
  else if (row["reference_low"].is_number() && row["reference_high"].is_number())
    text = readable(row["reference_low"], unit) + " to " + readable(row["reference_high"], unit);
  else if (row["reference_low"].is_number())
    text = "at least " + readable(row["reference_low"], unit);
  else if (row["reference_high"].is_number())
    text = "at most " + readable(row["reference_high"], unit);
  else
    text = "n/a";
  if (row["reference_uncertainty"].is_number() && row["reference_uncertainty"].get<double>() > 0)
    text += " ± " + readable(row["reference_uncertainty"], unit);
  return text;
}

std::string toleranceText(const Json& row) {
  const double rel = row["tolerance_relative"].get<double>(), abs = row["tolerance_absolute"].get<double>();
  std::string text;
  if (rel > 0) text = "± " + formatQuantity(100 * rel, "1") + " %";
  if (abs > 0) text += (text.empty() ? "± " : " + ") + formatQuantity(abs, row["unit"].get<std::string>());
  return text.empty() ? "the bound itself" : text;
}

std::string verdictText(const Json& row) {
  std::string text = row["verdict"];
  if (row["off"].is_number() && row["off"].get<double>() != 0) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, " (%+.1f %% off", 100 * row["off"].get<double>());
    text += buffer;
    if (row["deviation"].is_number()) {
      std::snprintf(buffer, sizeof buffer, ", %.2g× the tolerance)", row["deviation"].get<double>());
      text += buffer;
    } else {
      text += ")";
    }
  } else if (!row["ours"].is_number()) {
    text += " (no value)";
  }
  return text;
}

std::string cssClass(const std::string& verdict) {
  return verdict == "pass" ? "pass" : verdict == "known failure" ? "known" : verdict == "not run" ? "notrun" : "fail";
}

std::string escape(const std::string& text) { return io::xmlEscape(text); }

}  // namespace

std::vector<CaseListing> listValidationCases() {
  std::vector<CaseListing> out;
  for (const ValidationCase& c : validationCases()) out.push_back({c.id, c.title, c.paper, c.inQuick, c.quickNote});
  return out;
}

Json caseThatCouldNotRun(const std::string& caseId, const std::string& level, const std::string& why) {
  const ValidationCase* c = findValidationCase(caseId);
  return {{"case", caseId},
          {"title", c ? c->title : caseId},
          {"paper", c ? c->paper : ""},
          {"level", level},
          {"verdict", "fail"},
          {"comparison", "The case could not run: " + why},
          {"quantities",
           {{{"name", "run"},
             {"label", "the case's runs (" + why + ")"},
             {"unit", ""},
             {"ours", nullptr},
             {"reference", {{"uncertainty", 0}}},
             {"tolerance", {{"relative", 0}, {"absolute", 0}}},
             {"deviation", nullptr},
             {"off", nullptr},
             {"verdict", "fail"}}}}};
}

Json readCaseResult(const std::string& resultPath) {
  const io::Hdf5File file = io::Hdf5File::openReadOnly(resultPath);
  if (!file.exists("/validation/result"))
    throw std::runtime_error(resultPath + " holds no validation result (not a finished validation run)");
  const std::vector<std::string> text = file.readDatasetString("/validation/result");
  if (text.size() != 1) throw std::runtime_error(resultPath + ": /validation/result must hold one JSON text");
  return Json::parse(text.front());
}

SuiteReport buildSuiteReport(const std::vector<Json>& results, const std::string& level, const Json& context,
                             bool inlineFigures) {
  SuiteReport report;
  Json table = Json::array(), cases = Json::array();
  Json counts = {{"pass", 0}, {"fail", 0}, {"known failure", 0}, {"unexpected pass", 0}, {"not run", 0}};
  std::ostringstream rows, sections;
  std::vector<std::string> done;
  for (const Json& result : results) {
    const std::string id = result["case"];
    done.push_back(id);
    const std::string figureName = id + ".svg";
    report.figures.emplace_back(figureName, comparisonFigureSvg(result));
    int number = 0;
    for (const Json& q : result["quantities"]) {
      Json row = tableRow(result, q);
      const std::string verdict = row["verdict"];
      counts[verdict] = counts[verdict].get<int>() + 1;
      if (verdict == "fail" || verdict == "unexpected pass") report.passed = false;
      rows << "<tr class=\"" << cssClass(verdict) << "\" data-case=\"" << escape(id) << "\" data-quantity=\""
           << escape(row["quantity"]) << "\" data-ours=\"" << escape(csvField(row["ours"])) << "\" data-verdict=\""
           << escape(verdict) << "\"><td><a href=\"#" << escape(id) << "\">" << escape(id) << "</a></td><td>"
           << ++number << ". " << escape(row["label"]) << "</td><td>" << escape(referenceText(row)) << "</td><td>"
           << escape(readable(row["ours"], row["unit"])) << "</td><td>" << escape(toleranceText(row)) << "</td><td>"
           << escape(verdictText(row)) << "</td></tr>\n";
      table.push_back(std::move(row));
    }
    sections << "<section id=\"" << escape(id) << "\"><h2>" << escape(result.value("title", id)) << "</h2>\n"
             << "<p class=\"verdict " << cssClass(result["verdict"]) << "\">" << escape(result["verdict"]) << " · "
             << escape(result.value("paper", "")) << " · level " << escape(result.value("level", "")) << "</p>\n"
             << "<p><b>Reference.</b> " << escape(result.value("citation", "")) << "</p>\n"
             << "<p><b>How it was read.</b> " << escape(result.value("how_read", "")) << "</p>\n"
             << "<p><b>What is compared.</b> " << escape(result.value("comparison", "")) << "</p>\n";
    for (const Json& q : result["quantities"])
      if (q.contains("known_failure"))
        sections << "<p class=\"known\"><b>Known failure, " << escape(q["label"]) << ":</b> " << escape(q["known_failure"]) << "</p>\n";
    if (inlineFigures)
      sections << "<figure>" << report.figures.back().second << "</figure>\n";
    else
      sections << "<figure><img src=\"figures/" << escape(figureName) << "\" alt=\"" << escape(id)
               << ": ours against the reference\"></figure>\n";
    sections << "</section>\n";
    cases.push_back(result);
  }
  Json notRun = Json::array();
  for (const CaseListing& c : listValidationCases()) {
    if (std::find(done.begin(), done.end(), c.id) != done.end()) continue;
    const bool inLevel = level == "full" || c.quick;
    notRun.push_back({{"case", c.id}, {"title", c.title}, {"reason", inLevel ? "not run" : c.quickNote}});
    counts["not run"] = counts["not run"].get<int>() + 1;
    rows << "<tr class=\"notrun\" data-case=\"" << escape(c.id) << "\"><td>" << escape(c.id) << "</td><td colspan=\"5\">"
         << escape(c.title) << ": not run at this level. " << escape(inLevel ? std::string("not run") : c.quickNote)
         << "</td></tr>\n";
  }

  Json json = {{"level", level}, {"context", context}, {"passed", report.passed}, {"counts", counts},
               {"table", table}, {"not_run", notRun}, {"cases", cases}};
  report.json = json.dump(2) + "\n";

  std::ostringstream csv;
  const std::vector<std::string> columns = {"case", "quantity", "label", "unit", "ours", "reference", "reference_low",
                                            "reference_high", "reference_uncertainty", "tolerance_relative",
                                            "tolerance_absolute", "deviation", "off", "verdict", "known_failure"};
  for (std::size_t k = 0; k < columns.size(); ++k) csv << (k ? "," : "") << columns[k];
  csv << "\n";
  for (const Json& row : table) {
    for (std::size_t k = 0; k < columns.size(); ++k) csv << (k ? "," : "") << csvField(row[columns[k]]);
    csv << "\n";
  }
  report.csv = csv.str();

  std::ostringstream html;
  html << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>Rupture validation report (" << escape(level)
       << ")</title>\n<style>body{font-family:sans-serif;max-width:72rem;margin:1rem auto;padding:0 1rem;color:#222}"
          "table{border-collapse:collapse;width:100%}td,th{border:1px solid #ccc;padding:.3rem .5rem;text-align:left;vertical-align:top}"
          "tr.pass td:last-child{color:#1a7f37}tr.fail td:last-child{color:#c00;font-weight:bold}tr.known td:last-child{color:#b35900}"
          "tr.notrun{color:#777}p.verdict.pass{color:#1a7f37}p.verdict.fail{color:#c00}p.known{color:#b35900}"
          "figure{margin:0}figure img,figure svg{max-width:100%;height:auto}</style></head><body>\n"
       << "<h1>Rupture validation report</h1>\n<p>Level <b>" << escape(level) << "</b>: "
       << (report.passed ? "every quantity is within its tolerance or a documented known failure."
                         : "<b>some quantities fail</b> (or a known failure now passes: its case must be updated).")
       << " Counts: " << counts["pass"] << " pass, " << counts["fail"] << " fail, " << counts["known failure"]
       << " known failure, " << counts["unexpected pass"] << " unexpected pass; " << counts["not run"]
       << " case(s) not run at this level.</p>\n";
  if (!context.empty()) {
    html << "<p class=\"context\">";
    bool first = true;
    for (const auto& [key, value] : context.items()) {
      html << (first ? "" : " · ") << escape(key) << ": " << escape(value.is_string() ? value.get<std::string>() : value.dump());
      first = false;
    }
    html << "</p>\n";
  }
  html << "<p>The same table: <a href=\"report.json\">JSON</a>, <a href=\"report.csv\">CSV</a>. The deviation is "
          "|ours − reference| over the allowed difference (at most 1 passes); a range passes anywhere inside it.</p>\n"
       << "<table><thead><tr><th>case</th><th>quantity</th><th>reference</th><th>ours</th><th>tolerance</th>"
          "<th>verdict</th></tr></thead><tbody>\n"
       << rows.str() << "</tbody></table>\n" << sections.str() << "</body></html>\n";
  report.html = html.str();
  return report;
}

void writeSuiteReport(const SuiteReport& report, const std::string& directory) {
  fs::create_directories(fs::path(directory) / "figures");
  for (const auto& [name, svg] : report.figures) io::writeTextAtomically((fs::path(directory) / "figures" / name).string(), svg);
  io::writeTextAtomically((fs::path(directory) / "report.json").string(), report.json);
  io::writeTextAtomically((fs::path(directory) / "report.csv").string(), report.csv);
  io::writeTextAtomically((fs::path(directory) / "index.html").string(), report.html);
}

}  // namespace rupture::validation
