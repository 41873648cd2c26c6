// The files are the truth about a run, the store a record of it (issue 7, full disk): a run whose
// files are complete is recorded successful at start-up whatever the store says, an outcome the
// store refuses is kept and retried, runs wait below the disk-space floor, and a run that failed
// because the disk filled up is re-queued rather than failed.
#include <sqlite3.h>

#include <atomic>
#include <fstream>

#include <gtest/gtest.h>

#include "common/files.hpp"
#include "execution/scheduler.hpp"
#include "server_test_support.hpp"
#include "support/small_filesystem.hpp"

namespace rupture::server {
namespace {

namespace fs = std::filesystem;
using rupture::testing::SmallFilesystem;

NewJob jobOf(int runs) {
  NewJob job;
  job.processId = "dynamic-tension";
  job.sweepMode = "grid";
  job.sweptPaths = Json::array({"k"});
  job.inputs = Json::object();
  job.sweep = Json::object();
  for (int k = 0; k < runs; ++k) job.runs.emplace_back(Json::array({k}), Json{{"k", k}});
  return job;
}

/// Writes "result of run k" and reports a summary; counts its calls.
struct RecordingExecutor {
  std::atomic<int> calls{0};
  std::function<void(int call)> before;  // runs first, e.g. to throw on the first call
  RunExecutor executor() {
    return [this](const nlohmann::json& spec, const std::string& path, rupture::RunControl&, int) {
      const int call = ++calls;
      if (before) before(call);
      std::ofstream(path) << "result of run " << spec["k"].get<int>();
      return rupture::RunOutcome{{{"peak_stress", 1e6}}, true};
    };
  }
};

void writeFinishedRun(const fs::path& dataDir, RunKey key, double peak) {
  const fs::path dir = dataDir / "jobs" / std::to_string(key.job);
  fs::create_directories(dir);
  std::ofstream(dir / ("run-" + std::to_string(key.index) + ".h5")) << "complete";
  writeFileAtomic(dir / ("run-" + std::to_string(key.index) + ".summary.json"), Json{{"peak_stress", peak}}.dump());
}

TEST(OutcomeRecording, StartupRecordsCompleteRunsWhateverTheStoreSays) {
  test::TempDir dir;
  JobStore store((dir.path() / "db.sqlite").string());
  const auto id = store.createJob(jobOf(3));
  // Run 0: its success could not be recorded but its failure could (a full disk, issue 7).
  ASSERT_TRUE(store.startRun({id, 0}));
  store.finishFailed({id, 0}, "database or disk is full");
  writeFinishedRun(dir.path(), {id, 0}, 10.0);
  // Run 1: finished on disk, the store still says running.
  ASSERT_TRUE(store.startRun({id, 1}));
  writeFinishedRun(dir.path(), {id, 1}, 11.0);
  // Run 2: failed for real (no files): stays failed.
  ASSERT_TRUE(store.startRun({id, 2}));
  store.finishFailed({id, 2}, "diverged");

  RecordingExecutor fake;
  Scheduler scheduler(store, dir.path(), 1, 1, fake.executor());
  scheduler.start();
  scheduler.shutdown();
  EXPECT_EQ(fake.calls, 0) << "a finished result is never recomputed";
  EXPECT_EQ(store.run({id, 0})->status, Status::Successful);
  EXPECT_EQ(store.run({id, 0})->summary["peak_stress"], 10.0);
  EXPECT_EQ(store.run({id, 1})->status, Status::Successful);
  EXPECT_EQ(store.run({id, 1})->summary["peak_stress"], 11.0);
  EXPECT_EQ(store.run({id, 2})->status, Status::Failed);
  EXPECT_EQ(store.run({id, 2})->error, "diverged");
}

TEST(OutcomeRecording, AnOutcomeTheStoreRefusesIsKeptAndRetried) {
  test::TempDir dir;
  const std::string dbPath = (dir.path() / "db.sqlite").string();
  JobStore store(dbPath);
  const auto id = store.createJob(jobOf(1));
  // A second connection holds the write lock while the run finishes: the store's write fails
  // (SQLITE_BUSY after its 5 s busy timeout) as it would on a full disk.
  sqlite3* blocker = nullptr;
  ASSERT_EQ(sqlite3_open(dbPath.c_str(), &blocker), SQLITE_OK);
  std::atomic<bool> locked{false};
  RecordingExecutor fake;
  fake.before = [&](int) {
    ASSERT_EQ(sqlite3_exec(blocker, "BEGIN EXCLUSIVE", nullptr, nullptr, nullptr), SQLITE_OK);
    locked = true;
  };
  Scheduler scheduler(store, dir.path(), 1, 1, fake.executor());
  scheduler.start();
  scheduler.enqueue(id, 1);
  ASSERT_TRUE(test::waitFor([&] { return scheduler.unrecordedOutcomes() == 1; }, 30));
  EXPECT_TRUE(fs::exists(dir.path() / "jobs" / std::to_string(id) / "run-0.h5")) << "the result is on disk";
  EXPECT_EQ(sqlite3_exec(blocker, "COMMIT", nullptr, nullptr, nullptr), SQLITE_OK);
  ASSERT_TRUE(test::waitFor([&] { return store.run({id, 0})->status == Status::Successful; }, 30));
  EXPECT_EQ(scheduler.unrecordedOutcomes(), 0);
  EXPECT_EQ(store.run({id, 0})->summary["peak_stress"], 1e6);
  EXPECT_EQ(fake.calls, 1);
  scheduler.shutdown();
  sqlite3_close(blocker);
}

TEST(OutcomeRecording, ARunThatHitAFullDiskIsRequeuedNotFailed) {
  test::TempDir dir;
  JobStore store((dir.path() / "db.sqlite").string());
  const auto id = store.createJob(jobOf(1));
  RecordingExecutor fake;
  fake.before = [](int call) {
    if (call == 1)
      throw std::runtime_error("HDF5: cannot write file 'x' (its content is lost): H5FD__sec2_write: No space left on device");
  };
  Scheduler scheduler(store, dir.path(), 1, 1, fake.executor());
  scheduler.start();
  scheduler.enqueue(id, 1);
  ASSERT_TRUE(test::waitFor([&] { return store.run({id, 0})->status == Status::Successful; }, 30));
  EXPECT_EQ(fake.calls, 2);
  EXPECT_EQ(store.run({id, 0})->attempts, 2);
  scheduler.shutdown();
}

TEST(OutcomeRecording, ARunReQueuedForAFullDiskWaitsForSpaceInsteadOfBeingFailed) {
  SmallFilesystem disk(8u << 20);
  if (!disk.mounted()) GTEST_SKIP() << disk.whyNot();
  test::TempDir dir;  // the store elsewhere: only the runs' files on the full disk
  JobStore store((dir.path() / "db.sqlite").string());
  const auto id = store.createJob(jobOf(1));
  const fs::path ballast = disk.path() / "ballast";
  RecordingExecutor fake;
  fake.before = [&](int call) {
    if (call == 1) {  // the disk fills up under the run, and stays full
      SmallFilesystem::fillUp(ballast);
      throw std::runtime_error("HDF5: cannot write file 'x' (its content is lost): No space left on device");
    }
  };
  Scheduler scheduler(store, disk.path(), 1, 1, fake.executor());  // no floor: the run's own wait
  scheduler.start();  // queues the store's accepted run
  ASSERT_TRUE(test::waitFor([&] { return scheduler.waitingForDisk(); }, 10));
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));  // tries, were it not waiting
  EXPECT_EQ(fake.calls, 1) << "started again on a disk still full";
  EXPECT_EQ(store.run({id, 0})->status, Status::Accepted) << "waiting, not failed";
  fs::remove(ballast);
  ASSERT_TRUE(test::waitFor([&] { return store.run({id, 0})->status == Status::Successful; }, 30));
  EXPECT_EQ(fake.calls, 2);
  EXPECT_FALSE(scheduler.waitingForDisk());
  scheduler.shutdown();
}

