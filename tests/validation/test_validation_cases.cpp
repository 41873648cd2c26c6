// The validation suite's machinery (docs/validation.md) without running simulations: the embedded
// cases parse and agree with the scenario's schema; the comparison passes inside a tolerance and
// fails outside it (a perturbed reference fails); known failures and ranges; the report's HTML,
// JSON and CSV tables agree.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "rupture/run.hpp"
#include "rupture/spec_error.hpp"
#include "rupture/validation.hpp"
#include "validation/validation_case.hpp"

namespace fs = std::filesystem;
using nlohmann::json;
using namespace rupture::validation;

namespace {

/// A piston-column result as the scenario's summary gives it, and a bottom-pressure series.
CaseRunData pistonData(double bottomPeakV5, double bottomPeakV2) {
  RunData v5{{{"first_peak_bottom_pressure", bottomPeakV5}, {"acoustic_pressure", 7.25e6}}, {}};
  std::vector<double> t, p;
  for (int k = 0; k <= 100; ++k) {
    t.push_back(2e-6 * k);
    p.push_back(k == 35 ? 7.3e6 : 1e5);  // the incident wave passes the mid-height gauge at 70 us
  }
  v5.series = {{"time", t}, {"probe_pressure_1", p}, {"bottom_pressure", p}};
  RunData v2{{{"first_peak_bottom_pressure", bottomPeakV2}, {"acoustic_pressure", 2.9e6}}, {}};
  return {{"v5", {v5}}, {"v2", {v2}}};
}

const json& quantityNamed(const json& result, const std::string& name) {
  for (const json& q : result["quantities"])
    if (q["name"] == name) return q;
  throw std::runtime_error("no quantity " + name);
}

}  // namespace

TEST(ValidationCases, EveryCaseFolderIsEmbeddedParsedAndInTheSchema) {
  std::set<std::string> folders;
  for (const auto& entry : fs::directory_iterator(fs::path(RUPTURE_SOURCE_DIR) / "validation"))
    if (fs::exists(entry.path() / "case.json")) folders.insert(entry.path().filename().string());
  std::set<std::string> embedded;
  for (const ValidationCase& c : validationCases()) {
    embedded.insert(c.id);
    EXPECT_FALSE(c.citation.empty()) << c.id;
    EXPECT_FALSE(c.quantities.empty()) << c.id;
    for (const std::string level : {"quick", "full"}) {
      if (level == std::string("quick") && !c.inQuick) continue;
      for (const auto& [name, members] : caseSpecs(c, level))
        for (const json& spec : members) EXPECT_NO_THROW(rupture::validateSpec(spec)) << c.id << " " << name << " " << level;
    }
  }
  EXPECT_EQ(folders, embedded);
  const json schema = rupture::scenarioSchema("validation");
  std::set<std::string> inSchema;
  for (const json& id : schema["properties"]["case"]["enum"]) inSchema.insert(id.get<std::string>());
  EXPECT_EQ(inSchema, embedded) << "api/schemas/validation.schema.json's case enum must list every case";
}

TEST(ValidationCases, ASpecNamingAnUnknownCaseOrAMissingLevelIsRefusedNamingTheField) {
  try {
    rupture::validateSpec({{"scenario", "validation"}, {"case", "no-such-case"}});
    FAIL() << "accepted an unknown case";
  } catch (const rupture::SpecError& e) {
    EXPECT_EQ(e.field(), "case");
  }
  try {
    rupture::validateSpec({{"scenario", "validation"}, {"case", "seed000-table2"}, {"level", "quick"}});
    FAIL() << "accepted a quick level the case does not have";
  } catch (const rupture::SpecError& e) {
    EXPECT_EQ(e.field(), "level");
  }
}

