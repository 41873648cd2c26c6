// rupture validate-suite [--quick|--full] [-o DIR] [--case ID]... [--threads N]
// Runs the validation cases (validation/, docs/validation.md) one after the other, each as a
// "validation" scenario run whose file lands in DIR/cases/<case>.h5, and writes the report:
// DIR/index.html, DIR/report.json, DIR/report.csv, DIR/figures/<case>.svg. Exit 0 when every
// quantity is within its tolerance or a documented known failure, 1 otherwise (or when a case could
// not run), 2 for bad options, 130 when interrupted (the report then holds the cases done). The
// report covers every case of the level that DIR/cases holds a file of, so --case re-runs one case
// of an existing report.
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <iostream>

#include "cli/cli.hpp"
#include "cli/interrupt_guard.hpp"
#include "io/provenance.hpp"
#include "rupture/run.hpp"
#include "rupture/validation.hpp"

namespace rupture::cli {

namespace {

namespace fs = std::filesystem;

constexpr const char* kUsage =
    "usage: rupture validate-suite [--quick|--full] [-o DIR] [--case ID]... [--threads N]\n"
    "  --quick       reduced resolutions the docs show give the same answers (default; minutes)\n"
    "  --full        every case at the published resolution (hours on two cores)\n"
    "  -o DIR        where the report goes (default validation-report): index.html, report.json,\n"
    "                report.csv, figures/<case>.svg, and each case's run file in cases/<case>.h5\n"
    "  --case ID     run only this case (repeatable); `rupture validate-suite --list` lists them\n"
    "  --threads N   OpenMP threads of each run (default: all cores)\n"
    "exit codes: 0 every quantity within tolerance or a documented known failure, 1 otherwise,\n"
    "            2 invalid options, 130 interrupted\n";

}  // namespace

int validateSuiteCommand(const Args& args) {
  std::string level = "quick", directory = "validation-report";
  std::vector<std::string> only;
  long long threads = omp_get_max_threads();
  bool list = false;
  for (std::size_t k = 0; k < args.size(); ++k) {
    const std::string& a = args[k];
    if (a == "--quick" || a == "--full") {
      level = a.substr(2);
    } else if (a == "--list") {
      list = true;
    } else if (a == "-o" || a == "--output" || a == "--case" || a == "--threads") {
      if (k + 1 >= args.size()) return usageError("validate-suite: " + a + " needs a value");
      const std::string& value = args[++k];
      if (a == "--threads") {
        if (!parseIntOption("--threads", value, 1, 1024, threads)) return 2;
      } else if (a == "--case") {
        only.push_back(value);
      } else {
        directory = value;
      }
    } else {
      return usageError("validate-suite: unknown option '" + a + "'; allowed: --quick, --full, -o/--output, --case, "
                        "--threads, --list, --help\n" + kUsage);
    }
  }
  const std::vector<validation::CaseListing> all = validation::listValidationCases();
  if (list) {
    for (const validation::CaseListing& c : all)
      std::cout << c.id << (c.quick ? "  [quick, full]  " : "  [full]  ") << c.title << "\n";
    return 0;
  }
  for (const std::string& id : only)
    if (std::none_of(all.begin(), all.end(), [&](const validation::CaseListing& c) { return c.id == id; })) {
      std::string ids;
      for (const validation::CaseListing& c : all) ids += (ids.empty() ? "" : ", ") + c.id;
      return usageError("validate-suite: --case '" + id + "' is not a validation case; allowed: " + ids);
    }
  std::vector<validation::CaseListing> cases;
  for (const validation::CaseListing& c : all) {
    if (!only.empty() && std::find(only.begin(), only.end(), c.id) == only.end()) continue;
    if (level == "quick" && !c.quick) {
      if (!only.empty()) return usageError("validate-suite: case '" + c.id + "' has no quick level (" + c.quickNote + "); pass --full");
      continue;
    }
    cases.push_back(c);
  }
  try {
    fs::create_directories(fs::path(directory) / "cases");
  } catch (const fs::filesystem_error& e) {
    return usageError("validate-suite: -o '" + directory + "': cannot create the directory (" + e.code().message() + ")");
  }

  const auto start = std::chrono::steady_clock::now();
  std::vector<nlohmann::json> results;
  bool interrupted = false;
  RunControl control;
  InterruptGuard guard(control.cancel);
  for (std::size_t k = 0; k < cases.size() && !interrupted; ++k) {
    const validation::CaseListing& c = cases[k];
    std::string prefix = "[";
    prefix.append(std::to_string(k + 1)).append("/").append(std::to_string(cases.size())).append("] ");
    std::cerr << prefix << c.id << " (" << level << ")\n";
    control.progress.store(0);
    control.log = [&](const std::string& message) { std::cerr << prefix << message << "\n"; };
    const std::string path = (fs::path(directory) / "cases" / (c.id + ".h5")).string();
    std::error_code ignored;
    fs::remove(path, ignored);
    try {
      const RunOutcome outcome =
          runSpec(nlohmann::json{{"scenario", "validation"}, {"case", c.id}, {"level", level}}, path, control,
                  static_cast<int>(threads));
      if (!outcome.completed) {
        interrupted = true;
        break;
      }
      results.push_back(validation::readCaseResult(path));
    } catch (const std::exception& e) {
      std::cerr << prefix << c.id << ": could not run: " << e.what() << "\n";
      results.push_back(validation::caseThatCouldNotRun(c.id, level, e.what()));
    }
    std::cerr << prefix << c.id << ": " << results.back()["verdict"].get<std::string>() << "\n";
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // The report covers every case of this level whose file DIR/cases holds, so that re-running one
  // case (--case) updates a whole report; the cases run now come first in its list of runs.
  const std::size_t ranNow = results.size();
  for (const validation::CaseListing& c : all) {
    if (std::any_of(results.begin(), results.end(), [&](const nlohmann::json& r) { return r["case"] == c.id; })) continue;
    const fs::path earlier = fs::path(directory) / "cases" / (c.id + ".h5");
    if (!fs::exists(earlier)) continue;
    try {
      nlohmann::json result = validation::readCaseResult(earlier.string());
      if (result.value("level", "") == level) results.push_back(std::move(result));
    } catch (const std::exception&) {
      // an interrupted or foreign file: not part of the report
    }
  }
  std::sort(results.begin(), results.end(),
            [](const nlohmann::json& a, const nlohmann::json& b) { return a["case"] < b["case"]; });
  const io::BuildInfo& build = io::buildInfo();
  const nlohmann::json context = {{"rupture", build.version + " (" + build.commit + ")"},
                                  {"compiler", build.compiler + " " + build.buildType},
                                  {"host", io::hostProcessor()},
                                  {"threads", threads},
                                  {"finished", io::utcNow()},
                                  {"wall time of this invocation", std::to_string(static_cast<long long>(wall + 0.5)) + " s"}};
  const validation::SuiteReport report = validation::buildSuiteReport(results, level, context, false);
  try {
    validation::writeSuiteReport(report, directory);
  } catch (const std::exception& e) {
    std::cerr << "rupture validate-suite: " << e.what() << "\n";
    return 1;
  }
  std::cerr << "rupture validate-suite: " << (interrupted ? "interrupted; " : "") << ranNow << " case(s) run in "
            << static_cast<long long>(wall + 0.5) << " s, " << results.size() << " in the report: "
            << (report.passed ? "every quantity within tolerance or a known failure" : "FAILED") << "; report in "
            << (fs::path(directory) / "index.html").string() << "\n";
  if (interrupted) return 130;
  return report.passed ? 0 : 1;
}

}  // namespace rupture::cli
