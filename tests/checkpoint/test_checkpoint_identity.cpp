// What a checkpoint must match to be continued (docs/checkpoints.md): the scenario, the spec but for
// run.checkpoint_interval_s, and the build's version; anything else is refused with a message
// naming it, and nothing is written. Also: checkpoints come every interval of wall time, none at
// all with an interval of 0, and a resumed run's file records where it continued.
#include <atomic>
#include <thread>

#include <gtest/gtest.h>

#include "checkpoint/checkpoint_support.hpp"
#include "engine/test_dynamic_tension_support.hpp"

namespace rupture::test {
namespace {

nlohmann::json tension() {
  nlohmann::json spec = readJson(examplePath("dynamic-tension-small.json"));
  spec["loading"] = {{"strain_rate", 1e7}, {"initial_velocity", "VL"}};
  return spec;
}

/// Runs `spec` to `path` and stops it at `step` with a checkpoint.
void stopAt(const nlohmann::json& spec, const fs::path& path, std::int64_t step) {
  RunControl control;
  control.stopAtStep = step;
  const RunOutcome outcome = runSpec(spec, path.string(), control, 1);
  ASSERT_FALSE(outcome.completed);
  ASSERT_EQ(control.checkpointStep.load(), step);
}

std::string refusal(const nlohmann::json& spec, const fs::path& path) {
  RunControl control;
  control.resume = true;
  try {
    runSpec(spec, path.string(), control, 1);
  } catch (const CheckpointError& e) {
    return e.what();
  }
  return "";
}

TEST(CheckpointIdentity, OnlyTheSameRunOnTheSameBuildContinues) {
  useTestCache();
  ScratchDir dir;
  const fs::path path = dir / "run.h5";
  stopAt(tension(), path, 100);
  const std::string checkpoint = io::checkpointPathFor(path.string());

  nlohmann::json other = tension();
  other["sample"]["seed"] = 6;
  EXPECT_NE(refusal(other, path).find("another spec (they differ at sample.seed)"), std::string::npos)
      << refusal(other, path);

  {  // another version wrote it
    io::Hdf5File file = io::Hdf5File::openReadWrite(checkpoint);
    file.setAttribute("/checkpoint", "rupture_version", std::string("0.0.1"));
  }
  EXPECT_NE(refusal(tension(), path).find("written by rupture 0.0.1"), std::string::npos) << refusal(tension(), path);
  {
    io::Hdf5File file = io::Hdf5File::openReadWrite(checkpoint);
    file.setAttribute("/checkpoint", "rupture_version", std::string(RUPTURE_VERSION));
  }

  // Another scenario's checkpoint at the same path.
  nlohmann::json impact = readJson(examplePath("impact-branching-pmb.json"));
  EXPECT_NE(refusal(impact, path).find("is of a dynamic-tension run, not impact"), std::string::npos)
      << refusal(impact, path);

  // The interval is not the run's identity: a resume with another one continues.
  nlohmann::json interval = tension();
  interval["run"]["checkpoint_interval_s"] = 0;
  RunControl control;
  control.resume = true;
  const RunOutcome outcome = runSpec(interval, path.string(), control, 1);
  EXPECT_TRUE(outcome.completed);
  EXPECT_EQ(control.resumedFromStep.load(), 100);
  EXPECT_FALSE(fs::exists(checkpoint));
}

TEST(CheckpointIdentity, AnOlderBuildsCheckpointWithoutNewStateIsRefused) {
  // A build of the same version that saved less state (a part added since, such as the tank's jet
  // observers) is refused with the part it lacks named, and the checkpoint is kept for that build.
  useTestCache();
  ScratchDir dir;
  const fs::path path = dir / "run.h5";
  stopAt(tension(), path, 60);
  const std::string checkpoint = io::checkpointPathFor(path.string());
  const std::string part = "/checkpoint/state/bonded_system/damage";
  {
    io::Hdf5File file = io::Hdf5File::openReadWrite(checkpoint);
    ASSERT_TRUE(file.exists(part));
    file.remove(part);
  }
  const std::string why = refusal(tension(), path);
  EXPECT_NE(why.find("the checkpoint lacks " + part), std::string::npos) << why;
  EXPECT_TRUE(fs::exists(checkpoint));
}

TEST(CheckpointIdentity, IntervalCheckpointsAndNoneAtZero) {
  useTestCache();
  ScratchDir dir;
  nlohmann::json spec = tension();
  spec["loading"]["strain_rate"] = 2e6;  // long enough for several checkpoints
  {  // every 0.2 s of wall time: a checkpoint while it runs, removed when it completes
    RunControl control;
    control.checkpointInterval = 0.2;
    std::atomic<std::int64_t> seen{-1};
    control.log = [&](const std::string& text) {
      if (text.rfind("checkpoint at step", 0) == 0) seen.store(control.checkpointStep.load());
    };
    EXPECT_TRUE(runSpec(spec, (dir / "interval.h5").string(), control, 1).completed);
    EXPECT_GT(seen.load(), 0) << "no checkpoint was written during the run";
    EXPECT_GT(control.checkpointBytes.load(), 0.0);
    EXPECT_FALSE(fs::exists(io::checkpointPathFor((dir / "interval.h5").string())));
  }
  {  // 0: none, not even when stopped to be continued
    spec["run"]["checkpoint_interval_s"] = 0;
    RunControl control;
    control.checkpointOnCancel = true;
    control.log = [&](const std::string& text) {
      if (text.rfind("main run", 0) == 0) control.cancel = true;
    };
    EXPECT_FALSE(runSpec(spec, (dir / "none.h5").string(), control, 1).completed);
    EXPECT_EQ(control.checkpointStep.load(), -1);
    EXPECT_FALSE(fs::exists(io::checkpointPathFor((dir / "none.h5").string())));
  }
}

}  // namespace
}  // namespace rupture::test
