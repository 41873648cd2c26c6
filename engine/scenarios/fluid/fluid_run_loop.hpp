#pragma once
// The time loop both SPH scenarios share: steps an SphSystem to run.end_time with the fixed or
// the Monaghan–Kos time step, records a series row every output interval (and the last state),
// snapshots at the requested times, checks cancel every step and reports progress.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "sph/fluid_recorder.hpp"
#include "sph/fluid_spec.hpp"
#include "io/result_file.hpp"
#include "rupture/run.hpp"
#include "scenarios/fluid/fluid_results.hpp"
#include "scenarios/run_checkpoints.hpp"
#include "scenarios/run_support.hpp"
#include "sph/sph_system.hpp"

namespace rupture {

struct FluidLoopOutcome {
  std::string stopReason;  ///< end_time, max_steps or cancelled
  double minTimeStep = std::numeric_limits<double>::infinity(), maxTimeStep = 0;  ///< s
};

/// The checkpoints of a fluid loop: the scenario's own state (`state`: its recorder, observers and
/// structure; the loop adds the SPH system and its own counters) and the result file they copy.
struct FluidLoopCheckpoints {
  RunCheckpoints& checkpoints;
  io::ResultFile& result;
  RunCheckpoints::State state;
};

/// row(): append one series row from the current state; snapshot(trigger): write a snapshot;
/// afterStep(dt): observe every step (peaks between rows); advance(dt): the step itself (the
/// fluid's own, or a coupled step that also moves a structure). A resumed run restores the state
/// from the checkpoint instead of taking the first row.
template <class Row, class Snapshot, class AfterStep, class Advance>
FluidLoopOutcome runFluidLoop(sph::SphSystem& s, const io::FluidRunSpec& run, RunControl& control,
                              const FluidLoopCheckpoints& saved, Row&& row, Snapshot&& snapshot, AfterStep&& afterStep,
                              Advance&& advance) {
  using Clock = std::chrono::steady_clock;
  FluidLoopOutcome out;
  const double interval = run.outputIntervalOrDefault();
  std::size_t nextSnapshot = 0, lastRowStep = 0;
  double nextOutput = interval;
  saved.checkpoints.attach(saved.result, [&](StateArchive& a) {
    s.exchangeState(a);
    saved.state(a);
    StateGroup loop(a, "loop");
    a.value("next_snapshot", nextSnapshot);
    a.value("last_row_step", lastRowStep);
    a.value("next_output", nextOutput);
    a.value("min_time_step", out.minTimeStep);
    a.value("max_time_step", out.maxTimeStep);
  });
  auto snapshotsDue = [&] {  // one snapshot per step even if it crosses several requested times
    if (nextSnapshot >= run.snapshotTimes.size() || s.time < run.snapshotTimes[nextSnapshot] * (1 - 1e-12)) return;
    snapshot("time " + formatNumber(run.snapshotTimes[nextSnapshot]));
    while (nextSnapshot < run.snapshotTimes.size() && s.time >= run.snapshotTimes[nextSnapshot] * (1 - 1e-12)) ++nextSnapshot;
  };
  // List builds and snapshots poll the cancel flag between their passes; a run stopped to be
  // continued ends its step instead, and the poll below checkpoints it.
  s.cancel = Cancellation(&control.cancel, &control.checkpointOnCancel);
  if (saved.checkpoints.resuming()) {
    saved.checkpoints.restore();
  } else {
    row();
    lastRowStep = s.steps;
    try {
      snapshotsDue();
    } catch (const RunCancelled&) {
      out.stopReason = "cancelled";
      return out;
    }
  }
  // Where the run is, for the watcher's status line: the fluid's kinetic energy as its headline.
  auto publishStatus = [&] {
    RunStatus now;
    now.step = static_cast<std::int64_t>(s.steps);
    now.time = s.time;
    now.headlineName = "kinetic energy";
    now.headlineUnit = s.model.dimension == 2 ? "J/m" : "J";
    now.headline = s.kineticEnergy();
    now.particles = static_cast<double>(s.particles.size());
    reportStatus(control, now);
  };
  enterPhase(control, kSteppingPhase);
  auto lastReport = Clock::now();
  while (true) {
    if (saved.checkpoints.poll(s.steps, s.time) == RunCheckpoints::Action::Stop) {
      out.stopReason = "cancelled";
      break;
    }
    if (s.time >= run.endTime * (1 - 1e-12)) { out.stopReason = "end_time"; break; }
    if (static_cast<std::int64_t>(s.steps) >= run.maxSteps) { out.stopReason = "max_steps"; break; }
    double dt = run.timeStep ? *run.timeStep : s.stableTimeStep(run.cfl);
    // Land on end_time without a sliver of a last step.
    const double left = run.endTime - s.time;
    if (dt > left) dt = left;
    else if (dt > 0.5 * left) dt = 0.5 * left;
    try {
      advance(dt);
    } catch (const RunCancelled&) {
      // Stopped inside a step (a list build of millions of particles): the state is half a step
      // on and not for use, so no last row is taken from it.
      out.stopReason = "cancelled";
      return out;
    }
    out.minTimeStep = std::min(out.minTimeStep, dt);
    out.maxTimeStep = std::max(out.maxTimeStep, dt);
    afterStep(dt);
    if (s.time >= nextOutput * (1 - 1e-12)) {
      row();
      lastRowStep = s.steps;
      nextOutput = nextOutputTime(nextOutput, s.time * (1 + 1e-12), interval);
    }
    try {
      snapshotsDue();
    } catch (const RunCancelled&) {  // between a snapshot's datasets: the state itself is whole
      out.stopReason = "cancelled";
      return out;
    }
    if ((s.steps & 15) == 0 && Clock::now() - lastReport > std::chrono::milliseconds(100)) {
      lastReport = Clock::now();
      // The run ends at end_time or max_steps, whichever comes first.
      reportProgress(control, std::max(s.time / run.endTime,
                                        static_cast<double>(s.steps) / static_cast<double>(run.maxSteps)));
      publishStatus();
    }
  }
  if (lastRowStep != s.steps) row();  // the last state is always a row
  publishStatus();
  return out;
}

template <class Row, class Snapshot, class AfterStep>
FluidLoopOutcome runFluidLoop(sph::SphSystem& s, const io::FluidRunSpec& run, RunControl& control,
                              const FluidLoopCheckpoints& saved, Row&& row, Snapshot&& snapshot, AfterStep&& afterStep) {
  return runFluidLoop(s, run, control, saved, row, snapshot, afterStep, [&](double dt) { s.step(dt); });
}

/// The set-up of an SPH run (progress 0), with the system polling control.cancel: `setup()`
/// places particles, walls and bodies (and whatever else the scenario builds), then the first lists
/// and rates are built (SphSystem::initialise). Returns the set-up's value, or nullopt when it was
/// cancelled, after writing a file that holds the spec and a summary saying so (marked incomplete)
/// and setting `cancelled` to the outcome to return.
template <class Setup>
auto setUpFluidRun(sph::SphSystem& s, RunControl& control, const std::string& resultPath, const std::string& scenario,
                   const nlohmann::json& resolvedSpec, const nlohmann::json& inputSpec,
                   std::chrono::steady_clock::time_point wallStart, RunOutcome& cancelled, Setup&& setup)
    -> std::optional<decltype(setup())> {
  control.progress.store(0.0);
  s.cancel = &control.cancel;
  try {
    auto built = setup();
    s.initialise();
    return built;
  } catch (const RunCancelled&) {
    io::ResultFile result(resultPath, scenario);
    cancelled = cancelledBeforeStart(result, resolvedSpec, inputSpec, nlohmann::json::object(),
                                     {{"completed", "1"}, {"stop_reason", ""}, {"wall_time_s", "s"}}, "setting up",
                                     control, wallStart);
    return std::nullopt;
  }
}

/// The fluid particles of `s` (its walls and bodies not counted).
inline std::size_t fluidParticleCount(const sph::SphSystem& s) {
  return static_cast<std::size_t>(std::count(s.particles.body.begin(), s.particles.body.end(), sph::kFluid));
}

/// A fluid scenario's recorder: its declared `series` columns in `dimension` and one pressure
/// column per probe point.
inline io::FluidRecorder openFluidRecorder(const std::string& resultPath, const std::string& scenario,
                                           const ResultFields& series, int dimension,
                                           const std::vector<std::array<double, 3>>& probes,
                                           const std::string& continueFrom = "") {
  std::vector<std::string> positions;
  for (const auto& point : io::probesJson(probes, dimension)) positions.push_back(point.dump());
  return io::FluidRecorder(resultPath, scenario, seriesColumns(series, dimension), std::move(positions), continueFrom);
}

/// What a fluid run tracked while it ran, for the summary every SPH scenario reports.
struct FluidRunTotals {
  double initialFluidMass = 0;   ///< kg (kg/m in 2D)
  double maxDensityError = 0;    ///< max over fluid particles and rows of |ρ/ρ0 − 1|
  std::int64_t outsideMax = 0;   ///< most fluid particles outside the container at once
  std::size_t fluidParticles = 0;
  double soundSpeed = 0;         ///< c0 (m/s)
};

/// Adds the scalars every SPH run reports (completion, stop reason, mass and density errors,
/// particles outside, steps and time steps, counts, c0, h, list builds, wall time) to the
/// scenario's own, writes /summary (units from the scenario's `declared` fields in `dimension`),
/// finishes the file, removes the checkpoint of a completed run and tells the watcher.
inline RunOutcome finishFluidRun(io::FluidRecorder& recorder, const sph::SphSystem& s, const FluidLoopOutcome& loop,
                                 const FluidRunTotals& totals, nlohmann::json summary,
                                 const ResultFields& declared, int dimension, RunControl& control,
                                 std::chrono::steady_clock::time_point wallStart, RunCheckpoints& checkpoints) {
  const bool completed = loop.stopReason != "cancelled";
  auto nullUnless = [](bool known, double v) { return known ? nlohmann::json(v) : nlohmann::json(nullptr); };
  summary.update(nlohmann::json{
      {"completed", completed ? 1 : 0},
      {"stop_reason", loop.stopReason},
      {"mass_error", (s.fluidMass() - totals.initialFluidMass) / totals.initialFluidMass},
      {"max_density_error", totals.maxDensityError},
      {"particles_outside_max", totals.outsideMax},
      {"final_time", s.time},
      {"steps", static_cast<std::int64_t>(s.steps)},
      {"time_step_min", nullUnless(std::isfinite(loop.minTimeStep), loop.minTimeStep)},
      {"time_step_max", nullUnless(loop.maxTimeStep > 0, loop.maxTimeStep)},
      {"particles", static_cast<std::int64_t>(s.particles.size())},
      {"fluid_particles", static_cast<std::int64_t>(totals.fluidParticles)},
      {"sound_speed", totals.soundSpeed},
      {"smoothing_length", s.model.h()},
      {"neighbour_list_builds", static_cast<std::int64_t>(s.listBuilds())},
      {"wall_time_s", std::chrono::duration<double>(std::chrono::steady_clock::now() - wallStart).count()}});
  RunOutcome outcome = finishRun(recorder, summary, unitMap(declared, dimension), completed, loop.stopReason, control);
  checkpoints.finished(completed);
  return outcome;
}

}  // namespace rupture
