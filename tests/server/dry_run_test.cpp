// POST /processes/{id}/execution?dry_run=true (issue 55, item 3): the preview and cost of a job,
// checked as a submission is and answered with the run count, each run's elements, memory and
// steps, and an estimated time; nothing is stored or queued, and a bad request gets the very
// problem a real POST gets.
#include <gtest/gtest.h>

#include "jobs/job_preview.hpp"
#include "server_test_support.hpp"

namespace rupture::server {
namespace {

using test::expectProblem;
using test::getJson;
using test::LiveServer;

const std::string kDryRun = test::kExecutePath + "?dry_run=true";

/// A problem document without its `instance` (the request's own path differs by the query).
Json problemOf(const httplib::Result& res) {
  Json doc = Json::parse(res->body);
  doc.erase("instance");
  return doc;
}

TEST(DryRun, AnswersTheRunsElementsMemoryAndTimeAndQueuesNothing) {
  ASSERT_TRUE(test::scenarioAvailable());
  LiveServer live;
  auto client = live.client();
  const Json body = {{"inputs", test::smallInputs()},
                     {"name", "preview"},
                     {"sweep", {{"loading.strain_rate", test::twoStrainRates()}}},
                     {"replicates", {{"count", 3}, {"vary", "sample.seed"}}}};
  auto res = test::postJson(*client, kDryRun, body);
  ASSERT_TRUE(res);
  ASSERT_EQ(res->status, 200) << res->body;
  EXPECT_FALSE(res->has_header("Location")) << "no job was made";
  const Json d = Json::parse(res->body);
  EXPECT_EQ(d["dry_run"], true);
  EXPECT_EQ(d["processID"], test::kScenario);
  EXPECT_EQ(d["name"], "preview");
  EXPECT_EQ(d["runs"], 6) << "2 strain rates x 3 replicates";
  EXPECT_EQ(d["sweep_points"], 2);
  EXPECT_EQ(d["replicates"], 3);
  ASSERT_EQ(d["run_estimates"].size(), 6u);

  // Each run's figures are the spec's own estimate: the same sample (elements, memory) at both
  // rates, and more steps at the slower rate.
  auto estimateAt = [](double rate) {
    Json spec = test::smallInputs();
    spec["scenario"] = test::kScenario;
    spec["loading"]["strain_rate"] = rate;
    return rupture::estimateRun(nlohmann::json(spec));
  };
  const rupture::RunEstimate direct = estimateAt(1e6), faster = estimateAt(1e7);
  ASSERT_GT(direct.particles, 0);
  for (const Json& run : d["run_estimates"]) {
    EXPECT_EQ(run["elements"], std::llround(direct.particles)) << run.dump();
    EXPECT_EQ(run["memory_bytes"], std::llround(direct.memoryBytes)) << run.dump();
    EXPECT_GT(run["estimated_run_s"].get<double>(), 0) << run.dump();
  }
  const Json& first = d["run_estimates"][0];
  const Json& fasterRate = d["run_estimates"][3];  // replicates vary fastest: run 3 is the second rate
  EXPECT_EQ(first["swept"]["loading.strain_rate"], 1e6);
  EXPECT_EQ(fasterRate["swept"]["loading.strain_rate"], 1e7);
  EXPECT_EQ(first["replicate"], 0);
  EXPECT_EQ(d["run_estimates"][2]["replicate"], 2);
  EXPECT_EQ(first["steps"], std::llround(direct.steps));
  EXPECT_EQ(fasterRate["steps"], std::llround(faster.steps));
  EXPECT_GT(direct.steps, 3 * faster.steps);
  EXPECT_EQ(d["steps"], first["steps"]) << "the most steps a run takes";
  EXPECT_EQ(d["elements"]["max"], std::llround(direct.particles));
  EXPECT_EQ(d["elements"]["set_by"], direct.field);
  EXPECT_EQ(d["memory_bytes"], std::llround(direct.memoryBytes));
  EXPECT_GE(d["max_run_memory_bytes"].get<double>(), d["memory_bytes"].get<double>());

  // The time: each run elements x steps x the scenario's cost per element-step; the job's runs on the
  // server's two workers end no sooner than its longest run and no later than all of them in a row.
  const double cost = d["cost_model"]["seconds_per_element_step"].get<double>();
  EXPECT_GT(cost, 0);
  EXPECT_EQ(d["cost_model"]["workers"], 2);
  EXPECT_NEAR(first["estimated_run_s"].get<double>(), cost * direct.particles * direct.steps,
              1e-9 * first["estimated_run_s"].get<double>());
  EXPECT_NEAR(fasterRate["estimated_run_s"].get<double>(), cost * faster.particles * faster.steps,
              1e-9 * fasterRate["estimated_run_s"].get<double>());
  double total = 0;
  for (const Json& run : d["run_estimates"]) total += run["estimated_run_s"].get<double>();
  EXPECT_NEAR(d["estimated_total_s"].get<double>(), total, 1e-9 * total);
  EXPECT_GE(d["estimated_wall_s"].get<double>(), d["estimated_run_s"].get<double>());
  EXPECT_LT(d["estimated_wall_s"].get<double>(), total) << "two workers share the runs";
  EXPECT_EQ(d["picture"]["available"], false) << "drawn only when asked (picture=true)";
  EXPECT_EQ(d["queue"]["fits_now"], true);

  // Nothing was stored or queued.
  EXPECT_EQ(getJson(*client, "/jobs")["jobs"].size(), 0u);
  EXPECT_EQ(getJson(*client, "/health")["queue_depth"], 0);
}

TEST(DryRun, RefusesWhatARealSubmissionRefusesWithTheSameProblem) {
  ASSERT_TRUE(test::scenarioAvailable());
  // A small memory bound, so that the admission check is exercised as well.
  LiveServer live([](ServerConfig& c) { c.maxRunMemory = 1 << 20; });
  auto client = live.client();
  Json badValue = {{"inputs", test::smallInputs()}};
  badValue["inputs"]["loading"]["initial_velocity"] = "VX";
  Json badSweep = {{"inputs", test::smallInputs()}, {"sweep", {{"sample.element_radius", {1.2e-8, -1.0}}}}};
  Json unknownMember = {{"inputs", test::smallInputs()}, {"sweeps", Json::object()}};
  Json tooBig = {{"inputs", test::smallInputs()}};
  tooBig["inputs"]["sample"]["element_radius"] = 4e-9;
  for (const Json& body : {badValue, badSweep, unknownMember, tooBig}) {
    auto real = test::postJson(*client, test::kExecutePath, body);
    auto dry = test::postJson(*client, kDryRun, body);
    ASSERT_TRUE(real && dry);
    EXPECT_EQ(real->status, 400) << real->body;
    expectProblem(dry, 400);
    EXPECT_EQ(problemOf(dry), problemOf(real)) << "dry: " << dry->body << "\nreal: " << real->body;
  }
  // The value of dry_run is checked too.
  expectProblem(test::postJson(*client, test::kExecutePath + "?dry_run=yes", badValue), 400, "dry_run");
  EXPECT_EQ(getJson(*client, "/jobs")["jobs"].size(), 0u);
}

TEST(DryRun, AFullQueueDoesNotRefuseAPreview) {
  ASSERT_TRUE(test::scenarioAvailable());
  // No worker takes a run (the data disk never has the free space asked for): the queue stays full.
  LiveServer live([](ServerConfig& c) {
    c.maxQueuedRuns = 2;
    c.minFreeBytes = std::numeric_limits<long long>::max() / 2;
  });
  auto client = live.client();
  const Json body = {{"inputs", test::smallInputs()}, {"sweep", {{"loading.strain_rate", test::twoStrainRates()}}}};
  ASSERT_GT(test::submit(*client, body), 0);
  expectProblem(test::postJson(*client, test::kExecutePath, body), 503);
  auto dry = test::postJson(*client, kDryRun, body);
  ASSERT_TRUE(dry);
  ASSERT_EQ(dry->status, 200) << dry->body;
  const Json d = Json::parse(dry->body);
  EXPECT_EQ(d["queue"]["fits_now"], false);
  EXPECT_EQ(d["queue"]["queued_runs"], 2);
  EXPECT_EQ(getJson(*client, "/jobs")["jobs"].size(), 1u);
}

TEST(DryRun, TheJobsTimeTakesTheQueueFirstComeFirstServed) {
  EXPECT_DOUBLE_EQ(queueMakespan({3, 1, 1, 1}, 2), 3) << "one worker takes the long run, the other the three short";
  EXPECT_DOUBLE_EQ(queueMakespan({1, 1, 1, 3}, 2), 4) << "the long run, last, starts at 1 s on the worker freed first";
  EXPECT_DOUBLE_EQ(queueMakespan({2, 2, 2}, 2), 4);
  EXPECT_DOUBLE_EQ(queueMakespan({2, 2, 2}, 0), 6) << "no worker count: one at a time";
  EXPECT_DOUBLE_EQ(queueMakespan({}, 4), 0);
  // Runs of several ranks hold as many workers, and the queue's head waits for them.
  EXPECT_DOUBLE_EQ(queueMakespan({2, 2}, 2, {2, 2}), 4) << "each 2-rank run holds both workers";
  EXPECT_DOUBLE_EQ(queueMakespan({1, 2, 1}, 2, {1, 2, 1}), 4)
      << "the 2-rank run waits for the first to end (1 s), holds both to 3 s; the last starts then";
  EXPECT_DOUBLE_EQ(queueMakespan({3, 1, 1}, 2, {1, 2, 1}), 5)
      << "the 2-rank head waits 3 s for both workers, and the run behind it does not overtake it";
  EXPECT_DOUBLE_EQ(queueMakespan({2}, 2, {8}), 2) << "a run asking for more ranks than workers holds them all";
}

TEST(DryRun, TheFormPreviewsBeforeItSubmits) {
  LiveServer live;
  auto client = live.client();
  auto res = client->Get("/processes/dynamic-tension?f=html");
  ASSERT_TRUE(res);
  ASSERT_EQ(res->status, 200);
  EXPECT_NE(res->body.find("id=\"preview-button\""), std::string::npos);
  EXPECT_NE(res->body.find("id=\"preview\""), std::string::npos);
  EXPECT_NE(res->body.find("'?dry_run=true'"), std::string::npos) << "the script posts the dry run";
}

}  // namespace
}  // namespace rupture::server
