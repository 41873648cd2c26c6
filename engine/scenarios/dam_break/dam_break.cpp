// The dam-break scenario (Martin & Moyce 1952; Koshizuka & Oka 1996): a water column of width a
// and height H at the back of a tank is released under gravity. Weakly compressible SPH with
// Adami dummy-particle walls (engine/sph/README.md); contract and file layout in docs/sph.md.
#include <algorithm>
#include <chrono>
#include <cmath>

#include "scenarios/scenario_previews.hpp"
#include "sph/fluid_recorder.hpp"
#include "scenarios/dam_break/dam_break_lattice.hpp"
#include "scenarios/fluid/fluid_results.hpp"
#include "scenarios/fluid/fluid_run_loop.hpp"
#include "scenarios/run_support.hpp"
#include "scenarios/scenario.hpp"

namespace rupture {

namespace {

RunOutcome runDamBreak(const DamBreakSpec& spec, const nlohmann::json& json, const std::string& resultPath,
                       RunControl& control) {
  auto wallStart = std::chrono::steady_clock::now();
  RunCheckpoints checkpoints(control, resultPath, "dam-break", json, spec.run.checkpointInterval, wallStart);
  const int dim = spec.dimension;
  sph::SphSystem s;
  RunOutcome cancelled;
  const std::optional<DamBreakLattice> built = setUpFluidRun(
      s, control, resultPath, "dam-break", toJson(spec), json, wallStart, cancelled, [&] { return buildDamBreak(s, spec); });
  if (!built) return cancelled;
  const DamBreakLattice& g = *built;
  const std::size_t fluidCount = fluidParticleCount(s);
  logStage(control, "dam break: " + std::to_string(fluidCount) + " fluid and " +
                        std::to_string(s.particles.size() - fluidCount) + " wall particles, c0 " +
                        formatNumber(spec.soundSpeed) + " m/s");

  io::FluidRecorder recorder = openFluidRecorder(resultPath, "dam-break", damBreakSeriesFields(), dim, spec.probes,
                                                 checkpoints.continueFrom());
  if (!checkpoints.resuming()) recorder.writeSpec(toJson(spec), json);
  if (!checkpoints.resuming()) recorder.writeAttributes("/geometry",
                           {{"column_width", g.a()}, {"column_height", g.H()}, {"tank_length", g.L()},
                            {"tank_height", g.T()}, {"width", dim == 3 ? nlohmann::json(g.W()) : nlohmann::json(nullptr)},
                            {"spacing", g.dx}, {"smoothing_length", s.model.h()}, {"wall_layers", spec.resolution.wallLayers},
                            {"vertical_axis", dim == 3 ? "z" : "y"}},
                           {{"column_width", "m"}, {"column_height", "m"}, {"tank_length", "m"}, {"tank_height", "m"},
                            {"width", "m"}, {"spacing", "m"}, {"smoothing_length", "m"}, {"wall_layers", "1"}});

  const double mass0 = s.fluidMass(), rho0 = s.model.eos.referenceDensity;
  const double potential0 = s.potentialEnergy();
  double peakPressure = 0, maxDensityError = 0;
  std::int64_t outsideMax = 0;
  std::vector<double> probes(spec.probes.size());
  double lastStep = 0;
  auto row = [&] {
    const sph::FluidParticles& p = s.particles;
    double front = -1e300, densityError = 0;
    std::int64_t outside = 0;
    for (std::size_t k = 0; k < p.size(); ++k) {
      if (!p.isFluid(k)) continue;
      front = std::max(front, p.x[k]);
      densityError = std::max(densityError, std::fabs(p.rho[k] / rho0 - 1.0));
      const double v = dim == 3 ? p.z[k] : p.y[k];
      const bool in = p.x[k] >= 0 && p.x[k] <= g.L() && v >= 0 && v <= g.T() && (dim == 2 || (p.y[k] >= 0 && p.y[k] <= g.W()));
      outside += in ? 0 : 1;
    }
    for (std::size_t k = 0; k < probes.size(); ++k) {
      probes[k] = s.probePressure(spec.probes[k][0], spec.probes[k][1], spec.probes[k][2]);
      peakPressure = std::max(peakPressure, probes[k]);
    }
    maxDensityError = std::max(maxDensityError, densityError);
    outsideMax = std::max(outsideMax, outside);
    // The front: the foremost particle centre plus half a spacing (the particle's extent), so it
    // starts at exactly a.
    recorder.appendRow({s.time, front + 0.5 * g.dx, s.fluidMass(), s.kineticEnergy(), s.potentialEnergy(),
                        densityError, static_cast<double>(outside), lastStep},
                       probes);
  };
  auto snapshot = [&](const std::string& trigger) { recorder.writeSnapshot(s, trigger); };
  auto state = [&](StateArchive& a) {
    recorder.exchangeState(a);
    StateGroup observed(a, "observed");
    a.value("peak_pressure", peakPressure), a.value("max_density_error", maxDensityError);
    a.value("outside_max", outsideMax), a.value("last_step", lastStep);
  };
  const FluidLoopOutcome loop = runFluidLoop(s, spec.run, control, {checkpoints, recorder.result(), state}, row,
                                             snapshot, [&](double dt) { lastStep = dt; });
  recorder.writeSnapshot(s, "final");

  double front = -1e300;
  for (std::size_t k = 0; k < s.particles.size(); ++k)
    if (s.particles.isFluid(k)) front = std::max(front, s.particles.x[k]);
  nlohmann::json summary = {
      {"front_position_final", front + 0.5 * g.dx},
      {"peak_pressure", spec.probes.empty() ? nlohmann::json(nullptr) : nlohmann::json(peakPressure)},
      {"kinetic_energy_final", s.kineticEnergy()},
      {"potential_energy_initial", potential0},
      {"potential_energy_final", s.potentialEnergy()}};
  return finishFluidRun(recorder, s, loop, {mass0, maxDensityError, outsideMax, fluidCount, spec.soundSpeed},
                        std::move(summary), damBreakSummaryFields(), dim, control, wallStart, checkpoints);
}

}  // namespace

Scenario damBreakScenario() {
  return withPreview(scenarioOf<DamBreakSpec>("dam-break", damBreakSummaryFields(), damBreakSeriesFields(), parseDamBreakSpec,
                                  io::estimateFluidSpec<DamBreakSpec>, runDamBreak), previewDamBreak);
}

}  // namespace rupture
