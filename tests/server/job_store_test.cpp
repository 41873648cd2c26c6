// The SQLite job store: job and run lifecycle, status roll-up, dismissal, crash re-queue, reopen.
#include <gtest/gtest.h>

#include "jobs/job_store.hpp"
#include "server_test_support.hpp"

namespace rupture::server {
namespace {

NewJob threeRunJob(const std::string& name = "three") {
  NewJob job;
  job.processId = "dynamic-tension";
  job.name = name;
  job.sweepMode = "grid";
  job.sweptPaths = Json::array({"loading.strain_rate"});
  job.inputs = Json::parse(R"({"loading": {"strain_rate": 1}})");
  job.sweep = Json::parse(R"({"loading.strain_rate": [1, 2, 3]})");
  for (int k = 1; k <= 3; ++k) {
    job.runs.emplace_back(Json::array({k}), Json{{"scenario", "dynamic-tension"}, {"loading", {{"strain_rate", k}}}});
  }
  return job;
}

TEST(JobStore, CreatesJobsWithAcceptedRunsInOrder) {
  test::TempDir dir;
  JobStore store((dir.path() / "db.sqlite").string());
  const auto id = store.createJob(threeRunJob());
  EXPECT_GT(id, 0);
  auto job = store.job(id);
  ASSERT_TRUE(job);
  EXPECT_EQ(job->status, Status::Accepted);
  EXPECT_EQ(job->runsTotal, 3);
  EXPECT_EQ(job->runsAccepted, 3);
  EXPECT_EQ(job->name, "three");
  EXPECT_FALSE(job->created.empty());
  auto runs = store.runs(id);
  ASSERT_EQ(runs.size(), 3u);
  EXPECT_EQ(runs[2].swept, Json::array({3}));
  // Stored as a patch of the job's inputs, given back whole: by run() and by runSpec().
  EXPECT_TRUE(runs[2].spec.is_null());
  EXPECT_EQ(runSpec(*job, runs[2]), threeRunJob().runs[2].second);
  EXPECT_EQ(store.run({id, 2})->spec, threeRunJob().runs[2].second);
  EXPECT_EQ(store.queuedRuns().size(), 3u);
  EXPECT_EQ(store.queueDepth(), 3);
  EXPECT_FALSE(store.job(id + 100));
}

TEST(JobStore, RunSpecsAreStoredAsPatchesOfTheInputsAndComeBackBitForBit) {
  test::TempDir dir;
  JobStore store((dir.path() / "db.sqlite").string());
  NewJob job = threeRunJob();
  job.inputs = Json::parse(R"({"description": "long text", "loading": {"strain_rate": 1, "initial_velocity": "VL"},
                               "probes": [[0, 1], [2, 3]], "run": {"max_strain": 0.01}})");
  job.runs.clear();
  // A changed value, an added member (at the end, in order), a changed array element, a removed member.
  Json a = jobBaseSpec(job.processId, job.inputs);
  a["loading"]["strain_rate"] = 2.5;
  Json b = a;
  b["loading"]["extra"] = {{"x", 1}};
  b["probes"][1][0] = 7.0;
  Json c = a;
  c.erase("run");
  for (const Json& spec : {a, b, c}) job.runs.emplace_back(Json::array({0}), spec);
  const auto id = store.createJob(job);
  const auto record = store.job(id);
  ASSERT_TRUE(record);
  const auto runs = store.runs(id);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(store.run({id, k})->spec.dump(), job.runs[static_cast<std::size_t>(k)].second.dump()) << k;  // order too
    EXPECT_EQ(runSpec(*record, runs[static_cast<std::size_t>(k)]).dump(), job.runs[static_cast<std::size_t>(k)].second.dump()) << k;
    EXPECT_EQ(runs[static_cast<std::size_t>(k)].specPatch.dump().find("long text"), std::string::npos);  // the inputs once
  }
  const std::vector<int> added = store.appendRuns(id, {{Json::array({1}), b}}, {0}, Json::object());
  ASSERT_EQ(added, std::vector<int>({3}));
  EXPECT_EQ(store.run({id, 3})->spec.dump(), b.dump());
}

TEST(JobStore, StatusRollsUpFromRuns) {
  test::TempDir dir;
  JobStore store((dir.path() / "db.sqlite").string());
  const auto id = store.createJob(threeRunJob());
  ASSERT_TRUE(store.startRun({id, 0}));
  EXPECT_FALSE(store.startRun({id, 0}));  // already running
  EXPECT_EQ(store.job(id)->status, Status::Running);
  EXPECT_FALSE(store.job(id)->started.empty());
  store.setProgress({{{id, 0}, 0.5, ""}});
  EXPECT_NEAR(store.job(id)->progress, 0.5 / 3, 1e-9);
  store.finishSuccessful({id, 0}, Json{{"peak_stress", 1e8}}, "jobs/1/run-0.h5");
  ASSERT_TRUE(store.startRun({id, 1}));
  store.finishFailed({id, 1}, "boom");
  EXPECT_EQ(store.job(id)->status, Status::Running);
  ASSERT_TRUE(store.startRun({id, 2}));
  store.finishSuccessful({id, 2}, Json{{"peak_stress", 2e8}}, "jobs/1/run-2.h5");
  auto job = store.job(id);
  EXPECT_EQ(job->status, Status::Failed);  // one failed run fails the job; the others keep their results
  EXPECT_EQ(job->runsSuccessful, 2);
  EXPECT_EQ(job->runsFailed, 1);
  EXPECT_FALSE(job->finished.empty());
  EXPECT_NEAR(job->progress, 2.0 / 3, 1e-9);  // the failed run counts as far as it got (not at all)
  auto r1 = store.run({id, 1});
  EXPECT_EQ(r1->error, "boom");
  auto r0 = store.run({id, 0});
  EXPECT_EQ(r0->summary["peak_stress"], 1e8);
  EXPECT_EQ(r0->resultPath, "jobs/1/run-0.h5");
  EXPECT_EQ(r0->attempts, 1);
}

