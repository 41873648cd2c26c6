// One generic check over every registered scenario: a tiny run of each, and every summary scalar
// and series it writes has a declared unit, found the same in the HDF5 file, the summary JSON, the
// summary CSV header, the series CSV header and the merged job file's /summary table.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <optional>

#include "io/hdf5_file.hpp"
#include "views/results.hpp"
#include "rupture/run.hpp"
#include "server_test_support.hpp"
#include "studies/summary.hpp"

namespace rupture::server {
namespace fs = std::filesystem;
namespace {

/// The smallest meaningful run of each scenario (a few seconds at most). A new scenario gets one
/// here, or this test fails and names it.
const std::map<std::string, Json>& tinySpecs() {
  static const std::map<std::string, Json> specs = {
      {"dynamic-tension",
       {{"scenario", "dynamic-tension"}, {"dimension", 2},
        {"sample", {{"size", {0.3e-6, 0.3e-6}}, {"element_radius", 1.5e-8}, {"seed", 5}}},
        {"material", {{"model", "beam"}, {"density", 6060},
                      {"beam", {{"young_modulus", 2865e9}, {"poisson_ratio", 0.3}, {"radius_ratio", 0.3},
                                {"failure_stress", 4e9}}}}},
        {"loading", {{"strain_rate", 1e8}, {"initial_velocity", "VL"}}},
        {"run", {{"max_strain", 0.004}}}}},
      {"elastic-properties",
       {{"scenario", "elastic-properties"}, {"dimension", 2},
        {"sample", {{"size", {0.15e-6, 0.15e-6}}, {"element_radius", 3.3e-9}, {"seed", 7}}},
        {"material", {{"model", "beam"}, {"density", 6060.0},
                      {"beam", {{"young_modulus", 2865e9}, {"poisson_ratio", 0.3}, {"radius_ratio", 0.3},
                                {"failure_stress", 4e9}}}}}}},
      {"impact",
       {{"scenario", "impact"}, {"dimension", 2},
        {"sample", {{"lattice", "square"}, {"size", {0.01, 0.005}}, {"spacing", 5e-4}}},
        {"material", {{"model", "pmb"}, {"density", 2440}, {"pmb", {{"young_modulus", 72e9}, {"fracture_energy", 3.8}}}}},
        {"loading", {{"velocity_regions", {{{"min", {0.0, 0.0045}}, {"max", {0.01, 0.005}}, {"velocity", {0.0, 4.0}}}}}}},
        {"run", {{"end_time", 2e-6}}}}},
      {"dam-break",
       {{"scenario", "dam-break"}, {"dimension", 2},
        {"geometry", {{"column_width", 0.05}, {"column_height", 0.05}, {"tank_length", 0.1}, {"tank_height", 0.06}}},
        {"resolution", {{"spacing", 0.01}}},
        {"probes", {{0.005, 0.005}}},
        {"run", {{"end_time", 0.005}}}}},
      {"piston-column",
       {{"scenario", "piston-column"}, {"dimension", 2},
        {"geometry", {{"diameter", 0.04}, {"column_height", 0.04}}},
        {"resolution", {{"spacing", 0.005}}},
        {"probes", {{0.0, 0.005}}},
        {"run", {{"end_time", 5e-5}}}}},
      {"tank-impact",
       {{"scenario", "tank-impact"},
        {"tank", {{"inner_diameter", 0.04}, {"water_height", 0.03}}},
        {"impactor", {{"mass", 5.0}, {"speed", 2.0}}},
        {"plate", {{"thickness", 0.002}, {"spacing", 0.004}, {"precrack", {{"shape", "hole"}, {"hole_diameter", 0.012}}}}},
        {"resolution", {{"spacing", 0.005}}},
        {"run", {{"end_time", 2e-5}}}}},
      {"validation", {{"scenario", "validation"}, {"case", "lattice-elastic-constants"}, {"level", "quick"}}},
  };
  return specs;
}

/// Points RUPTURE_CACHE_DIR at a directory for this scope and restores it afterwards (the other
/// tests of this process rely on the server's own cache directory).
class CacheDirFor {
public:
  explicit CacheDirFor(const fs::path& dir) {
    if (const char* old = std::getenv("RUPTURE_CACHE_DIR")) m_old = old;
    ::setenv("RUPTURE_CACHE_DIR", dir.c_str(), 1);
  }
  ~CacheDirFor() {
    if (m_old) ::setenv("RUPTURE_CACHE_DIR", m_old->c_str(), 1);
    else ::unsetenv("RUPTURE_CACHE_DIR");
  }
  CacheDirFor(const CacheDirFor&) = delete;
  CacheDirFor& operator=(const CacheDirFor&) = delete;

private:
  std::optional<std::string> m_old;
};

std::string headerUnit(const std::string& cell) {
  const std::size_t open = cell.rfind(" [");
  return open == std::string::npos || cell.back() != ']' ? std::string("(none)") : cell.substr(open + 2, cell.size() - open - 3);
}

TEST(ResultUnits, EveryScenarioDeclaresAndWritesAUnitForEveryResult) {
  test::TempDir dir;
  const CacheDirFor cache(dir.path() / "cache");
  for (const ScenarioInfo& scenario : listScenarios()) {
    SCOPED_TRACE(scenario.name);
    auto spec = tinySpecs().find(scenario.name);
    ASSERT_NE(spec, tinySpecs().end()) << "add a tiny spec for scenario " << scenario.name;
    for (const ResultField& f : scenario.summary) {
      EXPECT_FALSE(f.label.empty()) << f.name;
      EXPECT_FALSE(f.description.empty()) << f.name;
    }
    const fs::path file = dir.path() / (scenario.name + ".h5");
    RunControl control;
    const RunOutcome outcome = runSpec(spec->second, file.string(), control, 1);
    ASSERT_TRUE(outcome.completed);

    // HDF5: every /summary attribute is declared and carries the declared unit; every /series
    // dataset is declared and carries its unit.
    {
      io::Hdf5File h5 = io::Hdf5File::openReadOnly(file.string());
      const int dimension = specDimension(scenarioSchema(scenario.name), spec->second);
      for (const std::string& name : h5.listAttributes("/summary")) {
        if (name.size() > 5 && name.compare(name.size() - 5, 5, "_unit") == 0) continue;
        const ResultField* f = findResultField(scenario.summary, name);
        ASSERT_NE(f, nullptr) << "undeclared summary scalar " << name;
        if (f->unit.empty()) continue;  // text (stop_reason)
        ASSERT_TRUE(h5.hasAttribute("/summary", name + "_unit")) << name;
        EXPECT_EQ(h5.readAttributeString("/summary", name + "_unit"), f->unitFor(dimension)) << name;
      }
      if (h5.exists("/series")) {
        for (const std::string& name : h5.listGroup("/series")) {
          const ResultField* f = findResultField(scenario.series, name);
          ASSERT_NE(f, nullptr) << "undeclared series " << name;
          EXPECT_EQ(h5.readAttributeString("/series/" + name, "unit"), f->unitFor(dimension)) << name;
        }
      }
    }

    // Summary JSON and CSV of a one-run job built from this run.
    JobRecord job;
    job.id = 1;
    job.processId = scenario.name;
    job.sweptPaths = Json::array();
    RunRecord run;
    run.key = {1, 0};
    run.status = Status::Successful;
    run.spec = spec->second;
    run.swept = Json::array();
    run.summary = outcome.summary;
    run.resultPath = file.filename().string();
    const SummaryTable table = buildSummary(job, {run});
    const Json doc = summaryJson(table);
    ASSERT_FALSE(table.scalarNames.empty());
    for (const std::string& name : table.scalarNames) {
      const ResultField* f = findResultField(scenario.summary, name);
      ASSERT_NE(f, nullptr) << name;
      EXPECT_EQ(doc["units"][name], f->unitFor(specDimension(scenarioSchema(scenario.name), spec->second))) << name;
    }
    for (const Json& column : doc["columns"]) {
      EXPECT_TRUE(column.contains("unit") && column.contains("label")) << column.dump();
      EXPECT_NE(column["label"], column["name"]) << "no human label for " << column["name"];
    }
    const auto csv = test::parseCsv(summaryCsv(table));
    ASSERT_EQ(csv.size(), 2u);
    ASSERT_EQ(csv[0].size(), 3 + doc["columns"].size());  // run, status, the columns, error
    for (std::size_t c = 2; c + 1 < csv[0].size(); ++c) {
      const std::string name = doc["columns"][c - 2]["name"];
      const std::string unit = doc["units"][name];
      EXPECT_EQ(headerUnit(csv[0][c]), unit.empty() ? "(none)" : unit) << csv[0][c];
    }

    // Series CSV: every column "name [unit]".
    if (!scenario.series.empty()) {
      const auto series = test::parseCsv(seriesCsv(readSeries(file, {})));
      ASSERT_FALSE(series.empty());
      for (const std::string& cell : series[0]) EXPECT_NE(headerUnit(cell), "(none)") << cell;
    }

    // The merged job file's /summary table: one dataset per column with its unit.
    const fs::path merged = mergedResults(job, {run}, dir.path());
    io::Hdf5File h5 = io::Hdf5File::openReadOnly(merged.string());
    for (const std::string& name : table.scalarNames) {
      ASSERT_TRUE(h5.exists("/summary/" + name)) << name;
      EXPECT_EQ(h5.readAttributeString("/summary/" + name, "unit"), doc["units"][name].get<std::string>()) << name;
    }
    fs::remove_all(dir.path() / "jobs");
  }
}

TEST(MergedResults, SummaryTableWithUnitsAndNoServerPaths) {
  test::TempDir dir;
  const CacheDirFor cache(dir.path() / "cache");
  Json spec = tinySpecs().at("dynamic-tension");
  spec["loading"]["initial_velocity"] = "V0";  // V0 without a ramp time: the cached preliminary run
  RunControl control;
  const RunOutcome outcome = runSpec(spec, (dir.path() / "run-0.h5").string(), control, 1);
  ASSERT_TRUE(outcome.completed);

  JobRecord job;
  job.id = 4;
  job.processId = "dynamic-tension";
  job.sweptPaths = Json::array({"loading.strain_rate", "loading.initial_velocity"});
  std::vector<RunRecord> runs;
  for (int k = 0; k < 3; ++k) {
    RunRecord r;
    r.key = {4, k};
    r.spec = spec;
    r.swept = Json::array({1e8, k == 1 ? "VL" : "V0"});
    r.status = k == 2 ? Status::Failed : Status::Successful;
    r.summary = k == 2 ? Json() : Json(outcome.summary);
    r.error = k == 2 ? "diverged" : "";
    r.resultPath = k == 2 ? "" : "run-0.h5";
    runs.push_back(r);
  }
  const fs::path merged = mergedResults(job, runs, dir.path());
  {
    io::Hdf5File h5 = io::Hdf5File::openReadOnly(merged.string());
    // One row per run, one column per swept value and scalar, each with its unit.
    EXPECT_EQ(h5.readDatasetInt("/summary/run"), (std::vector<std::int64_t>{0, 1, 2}));
    EXPECT_EQ(h5.readDatasetString("/summary/status"), (std::vector<std::string>{"successful", "successful", "failed"}));
    EXPECT_EQ(h5.readDatasetString("/summary/loading.initial_velocity"), (std::vector<std::string>{"V0", "VL", "V0"}));
    const double seed = spec["sample"].contains("seed") ? spec["sample"]["seed"].get<double>() : 1.0;  // schema default 1
    EXPECT_EQ(h5.readDatasetDouble("/summary/sample.seed"), (std::vector<double>{seed, seed, seed}));
    EXPECT_EQ(h5.readAttributeString("/summary/sample.seed", "unit"), "1");
    EXPECT_EQ(h5.readAttributeString("/summary/loading.strain_rate", "unit"), "1/s");
    EXPECT_EQ(h5.readAttributeString("/summary/loading.strain_rate", "label"), "Strain rate");
    const std::vector<double> peak = h5.readDatasetDouble("/summary/peak_stress");
    ASSERT_EQ(peak.size(), 3u);
    EXPECT_DOUBLE_EQ(peak[0], outcome.summary["peak_stress"].get<double>());
    EXPECT_TRUE(std::isnan(peak[2]));
    EXPECT_EQ(h5.readAttributeString("/summary/peak_stress", "unit"), "Pa");
    EXPECT_EQ(h5.readAttributeString("/summary/peak_stress", "label"), "Peak stress");
    EXPECT_FALSE(h5.exists("/summary/strain_rate"));  // the swept value is not repeated
    const Json columns = Json::parse(h5.readAttributeString("/summary", "columns"));
    EXPECT_EQ(columns[2], "loading.strain_rate");
    // Sweep values, snapshots and the sample carry units.
    EXPECT_EQ(h5.readAttributeString("/run-0", "sweep.loading.strain_rate_unit"), "1/s");
    EXPECT_EQ(h5.readAttributeString("/run-0/sample", "gauge_length_unit"), "m");
    EXPECT_EQ(h5.readAttributeString("/run-0/sample", "elements_unit"), "1");
    EXPECT_EQ(h5.readAttributeString("/run-0/preliminary", "wall_time_s_unit"), "s");
    for (const std::string& snap : h5.listGroup("/run-0/snapshots")) {
      EXPECT_EQ(h5.readAttributeString("/run-0/snapshots/" + snap, "time_unit"), "s");
    }
    EXPECT_EQ(h5.readAttributeString("/run-0/preliminary", "cache_file").find('/'), std::string::npos);
  }
  // No path of this machine anywhere in the file (attributes are stored uncompressed).
  std::ifstream in(merged, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(bytes.find(dir.path().string()), std::string::npos);
}

}  // namespace
}  // namespace rupture::server
