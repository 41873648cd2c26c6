#include "scenarios/scenario_previews.hpp"
#include "scenarios/dynamic_tension/dynamic_tension.hpp"
#include "scenarios/dynamic_tension/dynamic_tension_results.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "samples/sample_builder.hpp"
#include "bonded/bonded_spec.hpp"
#include "core/format_number.hpp"
#include "distributed/coordinate_bisection.hpp"
#include "distributed/subdomain.hpp"
#include "rupture/spec_error.hpp"
#include "scenarios/bonded/intact_network.hpp"
#include "scenarios/dynamic_tension/dynamic_tension_spec.hpp"
#include "scenarios/dynamic_tension/preliminary_field_cache.hpp"
#include "scenarios/bonded/bonded_run.hpp"
#include "scenarios/dynamic_tension/tension_loading.hpp"
#include "scenarios/dynamic_tension/tension_observables.hpp"
#include "scenarios/dynamic_tension/tension_recorder.hpp"
#include "scenarios/dynamic_tension/tension_step_observables.hpp"
#include "scenarios/dynamic_tension/tension_stop_forecast.hpp"
#include "scenarios/dynamic_tension/preliminary_velocity_field.hpp"
#include "scenarios/run_checkpoints.hpp"
#include "scenarios/run_support.hpp"
#include "rupture/quantity_text.hpp"