TEST(JobStore, DismissStopsQueuedRunsAndKeepsFinishedOnes) {
  test::TempDir dir;
  JobStore store((dir.path() / "db.sqlite").string());
  const auto id = store.createJob(threeRunJob());
  ASSERT_TRUE(store.startRun({id, 0}));
  store.finishSuccessful({id, 0}, Json::object(), "jobs/1/run-0.h5");
  ASSERT_TRUE(store.startRun({id, 1}));
  auto job = store.dismissJob(id);
  ASSERT_TRUE(job);
  EXPECT_EQ(job->status, Status::Dismissed);
  EXPECT_EQ(store.run({id, 0})->status, Status::Successful);
  EXPECT_EQ(store.run({id, 1})->status, Status::Running);  // the worker reports when it stopped
  EXPECT_EQ(store.run({id, 2})->status, Status::Dismissed);
  EXPECT_FALSE(store.startRun({id, 2}));
  EXPECT_TRUE(store.queuedRuns().empty());
  store.finishDismissed({id, 1});
  EXPECT_EQ(store.job(id)->status, Status::Dismissed);
  EXPECT_FALSE(store.dismissJob(id + 7));
}

TEST(JobStore, DismissingAFinishedJobChangesNothing) {
  test::TempDir dir;
  JobStore store((dir.path() / "db.sqlite").string());
  NewJob one = threeRunJob();
  one.runs.resize(1);
  const auto id = store.createJob(one);
  ASSERT_TRUE(store.startRun({id, 0}));
  store.finishSuccessful({id, 0}, Json::object(), "x.h5");
  EXPECT_EQ(store.dismissJob(id)->status, Status::Successful);
}

TEST(JobStore, ReopenRequeuesInterruptedRuns) {
  test::TempDir dir;
  const std::string path = (dir.path() / "db.sqlite").string();
  std::int64_t id = 0, other = 0;
  {
    JobStore store(path);
    id = store.createJob(threeRunJob("a"));
    other = store.createJob(threeRunJob("b"));
    ASSERT_TRUE(store.startRun({id, 0}));
    store.finishSuccessful({id, 0}, Json{{"peak_stress", 1.0}}, "jobs/1/run-0.h5");
    ASSERT_TRUE(store.startRun({id, 1}));
    ASSERT_TRUE(store.startRun({other, 0}));
    store.dismissJob(other);
  }  // "crash": runs left running
  JobStore store(path);
  EXPECT_EQ(store.unfinishedRuns().size(), 3u);  // id/1, id/2, other/0 (other/1..2 were dismissed)
  EXPECT_EQ(store.requeueInterrupted(), 2);
  EXPECT_EQ(store.run({id, 1})->status, Status::Accepted);
  EXPECT_EQ(store.run({other, 0})->status, Status::Dismissed);  // its job was dismissed
  EXPECT_EQ(store.run({id, 0})->status, Status::Successful);
  auto queued = store.queuedRuns();
  ASSERT_EQ(queued.size(), 2u);
  EXPECT_EQ(queued[0], (RunKey{id, 1}));
  EXPECT_EQ(queued[1], (RunKey{id, 2}));
  ASSERT_TRUE(store.startRun({id, 1}));
  EXPECT_EQ(store.run({id, 1})->attempts, 2);
}

TEST(JobStore, ListsNewestFirstWithFiltersAndPaging) {
  test::TempDir dir;
  JobStore store((dir.path() / "db.sqlite").string());
  std::vector<std::int64_t> ids;
  for (int i = 0; i < 5; ++i) ids.push_back(store.createJob(threeRunJob(std::string("j").append(std::to_string(i)))));
  store.dismissJob(ids[1]);
  std::int64_t total = 0;
  auto all = store.listJobs({}, total);
  EXPECT_EQ(total, 5);
  ASSERT_EQ(all.size(), 5u);
  EXPECT_EQ(all[0].id, ids[4]);
  JobFilter f;
  f.statuses = {Status::Dismissed};
  auto dismissed = store.listJobs(f, total);
  EXPECT_EQ(total, 1);
  ASSERT_EQ(dismissed.size(), 1u);
  EXPECT_EQ(dismissed[0].id, ids[1]);
  JobFilter page;
  page.limit = 2;
  page.offset = 2;
  auto p = store.listJobs(page, total);
  EXPECT_EQ(total, 5);
  ASSERT_EQ(p.size(), 2u);
  EXPECT_EQ(p[0].id, ids[2]);
  JobFilter proc;
  proc.processId = "nope";
  EXPECT_TRUE(store.listJobs(proc, total).empty());
  EXPECT_EQ(total, 0);
}

TEST(JobStore, UsesWriteAheadLogging) {
  test::TempDir dir;
  const auto path = dir.path() / "db.sqlite";
  JobStore store(path.string());
  store.createJob(threeRunJob());
  EXPECT_TRUE(std::filesystem::exists(path.string() + "-wal"));
}

}  // namespace
}  // namespace rupture::server
