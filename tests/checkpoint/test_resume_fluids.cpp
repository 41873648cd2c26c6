// The SPH scenarios stopped at random steps and resumed (dam-break in 2D and 3D, piston-column with
// a free and a prescribed piston, tank-impact with its plate, contact and cracks): the result file
// equals an uninterrupted run's, bit for bit. The particles are re-sorted every few list builds,
// so the stops fall between re-sorts and on them alike.
#include <chrono>
#include <filesystem>
#include <fstream>
#include <random>
#include <thread>

#include <gtest/gtest.h>

#include "checkpoint/checkpoint_support.hpp"

namespace rupture::test {
namespace {

nlohmann::json damBreak(int dimension) {
  nlohmann::json geometry = {{"column_width", 0.057}, {"column_height", 0.114}, {"tank_length", 0.2}, {"tank_height", 0.15}};
  if (dimension == 3) geometry["width"] = 0.03;
  return {{"scenario", "dam-break"},
          {"dimension", dimension},
          {"geometry", geometry},
          {"resolution", {{"spacing", dimension == 3 ? 0.006 : 0.003}}},
          {"probes", {dimension == 3 ? nlohmann::json{0.2, 0.015, 0.005} : nlohmann::json{0.2, 0.005}}},
          {"run", {{"end_time", 0.06}, {"snapshot_times", {0.0, 0.03}}}}};
}

TEST(ResumeFluids, DamBreak2d) {
  rupture::testing::ScratchDir dir;
  expectResumedRunMatches(damBreak(2), dir.path(), 3);
}

TEST(ResumeFluids, DamBreak3d) {
  rupture::testing::ScratchDir dir;
  expectResumedRunMatches(damBreak(3), dir.path());
}

// A stop to be continued (a server's SIGTERM) that lands inside a step, a list build or a snapshot
// lets the step end whole and checkpoints it, rather than losing the step's work and the checkpoint.
TEST(ResumeFluids, AStopFromAnotherThreadLandingMidStepStillCheckpoints) {
  nlohmann::json spec = damBreak(3);
  spec["run"]["end_time"] = 0.3;
  rupture::testing::ScratchDir dir;
  const std::string whole = (dir / "whole.h5").string(), stopped = (dir / "stopped.h5").string();
  RunControl plain;
  ASSERT_TRUE(runSpec(spec, whole, plain, 1).completed);
  std::random_device device;
  const int delayMs = std::uniform_int_distribution<int>(200, 900)(device);
  SCOPED_TRACE("stopped after " + std::to_string(delayMs) + " ms");
  RunControl control;
  std::thread stopper([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(delayMs));
    control.checkpointOnCancel = true;  // as the server's requestStop does
    control.cancel = true;
  });
  const RunOutcome outcome = runSpec(spec, stopped, control, 1);
  stopper.join();
  ASSERT_FALSE(outcome.completed) << "the run ended before the stop: lengthen it";
  ASSERT_GE(control.checkpointStep.load(), 0) << "stopped without a checkpoint";
  RunControl resume;
  resume.resume = true;
  ASSERT_TRUE(runSpec(spec, stopped, resume, 1).completed);
  EXPECT_EQ(rupture::testing::hdf5Differences(whole, stopped, rupture::testing::howARunRan()), "");
}

nlohmann::json pistonColumn(const nlohmann::json& piston) {
  return {{"scenario", "piston-column"},
          {"dimension", 2},
          {"geometry", {{"diameter", 0.08}, {"column_height", 0.2}}},
          {"resolution", {{"spacing", 0.004}}},
          {"fluid", {{"sound_speed", 100.0}}},
          {"piston", piston},
          {"probes", {{0.0, 0.1}}},
          {"run", {{"end_time", 4e-3}}}};
}

TEST(ResumeFluids, PistonColumnFreePiston) {
  rupture::testing::ScratchDir dir;
  expectResumedRunMatches(pistonColumn({{"motion", "free"}, {"mass", 5.0}, {"speed", 2.0}}), dir.path());
}

TEST(ResumeFluids, PistonColumnPrescribedPiston) {
  rupture::testing::ScratchDir dir;
  expectResumedRunMatches(
      pistonColumn({{"motion", "prescribed"}, {"speed_history", {{"time", {0.0, 1e-3}}, {"speed", {0.0, 2.0}}}}}),
      dir.path());
}

// The impactor's column (carriage, piston points, face force) is part of the state.
TEST(ResumeFluids, PistonColumnStruckThroughAnElasticPiston) {
  nlohmann::json spec = pistonColumn(nullptr);
  spec.erase("piston");
  spec["dimension"] = 3;
  spec["resolution"]["spacing"] = 0.008;
  spec["probes"] = {{0.0, 0.0, 0.1}};
  spec["impactor"] = {{"mass", 5.0}, {"speed", 2.0}, {"piston", {{"length", 0.05}, {"elements", 10}}}};
  rupture::testing::ScratchDir dir;
  const nlohmann::json summary = expectResumedRunMatches(spec, dir.path());
  EXPECT_EQ(summary.value("impactor_model", std::string()), "elastic_piston");
}

TEST(ResumeFluids, TankImpactWithPlateContactAndCracks) {
  std::ifstream in(std::filesystem::path(RUPTURE_SOURCE_DIR) / "examples" / "tank-impact-FUA5.json");
  nlohmann::json spec = nlohmann::json::parse(in);
  spec["resolution"]["spacing"] = 0.008;  // coarse: the state, not the physics, is under test
  spec["plate"]["spacing"] = 0.005;
  spec["run"]["end_time"] = 6e-4;
  spec["run"].erase("snapshot_times");
  rupture::testing::ScratchDir dir;
  const nlohmann::json summary = expectResumedRunMatches(spec, dir.path());
  EXPECT_GT(summary.value("shell_steps", std::int64_t{0}), 0);
  // The measured step estimate: its steps and frequencies are part of the state.
  spec["plate"]["step_estimate"] = "spectral";
  rupture::testing::ScratchDir spectralDir;
  const nlohmann::json spectral = expectResumedRunMatches(spec, spectralDir.path());
  EXPECT_GT(spectral.value("shell_spectrum_measurements", std::int64_t{0}), 0);
}

}  // namespace
}  // namespace rupture::test
