// The dam-break scenario (Martin & Moyce 1952; Koshizuka & Oka 1996): a water column of width a
// and height H at the back of a tank is released under gravity. Weakly compressible SPH with
// dynamic boundary particles (engine/sph/README.md); contract and file layout in docs/sph.md.
#include <algorithm>
#include <chrono>
#include <cmath>

#include "io/fluid_recorder.hpp"
#include "scenarios/dam_break/dam_break_spec.hpp"
#include "scenarios/fluid_run_loop.hpp"
#include "scenarios/run_support.hpp"
#include "scenarios/scenario.hpp"

namespace rupture {

namespace {

using Clock = std::chrono::steady_clock;

/// The tank and column on the lattice of spacing dx, sizes rounded to whole spacings.
struct DamBreakLattice {
  double dx;
  int nA, nH, nL, nT, nW;  ///< column width, column height, tank length, tank height, width (cells)
  double a() const { return nA * dx; }
  double H() const { return nH * dx; }
  double L() const { return nL * dx; }
  double T() const { return nT * dx; }
  double W() const { return nW * dx; }
};

DamBreakLattice lattice(const DamBreakSpec& s) {
  const double dx = s.resolution.spacing;
  auto cells = [dx](double length) { return std::max(1, static_cast<int>(std::lround(length / dx))); };
  const DamBreakGeometry& g = s.geometry;
  return {dx, cells(g.columnWidth), cells(g.columnHeight), cells(g.tankLength), cells(g.tankHeight),
          g.width ? cells(*g.width) : 1};
}

/// Fluid sites at ((i + ½) dx, ...) inside the column; wall sites in `layers` layers around the
/// floor, the back and front walls (and the side walls in 3D). Densities start hydrostatic.
void buildDamBreak(sph::SphSystem& s, const DamBreakSpec& spec, const DamBreakLattice& g) {
  const sph::EquationOfState& eos = s.model.eos;
  const double dx = g.dx, rho0 = eos.referenceDensity;
  const int dim = spec.dimension, layers = spec.resolution.wallLayers;
  const double mass = rho0 * std::pow(dx, dim);
  s.bodies.assign(1, {});
  s.bodies[0].name = "tank";
  auto hydrostatic = [&](double vertical) { return eos.density(rho0 * spec.gravity * (g.H() - vertical)); };
  const int j0 = dim == 3 ? -layers : 0, j1 = dim == 3 ? g.nW + layers : 1;
  for (int k = -layers; k < g.nT; ++k)
    for (int j = j0; j < j1; ++j)
      for (int i = -layers; i < g.nL + layers; ++i) {
        const double x = (i + 0.5) * dx, across = (j + 0.5) * dx, v = (k + 0.5) * dx;
        const bool inside = i >= 0 && i < g.nL && k >= 0 && (dim == 2 || (j >= 0 && j < g.nW));
        const double px = x, py = dim == 3 ? across : v, pz = dim == 3 ? v : 0.0;
        if (!inside) {
          // Walls beside and under the column start at the column's hydrostatic density.
          const bool loaded = i < g.nA && k < g.nH;
          s.particles.add(px, py, pz, mass, loaded ? hydrostatic(v) : rho0, 0);
        } else if (i < g.nA && k < g.nH) {
          s.particles.add(px, py, pz, mass, hydrostatic(v), sph::kFluid);
        }
      }
}

const std::vector<std::pair<std::string, std::string>>& seriesColumns() {
  static const std::vector<std::pair<std::string, std::string>> columns = {
      {"time", "s"},           {"front_position", "m"}, {"fluid_mass", "kg"},      {"kinetic_energy", "J"},
      {"potential_energy", "J"}, {"max_density_error", "1"}, {"particles_outside", "1"}, {"time_step", "s"}};
  return columns;
}

const std::map<std::string, std::string>& summaryUnits() {
  static const std::map<std::string, std::string> units = {
      {"front_position_final", "m"}, {"peak_pressure", "Pa"},   {"mass_error", "1"},
      {"max_density_error", "1"},    {"particles_outside_max", "1"}, {"final_time", "s"},
      {"steps", "1"},                {"time_step_min", "s"},    {"time_step_max", "s"},
      {"wall_time_s", "s"},          {"completed", "1"},        {"particles", "1"},
      {"fluid_particles", "1"},      {"sound_speed", "m/s"},    {"smoothing_length", "m"},
      {"kinetic_energy_final", "J"}, {"potential_energy_initial", "J"}, {"potential_energy_final", "J"},
      {"neighbour_list_builds", "1"}};
  return units;
}

RunOutcome runDamBreak(const nlohmann::json& json, const std::string& resultPath, RunControl& control) {
  const auto wallStart = Clock::now();
  const DamBreakSpec spec = parseDamBreakSpec(json);
  control.progress.store(0.0);
  const DamBreakLattice g = lattice(spec);
  const int dim = spec.dimension;

  sph::SphSystem s;
  s.model = io::fluidModel(spec.fluid, spec.resolution, dim, spec.soundSpeed, spec.gravity);
  buildDamBreak(s, spec, g);
  s.initialise();
  const std::size_t fluidCount = static_cast<std::size_t>(
      std::count(s.particles.body.begin(), s.particles.body.end(), sph::kFluid));
  logStage(control, "dam break: " + std::to_string(fluidCount) + " fluid and " +
                        std::to_string(s.particles.size() - fluidCount) + " wall particles, c0 " +
                        formatNumber(spec.soundSpeed) + " m/s");

  io::FluidRecorder recorder(resultPath, "dam-break", seriesColumns(), spec.probes.size());
  recorder.writeSpec(toJson(spec), json);
  recorder.writeAttributes("/geometry",
                           {{"column_width", g.a()}, {"column_height", g.H()}, {"tank_length", g.L()},
                            {"tank_height", g.T()}, {"width", dim == 3 ? nlohmann::json(g.W()) : nlohmann::json(nullptr)},
                            {"spacing", g.dx}, {"smoothing_length", s.model.h()}, {"wall_layers", spec.resolution.wallLayers},
                            {"vertical_axis", dim == 3 ? "z" : "y"}},
                           {{"column_width", "m"}, {"column_height", "m"}, {"tank_length", "m"}, {"tank_height", "m"},
                            {"width", "m"}, {"spacing", "m"}, {"smoothing_length", "m"}});

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
  const FluidLoopOutcome loop = runFluidLoop(s, spec.run, control, row, snapshot, [&](double dt) { lastStep = dt; });
  const bool completed = loop.stopReason != "cancelled";
  recorder.writeSnapshot(s, "final");

  double front = -1e300;
  for (std::size_t k = 0; k < s.particles.size(); ++k)
    if (s.particles.isFluid(k)) front = std::max(front, s.particles.x[k]);
  nlohmann::json summary = {
      {"completed", completed ? 1 : 0},
      {"stop_reason", loop.stopReason},
      {"front_position_final", front + 0.5 * g.dx},
      {"peak_pressure", spec.probes.empty() ? nlohmann::json(nullptr) : nlohmann::json(peakPressure)},
      {"mass_error", (s.fluidMass() - mass0) / mass0},
      {"max_density_error", maxDensityError},
      {"particles_outside_max", outsideMax},
      {"final_time", s.time},
      {"steps", static_cast<std::int64_t>(s.steps)},
      {"time_step_min", std::isfinite(loop.minTimeStep) ? nlohmann::json(loop.minTimeStep) : nlohmann::json(nullptr)},
      {"time_step_max", loop.maxTimeStep > 0 ? nlohmann::json(loop.maxTimeStep) : nlohmann::json(nullptr)},
      {"particles", static_cast<std::int64_t>(s.particles.size())},
      {"fluid_particles", static_cast<std::int64_t>(fluidCount)},
      {"sound_speed", spec.soundSpeed},
      {"smoothing_length", s.model.h()},
      {"kinetic_energy_final", s.kineticEnergy()},
      {"potential_energy_initial", potential0},
      {"potential_energy_final", s.potentialEnergy()},
      {"neighbour_list_builds", static_cast<std::int64_t>(s.listBuilds())}};
  summary["wall_time_s"] = std::chrono::duration<double>(Clock::now() - wallStart).count();
  recorder.writeAttributes("/summary", summary, summaryUnits());
  recorder.finish(completed);
  if (completed) reportProgress(control, 1.0);
  logStage(control, completed ? "done: " + loop.stopReason : "cancelled: file marked incomplete");
  return {summary, completed};
}

}  // namespace

Scenario damBreakScenario() {
  Scenario s;
  s.info.name = "dam-break";
  s.info.title = "Collapse of a water column in a tank (weakly compressible SPH)";
  s.info.description =
      "A water column of width a and height H at the back of a tank is released under gravity and surges along the "
      "floor (Martin & Moyce 1952). Weakly compressible SPH: cubic spline kernel, Tait or acoustic equation of state, "
      "Monaghan artificial viscosity, delta-SPH density diffusion, dynamic boundary particles for the walls, 2D or 3D. "
      "Outputs the surge front position, pressure at probe points, mass, kinetic and potential energy against time, "
      "and snapshots of position, velocity, density and pressure.";
  s.validate = [](const nlohmann::json& spec) { parseDamBreakSpec(spec); };
  s.run = runDamBreak;
  return s;
}

}  // namespace rupture
