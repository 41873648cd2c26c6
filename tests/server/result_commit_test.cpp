// The result commit as one durable sequence (docs/server.md, docs/checkpoints.md): the real
// rupture-server kills itself (RUPTURE_TEST_KILL_AT, server/execution/kill_points.hpp) at each step
// of a finished run's commit: after the engine returned, after the summary's temporary, after the
// summary's rename, after the result's rename and after the checkpoint's removal. The restarted
// server neither recomputes the run from step 0 nor loses its result: before the summary is in
// place it continues from the run's last checkpoint, after that it finishes the commit from the
// files without running anything; either way the result equals an uninterrupted run's.
#include <signal.h>
#include <stdlib.h>
#include <sys/stat.h>

#include <filesystem>

#include <gtest/gtest.h>

#include "io/checkpoint_file.hpp"
#include "rupture/run.hpp"
#include "server_test_support.hpp"
#include "support/hdf5_compare.hpp"

namespace rupture::server {
namespace {

namespace fs = std::filesystem;
using test::ChildServer;

struct KillPoint {
  const char* name;
  bool continuesFromCheckpoint;  ///< the restart resumes the run (the summary was not yet in place)
};

/// A few seconds of stepping with a checkpoint every 0.1 s: the run has checkpoints when it ends.
Json commitInputs() {
  Json inputs = test::smallInputs();
  inputs["loading"]["strain_rate"] = 2e5;
  inputs["run"]["checkpoint_interval_s"] = 0.1;
  return inputs;
}

class ResultCommit : public ::testing::TestWithParam<KillPoint> {
protected:
  static void SetUpTestSuite() {
    s_scratch = new test::TempDir();
    Json spec = commitInputs();
    spec["scenario"] = test::kScenario;
    RunControl control;
    const RunOutcome outcome = runSpec(spec, reference().string(), control, 1);
    s_referenceCompleted = outcome.completed;
    s_referenceSteps = outcome.summary.value("steps", std::int64_t{-1});
  }
  static void TearDownTestSuite() {
    delete s_scratch;
    s_scratch = nullptr;
  }
  static fs::path reference() { return s_scratch->path() / "uninterrupted.h5"; }

  static test::TempDir* s_scratch;
  static bool s_referenceCompleted;
  static std::int64_t s_referenceSteps;
};

test::TempDir* ResultCommit::s_scratch = nullptr;
bool ResultCommit::s_referenceCompleted = false;
std::int64_t ResultCommit::s_referenceSteps = -1;

ino_t inodeOf(const fs::path& p) {
  struct stat st {};
  return ::stat(p.c_str(), &st) == 0 ? st.st_ino : 0;
}

TEST_P(ResultCommit, AKillAtThisStepNeitherRestartsFromStepZeroNorLosesTheResult) {
  ASSERT_TRUE(test::scenarioAvailable()) << "the dynamic-tension scenario or its small example is missing";
  ASSERT_TRUE(s_referenceCompleted);
  const KillPoint point = GetParam();
  test::TempDir data;
  std::int64_t id = 0;
  fs::path dir;
  auto path = [&](const std::string& suffix) { return dir / ("run-0" + suffix); };

  // 1. The server kills itself at the step, once the run has finished computing.
  {
    ASSERT_EQ(::setenv("RUPTURE_TEST_KILL_AT", point.name, 1), 0);
    ChildServer server(data.path());
    ::unsetenv("RUPTURE_TEST_KILL_AT");  // the child has it; nothing else here needs it
    auto client = server.client();
    id = test::submit(*client, {{"inputs", commitInputs()}});
    ASSERT_GT(id, 0);
    dir = data.path() / "jobs" / std::to_string(id);
    EXPECT_EQ(server.stop(0, 180), 128 + SIGKILL) << "the server did not reach " << point.name;
  }

  // What the kill left: each step's files, and the checkpoint until its removal.
  const std::string at = point.name;
  const bool summaryKept = at != "after-engine" && at != "after-summary-tmp";
  EXPECT_EQ(fs::exists(path(".summary.json")), summaryKept);
  EXPECT_EQ(fs::exists(path(".summary.json.tmp")), at == "after-summary-tmp");
  const bool renamed = at == "after-result-rename" || at == "after-checkpoint-removal";
  EXPECT_EQ(fs::exists(path(".h5")), renamed);
  EXPECT_EQ(fs::exists(path(".h5.part")), !renamed);
  EXPECT_EQ(fs::exists(path(".h5.checkpoint")), at != "after-checkpoint-removal")
      << "the checkpoint is removed only after the summary and the result are in place";
  std::int64_t checkpointStep = -1;
  if (fs::exists(path(".h5.checkpoint"))) checkpointStep = io::readCheckpointHeader(path(".h5.checkpoint").string()).step;
  if (point.continuesFromCheckpoint) {
    ASSERT_GT(checkpointStep, 0) << "the run wrote no checkpoint before it ended";
  }
  const ino_t resultInode = inodeOf(renamed ? path(".h5") : path(".h5.part"));

  // 2. The restarted server ends the job successful, from the checkpoint or from the files.
  {
    ChildServer server(data.path());
    auto client = server.client();
    Json doc = test::waitForJob(*client, id, {"successful", "failed", "dismissed"}, 180);
    ASSERT_EQ(doc["status"], "successful") << doc.dump(2);
    if (point.continuesFromCheckpoint)  // the monitor may write the resume a moment after the outcome
      test::waitFor([&] { return (doc = test::getJson(*client, "/jobs/" + std::to_string(id)))["runs"][0].value("resumes", 0) > 0; }, 5);
    const Json& run = doc["runs"][0];
    if (point.continuesFromCheckpoint) {
      EXPECT_EQ(run.value("resumes", 0), 1) << run.dump(2);
      EXPECT_EQ(run.value("resumed_from_step", std::int64_t{-1}), checkpointStep)
          << "the run continued from its last checkpoint, not from step 0";
      EXPECT_EQ(run["attempts"], 2);
    } else {
      EXPECT_FALSE(run.contains("attempts")) << "a finished result is not computed again: " << run.dump(2);
      EXPECT_EQ(inodeOf(path(".h5")), resultInode) << "the result is the file the first server wrote";
    }
    EXPECT_FALSE(fs::exists(path(".h5.checkpoint"))) << "a committed run leaves no checkpoint";
    EXPECT_FALSE(fs::exists(path(".h5.part")));
    EXPECT_FALSE(fs::exists(path(".summary.json.tmp")));
    EXPECT_TRUE(fs::exists(path(".summary.json")));
    ASSERT_TRUE(run["summary"].is_object()) << run.dump(2);
    EXPECT_EQ(run["summary"]["steps"], s_referenceSteps) << "the recorded summary is the finished run's";
    EXPECT_EQ(server.stop(SIGTERM, 10), 0);
  }
  EXPECT_EQ(testing::hdf5Differences(reference().string(), path(".h5").string(), rupture::testing::howARunRan()), "");
}

INSTANTIATE_TEST_SUITE_P(EveryStep, ResultCommit,
                         ::testing::Values(KillPoint{"after-engine", true}, KillPoint{"after-summary-tmp", true},
                                           KillPoint{"after-summary-rename", false},
                                           KillPoint{"after-result-rename", false},
                                           KillPoint{"after-checkpoint-removal", false}),
                         [](const ::testing::TestParamInfo<KillPoint>& info) {
                           std::string name = info.param.name;
                           for (char& c : name)
                             if (c == '-') c = '_';
                           return name;
                         });

}  // namespace
}  // namespace rupture::server