TEST(ValidationCases, WithinTheToleranceItPassesAndAPerturbedReferenceFails) {
  const ValidationCase* c = findValidationCase("piston-column-first-peak");
  ASSERT_NE(c, nullptr);
  // 2 rho0 c0 V = 14.5 MPa at 5 m/s, 5.8 MPa at 2 m/s; 10 % tolerance.
  const json good = evaluateCase(*c, "quick", pistonData(15.0e6, 5.9e6));
  EXPECT_EQ(good["verdict"], "pass");
  EXPECT_NEAR(quantityNamed(good, "bottom_peak_v5")["reference"]["value"].get<double>(), 14.5e6, 1);
  EXPECT_NEAR(quantityNamed(good, "gauge_peak_v5")["ours"].get<double>(), 7.3e6, 1);  // the peak within t < H/c0
  EXPECT_NEAR(quantityNamed(good, "bottom_peak_v5")["deviation"].get<double>(), 0.5e6 / 1.45e6, 1e-9);

  const json low = evaluateCase(*c, "quick", pistonData(12.9e6, 5.9e6));  // 11 % low
  EXPECT_EQ(low["verdict"], "fail");
  EXPECT_EQ(quantityNamed(low, "bottom_peak_v5")["verdict"], "fail");
  EXPECT_EQ(quantityNamed(low, "bottom_peak_v2")["verdict"], "pass");

  // The same data against a perturbed reference (3 rho0 c0 V instead of 2): it fails.
  json text = json::parse(std::ifstream(fs::path(RUPTURE_SOURCE_DIR) / "validation/piston-column-first-peak/case.json"));
  text["quantities"][0]["reference"]["factor"] = 3;
  const json perturbed = evaluateCase(parseValidationCase("piston-column-first-peak", text), "quick", pistonData(15.0e6, 5.9e6));
  EXPECT_EQ(perturbed["verdict"], "fail");
  EXPECT_EQ(quantityNamed(perturbed, "bottom_peak_v5")["verdict"], "fail");
}

TEST(ValidationCases, KnownFailuresRangesAndMissingValues) {
  const json text = {
      {"title", "t"}, {"paper", "p"}, {"citation", "c"}, {"how_read", "h"}, {"comparison", "x"}, {"quick_note", "q"},
      {"runs", {{{"name", "r"}, {"example", "piston-column-seed.json"}}}},
      {"quantities",
       {{{"name", "in_range"}, {"label", "a"}, {"unit", "Pa"}, {"ours", {{"run", "r"}, {"summary", "a"}}},
         {"reference", {{"range", {200, 300}}}}, {"tolerance", {{"relative", 0.2}}}},
        {{"name", "below_range"}, {"label", "b"}, {"unit", "Pa"}, {"ours", {{"run", "r"}, {"summary", "b"}}},
         {"reference", {{"range", {200, 300}}}}, {"tolerance", {{"relative", 0.2}}}, {"known_failure", "documented"}},
        {{"name", "known_but_passes"}, {"label", "c"}, {"unit", "Pa"}, {"ours", {{"run", "r"}, {"summary", "a"}}},
         {"reference", {{"value", 250}}}, {"tolerance", {{"relative", 0.1}}}, {"known_failure", "was off"}},
        {{"name", "at_least"}, {"label", "d"}, {"unit", "1"}, {"ours", {{"run", "r"}, {"summary", "missing"}}},
         {"reference", {{"range", {2, nullptr}}}}, {"tolerance", json::object()}}}}};
  const ValidationCase c = parseValidationCase("synthetic", text);
  const CaseRunData data = {{"r", {RunData{{{"a", 250.0}, {"b", 150.0}}, {}}}}};
  const json result = evaluateCase(c, "full", data);
  EXPECT_EQ(quantityNamed(result, "in_range")["verdict"], "pass");
  EXPECT_EQ(quantityNamed(result, "in_range")["deviation"], 0.0);
  EXPECT_EQ(quantityNamed(result, "below_range")["verdict"], "known failure");  // 150 < 200 - 20 %
  EXPECT_NEAR(quantityNamed(result, "below_range")["deviation"].get<double>(), 50.0 / 40.0, 1e-12);
  EXPECT_EQ(quantityNamed(result, "known_but_passes")["verdict"], "unexpected pass");
  EXPECT_EQ(quantityNamed(result, "at_least")["verdict"], "fail");  // no value: never a pass
  EXPECT_TRUE(quantityNamed(result, "at_least")["ours"].is_null());
  EXPECT_EQ(result["verdict"], "fail");
}

