// Studies over HTTP on the small dynamic-tension example (runs of about a second): a 2-point x
// 3-replicate sweep whose statistics are checked against its own rows, the comparison of two jobs,
// and an adaptive refinement that adds exactly its budget.
#include <algorithm>
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "io/hdf5_file.hpp"
#include "server_test_support.hpp"
#include "views/html_page.hpp"

namespace rupture::server {
namespace {

using test::expectProblem;
using test::getJson;
using test::LiveServer;


class StudyHttp : public ::testing::Test {
protected:
  void SetUp() override { ASSERT_TRUE(test::scenarioAvailable()); }
};

TEST_F(StudyHttp, ReplicatedSweepReportsMeansAndIntervalsOfItsRowsAndComparesWithAnotherJob) {
  LiveServer live;
  auto client = live.client();
  const Json rates = test::twoStrainRates();
  const Json body = {{"name", "replicated"},
                     {"inputs", test::smallInputs()},
                     {"sweep", {{"loading.strain_rate", rates}}},
                     {"replicates", {{"count", 3}, {"vary", "sample.seed"}}}};
  const std::int64_t id = test::submit(*client, body);
  ASSERT_GT(id, 0);
  // A second, plain job to compare with: one run at the higher rate.
  const std::int64_t other = test::submit(
      *client, Json{{"name", "single"}, {"inputs", test::smallInputs()}, {"sweep", {{"loading.strain_rate", {rates[1]}}}}});
  // Unfinished jobs compare as they stand: every run is a row, the unfinished ones without scalars.
  const Json early = getJson(*client, "/summary?jobs=" + std::to_string(id) + "," + std::to_string(other));
  ASSERT_EQ(early["rows"].size(), 7u);
  EXPECT_NE(early["rows"][5]["status"], "successful");  // the last replicate of 6 runs on 2 workers
  EXPECT_TRUE(early["rows"][5].value("peak_stress", Json()).is_null());
  EXPECT_NE(early["jobs"][0]["status"], "successful");
  // Bad replicates are refused whole, naming the field.
  Json bad = body;
  bad["replicates"]["count"] = 0;
  expectProblem(test::postJson(*client, test::kExecutePath, bad), 400, "replicates.count");
  bad["replicates"] = {{"count", 2}, {"vary", "loading.strain_rate"}};
  expectProblem(test::postJson(*client, test::kExecutePath, bad), 400, "replicates.vary");

  const Json done = test::waitForJob(*client, id, {"successful", "failed", "dismissed"}, 240);
  ASSERT_EQ(done["status"], "successful") << done.dump(2);
  EXPECT_EQ(done["runs_total"], 6);
  EXPECT_EQ(done["replicates"], Json::parse(R"({"count": 3, "vary": "sample.seed"})"));
  const long long seed = test::smallInputs()["sample"]["seed"].get<long long>();
  for (int k = 0; k < 6; ++k) {
    EXPECT_EQ(done["runs"][k]["replicate"], k % 3);
    EXPECT_EQ(getJson(*client, "/jobs/" + std::to_string(id) + "/runs/" + std::to_string(k))["spec"]["sample"]["seed"],
              seed + k % 3);
  }

  // The statistics, recomputed from the per-replicate rows.
  const std::string base = "/jobs/" + std::to_string(id) + "/summary";
  const Json rows = getJson(*client, base);
  const Json points = getJson(*client, base + "?aggregate=replicates");
  EXPECT_EQ(points["aggregate"], "replicates");
  ASSERT_EQ(points["rows"].size(), 2u);
  for (int p = 0; p < 2; ++p) {
    std::vector<double> v;
    for (const auto& r : rows["rows"]) {
      if (r["loading.strain_rate"] == rates[p]) v.push_back(r["peak_stress"].get<double>());
    }
    ASSERT_EQ(v.size(), 3u);
    const double mean = (v[0] + v[1] + v[2]) / 3;
    double ss = 0;
    for (double x : v) ss += (x - mean) * (x - mean);
    const double sd = std::sqrt(ss / 2);
    const double half = 4.302653 * sd / std::sqrt(3.0);
    const Json& s = points["rows"][p]["peak_stress"];
    EXPECT_EQ(points["rows"][p]["loading.strain_rate"], rates[p]);
    EXPECT_EQ(s["n"], 3);
    EXPECT_NEAR(s["mean"].get<double>(), mean, 1e-9 * mean);
    EXPECT_NEAR(s["sd"].get<double>(), sd, 1e-9 * mean);
    EXPECT_NEAR(s["ci95_low"].get<double>(), mean - half, 1e-6 * mean);
    EXPECT_NEAR(s["ci95_high"].get<double>(), mean + half, 1e-6 * mean);
    EXPECT_EQ(points["rows"][p]["runs"], Json::array({3 * p, 3 * p + 1, 3 * p + 2}));
  }
  // Units and the rate-dependence figures ride along.
  EXPECT_EQ(points["columns"][0]["unit"], "1/s");
  ASSERT_TRUE(points.contains("rate_dependence"));
  EXPECT_EQ(points["rate_dependence"]["series"][0]["slopes"].size(), 1u);
  auto csv = client->Get((base + "?aggregate=replicates&format=csv").c_str());
  ASSERT_TRUE(csv);
  EXPECT_EQ(csv->status, 200);
  const auto table = test::parseCsv(csv->body);
  ASSERT_EQ(table.size(), 3u);
  EXPECT_EQ(table[0][3], "peak_stress.mean [Pa]");
  EXPECT_EQ(table[1][2], "3");
  auto svg = client->Get((base + ".svg").c_str());
  ASSERT_TRUE(svg);
  EXPECT_EQ(svg->status, 200);
  EXPECT_NE(svg->body.find("class=\"error-bar\""), std::string::npos);
  expectProblem(client->Get((base + "?aggregate=seeds").c_str()), 400, "aggregate");
  // The merged HDF5 file names each run's replicate and holds the study.
  {
    auto merged = client->Get(("/jobs/" + std::to_string(id) + "/results").c_str());
    ASSERT_TRUE(merged);
    ASSERT_EQ(merged->status, 200);
    test::TempDir dir;
    std::ofstream(dir.path() / "job.h5", std::ios::binary) << merged->body;
    const auto file = rupture::io::Hdf5File::openReadOnly((dir.path() / "job.h5").string());
    EXPECT_EQ(file.readAttributeInt("/run-4", "sweep.replicate"), 1);
    EXPECT_EQ(Json::parse(file.readAttributeString("/", "study"))["replicates"]["count"], 3);
  }

  // Comparison of the two jobs: rows of both, with a job column; one plot series per job.
  ASSERT_EQ(test::waitForJob(*client, other, {"successful", "failed"}, 120)["status"], "successful");
  const std::string both = std::to_string(id) + "," + std::to_string(other);
  const Json compared = getJson(*client, "/summary?jobs=" + both);
  ASSERT_EQ(compared["rows"].size(), 7u);
  EXPECT_EQ(compared["columns"][0]["name"], "job");
  EXPECT_EQ(compared["rows"][0]["job"], std::to_string(id));
  EXPECT_EQ(compared["rows"][6]["job"], std::to_string(other));
  EXPECT_EQ(compared["rows"][6]["peak_stress"], getJson(*client, "/jobs/" + std::to_string(other))["runs"][0]["summary"]["peak_stress"]);
  EXPECT_EQ(compared["jobs"][1]["label"], std::to_string(other) + ": single");
  const Json comparedPoints = getJson(*client, "/summary?aggregate=replicates&jobs=" + both);
  ASSERT_EQ(comparedPoints["rows"].size(), 3u);
  EXPECT_EQ(comparedPoints["rows"][1]["peak_stress"]["mean"], points["rows"][1]["peak_stress"]["mean"]);
  auto compareCsv = client->Get(("/summary?format=csv&jobs=" + both).c_str());
  ASSERT_TRUE(compareCsv);
  const auto compareRows = test::parseCsv(compareCsv->body);
  ASSERT_EQ(compareRows.size(), 8u);
  EXPECT_EQ(compareRows[0][0], "job");
  EXPECT_NE(std::find(compareRows[0].begin(), compareRows[0].end(), "peak_stress [Pa]"), compareRows[0].end())
      << "headers carry their units, as the per-job CSV's do";
  EXPECT_EQ(compared["units"]["peak_stress"], "Pa");
  EXPECT_EQ(compareRows[7][0], std::to_string(other));
  auto plot = client->Get(("/plot?jobs=" + both).c_str());
  ASSERT_TRUE(plot);
  EXPECT_EQ(plot->status, 200);
  EXPECT_EQ(plot->get_header_value("Content-Type"), "image/svg+xml");
  EXPECT_NE(plot->body.find("data-label=\"" + std::to_string(id) + ": replicated\""), std::string::npos);
  EXPECT_NE(plot->body.find("data-label=\"" + std::to_string(other) + ": single\""), std::string::npos);
  // Errors: an unknown job is named (404), too many jobs or a malformed list is a 400.
  const Json missing = expectProblem(client->Get(("/summary?jobs=" + both + ",999").c_str()), 404, "jobs");
  EXPECT_NE(missing["detail"].get<std::string>().find("999"), std::string::npos);
  expectProblem(client->Get("/plot?jobs=999"), 404, "jobs");
  expectProblem(client->Get("/summary?jobs=1,2,3,4,5,6,7,8,9,10,11"), 400, "jobs");
  expectProblem(client->Get("/summary?jobs=abc"), 400, "jobs");
  expectProblem(client->Get("/summary"), 400, "jobs");
}

TEST_F(StudyHttp, RefinementAddsItsBudgetBetweenTheNeighboursAndRecordsWhy) {
  LiveServer live;
  auto client = live.client();
  const Json rates = test::twoStrainRates();
  Json body = {{"name", "refined"},
               {"inputs", test::smallInputs()},
               {"sweep", {{"loading.strain_rate", rates}}},
               {"refine", {{"path", "loading.strain_rate"}, {"quantity", "peak_stress"}, {"max_runs", 1}, {"tolerance", 0.01}}}};
  Json bad = body;
  bad["refine"]["path"] = "loading.initial_velocity";
  expectProblem(test::postJson(*client, test::kExecutePath, bad), 400, "refine.path");
  bad = body;
  bad["refine"]["max_runs"] = 0;
  expectProblem(test::postJson(*client, test::kExecutePath, bad), 400, "refine.max_runs");

  const std::int64_t id = test::submit(*client, body);
  ASSERT_GT(id, 0);
  const Json done = test::waitForJob(*client, id, {"successful", "failed", "dismissed"}, 240);
  ASSERT_EQ(done["status"], "successful") << done.dump(2);
  const Json& record = done["refinement"];
  EXPECT_EQ(record["state"], "done");
  ASSERT_EQ(record["points"].size(), 1u) << record.dump(2);
  const Json& point = record["points"][0];
  const double a = rates[0].get<double>(), b = rates[1].get<double>();
  EXPECT_NEAR(point["value"].get<double>(), std::sqrt(a * b), 1e-6 * b);  // log-spaced: geometric mean
  EXPECT_EQ(point["between"], Json::array({a, b}));
  EXPECT_EQ(point["round"], 1);
  // The recorded change is the relative change of the two neighbours' peak stress.
  const double qa = done["runs"][0]["summary"]["peak_stress"], qb = done["runs"][1]["summary"]["peak_stress"];
  EXPECT_NEAR(point["change"].get<double>(), std::abs(qb - qa) / std::max(std::abs(qa), std::abs(qb)), 1e-12);
  EXPECT_NE(record["stopped"].get<std::string>().find("max_runs"), std::string::npos);
  ASSERT_EQ(done["runs_total"], 3);
  EXPECT_EQ(done["runs"][2]["swept"]["loading.strain_rate"], point["value"]);
  EXPECT_EQ(done["runs"][2]["status"], "successful");
}

// Issue 55: every table says which sample seed each run used (replicates: base + r; a spec without
// one: the schema's default), in JSON, CSV and on the job page. Admission only: nothing runs.
TEST_F(StudyHttp, TheSummaryCarriesTheSeedEachRunUsed) {
  LiveServer live([](ServerConfig& c) { c.minFreeBytes = std::numeric_limits<long long>::max(); });
  auto client = live.client();
  Json inputs = test::smallInputs();
  inputs["sample"]["seed"] = 40;
  const Json rates = test::twoStrainRates();
  const std::int64_t id = test::submit(*client, {{"inputs", inputs},
                                                 {"sweep", {{"loading.strain_rate", rates}}},
                                                 {"replicates", {{"count", 3}, {"vary", "sample.seed"}}}});
  ASSERT_GT(id, 0);
  const std::string base = "/jobs/" + std::to_string(id) + "/summary";
  const Json doc = getJson(*client, base);
  const auto column = std::find_if(doc["columns"].begin(), doc["columns"].end(),
                                   [](const Json& c) { return c["name"] == "sample.seed"; });
  ASSERT_NE(column, doc["columns"].end()) << doc["columns"].dump();
  EXPECT_EQ((*column)["kind"], "input");
  EXPECT_EQ((*column)["unit"], "1");
  ASSERT_EQ(doc["rows"].size(), 6u);
  for (int k = 0; k < 6; ++k) EXPECT_EQ(doc["rows"][k]["sample.seed"], 40 + k % 3) << doc["rows"][k].dump();

  auto csv = client->Get((base + "?format=csv").c_str());
  ASSERT_TRUE(csv);
  const auto table = test::parseCsv(csv->body);
  ASSERT_EQ(table.size(), 7u);
  const auto at = std::find(table[0].begin(), table[0].end(), "sample.seed [1]");
  ASSERT_NE(at, table[0].end()) << csv->body.substr(0, 300);
  const std::size_t c = at - table[0].begin();
  for (int k = 0; k < 6; ++k) EXPECT_EQ(table[k + 1][c], std::to_string(40 + k % 3));

  // The job page's table (once the runs have ended) from the same document: seeds that tell
  // replicates apart head it; a seed shared by every run waits under "All columns".
  const std::string headline = html::summaryTable(doc, "summary");
  EXPECT_NE(headline.substr(0, headline.find("</table>")).find("<th title=\"sample.seed\">"), std::string::npos)
      << headline;
  Json oneSeed = doc;
  for (auto& row : oneSeed["rows"]) row["sample.seed"] = 40;
  const std::string plain = html::summaryTable(oneSeed, "summary");
  EXPECT_EQ(plain.substr(0, plain.find("</table>")).find("<th title=\"sample.seed\">"), std::string::npos) << plain;
  EXPECT_NE(plain.find("<th title=\"sample.seed\">"), std::string::npos) << plain;

  // Without a seed in the spec, the schema's default (1) is the base.
  inputs["sample"].erase("seed");
  const std::int64_t defaulted =
      test::submit(*client, {{"inputs", inputs}, {"replicates", {{"count", 2}, {"vary", "sample.seed"}}}});
  const Json rows = getJson(*client, "/jobs/" + std::to_string(defaulted) + "/summary")["rows"];
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0]["sample.seed"], 1);
  EXPECT_EQ(rows[1]["sample.seed"], 2);
  // A swept seed is its swept column, not a second one.
  const std::int64_t swept = test::submit(*client, {{"inputs", inputs}, {"sweep", {{"sample.seed", {7, 9}}}}});
  const Json sweptDoc = getJson(*client, "/jobs/" + std::to_string(swept) + "/summary");
  EXPECT_EQ(std::count_if(sweptDoc["columns"].begin(), sweptDoc["columns"].end(),
                          [](const Json& c) { return c["name"] == "sample.seed"; }),
            1);
  EXPECT_EQ(sweptDoc["rows"][1]["sample.seed"], 9);
}

}  // namespace
}  // namespace rupture::server
