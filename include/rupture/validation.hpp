#pragma once
// The validation suite (docs/validation.md): the published cases of validation/, each run as a
// "validation" scenario run (one HDF5 file per case), and the report made from those files: an HTML
// page with the table (case, quantity, reference, ours, tolerance, verdict) and one figure per case,
// the same table as JSON and CSV. `rupture validate-suite` and the job server's
// GET /jobs/{id}/report build it with the same functions.
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace rupture::validation {

struct CaseListing {
  std::string id, title, paper;
  bool quick = true;      ///< the case has a quick level
  std::string quickNote;  ///< why the quick level stands in for the full one, or why it has none
};

/// The cases embedded in this build, in id order.
std::vector<CaseListing> listValidationCases();

/// The comparison a validation run wrote (/validation/result), as JSON; throws std::runtime_error
/// for a file that holds none (another scenario's, or a cancelled case).
nlohmann::json readCaseResult(const std::string& resultPath);

/// The result of a case whose runs could not finish (an error, a failed job run): one failing row
/// that says why.
nlohmann::json caseThatCouldNotRun(const std::string& caseId, const std::string& level, const std::string& why);

struct SuiteReport {
  std::string html, json, csv;
  std::vector<std::pair<std::string, std::string>> figures;  ///< file name ("<case>.svg") -> SVG
  bool passed = true;  ///< no quantity failed, and no known failure passed (its case must be updated)
};

/// The report of these case results. `level` "quick" or "full"; `context` is shown under the title
/// (the build, the host, the wall time); `inlineFigures`: the page holds the SVGs (a page served
/// alone) instead of linking figures/<case>.svg. Cases missing from `results` but in the level are
/// listed as not run.
SuiteReport buildSuiteReport(const std::vector<nlohmann::json>& results, const std::string& level,
                             const nlohmann::json& context, bool inlineFigures);

/// Writes index.html, report.json, report.csv and figures/<case>.svg under `directory` (created);
/// each file is written whole or not at all.
void writeSuiteReport(const SuiteReport& report, const std::string& directory);

}  // namespace rupture::validation