TEST(ValidationCases, AnArrivalTimeIsTheFirstCrossingOfTheLevelAndTellsThePWaveFromTheBarWave) {
  const ValidationCase* c = findValidationCase("lattice-wave-speed");
  ASSERT_NE(c, nullptr);
  const double gauge = 0.99e-6;
  const double cL = std::sqrt(220e9 / (6060 * (1 - 1.0 / 9))), cBorn = std::sqrt(220e9 / (6060 * 0.96));
  // A held face whose stress rises linearly from 0 to 76 MPa over 10 ps from `start` (rows every
  // 0.3 ps): it crosses the Hookean level, 38 MPa, at start + 5 ps whatever the rows.
  auto front = [&](double start, double plateau) {
    std::vector<double> t, s;
    for (int k = 0; k <= 1000; ++k) {
      t.push_back(0.3e-12 * k);
      s.push_back(std::clamp((t.back() - start) / 10e-12, 0.0, 1.0) * plateau);
    }
    return RunData{{{"gauge_length", gauge}}, {{"time", t}, {"stress_xmin", s}}};
  };
  auto data = [&](double hookeanArrival, double plateau) {
    return CaseRunData{{"hookean", {front(hookeanArrival - 5e-12, plateau)}}, {"born", {front(gauge / cBorn - 5e-12, 74e6)}}};
  };
  const json onTime = evaluateCase(*c, "quick", data(1.02 * gauge / cL, 76e6));
  EXPECT_EQ(onTime["verdict"], "pass");
  EXPECT_NEAR(quantityNamed(onTime, "hookean_arrival")["ours"].get<double>(), 1.02 * gauge / cL, 1e-18);
  EXPECT_NEAR(quantityNamed(onTime, "hookean_arrival")["reference"]["value"].get<double>(), gauge / cL, 1e-16);
  EXPECT_NEAR(quantityNamed(onTime, "hookean_arrival")["off"].get<double>(), 0.02, 1e-6);
  EXPECT_NEAR(quantityNamed(onTime, "born_arrival")["off"].get<double>(), 0.0, 1e-6);
  // The figure marks the reference arrival on its time axis (ps).
  ASSERT_EQ(onTime["figure"]["vertical_lines"].size(), 1u);
  EXPECT_NEAR(onTime["figure"]["vertical_lines"][0]["low"].get<double>(), gauge / cL * 1e12, 1e-6);

  // A front at the bar speed sqrt(E/rho), 6 % slower than the plane-stress P wave, fails.
  const json bar = evaluateCase(*c, "quick", data(gauge / std::sqrt(220e9 / 6060), 76e6));
  EXPECT_EQ(quantityNamed(bar, "hookean_arrival")["verdict"], "fail");
  // A face that never reaches the level has no arrival: not a pass.
  const json never = evaluateCase(*c, "quick", data(gauge / cL, 30e6));
  EXPECT_TRUE(quantityNamed(never, "hookean_arrival")["ours"].is_null());
  EXPECT_EQ(never["verdict"], "fail");

  // first_reaching is a level on a series, not with max_over.
  json text = json::parse(std::ifstream(fs::path(RUPTURE_SOURCE_DIR) / "validation/lattice-wave-speed/case.json"));
  text["quantities"][0]["ours"]["max_over"] = {0, 1};
  try {
    parseValidationCase("lattice-wave-speed", text);
    FAIL() << "accepted first_reaching with max_over";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("quantities[0].ours.first_reaching"), std::string::npos) << e.what();
  }
}