namespace rupture {

namespace {

using Clock = std::chrono::steady_clock;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double seconds(Clock::time_point since) { return std::chrono::duration<double>(Clock::now() - since).count(); }

/// The preliminary run's parameters and cache key. Its ramp uses eq. 6 with loading.wave_speed
/// when given, else the affine wave speed of the bond network (an upper bound: a shorter ramp).
struct PreliminaryPlan {
  PreliminaryParameters params;
  nlohmann::json key;
};

PreliminaryPlan planPreliminary(const DynamicTensionSpec& spec, const BondedSystem& system,
                                const TensionGeometry& geometry, double timeStep) {
  PreliminaryPlan plan;
  PreliminaryParameters& p = plan.params;
  p.strainRate = spec.loading.vhPreliminaryStrainRate;
  p.captureStrain = spec.loading.vhCaptureStrain;
  const double c = spec.loading.waveSpeed ? *spec.loading.waveSpeed : affineWaveSpeed(system, geometry);
  p.rampTime = spec.loading.rampWaveRoundTrips * 2.0 * geometry.gaugeLength / c;  // eq. 6
  p.timeStep = timeStep;
  p.maxStrain = spec.run.maxStrain;
  p.maxSteps = spec.run.maxSteps;
  plan.key = {{"format", 2},  // 2: the field of a sample in spatial order (samples/spatial_order.hpp)
              {"engine", RUPTURE_VERSION},
              {"dimension", spec.sample.dimension},
              {"sample", io::toJson(spec.sample)},
              {"material", io::toJson(spec.material)},
              {"preliminary",
               {{"strain_rate", p.strainRate},
                {"capture_strain", p.captureStrain ? nlohmann::json(*p.captureStrain) : nlohmann::json("half_onset")},
                {"ramp_time", p.rampTime},
                {"time_step", p.timeStep}}}};  // the guards never change a successful result
  return plan;
}

nlohmann::json preliminaryAttributes(const PreliminaryResult* r, bool fromCache, const std::string& cacheFile) {
  if (!r) return {{"used", 0}};
  return {{"used", 1},
          {"from_cache", fromCache ? 1 : 0},
          // The cache file's name only: the cache directory is the machine's (a server's path must
          // not leak into result files); the name is the cache key's hash.
          {"cache_file", std::filesystem::path(cacheFile).filename().string()},
          {"strain_rate", r->strainRate},
          {"ramp_time", r->rampTime},
          {"time_step", r->timeStep},
          {"capture_strain", r->captureStrain},
          {"capture_time", r->captureTime},
          {"capture_steps", r->captureSteps},
          {"steps", r->steps},
          {"onset_strain", std::isnan(r->onsetStrain) ? nlohmann::json(nullptr) : nlohmann::json(r->onsetStrain)},
          {"face_velocity", r->faceVelocity},
          {"modulus", r->modulus},
          {"wave_speed", r->waveSpeed},
          {"equilibrium_ratio", r->equilibriumRatio},
          {"wall_time_s", r->wallTime}};
}

const std::map<std::string, std::string>& preliminaryUnits() {
  static const std::map<std::string, std::string> units = {
      {"strain_rate", "1/s"},   {"ramp_time", "s"},     {"time_step", "s"},       {"capture_strain", "1"},
      {"capture_time", "s"},    {"onset_strain", "1"},  {"face_velocity", "m/s"}, {"modulus", "Pa"},
      {"wave_speed", "m/s"},    {"equilibrium_ratio", "1"}, {"wall_time_s", "s"},       {"capture_steps", "1"},
      {"steps", "1"},           {"used", "1"},          {"from_cache", "1"}};
  return units;
}

struct PreliminaryOutcome {
  std::optional<PreliminaryResult> result;  ///< empty when not needed, or cancelled
  bool fromCache = false, cancelled = false;
  std::string cacheFile;                    ///< where it was read or stored ("" if not cached)
  double steps = 0;                         ///< steps the computed preliminary run took (0: none, or cached)
};

/// The rules the main run stops by (tension_stop_forecast.hpp), with the settle time from
/// `waveSpeed` (the preliminary run's C0, else the affine bound).
TensionStopRules mainStopRules(const DynamicTensionSpec& spec, const TensionGeometry& geometry,
                               const VelocityRamp& ramp, double waveSpeed, double timeStep) {
  TensionStopRules rules;
  rules.settleTime = spec.run.settleRoundTrips * 2.0 * geometry.gaugeLength / waveSpeed;
  rules.capTime = std::min(ramp.timeToReach(spec.run.maxStrain * geometry.gaugeLength),
                           static_cast<double>(spec.run.maxSteps) * timeStep);
  return rules;
}

/// The whole run's progress while its preliminary run steps: the steps done over the preliminary's
/// and the main run's together, the main run forecast with the preliminary's target strain as its
/// onset (its field carries the same sample to the same first break, faster). `preliminaryStep`
/// and `timeStep`: the two runs' time steps (s).
double progressDuringPreliminary(const DynamicTensionSpec& spec, const BondedSystem& system,
                                 const TensionGeometry& geometry, double preliminaryStep, double timeStep,
                                 const PreliminaryProgress& pre) {
  const double waveSpeed = affineWaveSpeed(system, geometry);
  const bool ramped = spec.loading.initialVelocity == InitialVelocityField::V0;
  const VelocityRamp ramp{spec.loading.strainRate * geometry.gaugeLength,
                          ramped ? spec.loading.rampWaveRoundTrips * 2.0 * geometry.gaugeLength / waveSpeed : 0.0};
  const double onset = ramp.timeToReach(pre.targetStrain * geometry.gaugeLength);
  const double mainStop = forecastStopTime(0.0, TensionObservables(0), mainStopRules(spec, geometry, ramp, waveSpeed, timeStep),
                                           onset > 0 ? onset : std::numeric_limits<double>::quiet_NaN());
  const double total = std::max(pre.endTime, pre.time) / preliminaryStep + mainStop / timeStep;
  return total > 0 ? pre.time / preliminaryStep / total : 0.0;
}

/// The preliminary run when this spec needs it (VH, or V0 without ramp_time nor wave_speed): read
/// from the cache, else computed on a copy of the sample and stored. On several ranks it is computed
/// over the ranks (collective), and the first rank alone takes the cache's lock, reads the entry and
/// stores it; the others follow what it found.
PreliminaryOutcome obtainPreliminary(const DynamicTensionSpec& spec, const BondedSystem& system,
                                     const TensionGeometry& geometry, double timeStep,
                                     const std::string& resultPath, RunControl& control, const Communicator& comm) {
  PreliminaryOutcome out;
  const InitialVelocityField field = spec.loading.initialVelocity;
  const bool needed = field == InitialVelocityField::VH ||
                      (field == InitialVelocityField::V0 && !spec.loading.rampTime && !spec.loading.waveSpeed);
  if (!needed) return out;
  const PreliminaryPlan plan = planPreliminary(spec, system, geometry, timeStep);
  const bool first = comm.rank() == 0;
  std::optional<CacheEntryLock> lock;
  if (spec.output.cachePreliminary) {
    out.cacheFile = preliminaryCacheFile(preliminaryCacheDirectory(control.cacheDirectory, resultPath), plan.key);
    // Held until this function returns: a run that waited here finds the entry computed.
    constexpr double kMissing = 0, kFound = 1, kCancelled = 2;  // what the first rank found
    double found = kMissing;
    if (first) {
      lock.emplace(out.cacheFile, control.cancel);
      if (!lock->held()) {
        found = kCancelled;
      } else {
        out.result = loadPreliminary(out.cacheFile, plan.key, system.particles.size());
        if (out.result) found = kFound;
      }
    }
    if (comm.size() > 1) found = comm.max(found);
    if (found == kCancelled) {
      out.cancelled = true;
      return out;
    }
    // The entry cannot change while the first rank holds its lock: the others read what it read.
    if (found == kFound && !first) out.result = loadPreliminary(out.cacheFile, plan.key, system.particles.size());
    const bool everyRankHasIt = found == kFound && (comm.size() == 1 || comm.max(out.result ? 0.0 : 1.0) == 0);
    if (everyRankHasIt) {
      out.fromCache = true;
      logStage(control, "preliminary run read from the cache " + out.cacheFile);
      return out;
    }
    out.result.reset();
  }
  logStage(control, "preliminary run from rest at " + formatQuantity(plan.params.strainRate, "1/s"));
  enterPhase(control, "preliminary run");
  out.result = runPreliminary(system, geometry, plan.params, control, [&](const PreliminaryProgress& p) {
    reportProgress(control, progressDuringPreliminary(spec, system, geometry, plan.params.timeStep, timeStep, p));
  }, comm);
  if (out.result) out.steps = static_cast<double>(out.result->steps);
  if (!out.result) {
    out.cancelled = true;
  } else if (spec.output.cachePreliminary && first && !storePreliminary(out.cacheFile, plan.key, *out.result)) {
    logStage(control, "cannot write the preliminary-run cache " + out.cacheFile + " (continuing without it)");
    out.cacheFile.clear();
  }
  return out;
}

/// Sets the initial velocities of the main run (section 3.2). The face DOFs are overwritten by
/// TensionLoading::install afterwards.
void applyInitialField(BondedSystem& system, InitialVelocityField field, const TensionGeometry& geometry,
                       double maxVelocity, const PreliminaryResult* preliminary) {
  ParticleStore& p = system.particles;
  const std::size_t n = p.size();
  switch (field) {
    case InitialVelocityField::V0:  // eq. 5: at rest
      break;
    case InitialVelocityField::VL: {  // eq. 8: v_x = V_max (x − X_min) / (X_max − X_min)
      const double span = geometry.xmaxCentre - geometry.xminCentre;
      for (std::size_t k = 0; k < n; ++k) p.vx[k] = maxVelocity * (p.x[k] - geometry.xminCentre) / span;
      break;
    }
    case InitialVelocityField::VH: {  // eq. 9: V_i(0) = V_i⁰ V_max / V_max⁰, rotations included
      const VelocityField& f = preliminary->field;
      const double scale = maxVelocity / preliminary->faceVelocity;
      for (std::size_t k = 0; k < n; ++k) {
        p.vx[k] = scale * f.vx[k]; p.vy[k] = scale * f.vy[k]; p.vz[k] = scale * f.vz[k];
        p.wx[k] = scale * f.wx[k]; p.wy[k] = scale * f.wy[k]; p.wz[k] = scale * f.wz[k];
      }
      break;
    }
  }
}

/// A run cancelled while its sample was being built: no sample exists, so the file holds the spec
/// and a summary saying so (layout otherwise as any incomplete result, with no rows or snapshots).
RunOutcome cancelledDuringBuild(const DynamicTensionSpec& spec, const nlohmann::json& input,
                                const std::string& resultPath, RunControl& control, Clock::time_point wallStart) {
  TensionRecorder recorder(resultPath);
  return cancelledBeforeStart(recorder, toJson(spec), input,
                              {{"strain_rate", spec.loading.strainRate},
                               {"initial_velocity", toString(spec.loading.initialVelocity)}},
                              declaredUnits<dynamicTensionSummaryFields>(), "building the sample", control, wallStart);
}

}  // namespace

RunOutcome runDynamicTension(const DynamicTensionSpec& spec, const nlohmann::json& json, const std::string& resultPath,
                             RunControl& control) {
  auto wallStart = Clock::now();
  RunCheckpoints checkpoints(control, resultPath, "dynamic-tension", json, spec.run.checkpointInterval, wallStart);

  // Sample, loaded faces, time step.
  BondedSystem system;
  SampleCacheUse sampleCache;
  const std::string cacheDirectory =
      spec.output.cacheSample ? preliminaryCacheDirectory(control.cacheDirectory, resultPath) : "";
  const std::optional<SampleReport> built =
      buildRunSample(spec.sample, spec.material, system, control, cacheDirectory, &sampleCache);
  if (!built) return cancelledDuringBuild(spec, json, resultPath, control, wallStart);
  const SampleReport& report = *built;
  if (sampleCache.fromCache) logStage(control, "sample read from the cache " + sampleCache.file);
  const TensionGeometry geometry = tensionGeometry(system, spec.sample, report);
  const double criticalStep = system.criticalTimeStep();
  if (!std::isfinite(criticalStep) || !(criticalStep > 0))
    throw std::runtime_error("dynamic-tension: the sample has no bond with a finite stiffness (no stable time step)");
  const double dt = spec.run.timeStepSafety * criticalStep;
  logStage(control, "sample: " + std::to_string(report.elements) + " elements, " + std::to_string(report.bonds) +
                   " bonds, time step " + formatQuantity(dt, "s"));

  // A resumed run continues the checkpoint's copy of the file, which holds all of this already.
  // Only the first rank writes it; the others hold an empty file in memory, for their checkpoints.
  const Communicator comm = Communicator::world();
  const bool writes = comm.rank() == 0;
  TensionRecorder recorder(resultPath, writes ? checkpoints.continueFrom() : std::string(),
                           writes ? io::ResultFile::Destination::kDisk : io::ResultFile::Destination::kDiscarded);
  if (writes && !checkpoints.resuming()) {
    recorder.writeSpec(toJson(spec), json);
    recorder.writeSample(system, report, geometry);
  }

  // Preliminary run (VH field; the sample's wave speed for a V0 ramp without ramp_time).
  const InitialVelocityField field = spec.loading.initialVelocity;
  // On several ranks, every rank takes the same outcome (a cancel included) at the same step.
  PreliminaryOutcome pre = obtainPreliminary(spec, system, geometry, dt, resultPath, control, comm);
  const PreliminaryResult* preliminary = pre.result ? &*pre.result : nullptr;
  if (writes && !checkpoints.resuming())
    recorder.writeAttributes("/preliminary", preliminaryAttributes(preliminary, pre.fromCache, pre.cacheFile),
                             preliminaryUnits());

  // Loading (eqs. 3, 6): VL and VH start with the X_max face at V_max (Fig. 1b dashed line).
  const double waveSpeed = spec.loading.waveSpeed ? *spec.loading.waveSpeed : preliminary ? preliminary->waveSpeed : kNaN;
  double rampTime = 0;
  if (field == InitialVelocityField::V0)
    rampTime = spec.loading.rampTime ? *spec.loading.rampTime
                                     : spec.loading.rampWaveRoundTrips * 2.0 * geometry.gaugeLength / waveSpeed;
  TensionLoading loading(geometry, spec.loading.strainRate, rampTime);
  const double maxVelocity = loading.ramp().maxVelocity;

  // On several ranks (mpirun -np N, engine/distributed): each rank steps its sub-domain, cut from
  // the sample at rest, whose loads at t = 0 it evaluates as the builder evaluated the whole
  // sample's (at rest); then both take the initial field and the faces' prescription. The whole
  // system, on the first rank, takes the ranks' gathered state before each output, and each step's
  // observables are gathered in the whole sample's order (tension_step_observables.hpp):
  // everything that reads `system` reads it as on one process, bit for bit (docs/distributed.md).
  // The other ranks drop the whole once their part has its start, and leave the outputs to the first.
  std::optional<Subdomain> part;
  if (comm.size() > 1 && !pre.cancelled) {
    if (spec.material.localDamping > 0)
      throw SpecError("material.local_damping", formatNumber(spec.material.localDamping),
                      "0 on more than one rank (mpirun -np " + std::to_string(comm.size()) +
                          "): Silling's bond damping is not decomposed yet");
    part.emplace(system, bisectCoordinates(system.particles, system.bonds, comm.size()), comm);
    part->system.initialize();
  }
  if (!pre.cancelled) applyInitialField(system, field, geometry, maxVelocity, preliminary);
  loading.install(system);
  if (part) {
    ParticleStore& local = part->system.particles;
    const ParticleStore& w = system.particles;
    const std::vector<std::int32_t>& global = part->globalIndex();
    for (std::size_t k = 0; k < global.size(); ++k) {
      const auto g = static_cast<std::size_t>(global[k]);
      local.vx[k] = w.vx[g]; local.vy[k] = w.vy[g]; local.vz[k] = w.vz[g];
      local.wx[k] = w.wx[g]; local.wy[k] = w.wy[g]; local.wz[k] = w.wz[g];
    }
    loading.prescribeFaces(part->system, part->localMembers(geometry.xmin), part->localMembers(geometry.xmax));
  }
  BondedSystem& stepped = part ? part->system : system;
  std::size_t gatheredAtStep = system.steps;
  auto gatherWhole = [&] {
    if (!part || gatheredAtStep == part->system.steps) return;
    part->gatherInto(system);
    gatheredAtStep = system.steps;
  };

  // Main run: one step, the face stresses, the observables, rows and snapshots when due, the stop rules.
  TensionObservables observed(system.bonds.size());
  // Separation: no path of intact bonds from X_min to X_max. It can only change when bonds break,
  // so it is checked after breaks, at most every kSeparationCheckSteps steps (one union–find,
  // about a tenth of a step). Then the run goes on until no bond broke for settle_round_trips
  // wave round trips, so that cracks already running finish (C0 measured, else the affine bound).
  constexpr std::uint64_t kSeparationCheckSteps = 4;
  std::size_t brokenAtLastCheck = 0;
  std::uint64_t lastCheckStep = 0;
  const double settleWaveSpeed = std::isfinite(waveSpeed) ? waveSpeed : affineWaveSpeed(system, geometry);
  const double settleTime = spec.run.settleRoundTrips * 2.0 * geometry.gaugeLength / settleWaveSpeed;
  observed.setAveragingTime(settleTime);
  const double outputInterval = spec.outputInterval();
  const std::vector<double>& snapshotStrains = spec.run.snapshotStrains;
  std::size_t nextSnapshot = 0, lastRowStep = 0;
  std::string stopReason = pre.cancelled ? "cancelled" : "";
  FaceStresses stress = loading.stresses(system.particles);
  double strain = 0;
  const std::size_t elementCount = system.particles.size();
  if (part && !writes) system = system.withoutElements();
  const TensionStepObservables stepObservables(loading, part ? &*part : nullptr);
  auto record = [&] {
    gatherWhole();
    lastRowStep = system.steps;
    if (!writes) return;
    recorder.appendRow({system.time, strain, stress.xmin, stress.xmax, stress.mean, observed.brokenFraction(),
                        system.kineticEnergy(), system.elasticEnergy(), system.particles.vx[geometry.xmax.front()]});
  };
  auto snapshotsDue = [&] {  // one snapshot per step even if it crosses several requested strains
    if (nextSnapshot >= snapshotStrains.size() || strain < snapshotStrains[nextSnapshot]) return;
    const auto began = Clock::now();
    gatherWhole();
    if (writes)
      recorder.writeSnapshot(system, report.packingFraction, report.thickness, strain,
                             "strain " + formatNumber(snapshotStrains[nextSnapshot]));
    control.phases.charge("writing snapshots", seconds(began));
    while (nextSnapshot < snapshotStrains.size() && strain >= snapshotStrains[nextSnapshot]) ++nextSnapshot;
  };

  // The progress is the steps done over the steps to the forecast stop time
  // (tension_stop_forecast.hpp), a computed preliminary run's included.
  const TensionStopRules stopRules = mainStopRules(spec, geometry, loading.ramp(), settleWaveSpeed, dt);
  auto publishStatus = [&] {
    RunStatus now;
    now.step = static_cast<std::int64_t>(system.steps);
    now.time = system.time;
    now.strain = strain;
    now.headlineName = "mean stress";
    now.headlineUnit = "Pa";
    now.headline = stress.mean;
    now.brokenBonds = static_cast<std::int64_t>(observed.broken());
    now.particles = static_cast<double>(elementCount);
    reportStatus(control, now);
  };

  double nextOutput = outputInterval;
  // Everything the loop below changes (docs/checkpoints.md).
  checkpoints.attach(recorder.result(), [&](StateArchive& a) {
    system.exchangeState(a);
    if (part) part->exchangeState(a);
    observed.exchangeState(a);
    recorder.exchangeState(a);
    StateGroup loop(a, "loop");
    a.value("strain", strain);
    a.record("stress", stress);
    a.value("next_output", nextOutput);
    a.value("next_snapshot", nextSnapshot);
    a.value("last_row_step", lastRowStep);
    a.value("broken_at_last_check", brokenAtLastCheck);
    a.value("last_check_step", lastCheckStep);
  });

  if (!pre.cancelled) {
    logStage(control, "main run: " + toString(field) + " at " + formatQuantity(spec.loading.strainRate, "1/s") + ", V_max " +
                     formatQuantity(maxVelocity, "m/s") + ", ramp " + formatQuantity(rampTime, "s") + ", stops " +
                     formatQuantity(settleTime, "s") + " after the separation and the last break");
    if (checkpoints.resuming()) {
      checkpoints.restore();
    } else {
      record();
      snapshotsDue();
    }
    enterPhase(control, kSteppingPhase);
    auto lastReport = Clock::now();
    while (true) {
      if (checkpoints.poll(system.steps, system.time) == RunCheckpoints::Action::Stop) {
        stopReason = "cancelled";
        break;
      }
      if (static_cast<std::int64_t>(system.steps) >= spec.run.maxSteps) { stopReason = "max_steps"; break; }
      stepped.step(dt);
      system.time = stepped.time;
      system.steps = stepped.steps;
      const TensionStep now = stepObservables.measure(stepped);
      strain = now.strain;
      stress = now.stress;
      observed.observe(system.time, strain, stress, now.brokenBonds);
      if (system.time >= nextOutput) {
        record();
        nextOutput = nextOutputTime(nextOutput, system.time, outputInterval);
      }
      snapshotsDue();
      if (!observed.separated() && observed.broken() != brokenAtLastCheck &&
          system.steps - lastCheckStep >= kSeparationCheckSteps) {
        brokenAtLastCheck = observed.broken();
        lastCheckStep = system.steps;
        // The first rank decides on the gathered bonds, and every rank takes its decision.
        if (part) part->gatherBondsInto(system);
        bool connected = !writes || groupsConnected(system.bonds, system.particles.size(), geometry.xmin, geometry.xmax);
        if (part) connected = comm.broadcastFromFirst(connected);
        if (!connected) {
          observed.markSeparated(system.time, strain);
          logStage(control, "faces separated at strain " + formatQuantity(strain, "1"));
        }
      }
      if (observed.settledAfterSeparation(system.time, settleTime)) { stopReason = "separated"; break; }
      // A stalled crack can restart when the ligament is stretched further: at a low rate the quiet
      // spell is as long as it took to reach the peak (ε_peak / ε̇), at a high rate a round trip.
      const double unloadedQuietTime =
          observed.broken() > 0 ? std::max(settleTime, observed.strainAtPeak() / spec.loading.strainRate) : settleTime;
      if (observed.unloadedAndQuiet(system.time, unloadedQuietTime, spec.run.unloadedFraction)) {
        stopReason = "unloaded";
        break;
      }
      if (spec.run.stopFraction && observed.postPeakDrop(*spec.run.stopFraction)) {
        stopReason = "post_peak_drop";
        break;
      }
      if (strain >= spec.run.maxStrain) { stopReason = "max_strain"; break; }
      if ((system.steps & 63) == 0 && Clock::now() - lastReport > std::chrono::milliseconds(100)) {
        lastReport = Clock::now();
        // The worst bond's stress over its strength grows about linearly with ε: where it reaches 1.
        // (On several ranks, of this rank's bonds: an estimate, and no rank waits for another.)
        const double worstRatio = stepped.maxFailureRatio();
        const double onsetEstimate =
            worstRatio > 1e-3 ? loading.ramp().timeToReach(strain / worstRatio * geometry.gaugeLength) : kNaN;
        const double stop = forecastStopTime(system.time, observed, stopRules, onsetEstimate);
        reportProgress(control, (pre.steps + system.time / dt) / (pre.steps + stop / dt));
        publishStatus();
      }
    }
    if (lastRowStep != system.steps) record();  // the last state is always a row
    publishStatus();
  }
  enterPhase(control, "final snapshot and fragments");
  gatherWhole();
  const bool completed = stopReason != "cancelled";
  if (!writes) {  // the first rank writes the final state and the summary
    RunOutcome outcome = finishRun(recorder, {{"completed", completed ? 1 : 0}, {"stop_reason", stopReason}}, {},
                                   completed, stopReason, control);
    checkpoints.finished(completed);
    return outcome;
  }
  recorder.writeSnapshot(system, report.packingFraction, report.thickness, strain, "final");

  // The pieces of the final state: macroscopic fragments apart from debris, cracks across the section.
  const std::size_t minFragment = std::max<std::size_t>(
      2, static_cast<std::size_t>(std::ceil(spec.output.fragmentMinFraction * static_cast<double>(elementCount))));
  const FragmentAnalysis pieces = analyseFragments(system.bonds, elementCount, minFragment);
  const double crackLineSpacing = 2.0 * spec.sample.elementRadius;
  // A loaded face peeled off as debris is still a piece on its side of the crack (the grip).
  std::vector<std::int32_t> piece = pieces.elementFragment;
  const auto fragmentCount = static_cast<std::int32_t>(pieces.fragmentSizes.size());
  for (std::int32_t k : geometry.xmin) if (piece[k] < 0) piece[k] = fragmentCount;
  for (std::int32_t k : geometry.xmax) if (piece[k] < 0) piece[k] = fragmentCount + 1;
  const std::size_t cracks =
      cracksCrossing(system.particles, spec.sample.dimension, piece, crackLineSpacing, crackLineSpacing);
  recorder.writeFragments(pieces, minFragment, spec.output.fragmentMinFraction, cracks);

  // Summary (SI units; see dynamicTensionSummaryFields).
  const double onsetTime = observed.onsetTime();
  nlohmann::json summary = observed.summary();
  summary.update(nlohmann::json{
      {"completed", completed ? 1 : 0},
      {"stop_reason", stopReason},
      // The imposed rate when the first bond broke: below strain_rate when a V0 ramp was not over (eq. 7).
      {"strain_rate_at_onset", std::isnan(onsetTime) ? nlohmann::json(nullptr)
                                                     : nlohmann::json(loading.ramp().velocity(onsetTime) / geometry.gaugeLength)},
      {"fragments", static_cast<std::int64_t>(pieces.fragmentSizes.size())},
      {"debris", static_cast<std::int64_t>(pieces.debris)},
      {"largest_fragment_fraction",
       pieces.fragmentSizes.empty() ? 0.0
                                    : static_cast<double>(pieces.fragmentSizes.front()) / static_cast<double>(elementCount)},
      {"cracks_crossing", static_cast<std::int64_t>(cracks)},
      {"final_strain", strain},
      {"mean_coordination", report.meanCoordination},
      {"porosity", report.porosity},
      {"strain_rate", spec.loading.strainRate},
      {"initial_velocity", toString(field)},
      {"max_velocity", maxVelocity},
      {"ramp_time", nullIfNaN(rampTime)},
      {"wave_speed", nullIfNaN(waveSpeed)},
      {"modulus", preliminary ? nlohmann::json(preliminary->modulus) : nlohmann::json(nullptr)},
      {"gauge_length", geometry.gaugeLength},
      {"section", geometry.section},
      {"sample_from_cache", sampleCache.fromCache ? 1 : 0},
  });
  summary.update(bondedRunScalars(system, dt, criticalStep, report));
  if (field == InitialVelocityField::V0 && onsetTime < rampTime)
    logStage(control, "note: the first bond broke during the V0 ramp, at " +
                     formatQuantity(summary["strain_rate_at_onset"].get<double>(), "1/s") +
                     ": the requested strain rate is above eq. 7's limit for this ramp time");
  summary["wall_time_s"] = seconds(wallStart);
  RunOutcome outcome =
      finishRun(recorder, summary, declaredUnits<dynamicTensionSummaryFields>(), completed, stopReason, control);
  checkpoints.finished(completed);
  return outcome;
}

Scenario dynamicTensionScenario() {
  return withPreview(scenarioOf<DynamicTensionSpec>("dynamic-tension", dynamicTensionSummaryFields(), dynamicTensionSeriesFields(),
                                        parseDynamicTensionSpec, estimateDynamicTension,
                                        runDynamicTension), previewDynamicTension);
}

}  // namespace rupture
