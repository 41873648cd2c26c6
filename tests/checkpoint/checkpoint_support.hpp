#pragma once
// Interrupt-and-resume runs for the checkpoint tests: a spec run without a stop, then the same spec
// stopped at random steps (RunControl::stopAtStep writes a checkpoint there) and resumed from each
// checkpoint until it completes; the two result files must hold the same datasets and attributes
// bit for bit, but for what a run records about how it ran (wall times, cache hits, the resumes).
#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <random>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "io/checkpoint_file.hpp"
#include "io/hdf5_file.hpp"
#include "rupture/run.hpp"
#include "support/hdf5_compare.hpp"
#include "support/test_support.hpp"

namespace rupture::test {

namespace fs = std::filesystem;

/// `count` distinct steps in [1, steps − 1], drawn afresh at every test run (printed on failure).
inline std::vector<std::int64_t> randomStops(std::int64_t steps, int count) {
  std::random_device device;
  std::mt19937_64 random(device());
  std::uniform_int_distribution<std::int64_t> pick(1, std::max<std::int64_t>(1, steps - 1));
  std::set<std::int64_t> stops;
  for (int attempt = 0; static_cast<int>(stops.size()) < count && attempt < 100; ++attempt) stops.insert(pick(random));
  return {stops.begin(), stops.end()};
}

/// Runs `spec` to `dir/whole.h5`, then to `dir/resumed.h5` stopped at `stops` random steps and
/// resumed after each; expects the two files to agree. Returns the uninterrupted run's summary.
inline nlohmann::json expectResumedRunMatches(const nlohmann::json& spec, const fs::path& dir, int stops = 2,
                                              int threads = 1) {
  const fs::path whole = dir / "whole.h5", resumed = dir / "resumed.h5";
  RunControl plain;
  const RunOutcome reference = runSpec(spec, whole.string(), plain, threads);
  EXPECT_TRUE(reference.completed);
  EXPECT_FALSE(fs::exists(io::checkpointPathFor(whole.string()))) << "a completed run removes its checkpoint";
  const std::int64_t steps = reference.summary.value("steps", std::int64_t{0});
  EXPECT_GT(steps, 2) << "the run must take steps to be interrupted";
  const std::vector<std::int64_t> at = randomStops(steps, stops);
  std::string trace = "stopped at steps";
  for (std::int64_t s : at) trace.append(1, ' ').append(std::to_string(s));
  SCOPED_TRACE(trace + " of " + std::to_string(steps));

  for (std::size_t k = 0; k <= at.size(); ++k) {
    RunControl control;
    control.resume = k > 0;
    control.stopAtStep = k < at.size() ? at[k] : -1;
    const RunOutcome outcome = runSpec(spec, resumed.string(), control, threads);
    if (k < at.size()) {
      EXPECT_FALSE(outcome.completed) << "stop " << k;
      EXPECT_EQ(control.checkpointStep.load(), at[k]);
      EXPECT_TRUE(fs::exists(io::checkpointPathFor(resumed.string())));
    } else {
      EXPECT_TRUE(outcome.completed);
      EXPECT_FALSE(fs::exists(io::checkpointPathFor(resumed.string())));
    }
    if (k > 0) {
      EXPECT_EQ(control.resumedFromStep.load(), at[k - 1]);
    }
  }
  EXPECT_EQ(rupture::testing::hdf5Differences(whole.string(), resumed.string(), rupture::testing::howARunRan()), "");
  const io::Hdf5File file = io::Hdf5File::openReadOnly(resumed.string());
  EXPECT_EQ(file.readAttributeInt("/", "checkpoint_resumes"), static_cast<std::int64_t>(at.size()));
  EXPECT_EQ(file.readAttributeInt("/", "completed"), 1);
  return reference.summary;
}

}  // namespace rupture::test
