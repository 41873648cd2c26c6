#include "tank_impact_benchmark.hpp"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "rupture/run.hpp"

namespace rupture::bench {

nlohmann::json runTankImpactBenchmark(const TankImpactOptions& options) {
  const std::string path =
      options.spec.empty() ? std::string(RUPTURE_SOURCE_DIR) + "/examples/tank-impact-FXA5.json" : options.spec;
  std::ifstream in(path);
  if (!in) throw std::runtime_error("bench TANK: cannot read " + path);
  nlohmann::json spec = nlohmann::json::parse(in);
  // A long end time and max_steps: the run stops after `steps` fluid steps.
  // It stops at `steps` with a checkpoint, as a run stopped to be continued: the whole cost of one.
  spec["run"]["max_steps"] = options.steps + 1;
  spec["run"]["end_time"] = 0.01;
  spec["run"].erase("snapshot_times");
  const std::filesystem::path out =
      std::filesystem::temp_directory_path() / ("rupture-bench-tank-" + std::to_string(::getpid()) + ".h5");
  RunControl control;
  control.stopAtStep = options.steps;
  const RunOutcome outcome = runSpec(spec, out.string(), control, options.threads);
  std::filesystem::remove(out);
  std::filesystem::remove(out.string() + ".checkpoint");
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

}  // namespace rupture::bench
