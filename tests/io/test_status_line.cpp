// The status line and the timing breakdown, as a reader of a log sees them (io/status_line.hpp).
#include <gtest/gtest.h>

#include "io/status_line.hpp"

namespace rupture::io {
namespace {

RunStatus tensionAt(std::int64_t step, double time) {
  RunStatus s;
  s.step = step;
  s.time = time;
  s.strain = 1e6 * time;
  s.headlineName = "mean stress";
  s.headlineUnit = "Pa";
  s.headline = 5.84e7;
  s.brokenBonds = 120;
  s.particles = 1600;
  return s;
}

TEST(StatusLine, EveryFieldInEngineeringUnitsAndTheSpeedSinceThePreviousLine) {
  StatusLine line;
  line.observe(tensionAt(0, 0.0), 0.5);  // stepping starts: the speed counts from here
  line.observe(tensionAt(5000, 1.0e-9), 1.5);
  EXPECT_EQ(line.line(0.41, 17.2),
            "elapsed 1.5 s | 41 % | ETA 17.2 s | step 5000 | time 1 ns | strain 0.001 | mean stress 58.4 MPa | "
            "broken bonds 120 | 5000 steps/s | 8e6 particle-steps/s");
  line.observe(tensionAt(6000, 1.2e-9), 3.5);  // 1000 steps in 2 s since the previous line
  EXPECT_NE(line.line(0.5, -1).find("ETA unknown | step 6000 | time 1.2 ns | strain 0.0012 |"), std::string::npos);
  line.observe(tensionAt(6000, 1.2e-9), 4.5);
  EXPECT_NE(line.line(0.5, -1).find("| 0 steps/s |"), std::string::npos) << "a stalled run says so";
}

TEST(StatusLine, AFieldTheScenarioDoesNotHaveIsLeftOut) {
  StatusLine line;
  RunStatus fluid;
  fluid.step = 10;
  fluid.time = 0.25;
  line.observe(fluid, 2.0);
  EXPECT_EQ(line.line(0.25, -1), "elapsed 2 s | 25 % | ETA unknown | step 10 | time 250 ms");
  StatusLine building;
  building.observe(RunStatus{}, 0.3);  // nothing stepped yet: the sample is being built
  EXPECT_EQ(building.line(0.0, -1), "elapsed 300 ms | 0 % | ETA unknown");
}

TEST(TimingBreakdown, EachPhaseItsShareThenTheStepsAndTheSpeedOfTheStepping) {
  const std::vector<RunPhases::Phase> phases = {
      {"building the sample", 1.0}, {std::string(kSteppingPhase), 8.0}, {"writing checkpoints", 0.5},
      {"writing the result", 0.5}};
  const std::vector<std::string> lines = timingBreakdown(phases, tensionAt(16000, 2e-9), 10.0, 0);
  ASSERT_EQ(lines.size(), 5u);
  EXPECT_EQ(lines[0], "timing: building the sample 1 s (10 %)");
  EXPECT_EQ(lines[1], "timing: time stepping 8 s (80 %)");
  EXPECT_EQ(lines[2], "timing: writing checkpoints 500 ms (5 %)");
  EXPECT_EQ(lines[4], "timing: total 10 s | 16000 steps | 2000 steps/s | 3.2e6 particle-steps/s");
  // A resumed run counts the steps it took itself.
  EXPECT_EQ(timingBreakdown(phases, tensionAt(16000, 2e-9), 10.0, 12000).back(),
            "timing: total 10 s | 4000 steps | 500 steps/s | 8e5 particle-steps/s");
}

TEST(RunPhases, InTheOrderFirstEnteredWithAReturnAddingToItsLine) {
  RunPhases phases;
  phases.enter("building the sample");
  phases.enter(kSteppingPhase);
  phases.charge("writing snapshots", 0.0);
  phases.enter("building the sample");
  phases.finish();
  const auto totals = phases.totals();
  ASSERT_EQ(totals.size(), 3u);
  EXPECT_EQ(totals[0].name, "building the sample");
  EXPECT_EQ(totals[1].name, kSteppingPhase);
  EXPECT_EQ(totals[2].name, "writing snapshots");
}

}  // namespace
}  // namespace rupture::io
