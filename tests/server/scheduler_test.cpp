// The scheduler with a stand-in executor (the engine's runSpec is exercised end to end elsewhere):
// order, isolation of failures, cancellation, re-queue on shutdown, crash repair, file layout.
#include <atomic>
#include <fstream>
#include <mutex>

#include <gtest/gtest.h>

#include "common/files.hpp"
#include "execution/scheduler.hpp"
#include "server_test_support.hpp"

namespace rupture::server {
namespace {

NewJob jobOf(int runs, const std::string& behaviour = "ok") {
  NewJob job;
  job.processId = "dynamic-tension";
  job.sweepMode = "grid";
  job.sweptPaths = Json::array({"k"});
  job.inputs = Json::object();
  job.sweep = Json::object();
  for (int k = 0; k < runs; ++k) job.runs.emplace_back(Json::array({k}), Json{{"k", k}, {"behaviour", behaviour}});
  return job;
}

/// Executes specs {"k", "behaviour"}: "ok" writes a file, "throw" throws, "slow" waits for cancel.
struct FakeExecutor {
  std::mutex mutex;
  std::vector<int> order;
  std::atomic<int> concurrent{0}, maxConcurrent{0};

  RunExecutor executor() {
    return [this](const nlohmann::json& spec, const std::string& path, rupture::RunControl& control, int threads) {
      EXPECT_EQ(threads, 3);
      {
        std::lock_guard lock(mutex);
        order.push_back(spec["k"].get<int>());
      }
      const int now = ++concurrent;
      int prev = maxConcurrent;
      while (now > prev && !maxConcurrent.compare_exchange_weak(prev, now)) {}
      struct Leave { std::atomic<int>& c; ~Leave() { --c; } } leave{concurrent};
      const std::string behaviour = spec["behaviour"];
      if (behaviour == "throw" && spec["k"] == 1) throw std::runtime_error("run 1 exploded");
      if (behaviour == "oom" && spec["k"] == 1) {
        if (control.log) control.log("building the sample");
        throw std::bad_alloc();
      }
      if (behaviour == "incomplete") return rupture::RunOutcome{nlohmann::json::object(), false};
      if (behaviour == "slow") {
        for (int i = 0; i < 1000 && !control.cancel; ++i) {
          control.progress = i / 1000.0;
          std::this_thread::sleep_for(std::chrono::milliseconds(5));
        }
        if (control.cancel) return rupture::RunOutcome{nlohmann::json::object(), false};
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      std::ofstream(path) << "result of run " << spec["k"].get<int>();
      return rupture::RunOutcome{{{"peak_stress", 1e6 * (spec["k"].get<int>() + 1)}}, true};
    };
  }
};

bool jobDone(JobStore& store, std::int64_t id) { return isTerminal(store.job(id)->status) && store.job(id)->runsRunning == 0; }

TEST(Scheduler, RunsInOrderAndWritesOneFilePerRun) {
  test::TempDir dir;
  JobStore store((dir.path() / "db.sqlite").string());
  FakeExecutor fake;
  Scheduler scheduler(store, dir.path(), 1, 3, fake.executor());
  scheduler.start();
  const auto id = store.createJob(jobOf(4));
  scheduler.enqueue(id, 4);
  ASSERT_TRUE(test::waitFor([&] { return jobDone(store, id); }, 10));
  EXPECT_EQ(store.job(id)->status, Status::Successful);
  EXPECT_EQ(fake.order, (std::vector<int>{0, 1, 2, 3}));
  for (int k = 0; k < 4; ++k) {
    auto run = store.run({id, k});
    EXPECT_EQ(run->resultPath, "jobs/" + std::to_string(id) + "/run-" + std::to_string(k) + ".h5");
    EXPECT_EQ(test::readText(dir.path() / run->resultPath), "result of run " + std::to_string(k));
    EXPECT_TRUE(std::filesystem::exists(dir.path() / "jobs" / std::to_string(id) / ("run-" + std::to_string(k) + ".summary.json")));
    EXPECT_FALSE(std::filesystem::exists(dir.path() / "jobs" / std::to_string(id) / ("run-" + std::to_string(k) + ".h5.part")));
  }
  EXPECT_EQ(store.run({id, 3})->summary["peak_stress"], 4e6);
}

TEST(Scheduler, ARunOutOfMemoryFailsNamingItsStageNotABareBadAlloc) {
  test::TempDir dir;
  JobStore store((dir.path() / "db.sqlite").string());
  FakeExecutor fake;
  Scheduler scheduler(store, dir.path(), 2, 3, fake.executor());
  scheduler.start();
  const auto id = store.createJob(jobOf(3, "oom"));
  scheduler.enqueue(id, 3);
  ASSERT_TRUE(test::waitFor([&] { return jobDone(store, id); }, 10));
  EXPECT_EQ(store.run({id, 1})->status, Status::Failed);
  const std::string error = store.run({id, 1})->error;
  EXPECT_EQ(error.rfind("out of memory after the stage 'building the sample'", 0), 0u) << error;
  EXPECT_EQ(error.find("bad_alloc"), std::string::npos) << error;
  EXPECT_EQ(store.run({id, 0})->status, Status::Successful);
  EXPECT_EQ(store.run({id, 2})->status, Status::Successful);
}

TEST(Scheduler, AThrowingRunFailsOnlyItself) {
  test::TempDir dir;
  JobStore store((dir.path() / "db.sqlite").string());
  FakeExecutor fake;
  Scheduler scheduler(store, dir.path(), 2, 3, fake.executor());
  scheduler.start();
  const auto id = store.createJob(jobOf(3, "throw"));
  scheduler.enqueue(id, 3);
  ASSERT_TRUE(test::waitFor([&] { return jobDone(store, id); }, 10));
  EXPECT_EQ(store.run({id, 0})->status, Status::Successful);
  EXPECT_EQ(store.run({id, 1})->status, Status::Failed);
  EXPECT_EQ(store.run({id, 1})->error, "run 1 exploded");
  EXPECT_EQ(store.run({id, 2})->status, Status::Successful);
  EXPECT_EQ(store.job(id)->status, Status::Failed);
  EXPECT_LE(fake.maxConcurrent.load(), 2);
}

TEST(Scheduler, ARunEndingIncompleteWithoutCancelFails) {
  test::TempDir dir;
  JobStore store((dir.path() / "db.sqlite").string());
  FakeExecutor fake;
  Scheduler scheduler(store, dir.path(), 1, 3, fake.executor());
  scheduler.start();
  const auto id = store.createJob(jobOf(1, "incomplete"));
  scheduler.enqueue(id, 1);
  ASSERT_TRUE(test::waitFor([&] { return jobDone(store, id); }, 10));
  EXPECT_EQ(store.run({id, 0})->status, Status::Failed);
  EXPECT_FALSE(store.run({id, 0})->error.empty());
  EXPECT_FALSE(std::filesystem::exists(scheduler.runFile({id, 0})));
}

TEST(Scheduler, DismissCancelsRunningAndQueuedRuns) {
  test::TempDir dir;
  JobStore store((dir.path() / "db.sqlite").string());
  FakeExecutor fake;
  Scheduler scheduler(store, dir.path(), 1, 3, fake.executor());
  scheduler.start();
  const auto id = store.createJob(jobOf(3, "slow"));
  scheduler.enqueue(id, 3);
  ASSERT_TRUE(test::waitFor([&] { return store.run({id, 0})->status == Status::Running; }, 5));
  // Progress reaches the store within about a second.
  EXPECT_TRUE(test::waitFor([&] { return store.run({id, 0})->progress > 0; }, 3));
  const auto t0 = std::chrono::steady_clock::now();
  auto job = scheduler.dismiss(id);
  ASSERT_TRUE(job);
  EXPECT_EQ(job->status, Status::Dismissed);
  ASSERT_TRUE(test::waitFor([&] { return store.job(id)->runsRunning == 0; }, 2));
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 1.0);
  EXPECT_EQ(store.run({id, 0})->status, Status::Dismissed);
  EXPECT_EQ(store.run({id, 2})->status, Status::Dismissed);
  EXPECT_EQ(fake.order, (std::vector<int>{0}));  // queued runs never started
  EXPECT_FALSE(std::filesystem::exists(scheduler.runFile({id, 0})));
  EXPECT_FALSE(scheduler.dismiss(id + 1));
}

TEST(Scheduler, ShutdownRequeuesRunningRunsAndRestartFinishesThem) {
  test::TempDir dir;
  JobStore store((dir.path() / "db.sqlite").string());
  FakeExecutor fake;
  std::int64_t id = 0;
  {
    Scheduler scheduler(store, dir.path(), 1, 3, fake.executor());
    scheduler.start();
    id = store.createJob(jobOf(2, "slow"));
    scheduler.enqueue(id, 2);
    ASSERT_TRUE(test::waitFor([&] { return store.run({id, 0})->status == Status::Running; }, 5));
    scheduler.shutdown();
    EXPECT_EQ(store.run({id, 0})->status, Status::Accepted);
    EXPECT_EQ(store.job(id)->status, Status::Accepted);
  }
  // Next start: the re-queued run runs again (this time to completion: "ok").
  FakeExecutor fake2;
  Scheduler again(store, dir.path(), 1, 3, [&](const nlohmann::json& spec, const std::string& path,
                                              rupture::RunControl& c, int t) {
    nlohmann::json ok = spec;
    ok["behaviour"] = "ok";
    return fake2.executor()(ok, path, c, t);
  });
  again.start();
  ASSERT_TRUE(test::waitFor([&] { return jobDone(store, id); }, 10));
  EXPECT_EQ(store.job(id)->status, Status::Successful);
  EXPECT_EQ(store.run({id, 0})->attempts, 2);
}

TEST(Scheduler, ARunFinishedButNotRecordedIsRecoveredFromItsFilesNotRecomputed) {
  test::TempDir dir;
  JobStore store((dir.path() / "db.sqlite").string());
  const auto id = store.createJob(jobOf(2));
  ASSERT_TRUE(store.startRun({id, 0}));  // the crash came after the rename, before the store update
  FakeExecutor fake;
  Scheduler scheduler(store, dir.path(), 1, 3, fake.executor());
  std::filesystem::create_directories(scheduler.jobDir(id));
  std::ofstream(scheduler.runFile({id, 0})) << "finished before the crash";
  writeFileAtomic(scheduler.jobDir(id) / "run-0.summary.json", R"({"peak_stress": 123.0})");
  // A run file without its summary is not trusted: it runs again.
  std::ofstream(scheduler.runFile({id, 1})) << "stale";
  scheduler.start();
  ASSERT_TRUE(test::waitFor([&] { return jobDone(store, id); }, 10));
  EXPECT_EQ(fake.order, (std::vector<int>{1}));
  EXPECT_EQ(store.run({id, 0})->summary["peak_stress"], 123.0);
  EXPECT_EQ(test::readText(scheduler.runFile({id, 0})), "finished before the crash");
  EXPECT_EQ(test::readText(scheduler.runFile({id, 1})), "result of run 1");
}

}  // namespace
}  // namespace rupture::server
