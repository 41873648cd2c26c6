// The tank-impact scenario (Caleyron et al. 2013 §2, issue 11): the piston-column set-up with its rigid bottom
// replaced by the AU4G plate, an SPH shell (the spot face in its thick bottom, or clamped at its
// rim: plate.clamp), coupled to the water through the
// fluid–shell contact of engine/fsi (pinball or master–slave). The carriage strikes the piston
// at V (fsi/impactor_column.hpp: an elastic or a rigid piston, or carriage and piston one rigid
// body of mass M); the water goes through the hole or the opened cracks. Contract:
// api/schemas/tank-impact.schema.json, docs/tank-impact.md; contact: docs/fsi-contact.md.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>

#include "scenarios/scenario_previews.hpp"
#include "fsi/fluid_shell_coupling.hpp"
#include "fsi/piston_drive.hpp"
#include "sph/fluid_recorder.hpp"
#include "scenarios/fluid/fluid_run_loop.hpp"
#include "scenarios/fluid/pressure_peaks.hpp"
#include "scenarios/run_support.hpp"
#include "scenarios/scenario.hpp"
#include "scenarios/tank_impact/plate_geometry.hpp"
#include "scenarios/tank_impact/plate_observables.hpp"
#include "scenarios/fluid/fluid_results.hpp"
#include "scenarios/tank_impact/tank_impact_results.hpp"
#include "scenarios/tank_impact/seed_specimens.hpp"
#include "scenarios/tank_impact/tank_impact_spec.hpp"
#include "scenarios/tank_impact/tank_lattice.hpp"

namespace rupture {

namespace {

/// Body index the plate nodes carry in snapshots (after the cylinder and the piston).
constexpr std::int32_t kPlateBody = 2;

/// Which fluid particles are below the plate: under the lowest intact node of their radial band
/// by more than t/2 + r_f (a band without nodes, the hole, takes its nearest outer band's level).
class BelowPlate {
public:
  BelowPlate(double radius, double spacing, double standOff)
      : m_band(spacing), m_standOff(standOff), m_level(static_cast<std::size_t>(radius / spacing) + 2) {}

  void update(const SphShell& shell) {
    std::fill(m_level.begin(), m_level.end(), std::numeric_limits<double>::infinity());
    const auto& x = shell.positions();
    for (std::size_t n = 0; n < shell.size(); ++n) {
      if (shell.fractured(n)) continue;
      const std::size_t b = std::min(m_level.size() - 1, static_cast<std::size_t>(std::hypot(x[n][0], x[n][1]) / m_band));
      m_level[b] = std::min(m_level[b], x[n][2]);
    }
    double outer = 0.0;  // beyond the plate: the clamp's level
    for (std::size_t b = m_level.size(); b-- > 0;) {
      if (std::isfinite(m_level[b])) outer = m_level[b];
      else m_level[b] = outer;
    }
  }

  bool below(double x, double y, double z) const { return depth(x, y, z) > 0; }