TEST(ValidationCases, AMalformedCaseIsRefusedNamingTheFileAndField) {
  json text = json::parse(std::ifstream(fs::path(RUPTURE_SOURCE_DIR) / "validation/piston-column-first-peak/case.json"));
  text["quantities"][1]["tolerance"]["relative"] = -0.1;
  try {
    parseValidationCase("piston-column-first-peak", text);
    FAIL() << "accepted a negative tolerance";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("validation/piston-column-first-peak/case.json: quantities[1].tolerance"), std::string::npos) << e.what();
  }
  text = json::parse(std::ifstream(fs::path(RUPTURE_SOURCE_DIR) / "validation/piston-column-first-peak/case.json"));
  text["quantities"][0]["ours"]["run"] = "v9";
  EXPECT_THROW(parseValidationCase("piston-column-first-peak", text), std::runtime_error);
  text = json::parse(std::ifstream(fs::path(RUPTURE_SOURCE_DIR) / "validation/piston-column-first-peak/case.json"));
  text["runs"][0]["example"] = "no-such-example.json";
  EXPECT_THROW(parseValidationCase("piston-column-first-peak", text), std::runtime_error);
}

TEST(ValidationReport, TheHtmlTableAgreesWithTheJsonAndTheCsvAndEveryFigureHasContent) {
  const ValidationCase* piston = findValidationCase("piston-column-first-peak");
  const json passing = evaluateCase(*piston, "quick", pistonData(15.0e6, 5.9e6));
  const json failing = evaluateCase(*piston, "quick", pistonData(12.9e6, 5.9e6));
  json renamed = failing;
  renamed["case"] = "dam-break-martin-moyce";  // two distinct cases in one report
  const SuiteReport report = buildSuiteReport({passing, renamed}, "quick", {{"host", "test"}}, false);
  EXPECT_FALSE(report.passed);
  const json doc = json::parse(report.json);
  ASSERT_EQ(doc["table"].size(), 6u);
  // CSV: a header and one line per table row, in order, with the same verdicts and numbers.
  std::istringstream csv(report.csv);
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line.rfind("case,quantity,label,unit,ours,reference", 0), 0u);
  std::size_t k = 0;
  const std::regex row(R"re(<tr class="[a-z]+" data-case="([^"]*)" data-quantity="([^"]*)" data-ours="([^"]*)" data-verdict="([^"]*)">)re");
  std::vector<std::smatch> htmlRows;
  for (std::sregex_iterator it(report.html.begin(), report.html.end(), row), end; it != end; ++it) htmlRows.push_back(*it);
  ASSERT_EQ(htmlRows.size(), doc["table"].size());
  while (std::getline(csv, line)) {
    ASSERT_LT(k, doc["table"].size());
    const json& r = doc["table"][k];
    EXPECT_EQ(line.rfind(r["case"].get<std::string>() + "," + r["quantity"].get<std::string>() + ",", 0), 0u) << line;
    EXPECT_NE(line.find("," + r["verdict"].get<std::string>() + ","), std::string::npos) << line;
    EXPECT_EQ(htmlRows[k][1].str(), r["case"]);
    EXPECT_EQ(htmlRows[k][2].str(), r["quantity"]);
    EXPECT_EQ(htmlRows[k][4].str(), r["verdict"]);
    EXPECT_NEAR(std::stod(htmlRows[k][3].str()), r["ours"].get<double>(), 1e-9 * std::fabs(r["ours"].get<double>()));
    ++k;
  }
  EXPECT_EQ(k, doc["table"].size());
  ASSERT_EQ(report.figures.size(), 2u);
  for (const auto& [name, svg] : report.figures) {
    EXPECT_NE(svg.find("<polyline"), std::string::npos) << name;  // our curve
    EXPECT_NE(svg.find("</svg>"), std::string::npos) << name;
  }
  // Every case not given is listed as not run.
  EXPECT_EQ(doc["not_run"].size(), validationCases().size() - 2);
}
