#include "tank_impact_benchmark.hpp"

#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "rupture/run.hpp"
#include "scenarios/tank_impact/tank_impact_spec.hpp"

namespace rupture::bench {
namespace {

nlohmann::json readSpec(const std::string& path, const std::string& workload) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("bench " + workload + ": cannot read " + path);
  return nlohmann::json::parse(in);
}

/// Runs `spec` into a temporary file, removed with its checkpoint afterwards.
RunOutcome runInTemporaryFile(const nlohmann::json& spec, RunControl& control, int threads) {
  const std::filesystem::path out =
      std::filesystem::temp_directory_path() / ("rupture-bench-tank-" + std::to_string(::getpid()) + ".h5");
  RunOutcome outcome = runSpec(spec, out.string(), control, threads);
  std::filesystem::remove(out);
  std::filesystem::remove(out.string() + ".checkpoint");
  return outcome;
}

}  // namespace

nlohmann::json runTankImpactBenchmark(const TankImpactOptions& options) {
  const std::string path =
      options.spec.empty() ? std::string(RUPTURE_SOURCE_DIR) + "/examples/tank-impact-FXA5-coarse.json" : options.spec;
  nlohmann::json spec = readSpec(path, "TANK");
  // A long end time and max_steps: the run stops after `steps` fluid steps.
  // It stops at `steps` with a checkpoint, as a run stopped to be continued: the whole cost of one.
  spec["run"]["max_steps"] = options.steps + 1;
  spec["run"]["end_time"] = 0.01;
  spec["run"].erase("snapshot_times");
  RunControl control;
  control.stopAtStep = options.steps;
  const RunOutcome outcome = runInTemporaryFile(spec, control, options.threads);
  const nlohmann::json& s = outcome.summary;
  const double steps = s["steps"].get<double>(), shellSteps = s["shell_steps"].get<double>();
  const double fluidParticles = s["particles"].get<double>(), nodes = s["plate_nodes"].get<double>();
  const double fluidSeconds = s["fluid_time_s"], shellSeconds = s["shell_time_s"], contactSeconds = s["contact_time_s"];
  return {{"workload", "TANK (tank-impact FXA5)"},
          {"spec", path},
          {"threads", options.threads},
          {"fluid_particles", s["fluid_particles"]},
          {"sph_particles", fluidParticles},
          {"plate_nodes", nodes},
          {"steps", steps},
          {"shell_steps", shellSteps},
          {"simulated_time_s", s["final_time"]},
          {"fluid_seconds", fluidSeconds},
          {"shell_seconds", shellSeconds},
          {"contact_seconds", contactSeconds},
          {"fluid_particle_steps_per_s", fluidParticles * steps / fluidSeconds},
          {"shell_node_steps_per_s", nodes * shellSteps / shellSeconds},
          {"contact_particle_steps_per_s", fluidParticles * steps / contactSeconds},
          {"checkpoint_bytes", control.checkpointBytes.load()},
          {"checkpoint_seconds", control.checkpointSeconds.load()},
          {"checkpoint_overhead_at_300_s", control.checkpointSeconds.load() / 300.0}};
}

nlohmann::json runTankSeedBenchmark(const TankSeedOptions& options) {
  // The example is the seed's inputs: fluid 2 mm (§4.2), 0.5 mm at the step where it tears (§5.3.1).
  nlohmann::json spec = readSpec(std::string(RUPTURE_SOURCE_DIR) + "/examples/tank-impact-TF14A5.json", "TANK-SEED");
  spec["run"]["end_time"] = options.endTime;
  spec["run"].erase("snapshot_times");
  if (options.subcycling >= 0) spec["plate"]["subcycling"] = options.subcycling == 1;
  if (!options.stepEstimate.empty()) spec["plate"]["step_estimate"] = options.stepEstimate;
  const ShellParameters shell = parseTankImpactSpec(spec).plate.shell;  // the options as the run reads them
  RunControl control;
  const auto start = std::chrono::steady_clock::now();
  const RunOutcome outcome = runInTemporaryFile(spec, control, options.threads);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const nlohmann::json& s = outcome.summary;
  const double steps = s["steps"].get<double>(), fineSteps = s["shell_steps"].get<double>();
  const double particles = s["particles"].get<double>(), nodes = s["plate_nodes"].get<double>();
  const double shellSeconds = s["shell_time_s"].get<double>(), fluidSeconds = s["fluid_time_s"].get<double>();
  return {{"workload", "TANK-SEED (tank-impact TF14A5 at the seed's inputs)"},
          {"threads", options.threads},
          {"subcycling", shell.subcycling},
          {"step_estimate", stepEstimateName(shell.stepEstimate)},
          {"end_time_s", options.endTime},
          {"sph_particles", particles},
          {"plate_nodes", nodes},
          {"fluid_steps", steps},
          {"shell_fine_steps", fineSteps},
          {"shell_fine_steps_per_fluid_step", fineSteps / steps},
          {"shell_coarsest_class", s["shell_coarsest_class"]},
          {"shell_points_per_class", s["shell_points_per_class"]},
          {"shell_point_evaluations", s["shell_point_evaluations"]},
          {"wall_seconds", wall},
          {"fluid_seconds", fluidSeconds},
          {"shell_seconds", shellSeconds},
          {"contact_seconds", s["contact_time_s"]},
          {"shell_profile_s",
           {{"gradients", s["shell_gradients_time_s"]}, {"layers", s["shell_layers_time_s"]},
            {"forces", s["shell_forces_time_s"]}, {"integration", s["shell_integration_time_s"]},
            {"fracture", s["shell_fracture_time_s"]}, {"spectrum", s["shell_spectrum_time_s"]}}},
          {"shell_spectrum_measurements", s["shell_spectrum_measurements"]},
          {"shell_max_frequency_rad_s", s["shell_max_frequency"]},
          {"fluid_particle_steps_per_s", particles * steps / fluidSeconds},
          {"shell_node_updates_per_s", nodes * fineSteps / shellSeconds},
          {"shell_point_evaluations_per_s", s["shell_point_evaluations"].get<double>() / shellSeconds},
          {"time_to_fracture_s", s["time_to_fracture"]},
          {"fracture_radius_m", s["fracture_radius"]},
          {"first_pressure_peak_pa", s["first_pressure_peak"]},
          {"fractured_nodes", s["fractured_nodes"]},
          {"rim_torn_fraction", s["rim_torn_fraction"]}};
}

}  // namespace rupture::bench