  /// How far below the plate's lower face (and the contact's stand-off) the point is: > 0 below.
  double depth(double x, double y, double z) const {
    const std::size_t b = std::min(m_level.size() - 1, static_cast<std::size_t>(std::hypot(x, y) / m_band));
    return m_level[b] - m_standOff - z;
  }

private:
  double m_band, m_standOff;
  std::vector<double> m_level;
};

io::StructurePoints plateSnapshot(const SphShell& shell, double density) {
  io::StructurePoints out;
  for (std::size_t n = 0; n < shell.size(); ++n) {
    for (int a = 0; a < 3; ++a) {
      out.position.push_back(shell.positions()[n][a]);
      out.velocity.push_back(shell.velocities()[n][a]);
    }
    out.density.push_back(density);
    out.damage.push_back(shell.maxDamage(n));
    out.body.push_back(kPlateBody);
    out.fractured.push_back(shell.fractured(n) ? 1 : 0);
  }
  return out;
}

RunOutcome runTankImpact(const TankImpactSpec& spec, const nlohmann::json& json, const std::string& resultPath,
                         RunControl& control) {
  auto wallStart = std::chrono::steady_clock::now();
  RunCheckpoints checkpoints(control, resultPath, "tank-impact", json, spec.run.checkpointInterval, wallStart);
  const double t = spec.plate.shell.thickness, dx = spec.resolution.spacing;

  // Water, cylinder and piston.
  sph::SphSystem s;
  s.model = io::fluidModel(spec.fluid, spec.resolution, 3, spec.soundSpeed, spec.gravity);
  const TankLatticeParams lattice = tankLatticeParams(spec);
  // The plate is built inside the cancellable set-up too: at fine spacings it holds a million nodes.
  std::optional<SphShell> plateBuilt;
  std::optional<fsi::PistonDrive> drive;  // the carriage and piston as two bodies (not `rigid`)
  const PlateGeometry geometry = plateGeometry(spec.plate);
  RunOutcome cancelled;
  const std::optional<TankLattice> built =
      setUpFluidRun(s, control, resultPath, "tank-impact", toJson(spec), json, wallStart, cancelled, [&] {
        TankLattice tank = buildTankLattice(s, lattice);
        // The column carries real masses: the fluid's force on the lattice's section scales to the bore.
        if (spec.impactor.model != fsi::ImpactorModel::Rigid)
          drive.emplace(s, kTankPiston, spec.impactor, std::numbers::pi * lattice.radius * lattice.radius / tank.area);
        s.cancel.throwIfRequested();
        plateBuilt.emplace(buildPlate(spec.plate, geometry));
        return tank;
      });
  if (!built) return cancelled;
  const TankLattice& g = *built;
  const sph::RigidBody& piston = s.bodies[kTankPiston];

  // The plate and the contact.
  SphShell& plate = *plateBuilt;
  const double nodeSpacing = geometry.nodes.spacing;
  const fsi::ContactGeometry contact = fsi::contactGeometry(dx, t, nodeSpacing);
  fsi::FluidShellCoupling coupling(s, plate, spec.contact.method, contact);
  const std::size_t initiallyFractured = plate.fracturedCount();
  const double holeDiameter = 2.0 * geometry.holeRadius;
  const double deflectionRadius = 0.25 * (spec.plate.diameter + holeDiameter);
  const bool uShape = spec.plate.precrack.shape == PrecrackShape::U;
  BelowPlate belowPlate(0.5 * spec.plate.diameter + nodeSpacing, nodeSpacing, contact.standOff());

  logStage(control, "tank impact: " + std::to_string(g.fluidParticles) + " fluid and " +
                        std::to_string(s.particles.size() - g.fluidParticles) + " boundary particles, " +
                        std::to_string(plate.size()) + " plate nodes, " + contactMethodName(spec.contact.method) +
                        " contact, carriage " + formatNumber(spec.impactor.mass) + " kg at " +
                        formatNumber(spec.impactor.speed) + " m/s, impactor " + fsi::toString(spec.impactor.model));
  // Carriage and piston face: the column's points, or the one rigid body.
  auto carriageDisplacement = [&] { return drive ? drive->column().carriageDisplacement() : piston.displacement; };
  auto carriageSpeed = [&] { return drive ? drive->column().carriageSpeed() : piston.speed; };
  auto faceSpeed = [&] { return drive ? drive->column().faceSpeed() : piston.speed; };
  double maxFaceSpeed = faceSpeed();

  io::FluidRecorder recorder = openFluidRecorder(resultPath, "tank-impact", tankImpactSeriesFields(), 3, spec.probes,
                                                 checkpoints.continueFrom());
  if (!checkpoints.resuming()) recorder.writeSpec(toJson(spec), json);
  if (!checkpoints.resuming()) recorder.writeAttributes("/geometry",
                           {{"inner_diameter", 2 * g.R()}, {"water_height", g.H()}, {"section_area", g.area},
                            {"spacing", dx}, {"smoothing_length", s.model.h()}, {"wall_layers", spec.resolution.wallLayers},
                            {"plate_thickness", t}, {"plate_spacing", nodeSpacing}, {"plate_nodes", plate.size()},
                            {"hole_diameter", holeDiameter}, {"contact_stand_off", contact.standOff()},
                            {"contact_cell_radius", contact.cellRadius}, {"plate_body", kPlateBody},
                            {"vertical_axis", "z"}},
                           {{"inner_diameter", "m"}, {"water_height", "m"}, {"section_area", "m^2"}, {"spacing", "m"},
                            {"smoothing_length", "m"}, {"wall_layers", "1"}, {"plate_thickness", "m"},
                            {"plate_spacing", "m"}, {"plate_nodes", "1"}, {"hole_diameter", "m"},
                            {"contact_stand_off", "m"}, {"contact_cell_radius", "m"}, {"plate_body", "1"}});

  const double rho0 = s.model.eos.referenceDensity;
  const double mass0 = s.fluidMass();
  auto gauge = [&] { return s.probePressure(spec.gauge[0], spec.gauge[1], spec.gauge[2]); };
  PressurePeaks gaugePeaks(firstTransitWindow(g.H(), spec.soundSpeed), gauge());
  double peakProbe = 0, maxDensityError = 0;
  double maxJet = 0, lastJet = 0, maxDeflection = 0, lastStep = 0;
  double frontSpeed = 0, outflowSpeed = 0;  // the jet's leading water and the water leaving the plate, at the last row
  double outflowSum = 0;                     // the outflow speed summed over the rows of the run's second half
  std::int64_t outflowRows = 0;              // with water below the plate
  std::vector<std::size_t> jetParticles;
  double timeToFracture = std::numeric_limits<double>::quiet_NaN();
  bool anyJet = false;
  std::int64_t outsideMax = 0, belowCount = 0;
  std::vector<double> probes(spec.probes.size());
  auto row = [&] {
    const sph::FluidParticles& p = s.particles;
    belowPlate.update(plate);
    double densityError = 0, momentum = 0, mass = 0;
    std::int64_t below = 0, outside = 0;
    const double R = g.R() + 0.5 * dx, top = g.bottom + g.H() - piston.displacement + 0.5 * dx;
    jetParticles.clear();
    double frontDepth = 0;
    for (std::size_t k = 0; k < p.size(); ++k) {
      if (!p.isFluid(k)) continue;
      densityError = std::max(densityError, std::fabs(p.rho[k] / rho0 - 1.0));
      const double depth = belowPlate.depth(p.x[k], p.y[k], p.z[k]);
      if (depth > 0) {
        ++below;
        momentum -= p.mass[k] * p.vz[k];
        mass += p.mass[k];
        jetParticles.push_back(k);
        frontDepth = std::max(frontDepth, depth);
      } else if (std::hypot(p.x[k], p.y[k]) > R || p.z[k] > top) {
        ++outside;  // through the cylinder or the piston
      }
    }
    const double jet = mass > 0 ? momentum / mass : 0.0;
    if (mass > 0) {
      anyJet = true;
      maxJet = std::max(maxJet, jet);
      lastJet = jet;
    }
    // A film sees the jet's front, and the flow leaves the plate at the exit: the mean downward
    // speed of the water within one smoothing length of the lowest water, and of the plate's face.
    const double h = s.model.h();
    double frontMomentum = 0, frontMass = 0, exitMomentum = 0, exitMass = 0;
    for (const std::size_t k : jetParticles) {
      const double depth = belowPlate.depth(p.x[k], p.y[k], p.z[k]);
      if (depth >= frontDepth - h) frontMomentum -= p.mass[k] * p.vz[k], frontMass += p.mass[k];
      if (depth <= h) exitMomentum -= p.mass[k] * p.vz[k], exitMass += p.mass[k];
    }
    frontSpeed = frontMass > 0 ? frontMomentum / frontMass : 0.0;
    outflowSpeed = exitMass > 0 ? exitMomentum / exitMass : 0.0;
    // The steady jet: the outflow averaged over the run's second half, past the first burst.
    if (exitMass > 0 && s.time >= 0.5 * spec.run.endTime) outflowSum += outflowSpeed, ++outflowRows;
    belowCount = below;
    for (std::size_t k = 0; k < probes.size(); ++k) {
      probes[k] = s.probePressure(spec.probes[k][0], spec.probes[k][1], spec.probes[k][2]);
      peakProbe = std::max(peakProbe, probes[k]);
    }
    maxDensityError = std::max(maxDensityError, densityError);
    outsideMax = std::max(outsideMax, outside);
    const double deflection = deflectionAtRadius(plate, geometry, deflectionRadius);
    maxDeflection = std::max(maxDeflection, deflection);
    recorder.appendRow({s.time, gauge(), carriageDisplacement(), carriageSpeed(), faceSpeed(),
                        drive ? drive->column().contactForce() : 0.0, jet, frontSpeed, outflowSpeed, deflection,
                        uShape ? tongueOpeningAngle(plate, geometry, spec.plate) : 0.0, crackedLength(plate, geometry),
                        static_cast<double>(below), -coupling.plateForce()[2], s.fluidMass(), densityError, lastStep},
                       probes);
  };
  auto afterStep = [&](double dt) {
    lastStep = dt;
    gaugePeaks.observe(s.time, gauge());
    maxFaceSpeed = std::max(maxFaceSpeed, faceSpeed());
    if (std::isnan(timeToFracture) && plate.fracturedCount() > initiallyFractured) timeToFracture = s.time;
  };
  auto snapshot = [&](const std::string& trigger) {
    recorder.writeSnapshot(s, trigger, plateSnapshot(plate, spec.plate.shell.density));
  };
  auto advance = [&](double dt) {
    if (drive) drive->beforeFluidStep(dt);
    coupling.step(dt);
  };
  auto state = [&](StateArchive& a) {
    plate.exchangeState(a);
    coupling.exchangeState(a);
    if (drive) drive->exchangeState(a);
    recorder.exchangeState(a);
    StateGroup observed(a, "observed");
    a.record("gauge_peaks", gaugePeaks);
    a.value("peak_probe", peakProbe), a.value("max_density_error", maxDensityError);
    a.value("max_jet", maxJet), a.value("last_jet", lastJet), a.value("max_deflection", maxDeflection);
    a.value("last_step", lastStep), a.value("time_to_fracture", timeToFracture), a.value("any_jet", anyJet);
    a.value("outside_max", outsideMax), a.value("below_count", belowCount);
    a.value("max_face_speed", maxFaceSpeed);
    a.value("front_speed", frontSpeed), a.value("outflow_speed", outflowSpeed);
    a.value("outflow_sum", outflowSum), a.value("outflow_rows", outflowRows);
  };
  const FluidLoopOutcome loop =
      runFluidLoop(s, spec.run, control, {checkpoints, recorder.result(), state}, row, snapshot, afterStep, advance);
  // A cancelled run ends at once: no final snapshot of millions of particles (seconds to write).
  if (loop.stopReason != "cancelled") snapshot("final");

  // The crack paths: reference positions of the fractured nodes in the order they failed.
  const std::vector<std::array<double, 2>> path = crackPath(plate, geometry);
  std::vector<double> flat;
  for (const auto& q : path) flat.insert(flat.end(), q.begin(), q.end());
  recorder.file().writeDataset("/crack_path", flat, {path.size(), 2}, "m");

  auto nullUnless = [](bool known, double v) { return known ? nlohmann::json(v) : nlohmann::json(nullptr); };
  // Where the impact tore the plate first: the rim (the seed's TF14A5) or elsewhere.
  auto firstFractureRadius = [&] {
    const std::vector<std::size_t>& order = plate.fractureOrder();
    if (order.size() <= initiallyFractured) return nlohmann::json(nullptr);
    const std::size_t i = order[initiallyFractured];
    return nlohmann::json(std::hypot(geometry.nodes.x[i], geometry.nodes.y[i]));
  };
  nlohmann::json summary = {
      {"first_pressure_peak", gaugePeaks.first},
      {"time_of_first_peak", gaugePeaks.firstTime},
      {"peak_gauge_pressure", gaugePeaks.peak},
      {"peak_pressure", nullUnless(!spec.probes.empty(), peakProbe)},
      {"acoustic_pressure", rho0 * spec.soundSpeed * spec.impactor.speed},
      {"max_jet_speed", nullUnless(anyJet, maxJet)},
      {"final_jet_speed", nullUnless(anyJet && belowCount > 0, lastJet)},
      {"jet_front_speed", nullUnless(belowCount > 0, frontSpeed)},
      {"final_outflow_speed", nullUnless(belowCount > 0, outflowSpeed)},
      {"mean_outflow_speed", nullUnless(outflowRows > 0, outflowRows > 0 ? outflowSum / outflowRows : 0.0)},
      {"max_deflection", maxDeflection},
      {"deflection_radius", deflectionRadius},
      {"final_tongue_angle", nullUnless(uShape, uShape ? tongueOpeningAngle(plate, geometry, spec.plate) : 0.0)},
      {"time_to_fracture", nullUnless(!std::isnan(timeToFracture), timeToFracture)},
      {"fracture_radius", firstFractureRadius()},
      {"cracked_length", crackedLength(plate, geometry)},
      {"rim_torn_fraction", rimTornFraction(plate, geometry, 0.5 * spec.plate.diameter, 2.0 * spec.plate.spacing)},
      {"fractured_nodes", static_cast<std::int64_t>(plate.fracturedCount() - initiallyFractured)},
      {"fluid_below_final", belowCount},
      {"carriage_initial_speed", spec.impactor.speed},
      {"carriage_final_speed", carriageSpeed()},
      {"carriage_final_displacement", carriageDisplacement()},
      {"carriage_mass", spec.impactor.mass},
      {"impactor_model", fsi::toString(spec.impactor.model)},
      {"piston_mass", nullUnless(drive.has_value(), drive ? drive->column().pistonMass() : 0.0)},
      {"max_piston_face_speed", maxFaceSpeed},
      {"piston_final_speed", nullUnless(drive.has_value(), drive ? drive->column().pistonSpeed() : 0.0)},
      {"plate_nodes", static_cast<std::int64_t>(plate.size())},
      {"shell_steps", static_cast<std::int64_t>(coupling.shellSteps())},
      {"fluid_time_s", coupling.timings().fluid},
      {"shell_time_s", coupling.timings().shell},
      {"contact_time_s", coupling.timings().contact},
      {"shell_point_evaluations", static_cast<std::int64_t>(plate.pointEvaluations())},
      {"shell_coarsest_class", plate.stepClasses().coarsest},
      {"shell_points_per_class", pointsPerClass(plate.stepClasses())},
      {"shell_gradients_time_s", plate.timings().gradients},
      {"shell_layers_time_s", plate.timings().layers},
      {"shell_forces_time_s", plate.timings().forces},
      {"shell_integration_time_s", plate.timings().integration},
      {"shell_fracture_time_s", plate.timings().fracture},
      {"shell_spectrum_time_s", plate.timings().spectrum},
      {"shell_spectrum_measurements", plate.spectrumMeasurements()},
      {"shell_max_frequency", nullUnless(!plate.measuredFrequencies().empty(),
                                         plate.measuredFrequencies().empty() ? 0.0 : plate.measuredFrequencies().front())},
      {"contact_method", contactMethodName(spec.contact.method)}};
  // The seed's measurements on this specimen, beside ours (null where the seed gives none).
  const SeedSpecimen* seed = spec.specimen.empty() ? nullptr : findSeedSpecimen(spec.specimen);
  auto seedValue = [&](double SeedSpecimen::*field) {
    return seed && !std::isnan(seed->*field) ? nlohmann::json(seed->*field) : nlohmann::json(nullptr);
  };
  summary["specimen"] = seed ? nlohmann::json(seed->name) : nlohmann::json(nullptr);
  summary["seed_first_peak_low"] = seedValue(&SeedSpecimen::firstPeakLow);
  summary["seed_first_peak_high"] = seedValue(&SeedSpecimen::firstPeakHigh);
  summary["seed_jet_speed"] = seedValue(&SeedSpecimen::jetSpeed);
  summary["seed_simulated_jet_speed"] = seedValue(&SeedSpecimen::simulatedJetSpeed);
  summary["seed_tongue_angle"] = seedValue(&SeedSpecimen::tongueAngle);
  summary["seed_time_to_fracture"] = seedValue(&SeedSpecimen::timeToFracture);
  summary["seed_outcome"] = seed ? nlohmann::json(seed->outcome) : nlohmann::json(nullptr);
  return finishFluidRun(recorder, s, loop, {mass0, maxDensityError, outsideMax, g.fluidParticles, spec.soundSpeed},
                        std::move(summary), tankImpactSummaryFields(), 3, control, wallStart, checkpoints);
}

}  // namespace

Scenario tankImpactScenario() {
  return withPreview(scenarioOf<TankImpactSpec>("tank-impact", tankImpactSummaryFields(), tankImpactSeriesFields(),
                                    parseTankImpactSpec, io::estimateFluidSpec<TankImpactSpec>, runTankImpact), previewTankImpact);
}

}  // namespace rupture