TEST(OutcomeRecording, ARunThatFillsTheDiskEveryTimeWithoutProgressFailsAfterThreeSayingSo) {
  test::TempDir dir;
  JobStore store((dir.path() / "db.sqlite").string());
  const auto id = store.createJob(jobOf(1));
  RecordingExecutor fake;
  fake.before = [](int) { throw std::runtime_error("cannot write: No space left on device"); };
  Scheduler scheduler(store, dir.path(), 1, 1, fake.executor());
  scheduler.start();  // queues the store's accepted run
  ASSERT_TRUE(test::waitFor([&] { return store.run({id, 0})->status == Status::Failed; }, 30));
  EXPECT_EQ(fake.calls, 4);
  EXPECT_NE(store.run({id, 0})->error.find("needs more space than the data disk has"), std::string::npos)
      << store.run({id, 0})->error;
  scheduler.shutdown();
}

TEST(OutcomeRecording, QueuedRunsWaitBelowTheDiskFloor) {
  SmallFilesystem disk(8u << 20);
  if (!disk.mounted()) GTEST_SKIP() << disk.whyNot();
  JobStore store((disk.path() / "db.sqlite").string());
  const auto id = store.createJob(jobOf(2));
  const fs::path ballast = disk.path() / "ballast";
  SmallFilesystem::fillUp(ballast, 1u << 20);  // 1 MiB left, below the 4 MiB floor
  RecordingExecutor fake;
  Scheduler scheduler(store, disk.path(), 1, 1, fake.executor());
  scheduler.setMinFreeBytes(4u << 20);
  scheduler.start();
  scheduler.enqueue(id, 2);
  ASSERT_TRUE(test::waitFor([&] { return scheduler.waitingForDisk(); }, 10));
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  EXPECT_EQ(fake.calls, 0);
  EXPECT_EQ(store.job(id)->runsAccepted, 2) << "waiting, not failed";
  fs::remove(ballast);
  ASSERT_TRUE(test::waitFor([&] { return store.job(id)->status == Status::Successful; }, 30));
  EXPECT_FALSE(scheduler.waitingForDisk());
  EXPECT_EQ(fake.calls, 2);
  scheduler.shutdown();
}

}  // namespace
}  // namespace rupture::server
