// A checkpoint the disk has no room for (docs/checkpoints.md): on a real tmpfs filled up after the
// run's first checkpoints, the next checkpoint is skipped and logged, the last good one stays as it
// was, the run goes on, and once space returns it ends with the result of a run that never met a
// full disk. (tests/server/full_disk_test.cpp does the same through the server.)
#include <atomic>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "engine/test_dynamic_tension_support.hpp"
#include "io/checkpoint_file.hpp"
#include "rupture/run.hpp"
#include "support/hdf5_compare.hpp"
#include "support/small_filesystem.hpp"

namespace rupture::test {
namespace {

using rupture::testing::SmallFilesystem;

nlohmann::json slowSmallTension() {
  nlohmann::json spec = readJson(examplePath("dynamic-tension-small.json"));
  spec["loading"]["initial_velocity"] = "VL";
  spec["loading"]["strain_rate"] = 1e5;  // a few seconds of stepping on one core
  spec["run"]["checkpoint_interval_s"] = 0.1;
  return spec;
}

TEST(CheckpointFullDisk, ACheckpointWithoutRoomIsSkippedTheRunGoesOnToTheUninterruptedResult) {
  useTestCache();  // the sample cache elsewhere: only the run's own files on the small disk
  SmallFilesystem small(64u << 20);
  if (!small.mounted()) GTEST_SKIP() << small.whyNot();
  const nlohmann::json spec = slowSmallTension();
  const fs::path whole = small.path() / "whole.h5";
  {
    RunControl plain;
    ASSERT_TRUE(runSpec(spec, whole.string(), plain, 1).completed);
  }

  // The disk fills up at a checkpoint past the snapshots (they are all taken by 0.0004 of 0.003
  // strain; the series rows are state, written at the end), so that nothing else writes to it
  // until the next checkpoint finds no room; space returns as that checkpoint is skipped.
  const fs::path result = small.path() / "full.h5";
  const fs::path checkpoint = io::checkpointPathFor(result.string());
  const fs::path filler = small.path() / "filler";
  RunControl control;
  bool filled = false, skipped = false;
  std::int64_t stepAtFill = -1, stepAfterSkip = -1;
  std::string skipMessage;
  control.log = [&](const std::string& message) {
    if (!filled && message.rfind("checkpoint at step", 0) == 0 && control.progress.load() > 0.3) {
      stepAtFill = io::readCheckpointHeader(checkpoint.string()).step;
      SmallFilesystem::fillUp(filler);
      filled = true;
    } else if (filled && !skipped && message.rfind("no room for the checkpoint", 0) == 0) {
      skipMessage = message;
      stepAfterSkip = io::readCheckpointHeader(checkpoint.string()).step;  // the last good one, readable
      fs::remove(filler);
      skipped = true;
    }
  };
  const RunOutcome outcome = runSpec(spec, result.string(), control, 1);
  ASSERT_TRUE(filled) << "the run ended before a checkpoint past 30 %";
  ASSERT_TRUE(skipped) << "no checkpoint was skipped on the full disk";
  EXPECT_TRUE(outcome.completed) << "a checkpoint that cannot be written must not end the run";
  EXPECT_GE(control.checkpointsSkipped.load(), 1);
  EXPECT_EQ(stepAfterSkip, stepAtFill) << "the last good checkpoint stays as it was";
  EXPECT_NE(skipMessage.find("MB free"), std::string::npos) << skipMessage;
  EXPECT_NE(skipMessage.find("its last checkpoint (step " + std::to_string(stepAtFill) + ") stays"), std::string::npos)
      << skipMessage;
  EXPECT_FALSE(fs::exists(checkpoint)) << "a completed run removes its checkpoint";
  EXPECT_EQ(rupture::testing::hdf5Differences(whole.string(), result.string(), rupture::testing::howARunRan()), "");
}

}  // namespace
}  // namespace rupture::test
