// Issue 55, item 5: what was asked is kept. A variant of a sweep starts from the sweep's request
// (rows, mode, replicates, name) and posts it back unchanged; a cancelled job resumes its unfinished
// runs until every run is successful; the job page shows attempts and a mark on retried runs; the
// comparison lists the inputs that differ between the jobs.
#include <gtest/gtest.h>

#include "server_test_support.hpp"
#include "views/html_views.hpp"
#include "views/submit_form.hpp"

namespace rupture::server {
namespace {

using test::expectProblem;
using test::getJson;
using test::LiveServer;

std::string getPageBody(httplib::Client& client, const std::string& path) {
  auto res = client.Get(path.c_str());
  if (!res) return "";
  EXPECT_EQ(res->status, 200) << path << ": " << res->body.substr(0, 400);
  return res->body;
}

/// The same JSON whatever the order of its members (the server keeps members in the order sent).
::testing::AssertionResult sameJson(const Json& a, const Json& b) {
  if (nlohmann::json::parse(a.dump()) == nlohmann::json::parse(b.dump())) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << a.dump(1) << "\n  differs from\n" << b.dump(1);
}

Json sweepRequest() {
  return {{"inputs", test::smallInputs()},
          {"name", "rate sweep, three seeds"},
          {"sweep", {{"loading.strain_rate", test::twoStrainRates()}, {"loading.initial_velocity", {"VL", "VH"}}}},
          {"sweep_mode", "zip"},
          {"replicates", {{"count", 3}, {"vary", "sample.seed"}}}};
}

TEST(KeepWhatWasAsked, TheStoreKeepsTheRequestAsPosted) {
  test::TempDir dir;
  JobStore store((dir.path() / "db.sqlite").string());
  NewJob job;
  job.processId = test::kScenario;
  job.inputs = sweepRequest()["inputs"];
  job.request = sweepRequest();
  job.request["refine"] = {{"path", "loading.strain_rate"}};  // kept even where the form has no field
  job.sweptPaths = Json::array();
  job.sweep = Json::object();
  job.runs.push_back({Json::array(), jobBaseSpec(job.processId, job.inputs)});
  const std::int64_t id = store.createJob(job);
  const JobRecord record = *store.job(id);
  EXPECT_TRUE(sameJson(submittedRequest(record), job.request));
  EXPECT_FALSE(record.request.contains("inputs")) << "the inputs are stored once, with the job";

  // A job from before requests were kept: rebuilt from its parts.
  JobRecord older = record;
  older.request = Json();
  older.name = "older";
  older.sweep = {{"loading.strain_rate", test::twoStrainRates()}};
  older.sweepMode = "grid";
  const Json rebuilt = submittedRequest(older);
  EXPECT_EQ(rebuilt["name"], "older");
  EXPECT_EQ(rebuilt["sweep"], older.sweep);
  EXPECT_EQ(rebuilt["inputs"], job.inputs);
}

TEST(KeepWhatWasAsked, AVariantOfASweepPostsTheSweepsRequestBack) {
  if (!test::scenarioAvailable()) GTEST_SKIP();
  LiveServer live([](ServerConfig& c) { c.minFreeBytes = std::numeric_limits<long long>::max(); });  // nothing runs
  auto client = live.client();
  const Json body = sweepRequest();
  const std::int64_t id = test::submit(*client, body);
  ASSERT_GT(id, 0);
  const Json process = getJson(*client, std::string("/processes/") + test::kScenario);
  // What the form posts unchanged is the sweep's request, member for member.
  EXPECT_TRUE(sameJson(formRequest(process, body), body));
  // And the page the job links to is filled from the request the server kept.
  const std::string page =
      getPageBody(*client, std::string("/processes/") + test::kScenario + "?f=html&from=" + std::to_string(id));
  EXPECT_NE(page.find("<option selected>loading.strain_rate</option>"), std::string::npos);
  EXPECT_NE(page.find("<option selected>loading.initial_velocity</option>"), std::string::npos);
  EXPECT_NE(page.find("value=\"1e6, 1e7\""), std::string::npos);
  EXPECT_NE(page.find("value=\"VL, VH\""), std::string::npos);
  EXPECT_NE(page.find("<option value=\"zip\" selected>"), std::string::npos);
  EXPECT_NE(page.find("id=\"replicates\" size=\"4\" value=\"3\""), std::string::npos);
  EXPECT_NE(page.find("id=\"job-name\" size=\"40\" value=\"rate sweep, three seeds\""), std::string::npos);
  // A fresh form leaves the job part empty.
  const std::string fresh = getPageBody(*client, std::string("/processes/") + test::kScenario + "?f=html");
  EXPECT_EQ(fresh.find("<option selected>loading.strain_rate</option>"), std::string::npos);
  EXPECT_NE(fresh.find("id=\"replicates\" size=\"4\" value=\"1\""), std::string::npos);
  // Members with no field in the form travel with it unchanged.
  Json refined = {{"inputs", test::smallInputs()}, {"sweep", {{"loading.strain_rate", test::twoStrainRates()}}},
                  {"refine", {{"path", "loading.strain_rate"}, {"quantity", "peak_stress"}, {"max_runs", 4}}}};
  EXPECT_TRUE(sameJson(formRequest(process, refined), refined));
  EXPECT_NE(processHtml(process, refined["inputs"], refined).body.find("data-extra="), std::string::npos);
}

TEST(KeepWhatWasAsked, ACancelledJobResumedEndsWithEveryRunSuccessful) {
  if (!test::scenarioAvailable()) GTEST_SKIP();
  LiveServer live([](ServerConfig& c) { c.workers = 1; });
  auto client = live.client();
  const auto knob = test::runLengthKnob();
  Json inputs = test::smallInputs();
  inputs["run"]["max_strain"] = 4e-4;
  const Json body = {{"inputs", inputs}, {"sweep", {{knob.path, {knob.quick, knob.medium, knob.quick}}}}};
  const std::int64_t id = test::submit(*client, body);
  const std::string job = "/jobs/" + std::to_string(id);
  expectProblem(client->Post((job + "/resume").c_str(), "{}", "application/json"), 409);  // still running
  ASSERT_TRUE(test::waitFor([&] {
    const Json doc = getJson(*client, job);
    return doc["runs"][0]["status"] == "successful" && doc["runs"][1]["status"] == "running" &&
           doc["runs"][1]["progress"].get<int>() > 0;
  }, 120)) << getJson(*client, job).dump(2);
  ASSERT_EQ(client->Delete(job.c_str())->status, 200);
  ASSERT_TRUE(test::waitFor([&] { return getJson(*client, job)["runs"][1]["status"] == "dismissed"; }, 10));
  EXPECT_EQ(getJson(*client, job)["status"], "dismissed");
  // The page offers to resume the two unfinished runs (the retry of failed runs does not apply).
  const std::string dismissedPage = getPageBody(*client, job + "?f=html");
  EXPECT_NE(dismissedPage.find("id=\"resume\""), std::string::npos);
  EXPECT_NE(dismissedPage.find("run the 2 unfinished runs again"), std::string::npos);
  expectProblem(client->Post((job + "/retry").c_str(), "{}", "application/json"), 409);

  auto resumed = client->Post((job + "/resume").c_str(), "{}", "application/json");
  ASSERT_TRUE(resumed);
  ASSERT_EQ(resumed->status, 200) << resumed->body;
  const Json after = Json::parse(resumed->body);
  EXPECT_EQ(after["resumed_runs"], Json::array({1, 2}));
  EXPECT_TRUE(after["status"] == "accepted" || after["status"] == "running") << after["status"];
  EXPECT_EQ(after["runs"][0]["status"], "successful") << "a successful run is kept";

  const Json done = test::waitForJob(*client, id, {"successful", "failed", "dismissed"}, 240);
  ASSERT_EQ(done["status"], "successful") << done.dump(2);
  for (const Json& run : done["runs"]) EXPECT_EQ(run["status"], "successful") << run.dump();
  EXPECT_EQ(done["runs"][1]["attempts"], 2) << "started, cancelled, started again";
  EXPECT_FALSE(done["runs"][2].contains("attempts")) << "never started before the resume: one start";
  // The page shows each run's attempts and marks the one that ran again.
  const std::string page = getPageBody(*client, job + "?f=html");
  const std::size_t row1 = page.find("id=\"run-1\""), row2 = page.find("id=\"run-2\"");
  ASSERT_NE(row1, std::string::npos);
  ASSERT_NE(row2, std::string::npos);
  EXPECT_NE(page.substr(row1, row2 - row1).find(">2 <span class=\"mark\">&#x21bb; retried</span>"), std::string::npos)
      << page.substr(row1, row2 - row1);
  EXPECT_EQ(page.substr(row2, 400).find("retried"), std::string::npos);
  // Nothing is left to resume.
  expectProblem(client->Post((job + "/resume").c_str(), "{}", "application/json"), 409);
  expectProblem(client->Post("/jobs/999/resume", "{}", "application/json"), 404);
}

TEST(KeepWhatWasAsked, TheComparisonListsTheInputsThatDiffer) {
  if (!test::scenarioAvailable()) GTEST_SKIP();
  LiveServer live([](ServerConfig& c) { c.minFreeBytes = std::numeric_limits<long long>::max(); });  // nothing runs
  auto client = live.client();
  Json a = {{"inputs", test::smallInputs()}, {"sweep", {{"loading.strain_rate", test::twoStrainRates()}}}};
  Json b = a;
  b["inputs"]["loading"]["initial_velocity"] = "VH";
  b["replicates"] = {{"count", 2}, {"vary", "sample.seed"}};
  const std::int64_t ja = test::submit(*client, a), jb = test::submit(*client, b);
  const std::string ids = std::to_string(ja) + "," + std::to_string(jb);
  const Json cmp = getJson(*client, "/summary?jobs=" + ids);
  Json paths = Json::array();
  for (const Json& d : cmp["differing_inputs"]) paths.push_back(d["path"]);
  EXPECT_EQ(paths, Json::array({"loading.initial_velocity", "replicates"})) << cmp["differing_inputs"].dump(2);
  const Json& velocity = cmp["differing_inputs"][0]["values"];
  EXPECT_EQ(velocity[std::to_string(ja)], "VL");
  EXPECT_EQ(velocity[std::to_string(jb)], "VH");
  EXPECT_TRUE(cmp["differing_inputs"][1]["values"][std::to_string(ja)].is_null()) << "no replicates: the default";
  const std::string page = getPageBody(*client, "/summary?f=html&jobs=" + ids);
  EXPECT_NE(page.find("<table id=\"differing\">"), std::string::npos);
  EXPECT_NE(page.find("<code>loading.initial_velocity</code></td><td>VL</td><td>VH</td>"), std::string::npos) << page;
  // The same inputs: said in words; one job alone: nothing to list.
  const std::int64_t jc = test::submit(*client, a);
  EXPECT_TRUE(getJson(*client, "/summary?jobs=" + std::to_string(ja) + "," + std::to_string(jc))["differing_inputs"].empty());
  EXPECT_NE(getPageBody(*client, "/summary?f=html&jobs=" + std::to_string(ja) + "," + std::to_string(jc))
                .find("The jobs were asked with the same inputs."),
            std::string::npos);
  EXPECT_TRUE(getJson(*client, "/summary?jobs=" + std::to_string(ja))["differing_inputs"].empty());
}

}  // namespace
}  // namespace rupture::server
