// Live progress over HTTP: a running run and its job carry a stage, elapsed_s, eta_s and an
// `updated` that moves while the progress rises; a dismissed job keeps the progress of what ran.
#include <gtest/gtest.h>

#include "jobs/progress_info.hpp"
#include "rupture/progress.hpp"
#include "server_test_support.hpp"

namespace rupture::server {
namespace {

using test::getJson;
using test::LiveServer;

Json slowThenQuick() {
  const auto knob = test::runLengthKnob();
  return Json{{"inputs", test::smallInputs()}, {"sweep", {{knob.path, Json::array({knob.slow, knob.quick})}}}};
}

TEST(LiveProgress, EstimatorAndTimestamps) {
  // A run that built its sample for 60 s (no progress), then went from 10 % at 60 s to 30 % at 70 s:
  // 2 %/s, so 70 % more takes 35 s. Asked 5 s after that report with nothing new, its rate is 20 %
  // in 15 s, so 70 % more takes 52.5 s: a run that reports nothing is slowing down, never done. The
  // set-up minute does not count as slow progress (the old elapsed · (1 − f) / f said 163 s).
  EXPECT_DOUBLE_EQ(remainingSeconds(60.0, 0.1, 70.0, 0.3, 70.0), 35.0);
  EXPECT_DOUBLE_EQ(remainingSeconds(60.0, 0.1, 70.0, 0.3, 75.0), 52.5);
  EXPECT_DOUBLE_EQ(remainingSeconds(60.0, 0.1, 70.0, 1.0, 75.0), 0.0);
  EXPECT_LT(remainingSeconds(60.0, 0.1, 61.0, 0.3, 61.0), 0.0) << "a second of progress says too little";
  EXPECT_LT(remainingSeconds(60.0, 0.3, 70.0, 0.3, 70.0), 0.0) << "no gain, no rate";
  EXPECT_LT(remainingSeconds(-1.0, 0.0, 70.0, 0.3, 70.0), 0.0) << "no anchor yet";
  EXPECT_GT(remainingSeconds(60.0, 0.1, 70.0, 0.3, 200.0), 35.0) << "overdue: later, never 0 while it runs";
  RemainingTime watch;
  watch.observe(0.0, 0.0);
  watch.observe(30.0, 0.0);  // set-up
  EXPECT_LT(watch.at(30.0), 0.0);
  watch.observe(31.0, 0.05);
  watch.observe(41.0, 0.25);
  EXPECT_DOUBLE_EQ(watch.at(41.0), 37.5);  // 2 %/s from the anchor at 31 s: 75 % in 37.5 s
  EXPECT_DOUBLE_EQ(secondsBetween("2026-01-02T03:04:05.500Z", "2026-01-02T03:05:07.000Z"), 61.5);
  EXPECT_DOUBLE_EQ(secondsBetween("2025-12-31T23:59:59.000Z", "2026-01-01T00:00:01.000Z"), 2.0);
  EXPECT_LT(secondsBetween("yesterday", "2026-01-01T00:00:01.000Z"), 0.0);
}

TEST(LiveProgress, AJobsProgressWeighsItsRunsByCost) {
  // Run 0 took 100 s; run 1 has run 10 s and is half done at 5 %/s (10 s left: 20 s in all); run 2
  // waits (weighed as the mean, 60 s). Equal weights would say (1 + 0.5 + 0) / 3 = 50 %; by cost it
  // is (100 + 10 + 0) / 180.
  std::vector<RunRecord> runs(3);
  runs[0].status = Status::Successful;
  runs[0].started = "2026-01-01T00:00:00.000Z";
  runs[0].finished = "2026-01-01T00:01:40.000Z";
  runs[1].status = Status::Running;
  runs[1].started = "2026-01-01T00:01:40.000Z";
  runs[1].rateFrom = "2026-01-01T00:01:41.000Z";  // 5 % after 1 s, 50 % after 10 s: 5 %/s
  runs[1].rateFromProgress = 0.05;
  runs[1].progress = 0.5;
  runs[1].updated = "2026-01-01T00:01:50.000Z";
  runs[2].status = Status::Accepted;
  const std::string now = "2026-01-01T00:01:50.000Z";
  EXPECT_NEAR(jobProgress(runs, now), 110.0 / 180.0, 1e-12);
  // Before any run has a known cost, every run weighs the same.
  runs[0].status = Status::Running;
  runs[0].progress = 0.2;
  runs[0].finished.clear();
  runs[1].rateFrom.clear();
  EXPECT_NEAR(jobProgress(runs, now), (0.2 + 0.5 + 0) / 3, 1e-12);
}

TEST(LiveProgress, AJobsEtaFillsTheSlotsItsRunsFreeWithTheirMeasuredLength) {
  // Two workers: run 0 ends in 10 s (50 % done at 5 %/s), run 1 in 90 s (10 % done at 1 %/s); run 2
  // finished in 100 s; run 3 waits. Run 3 starts when run 0's worker comes free
  // and takes the 100 s the finished run took: 110 s. (Rounds of the longest, 90 + 100 = 190 s,
  // said nearly twice that.)
  JobRecord job;
  job.status = Status::Running;
  std::vector<RunRecord> runs(4);
  runs[0].status = runs[1].status = Status::Running;
  runs[0].started = runs[1].started = "2026-01-01T00:00:00.000Z";
  runs[0].rateFrom = "2026-01-01T00:00:00.000Z";
  runs[0].rateFromProgress = 0.0001;
  runs[0].progress = 0.5001;
  runs[1].rateFrom = "2026-01-01T00:00:00.000Z";
  runs[1].rateFromProgress = 0.0001;
  runs[1].progress = 0.1001;
  runs[0].updated = runs[1].updated = "2026-01-01T00:00:10.000Z";
  runs[2].status = Status::Successful;
  runs[2].started = "2025-12-31T23:58:00.000Z";
  runs[2].finished = "2025-12-31T23:59:40.000Z";
  runs[3].status = Status::Accepted;
  const std::string now = "2026-01-01T00:00:10.000Z";
  Json doc;
  addJobProgress(doc, job, &runs, now);
  ASSERT_TRUE(doc["eta_s"].is_number()) << doc.dump();
  EXPECT_NEAR(doc["eta_s"].get<double>(), 110.0, 0.1);
  // A run not measured yet (no rate) counts as a typical run less what it has run: 100 - 10 s.
  runs[1].rateFrom.clear();
  addJobProgress(doc, job, &runs, now);
  ASSERT_TRUE(doc["eta_s"].is_number()) << doc.dump();
  EXPECT_NEAR(doc["eta_s"].get<double>(), 110.0, 0.1);  // 10 + 100 on one slot, 90 on the other
}

TEST(LiveProgress, RunningRunAndJobReportStageElapsedEtaAndUpdated) {
  ASSERT_TRUE(test::scenarioAvailable());
  LiveServer live([](ServerConfig& c) { c.workers = 1; });
  auto client = live.client();
  const std::int64_t id = test::submit(*client, slowThenQuick());
  ASSERT_GT(id, 0);
  const std::string path = "/jobs/" + std::to_string(id);
  Json first;
  ASSERT_TRUE(test::waitFor([&] {
    first = getJson(*client, path);
    // A run's ETA needs 2 s of its own progress; the job's needs its running run's.
    return !first["runs"][0]["eta_s"].is_null() && !first["eta_s"].is_null();
  }, 120)) << first.dump(2);
  const Json& run = first["runs"][0];
  EXPECT_EQ(run["status"], "running");
  EXPECT_TRUE(run["stage"].is_string());
  EXPECT_NE(run["stage"], "queued");
  EXPECT_GT(run["elapsed_s"].get<double>(), 0.0);
  EXPECT_GT(run["eta_s"].get<double>(), 0.0);
  EXPECT_EQ(first["runs"][1]["stage"], "queued");
  EXPECT_TRUE(first["runs"][1]["elapsed_s"].is_null());
  EXPECT_TRUE(first["stage"].get<std::string>().find("0 of 2 runs finished, 1 running") == 0) << first["stage"];
  EXPECT_GT(first["elapsed_s"].get<double>(), 0.0);
  // The queued run comes after the running one: the job needs longer than its running run.
  EXPECT_GT(first["eta_s"].get<double>(), run["eta_s"].get<double>());

  // While the progress rises, both `updated` stamps move and elapsed grows.
  Json later;
  ASSERT_TRUE(test::waitFor([&] {
    later = getJson(*client, path);
    return later["runs"][0]["progress"].get<int>() > run["progress"].get<int>();
  }, 120)) << later.dump(2);
  EXPECT_GT(later["runs"][0]["updated"].get<std::string>(), run["updated"].get<std::string>());
  EXPECT_GT(later["updated"].get<std::string>(), first["updated"].get<std::string>());
  // The job and its runs are one read: the job's stamp is never older than a run it lists.
  for (const Json& r : later["runs"]) {
    if (r["updated"].is_string()) {
      EXPECT_GE(later["updated"].get<std::string>(), r["updated"].get<std::string>());
    }
  }
  EXPECT_GT(later["runs"][0]["elapsed_s"].get<double>(), run["elapsed_s"].get<double>());
  // The job list carries the same members.
  const Json list = getJson(*client, "/jobs");
  ASSERT_EQ(list["jobs"].size(), 1u);
  for (const char* key : {"stage", "elapsed_s", "eta_s", "updated"}) EXPECT_TRUE(list["jobs"][0].contains(key)) << key;

  // Dismissed: the job's progress is what ran (run 0's share), not the dismissed runs counted as done.
  auto res = client->Delete(path.c_str());
  ASSERT_TRUE(res);
  ASSERT_EQ(res->status, 200) << res->body;
  Json done = test::waitForJob(*client, id, {"dismissed"}, 30);
  ASSERT_TRUE(test::waitFor([&] {
    done = getJson(*client, path);
    return done["runs"][0]["status"] == "dismissed";
  }, 30)) << done.dump(2);
  const int ran = done["runs"][0]["progress"].get<int>();
  EXPECT_GT(ran, 0);
  EXPECT_LT(ran, 100);
  EXPECT_EQ(done["runs"][1]["progress"], 0);
  EXPECT_LE(done["progress"].get<int>(), (ran + 1) / 2);
  EXPECT_GE(done["progress"].get<int>(), ran / 2 - 1);
  EXPECT_TRUE(done["eta_s"].is_null());
  EXPECT_EQ(done["runs"][1]["stage"], "dismissed");
}

}  // namespace
}  // namespace rupture::server
