// The piston-column scenario (Caleyron et al. 2013 §2 and §4): a water column in a rigid tube, closed by a rigid
// bottom, hit by a piston. The pressure wave it carries (ρ0 c0 V for a heavy piston, doubled on
// reflection at a rigid bottom) is what loads the bottom plate. Weakly compressible SPH with
// Adami dummy-particle walls and piston (engine/sph/README.md); contract and file layout in docs/sph.md.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>

#include "scenarios/scenario_previews.hpp"
#include "fsi/piston_drive.hpp"
#include "sph/fluid_recorder.hpp"
#include "scenarios/fluid/fluid_results.hpp"
#include "scenarios/fluid/fluid_run_loop.hpp"
#include "scenarios/fluid/pressure_peaks.hpp"
#include "scenarios/piston_column/piston_column_lattice.hpp"
#include "scenarios/run_support.hpp"
#include "scenarios/scenario.hpp"

namespace rupture {

namespace {

RunOutcome runPistonColumn(const PistonColumnSpec& spec, const nlohmann::json& json, const std::string& resultPath,
                           RunControl& control) {
  auto wallStart = std::chrono::steady_clock::now();
  RunCheckpoints checkpoints(control, resultPath, "piston-column", json, spec.run.checkpointInterval, wallStart);
  const int dim = spec.dimension;

  sph::SphSystem s;
  RunOutcome cancelled;
  std::optional<fsi::PistonDrive> drive;  // the impactor's column, when the spec has one
  const std::optional<ColumnLattice> built =
      setUpFluidRun(s, control, resultPath, "piston-column", toJson(spec), json, wallStart, cancelled, [&] {
        ColumnLattice column = buildPistonColumn(s, spec);
        // The column carries real masses: the fluid's force on the lattice's section scales to the bore.
        if (spec.impactor)
          drive.emplace(s, kColumnPiston, *spec.impactor, 0.25 * std::numbers::pi * spec.diameter * spec.diameter / column.area);
        return column;
      });
  if (!built) return cancelled;
  const ColumnLattice& g = *built;
  const std::size_t fluidCount = fluidParticleCount(s);
  const sph::RigidBody& piston = s.bodies[kColumnPiston];
  // The impact speed: the carriage's with an impactor (the piston starts at rest), else the piston's.
  const double v0 = spec.impactor ? spec.impactor->speed : piston.speed, rho0 = s.model.eos.referenceDensity;
  logStage(control, "piston column: " + std::to_string(fluidCount) + " fluid and " +
                        std::to_string(s.particles.size() - fluidCount) + " boundary particles, piston " +
                        (spec.impactor ? "struck by a carriage (" + fsi::toString(spec.impactor->model) + ")"
                                       : sph::toString(piston.motion)) +
                        " at " + formatNumber(v0) + " m/s");

  io::FluidRecorder recorder =
      openFluidRecorder(resultPath, "piston-column", pistonColumnSeriesFields(), dim, spec.probes,
                        checkpoints.continueFrom());
  if (!checkpoints.resuming()) recorder.writeSpec(toJson(spec), json);
  if (!checkpoints.resuming()) recorder.writeAttributes("/geometry",
                           {{"diameter", 2 * g.R()}, {"column_height", g.H()}, {"section_area", g.area},
                            {"spacing", g.dx}, {"smoothing_length", s.model.h()},
                            {"wall_layers", spec.resolution.wallLayers}, {"piston_mass", piston.mass},
                            {"vertical_axis", dim == 3 ? "z" : "y"}},
                           {{"diameter", "m"}, {"column_height", "m"}, {"section_area", dim == 3 ? "m^2" : "m"},
                            {"spacing", "m"}, {"smoothing_length", "m"}, {"piston_mass", dim == 3 ? "kg" : "kg/m"},
                            {"wall_layers", "1"}});

  // The fluid's push on the bottom, over its area: the mean bottom pressure.
  auto bottomPressure = [&] { return -s.bodies[kColumnBottom].force[dim - 1] / g.area; };
  PressurePeaks bottomPeaks(firstTransitWindow(g.H(), spec.soundSpeed), bottomPressure());
  const double mass0 = s.fluidMass();
  double peakProbe = 0, maxDensityError = 0;
  std::int64_t outsideMax = 0;
  std::vector<double> probes(spec.probes.size());
  double lastStep = 0, maxFaceSpeed = piston.speed;
  auto row = [&] {
    const sph::FluidParticles& p = s.particles;
    double densityError = 0;
    std::int64_t outside = 0;
    const double face = g.H() - piston.displacement, R = g.R();
    for (std::size_t k = 0; k < p.size(); ++k) {
      if (!p.isFluid(k)) continue;
      densityError = std::max(densityError, std::fabs(p.rho[k] / rho0 - 1.0));
      const double radial = dim == 3 ? std::hypot(p.x[k], p.y[k]) : std::fabs(p.x[k]);
      const double v = dim == 3 ? p.z[k] : p.y[k];
      outside += (radial > R || v < 0 || v > face) ? 1 : 0;
    }
    for (std::size_t k = 0; k < probes.size(); ++k) {
      probes[k] = s.probePressure(spec.probes[k][0], spec.probes[k][1], spec.probes[k][2]);
      peakProbe = std::max(peakProbe, probes[k]);
    }
    maxDensityError = std::max(maxDensityError, densityError);
    outsideMax = std::max(outsideMax, outside);
    // piston_force: the fluid's force on the piston, positive when it pushes the piston back out.
    recorder.appendRow({s.time, bottomPressure(), piston.displacement, piston.speed, -piston.axialForce(),
                        s.fluidMass(), s.kineticEnergy(), densityError, static_cast<double>(outside), lastStep},
                       probes);
  };
  auto afterStep = [&](double dt) {
    lastStep = dt;
    bottomPeaks.observe(s.time, bottomPressure());
    maxFaceSpeed = std::max(maxFaceSpeed, piston.speed);
  };
  auto advance = [&](double dt) {
    if (drive) drive->beforeFluidStep(dt);
    s.step(dt);
  };
  auto snapshot = [&](const std::string& trigger) { recorder.writeSnapshot(s, trigger); };
  auto state = [&](StateArchive& a) {
    recorder.exchangeState(a);
    if (drive) drive->exchangeState(a);
    StateGroup observed(a, "observed");
    a.record("bottom_peaks", bottomPeaks);
    a.value("peak_probe", peakProbe), a.value("max_density_error", maxDensityError);
    a.value("outside_max", outsideMax), a.value("last_step", lastStep);
    a.value("max_face_speed", maxFaceSpeed);
  };
  const FluidLoopOutcome loop =
      runFluidLoop(s, spec.run, control, {checkpoints, recorder.result(), state}, row, snapshot, afterStep, advance);
  // A cancelled run ends at once: no final snapshot of millions of particles (seconds to write).
  if (loop.stopReason != "cancelled") recorder.writeSnapshot(s, "final");

  const sph::PistonShock shock = sph::pistonShock(s.model.eos, std::max(v0, 1e-12));
  nlohmann::json summary = {
      {"peak_pressure", spec.probes.empty() ? nlohmann::json(nullptr) : nlohmann::json(peakProbe)},
      {"peak_bottom_pressure", bottomPeaks.peak},
      {"first_peak_bottom_pressure", bottomPeaks.first},
      {"time_of_first_peak", bottomPeaks.firstTime},
      {"acoustic_pressure", rho0 * spec.soundSpeed * v0},
      {"shock_pressure", v0 > 0 ? nlohmann::json(shock.pressure) : nlohmann::json(0.0)},
      {"piston_initial_speed", spec.impactor ? 0.0 : v0},
      {"max_piston_speed", maxFaceSpeed},
      {"impactor_model", spec.impactor ? nlohmann::json(fsi::toString(spec.impactor->model)) : nlohmann::json(nullptr)},
      {"carriage_final_speed",
       drive ? nlohmann::json(drive->column().carriageSpeed()) : nlohmann::json(nullptr)},
      {"piston_final_speed", piston.speed},
      {"piston_final_position", piston.displacement},
      {"piston_impulse", -piston.along(piston.impulse)},
      {"piston_mass", drive ? nlohmann::json(drive->column().pistonMass())
                      : piston.motion == sph::BodyMotion::Free ? nlohmann::json(piston.mass) : nlohmann::json(nullptr)},
      {"section_area", g.area}};
  return finishFluidRun(recorder, s, loop, {mass0, maxDensityError, outsideMax, fluidCount, spec.soundSpeed},
                        std::move(summary), pistonColumnSummaryFields(), dim, control, wallStart, checkpoints);
}

}  // namespace

Scenario pistonColumnScenario() {
  return withPreview(scenarioOf<PistonColumnSpec>("piston-column", pistonColumnSummaryFields(), pistonColumnSeriesFields(),
                                      parsePistonColumnSpec, io::estimateFluidSpec<PistonColumnSpec>, runPistonColumn), previewPistonColumn);
}

}  // namespace rupture
