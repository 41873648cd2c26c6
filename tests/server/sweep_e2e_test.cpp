// End to end on a real loopback server with the real dynamic-tension scenario: a 2 x 2 grid sweep
// with every output format, zip vs grid counts, whole-job rejection, and cancellation.
#include <gtest/gtest.h>

#include "io/sha256.hpp"
#include "io/provenance.hpp"
#include "io/hdf5_file.hpp"
#include "server_test_support.hpp"

namespace rupture::server {
namespace {
namespace fs = std::filesystem;

using test::expectProblem;
using test::getJson;
using test::LiveServer;


/// Downloads `path` into a file in `dir` and opens it with the HDF5 API.
rupture::io::Hdf5File download(httplib::Client& client, const std::string& path, const test::TempDir& dir,
                               const std::string& name, std::string* bytes = nullptr) {
  auto res = client.Get(path.c_str());
  EXPECT_TRUE(res);
  EXPECT_EQ(res->status, 200) << res->body.substr(0, 300);
  EXPECT_EQ(res->get_header_value("Content-Type"), "application/x-hdf5");
  EXPECT_EQ(res->get_header_value("Content-Length"), std::to_string(res->body.size()));
  const auto file = dir.path() / name;
  std::ofstream(file, std::ios::binary) << res->body;
  if (bytes) *bytes = res->body;
  return rupture::io::Hdf5File::openReadOnly(file.string());
}

class SweepEndToEnd : public ::testing::Test {
protected:
  void SetUp() override {
    ASSERT_TRUE(test::scenarioAvailable()) << "the dynamic-tension scenario or " << test::exampleFile()
                                           << " is missing";
  }
};

TEST_F(SweepEndToEnd, GridOfTwoByTwoCompletesWithSummaryPlotAndFiles) {
  LiveServer live;
  auto client = live.client();
  Json body = {{"name", "2x2 grid"},
               {"inputs", test::smallInputs()},
               {"sweep", {{"loading.strain_rate", test::twoStrainRates()}, {"loading.initial_velocity", {"V0", "VL"}}}},
               {"sweep_mode", "grid"}};
  const auto posted = std::chrono::steady_clock::now();
  auto res = test::postJson(*client, test::kExecutePath, body, {{"Prefer", "respond-async"}});
  ASSERT_TRUE(res);
  ASSERT_EQ(res->status, 201) << res->body;
  EXPECT_EQ(res->get_header_value("Preference-Applied"), "respond-async");
  Json accepted = Json::parse(res->body);
  const std::string id = accepted["jobID"];
  EXPECT_EQ(res->get_header_value("Location"), "/jobs/" + id);
  EXPECT_EQ(accepted["runs_total"], 4);
  EXPECT_EQ(accepted["swept"], Json::array({"loading.strain_rate", "loading.initial_velocity"}));
  EXPECT_EQ(accepted["runs"][1]["swept"]["loading.initial_velocity"], "VL");
  EXPECT_EQ(accepted["runs"][2]["swept"]["loading.strain_rate"], test::twoStrainRates()[1]);

  // While it runs: status document, progress, and no merged results yet.
  ASSERT_TRUE(test::waitFor([&] {
    Json doc = getJson(*client, "/jobs/" + id);
    return doc["runs_by_status"]["running"].get<int>() > 0 || doc["status"] != "accepted";
  }, 30));
  const double startedAfter = std::chrono::duration<double>(std::chrono::steady_clock::now() - posted).count();
  EXPECT_LT(startedAfter, 2.0);
  auto early = client->Get(("/jobs/" + id + "/results").c_str());
  if (early && early->status != 200) expectProblem(early, 409);

  Json done = test::waitForJob(*client, std::stoll(id), {"successful", "failed", "dismissed"}, 150);
  ASSERT_EQ(done["status"], "successful") << done.dump(2);
  EXPECT_EQ(done["progress"], 100);
  EXPECT_TRUE(done.contains("finished"));
  for (const auto& run : done["runs"]) {
    EXPECT_EQ(run["status"], "successful");
    EXPECT_GT(run["summary"]["peak_stress"].get<double>(), 0);
  }
  // The V0 runs needed the sample's preliminary run (its wave speed sets the ramp): computed once
  // for both, and cached inside the data directory; so is the packed sample, shared by all four.
  std::size_t cached = 0, samples = 0;
  for (const auto& entry : fs::directory_iterator(live.dataDir() / "cache")) {
    if (entry.path().extension() != ".h5") continue;
    const bool sample = entry.path().filename().string().rfind("bonded-sample-", 0) == 0;
    samples += sample;
    cached += !sample;
  }
  EXPECT_EQ(cached, 1u);
  EXPECT_EQ(samples, 1u);
  int fromCache = 0;
  for (const auto& run : done["runs"]) fromCache += run["summary"]["sample_from_cache"].get<int>();
  EXPECT_EQ(fromCache, 3);  // the first run packs it, the three others read it

  // Summary as JSON: 4 rows, swept values, positive peak stress.
  Json summary = getJson(*client, "/jobs/" + id + "/summary");
  ASSERT_EQ(summary["rows"].size(), 4u);
  std::set<std::pair<double, std::string>> combos;
  for (const auto& row : summary["rows"]) {
    combos.insert({row["loading.strain_rate"].get<double>(), row["loading.initial_velocity"].get<std::string>()});
    EXPECT_GT(row["peak_stress"].get<double>(), 0) << row.dump();
  }
  EXPECT_EQ(combos.size(), 4u);

  // CSV, by query and by Accept header.
  auto checkCsv = [&](const httplib::Result& csv) {
    ASSERT_TRUE(csv);
    EXPECT_EQ(csv->status, 200);
    EXPECT_EQ(csv->get_header_value("Content-Type").rfind("text/csv", 0), 0u);
    auto rows = test::parseCsv(csv->body);
    ASSERT_EQ(rows.size(), 5u);
    const auto& header = rows[0];
    // Every column named with its unit; the swept strain rate once (not again as strain_rate).
    const auto col = std::find(header.begin(), header.end(), "peak_stress [Pa]") - header.begin();
    EXPECT_NE(std::find(header.begin(), header.end(), "loading.strain_rate [1/s]"), header.end());
    EXPECT_EQ(std::find(header.begin(), header.end(), "strain_rate [1/s]"), header.end());
    ASSERT_LT(col, static_cast<long>(header.size()));
    for (std::size_t r = 1; r < rows.size(); ++r) {
      ASSERT_EQ(rows[r].size(), header.size());
      EXPECT_GT(std::stod(rows[r][col]), 0);
    }
  };
  checkCsv(client->Get(("/jobs/" + id + "/summary?format=csv").c_str()));
  checkCsv(client->Get(("/jobs/" + id + "/summary").c_str(), httplib::Headers{{"Accept", "text/csv"}}));

  // SVG plot: well-formed, log axis over a decade of strain rates, legend with V0 and VL.
  auto svg = client->Get(("/jobs/" + id + "/summary.svg?x=loading.strain_rate&y=peak_stress").c_str());
  ASSERT_TRUE(svg);
  EXPECT_EQ(svg->status, 200);
  EXPECT_EQ(svg->get_header_value("Content-Type"), "image/svg+xml");
  std::string error;
  EXPECT_TRUE(test::wellFormedXml(svg->body, error)) << error;
  EXPECT_NE(svg->body.find(">Strain rate [1/s]</text>"), std::string::npos);
  EXPECT_NE(svg->body.find(">Peak stress [MPa]</text>"), std::string::npos);
  EXPECT_NE(svg->body.find(">10⁶</text>"), std::string::npos);
  EXPECT_NE(svg->body.find("data-label=\"V0\""), std::string::npos);
  EXPECT_NE(svg->body.find("data-label=\"VL\""), std::string::npos);
  expectProblem(client->Get(("/jobs/" + id + "/summary.svg?y=nope").c_str()), 400, "y");
  // The same plot as a PNG of the asked size (IHDR width and height, big-endian).
  auto png = client->Get(("/jobs/" + id + "/summary.svg?format=png&width=640&height=400&scale=2").c_str());
  ASSERT_TRUE(png);
  EXPECT_EQ(png->status, 200);
  EXPECT_EQ(png->get_header_value("Content-Type"), "image/png");
  ASSERT_GT(png->body.size(), 24u);
  EXPECT_EQ(png->body.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  auto u32 = [&](std::size_t at) {
    return (std::uint32_t(std::uint8_t(png->body[at])) << 24) | (std::uint32_t(std::uint8_t(png->body[at + 1])) << 16) |
           (std::uint32_t(std::uint8_t(png->body[at + 2])) << 8) | std::uint32_t(std::uint8_t(png->body[at + 3]));
  };
  EXPECT_EQ(png->body.substr(12, 4), "IHDR");
  EXPECT_EQ(u32(16), 1280u);
  EXPECT_EQ(u32(20), 800u);
  expectProblem(client->Get(("/jobs/" + id + "/summary.svg?format=gif").c_str()), 400, "format");
  expectProblem(client->Get(("/jobs/" + id + "/summary.svg?width=10").c_str()), 400, "width");
  expectProblem(client->Get(("/jobs/" + id + "/summary.svg?ymin=abc").c_str()), 400, "ymin");
  // Every plot option is honoured or refused, never ignored.
  expectProblem(client->Get(("/jobs/" + id + "/summary.svg?colour=red").c_str()), 400, "colour");
  expectProblem(client->Get(("/jobs/" + id + "/summary.svg?fontsize=100").c_str()), 400, "fontsize");
  auto large = client->Get(("/jobs/" + id + "/summary.svg?fontsize=24").c_str());  // twice the default 12 px
  ASSERT_TRUE(large);
  EXPECT_EQ(large->status, 200);
  EXPECT_NE(large->body.find("font-size=\"24.00\""), std::string::npos) << large->body.substr(0, 400);
  EXPECT_NE(large->body.find("font-size=\"30.00\" font-weight=\"bold\""), std::string::npos) << "the title scales too";
  auto pdf = client->Get(("/jobs/" + id + "/summary.svg?format=pdf").c_str());
  ASSERT_TRUE(pdf);
  EXPECT_EQ(pdf->status, 200);
  EXPECT_EQ(pdf->get_header_value("Content-Type"), "application/pdf");
  EXPECT_EQ(pdf->body.rfind("%PDF", 0), 0u);
  EXPECT_EQ(pdf->body.find("/Subtype /Image"), std::string::npos) << "vector: the PDF embeds no raster image";
  auto titled = client->Get(("/jobs/" + id + "/summary.svg?title=Figure%203%20of%20the%20seed").c_str());
  ASSERT_TRUE(titled);
  EXPECT_EQ(titled->status, 200);
  EXPECT_NE(titled->body.find("Figure 3 of the seed"), std::string::npos);

  // Both HDF5 downloads open with the HDF5 API; the merged one has a self-contained group per run.
  test::TempDir tmp;
  {
    auto merged = download(*client, "/jobs/" + id + "/results", tmp, "merged.h5");
    auto groups = merged.listGroup("/");
    for (int k = 0; k < 4; ++k) {
      const std::string g = "/run-" + std::to_string(k);
      ASSERT_TRUE(merged.exists(g)) << g;
      EXPECT_EQ(merged.readAttributeInt(g, "sweep.run_index"), k);
      EXPECT_TRUE(merged.exists(g + "/series/stress_mean")) << g;
    }
    EXPECT_EQ(merged.readAttributeInt("/", "runs_included"), 4);
    EXPECT_EQ(merged.readDatasetDouble("/summary/peak_stress").size(), 4u);
    EXPECT_EQ(merged.readAttributeString("/summary/peak_stress", "unit"), "Pa");
    EXPECT_EQ(merged.readAttributeString("/summary/loading.strain_rate", "unit"), "1/s");
    EXPECT_EQ(merged.readAttributeString("/", "process_id"), test::kScenario);
  }
  std::string runBytes;
  {
    auto run = download(*client, "/jobs/" + id + "/runs/3/results", tmp, "run3.h5", &runBytes);
    EXPECT_TRUE(run.exists("/series/strain"));
    EXPECT_GT(run.readDatasetDouble("/series/strain").size(), 1u);
    // Provenance (docs/provenance.md): the run's file says what made it, as the job does.
    EXPECT_EQ(run.readAttributeString("/provenance", "git_commit"), done["provenance"]["git_commit"]);
    EXPECT_EQ(run.readAttributeString("/provenance", "spec_sha256"),
              rupture::sha256Hex(run.readAttributeString("/spec", "json")));
    EXPECT_EQ(Json::parse(run.readAttributeString("/provenance", "seeds")),
              (Json{{"sample.seed", Json::parse(run.readAttributeString("/spec", "json"))["sample"]["seed"]}}));
  }
  // The job records the build and host it was submitted to; /health shows the server's.
  EXPECT_EQ(done["provenance"]["rupture_version"], RUPTURE_VERSION);
  EXPECT_EQ(done["provenance"]["executor"], "local");
  EXPECT_EQ(done["provenance"]["host_processor"], rupture::io::hostProcessor());
  const Json health = getJson(*client, "/health");
  EXPECT_EQ(health["build"]["git_commit"], done["provenance"]["git_commit"]);
  EXPECT_EQ(health["build"]["compile_flags"], done["provenance"]["compile_flags"]);
  // Range requests work on downloads.
  auto range = client->Get(("/jobs/" + id + "/runs/3/results").c_str(), httplib::Headers{{"Range", "bytes=0-7"}});
  ASSERT_TRUE(range);
  EXPECT_EQ(range->status, 206);
  EXPECT_EQ(range->body, runBytes.substr(0, 8));

  // Series as JSON and CSV.
  Json series = getJson(*client, "/jobs/" + id + "/runs/0/series?names=strain,stress_mean");
  EXPECT_EQ(series["names"], Json::array({"strain", "stress_mean"}));
  EXPECT_EQ(series["series"]["strain"].size(), series["series"]["stress_mean"].size());
  EXPECT_GT(series["length"].get<int>(), 1);
  EXPECT_EQ(series["units"]["stress_mean"], "Pa");
  auto seriesCsv = client->Get(("/jobs/" + id + "/runs/0/series?names=strain,stress_mean&format=csv").c_str());
  ASSERT_TRUE(seriesCsv);
  auto csvRows = test::parseCsv(seriesCsv->body);
  ASSERT_EQ(csvRows.size(), series["length"].get<std::size_t>() + 1);
  EXPECT_EQ(csvRows[0], (std::vector<std::string>{"strain [1]", "stress_mean [Pa]"}));
  EXPECT_EQ(series["labels"]["stress_mean"], "Mean stress");
  expectProblem(client->Get(("/jobs/" + id + "/runs/0/series?names=nope").c_str()), 400, "names");
  expectProblem(client->Get(("/jobs/" + id + "/runs/4/results").c_str()), 404, "run");

  // The job list shows it.
  Json jobs = getJson(*client, "/jobs?status=successful");
  ASSERT_EQ(jobs["numberMatched"], 1);
  EXPECT_EQ(jobs["jobs"][0]["jobID"], id);
  EXPECT_EQ(jobs["jobs"][0]["name"], "2x2 grid");
}

TEST_F(SweepEndToEnd, ZipAndGridExpandToDifferentCounts) {
  LiveServer live([](ServerConfig& c) { c.workers = 1; });
  auto client = live.client();
  const auto knob = test::runLengthKnob();
  Json sweep = {{"loading.initial_velocity", {"V0", "VL", "VH"}}, {"run.max_strain", {0.004, 0.005, 0.006}},
                {knob.path, {knob.slow, knob.slow, knob.slow}}};
  Json grid = {{"inputs", test::smallInputs()}, {"sweep", sweep}};
  Json zip = grid;
  zip["sweep_mode"] = "zip";
  const auto gridId = test::submit(*client, grid);
  const auto zipId = test::submit(*client, zip);
  Json g = getJson(*client, "/jobs/" + std::to_string(gridId));
  Json z = getJson(*client, "/jobs/" + std::to_string(zipId));
  EXPECT_EQ(g["runs_total"], 27);
  EXPECT_EQ(z["runs_total"], 3);
  EXPECT_EQ(z["sweep_mode"], "zip");
  EXPECT_EQ(z["runs"][2]["swept"]["loading.initial_velocity"], "VH");
  EXPECT_EQ(z["runs"][2]["swept"]["run.max_strain"], 0.006);
  EXPECT_EQ(g["runs"][5]["swept"], (Json{{"loading.initial_velocity", "V0"}, {"run.max_strain", 0.005},
                                        {knob.path, knob.slow}}));
  // Unequal zip lists are refused, naming the list that differs.
  Json bad = zip;
  bad["sweep"]["run.max_strain"] = {0.004, 0.005};
  expectProblem(test::postJson(*client, test::kExecutePath, bad), 400, "run.max_strain");
  for (auto id : {gridId, zipId}) EXPECT_EQ(client->Delete(("/jobs/" + std::to_string(id)).c_str())->status, 200);
}

TEST_F(SweepEndToEnd, OneInvalidSweepPointRejectsTheWholeJob) {
  LiveServer live;
  auto client = live.client();
  Json body = {{"inputs", test::smallInputs()},
               {"sweep", {{"loading.initial_velocity", {"V0", "VL"}}, {"loading.strain_rate", {1e5, -3.0, 1e6}}}}};
  auto res = test::postJson(*client, test::kExecutePath, body);
  Json p = expectProblem(res, 400, "loading.strain_rate");
  EXPECT_EQ(p["type"], problem::kInvalidSpec);
  EXPECT_EQ(p["in"], "sweep");
  EXPECT_EQ(p["sweep_point"], 1);  // (V0, -3): the first point holding the bad value
  EXPECT_EQ(p["swept"]["loading.strain_rate"], -3.0);
  EXPECT_NE(p["detail"].get<std::string>().find("loading.strain_rate"), std::string::npos);
  EXPECT_EQ(getJson(*client, "/jobs")["numberMatched"], 0);
  Json bad = body;
  bad["sweep"] = {{"loading.initial_velocity", {"V0", "VX"}}};
  expectProblem(test::postJson(*client, test::kExecutePath, bad), 400, "loading.initial_velocity");
  EXPECT_EQ(getJson(*client, "/health")["queue_depth"], 0);
}

TEST_F(SweepEndToEnd, CancelWhileRunningDismissesWithinASecondAndKeepsFinishedRuns) {
  LiveServer live([](ServerConfig& c) { c.workers = 1; });
  auto client = live.client();
  const auto knob = test::runLengthKnob();
  Json inputs = test::smallInputs();
  inputs["run"]["max_strain"] = 4e-4;  // past the peak, and progress moves in whole percents sooner
  Json body = {{"inputs", inputs}, {"sweep", {{knob.path, {knob.quick, knob.slow, knob.quick}}}}, {"name", "to be cancelled"}};
  const auto id = test::submit(*client, body);
  const std::string job = "/jobs/" + std::to_string(id);
  // Cancel once run 1 is in its time loop (progress > 0): the engine checks the cancel flag there
  // at least every 0.2 s, but not while it builds the sample.
  ASSERT_TRUE(test::waitFor([&] {
    Json doc = getJson(*client, job);
    return doc["runs"][0]["status"] == "successful" && doc["runs"][1]["status"] == "running" &&
           doc["runs"][1]["progress"].get<int>() > 0;
  }, 60)) << getJson(*client, job).dump(2);
  expectProblem(client->Get((job + "/results").c_str()), 409);
  expectProblem(client->Get((job + "/runs/1/results").c_str()), 409);

  const auto t0 = std::chrono::steady_clock::now();
  auto del = client->Delete(job.c_str());
  ASSERT_TRUE(del);
  ASSERT_EQ(del->status, 200) << del->body;
  EXPECT_EQ(Json::parse(del->body)["status"], "dismissed");
  // The running run stops within a second; the queued one never starts.
  ASSERT_TRUE(test::waitFor([&] { return getJson(*client, job)["runs"][1]["status"] == "dismissed"; }, 1.0));
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 1.0);
  Json doc = getJson(*client, job);
  EXPECT_EQ(doc["status"], "dismissed");
  EXPECT_EQ(doc["runs"][0]["status"], "successful");
  EXPECT_EQ(doc["runs"][2]["status"], "dismissed");
  EXPECT_FALSE(doc["runs"][2].contains("started"));
  EXPECT_EQ(getJson(*client, "/health")["running"], 0);

  // The finished run stays downloadable, alone and in the merged file; the others have no results.
  test::TempDir tmp;
  {
    auto run0 = download(*client, job + "/runs/0/results", tmp, "run0.h5");
    EXPECT_TRUE(run0.exists("/series"));
  }
  {
    auto merged = download(*client, job + "/results", tmp, "merged.h5");
    EXPECT_TRUE(merged.exists("/run-0"));
    EXPECT_FALSE(merged.exists("/run-1"));
  }
  expectProblem(client->Get((job + "/runs/1/results").c_str()), 404);
  // Dismissing again is harmless.
  EXPECT_EQ(Json::parse(client->Delete(job.c_str())->body)["status"], "dismissed");
}

}  // namespace
}  // namespace rupture::server
