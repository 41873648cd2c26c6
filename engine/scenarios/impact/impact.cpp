// The impact scenario: a bonded plate loaded by a rigid projectile, imposed velocities or
// tractions; outputs the crack tip, its speed, branching, fragments and energies (docs/impact.md).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

#include "rupture/quantity_text.hpp"
#include "scenarios/scenario_previews.hpp"
#include "samples/sample_builder.hpp"
#include "bonded/bonded_spec.hpp"
#include "io/interleave.hpp"
#include "scenarios/impact/impact_results.hpp"
#include "io/result_file.hpp"
#include "scenarios/bonded/intact_network.hpp"
#include "scenarios/bonded/bond_snapshot.hpp"
#include "scenarios/impact/crack_tracking.hpp"
#include "scenarios/impact/impact_spec.hpp"
#include "scenarios/bonded/bonded_run.hpp"
#include "distributed/coordinate_bisection.hpp"
#include "distributed/subdomain.hpp"
#include "scenarios/run_checkpoints.hpp"
#include "scenarios/run_support.hpp"
#include "rupture/spec_error.hpp"
#include "scenarios/scenario.hpp"

namespace rupture {

namespace {

using Clock = std::chrono::steady_clock;

/// Particles whose centre lies in the box (at t = 0).
std::vector<std::int32_t> inside(const ParticleStore& p, const Box& box) {
  std::vector<std::int32_t> out;
  for (std::size_t k = 0; k < p.size(); ++k)
    if (box.contains(p.x[k], p.y[k], p.z[k])) out.push_back(static_cast<std::int32_t>(k));
  return out;
}

/// A loading box that holds no particle of the built sample would load nothing: an input error.
SpecError emptyRegion(const std::string& list, std::size_t index, const Box& box, int d) {
  std::string value = "{\"min\": [";
  for (int a = 0; a < d; ++a) value += (a ? ", " : "") + formatNumber(box.min[a]);
  value += "], \"max\": [";
  for (int a = 0; a < d; ++a) value += (a ? ", " : "") + formatNumber(box.max[a]);
  value += "]}";
  return SpecError(list + "[" + std::to_string(index) + "]", value,
                   "a box holding at least one particle centre of the built sample (m)");
}

/// Area of the box's largest face inside the sample (m²; 2D: length × thickness, the thickness the
/// sample's masses were built with: sample.thickness on lattices, R_DE on random packings).
double loadedArea(const Box& box, const SampleSpec& s, double thickness) {
  double e[3];
  for (int a = 0; a < 3; ++a)
    e[a] = a < s.dimension ? std::max(0.0, std::min(box.max[a], s.size[a]) - std::max(box.min[a], 0.0)) : 0.0;
  if (s.dimension == 2) return std::max(e[0], e[1]) * thickness;
  return std::max({e[0] * e[1], e[1] * e[2], e[0] * e[2]});
}

/// Per-particle virial stress with the particle's own volume (tension positive), {n, 3, 3}.
std::vector<double> particleStress(const BondedSystem& s) {
  const ParticleStore& p = s.particles;
  const BondStore& bonds = s.bondLoads();
  std::vector<double> sigma(9 * p.size(), 0.0);
  for (std::size_t b = 0; b < bonds.size(); ++b) {
    if (bonds.intact[b] <= 0.0) continue;
    const std::int32_t i = bonds.i[b], j = bonds.j[b];
    const double d[3] = {p.x[j] - p.x[i], p.y[j] - p.y[i], p.z[j] - p.z[i]};
    const double f[3] = {bonds.fjx[b], bonds.fjy[b], bonds.fjz[b]};
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) {
        const double t = -0.25 * (d[r] * f[c] + f[r] * d[c]);
        sigma[9 * i + 3 * r + c] += t / p.volume[i];
        sigma[9 * j + 3 * r + c] += t / p.volume[j];
      }
  }
  return sigma;
}

struct Projectile {
  ProjectileSpec spec;
  double x[3], v[3], f[3] = {0, 0, 0};
};

}  // namespace

RunOutcome runImpact(const ImpactSpec& spec, const nlohmann::json& json, const std::string& resultPath,
                     RunControl& control) {
  auto wallStart = Clock::now();
  RunCheckpoints checkpoints(control, resultPath, "impact", json, spec.checkpointInterval, wallStart);
  BondedSystem system;
  const std::optional<SampleReport> built = buildRunSample(spec.sample, spec.material, system, control);
  if (!built) {  // no sample: the file holds the spec and a summary saying so
    io::ResultFile result(resultPath, "impact");
    return cancelledBeforeStart(result, toJson(spec), json, nlohmann::json::object(),
                                declaredUnits<impactSummaryFields>(), "building the sample", control, wallStart);
  }
  const SampleReport& report = *built;
  ParticleStore& p = system.particles;
  const int d = spec.sample.dimension;
  const double spacing = spec.sample.lattice == "random" ? 2.0 * spec.sample.elementRadius : spec.sample.spacing;
  const double criticalStep = system.criticalTimeStep();
  if (!std::isfinite(criticalStep) || !(criticalStep > 0))
    throw std::runtime_error("impact: the sample has no bond with a finite stiffness (no stable time step)");
  const double dt = spec.timeStepSafety * criticalStep;
  logStage(control, "sample: " + std::to_string(report.elements) + " elements, " + std::to_string(report.bonds) +
                        " bonds, time step " + formatQuantity(dt, "s"));

  // Imposed velocities: a linear ramp to the region's velocity over its ramp time.
  std::vector<std::pair<std::vector<std::int32_t>, const VelocityRegion*>> driven;
  for (std::size_t i = 0; i < spec.velocityRegions.size(); ++i) {
    const VelocityRegion& r = spec.velocityRegions[i];
    driven.push_back({inside(p, r.box), &r});
    if (driven.back().first.empty()) throw emptyRegion("loading.velocity_regions", i, r.box, d);
    for (std::int32_t k : driven.back().first) p.fixedDofs[k] |= kFixX | kFixY | kFixZ;
  }
  // Tractions: the traction times the loaded area, shared equally by the region's particles.
  std::vector<std::pair<std::vector<std::int32_t>, std::array<double, 3>>> pushed;
  for (std::size_t i = 0; i < spec.tractions.size(); ++i) {
    const TractionRegion& r = spec.tractions[i];
    std::vector<std::int32_t> members = inside(p, r.box);
    if (members.empty()) throw emptyRegion("loading.tractions", i, r.box, d);
    const double share = loadedArea(r.box, spec.sample, report.thickness) / static_cast<double>(members.size());
    pushed.push_back({members, {r.traction[0] * share, r.traction[1] * share, r.traction[2] * share}});
  }
  std::optional<Projectile> projectile;
  if (spec.projectile) {
    Projectile pr{*spec.projectile, {}, {}};
    for (int a = 0; a < 3; ++a) { pr.x[a] = pr.spec.position[a]; pr.v[a] = pr.spec.velocity[a]; }
    if (pr.spec.stiffness <= 0) pr.spec.stiffness = spec.material.contact.youngModulus;
    projectile = pr;
  }

  // On several ranks (mpirun -np N, engine/distributed): each rank steps its sub-domain, and the
  // whole system, on the first rank, takes the ranks' gathered state before each output; everything
  // that reads `system` below reads it as on one process, bit for bit (docs/distributed.md). The
  // other ranks drop the whole once their part is cut, and leave the outputs to the first.
  const Communicator comm = Communicator::world();
  const bool writes = comm.rank() == 0;
  std::optional<Subdomain> part;
  if (comm.size() > 1) {
    if (spec.material.localDamping > 0)
      throw SpecError("material.local_damping", formatNumber(spec.material.localDamping),
                      "0 on more than one rank (mpirun -np " + std::to_string(comm.size()) +
                          "): Silling's bond damping is not decomposed yet");
    part.emplace(system, bisectCoordinates(p, system.bonds, comm.size()), comm);
  }
  BondedSystem& stepped = part ? part->system : system;
  // The loaded sets in the numbering of the system stepped here (a sub-domain's: its owned
  // particles and ghosts).
  auto drivenHere = driven;
  auto pushedHere = pushed;
  if (part) {
    for (auto& entry : drivenHere) entry.first = part->localMembers(entry.first);
    for (auto& entry : pushedHere) entry.first = part->localMembers(entry.first);
  }
  auto prescriber = [](const decltype(driven)& sets) {
    return [&sets](ParticleStore& ps, double t) {
      for (const auto& [members, region] : sets) {
        const double f = region->rampTime > 0 ? std::min(1.0, t / region->rampTime) : 1.0;
        for (std::int32_t k : members) {
          ps.vx[k] = f * region->velocity[0]; ps.vy[k] = f * region->velocity[1]; ps.vz[k] = f * region->velocity[2];
        }
      }
    };
  };
  stepped.prescribe = prescriber(drivenHere);
  // The projectile's reaction: each touched particle's term, added in particle order from 0 (on
  // several ranks over all of them: Subdomain::sumInWholeOrder), the same sum on any rank count.
  std::vector<std::int64_t> touched;
  std::vector<double> reaction;
  stepped.externalLoads = [&](ParticleStore& ps, double) {
    for (const auto& [members, force] : pushedHere)
      for (std::int32_t k : members) { ps.fx[k] += force[0]; ps.fy[k] += force[1]; ps.fz[k] += force[2]; }
    if (!projectile) return;
    Projectile& pr = *projectile;
    touched.clear();
    reaction.clear();
    const double R = pr.spec.radius;
    for (std::size_t k = 0; k < ps.size(); ++k) {  // penalty F = K δ² on every particle inside
      if (part && !part->owns(k)) continue;
      const double ex = ps.x[k] - pr.x[0], ey = ps.y[k] - pr.x[1], ez = d == 3 ? ps.z[k] - pr.x[2] : 0.0;
      if (std::fabs(ex) > R || std::fabs(ey) > R || std::fabs(ez) > R) continue;
      const double r2 = ex * ex + ey * ey + ez * ez;
      if (r2 >= R * R || r2 == 0) continue;
      const double r = std::sqrt(r2), overlap = R - r, f = pr.spec.stiffness * overlap * overlap / r;
      ps.fx[k] += f * ex; ps.fy[k] += f * ey; ps.fz[k] += f * ez;
      touched.push_back(part ? part->globalIndex()[k] : static_cast<std::int64_t>(k));
      reaction.insert(reaction.end(), {-(f * ex), -(f * ey), -(f * ez)});
    }
    std::array<double, 3> sum{0.0, 0.0, 0.0};
    if (part) {
      sum = part->sumInWholeOrder(touched, reaction);
    } else {
      for (std::size_t t = 0; t < touched.size(); ++t)
        for (int c = 0; c < 3; ++c) sum[c] += reaction[3 * t + c];
    }
    for (int c = 0; c < 3; ++c) pr.f[c] = sum[c];
  };
  stepped.prescribe(stepped.particles, 0.0);
  stepped.initialize();
  // Bonds broken since the start: counted step by step on one rank, from the gathered bonds on several.
  const std::size_t brokenAtStart = system.bonds.size() - system.bonds.intactCount();
  const std::size_t wholeCount = p.size();
  if (part && writes) {  // the whole system, for the outputs: its velocities at t = 0 and its bond arrays
    system.prescribe = prescriber(driven);
    system.prescribe(p, 0.0);
    system.initialize();
  } else if (part) {
    system = system.withoutElements();
  }
  std::size_t broken = 0;
  std::size_t gatheredAtStep = system.steps;
  auto gatherWhole = [&] {
    if (!part || gatheredAtStep == part->system.steps) return;
    part->gatherInto(system);
    gatheredAtStep = system.steps;
    if (writes) broken = system.bonds.size() - system.bonds.intactCount() - brokenAtStart;
  };

  // Crack origin: the end of the first notch, else where the load is applied.
  std::array<double, 3> origin{0.5 * spec.sample.size[0], 0.5 * spec.sample.size[1], 0.5 * spec.sample.size[2]};
  if (!spec.sample.notches.empty()) origin = spec.sample.notches.front().end;
  else if (spec.projectile) origin = spec.projectile->position;
  else if (!spec.velocityRegions.empty())
    for (int a = 0; a < 3; ++a) origin[a] = 0.5 * (spec.velocityRegions.front().box.min[a] + spec.velocityRegions.front().box.max[a]);
  if (d == 2) origin[2] = 0;
  // The crack's angle is measured from the first notch's direction, from its end (the origin);
  // NaN without a notch or a crack.
  const Notch* notch = spec.sample.notches.empty() ? nullptr : &spec.sample.notches.front();
  // A tip gaining faster than twice the bar wave speed sqrt(E/rho) of the model's E has joined a
  // zone that cracked apart from it: a crack runs below the Rayleigh speed, about 0.57 sqrt(E/rho)
  // in glass.
  CrackTracker tracker(origin, spec.damageThreshold, spacing, 5, 2 * spec.material.dampingWaveSpeed);
  auto crackAngleNow = [&] {
    const std::optional<double> angle = notch ? crackAngle(tracker.tip(), notch->start, notch->end, d) : std::nullopt;
    return angle.value_or(std::numeric_limits<double>::quiet_NaN());
  };

  // A resumed run continues the checkpoint's copy of the file, which holds the set-up's groups.
  // Only the first rank writes it; the others hold an empty file in memory, for their checkpoints.
  io::ResultFile result = writes ? io::ResultFile(resultPath, "impact", checkpoints.continueFrom())
                                 : io::ResultFile(resultPath, "impact", io::ResultFile::Destination::kDiscarded);
  io::Hdf5File& file = result.file();
  const std::size_t n = p.size();
  if (writes && !checkpoints.resuming()) {
    result.writeSpec(toJson(spec), json);
    file.createGroup("/sample");
    file.writeDataset("/sample/initial_position", io::interleave(p.x, p.y, p.z), {n, 3}, "m");
    file.writeDataset("/sample/radius", p.radius, {n}, "m");
    file.writeDataset("/sample/volume", p.volume, {n}, "m^3");
    writeBondPairs(file, system.bonds);
    file.createGroup("/snapshots");
  }
  std::size_t snapshots = 0;
  auto snapshot = [&](const std::string& trigger, const std::vector<double>& damage) {
    gatherWhole();
    if (!writes) return;
    char name[32];
    std::snprintf(name, sizeof name, "/snapshots/%06zu", snapshots++);
    const std::string base = name;
    file.createGroup(base);
    file.setAttribute(base, "time", system.time);
    file.setAttribute(base, "strain", 0.0);  // the XDMF layout's attribute; impact has no imposed strain
    file.setAttribute(base, "trigger", trigger);
    file.setAttribute(base, "time_unit", std::string("s"));
    file.setAttribute(base, "strain_unit", std::string("1"));
    file.writeDataset(base + "/position", io::interleave(p.x, p.y, p.z), {n, 3}, "m");
    file.writeDataset(base + "/velocity", io::interleave(p.vx, p.vy, p.vz), {n, 3}, "m/s");
    file.writeDataset(base + "/stress", particleStress(system), {n, 3, 3}, "Pa");
    file.writeDataset(base + "/damage", damage, {n}, "1");
    file.writeDataset(base + "/radius", p.radius, {n}, "m");
    writeBondState(file, base, system);
  };

  std::vector<std::string> columns, units;  // in the row order of record() below
  for (const ResultField& f : impactSeriesFields()) {
    columns.push_back(f.name);
    units.push_back(f.unit);
  }
  std::vector<std::vector<double>> series(columns.size());
  const double bondCount = std::max<double>(1.0, static_cast<double>(system.bonds.size()));
  auto projectileEnergy = [&] {
    if (!projectile) return 0.0;
    const double* v = projectile->v;
    return 0.5 * projectile->spec.mass * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  };
  std::vector<double> damage = elementDamage(system.bonds, n, &p.volume);
  auto record = [&] {
    gatherWhole();
    if (!writes) return;
    damage = elementDamage(system.bonds, n, &p.volume);
    const double speed = tracker.observe(system.time, p, damage);
    const CrackTip& tip = tracker.tip();
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double row[] = {system.time, tip.found ? tip.x : nan, tip.found ? tip.y : nan, tip.found ? tip.z : nan,
                          tip.distance, speed, tracker.jump(), crackAngleNow(), system.kineticEnergy(), system.elasticEnergy(),
                          projectileEnergy(), static_cast<double>(broken) / bondCount};
    for (std::size_t c = 0; c < columns.size(); ++c) series[c].push_back(row[c]);
  };

  logStage(control, "impact run to " + formatQuantity(spec.endTime, "s"));
  std::string stopReason = "end_time";
  std::size_t nextSnapshot = 0;
  double nextOutput = 0;
  // Everything the loop below changes (docs/checkpoints.md).
  checkpoints.attach(result, [&](StateArchive& a) {
    system.exchangeState(a);
    if (part) part->exchangeState(a);
    tracker.exchangeState(a);
    StateGroup loop(a, "loop");
    if (projectile) {
      std::vector<double> body(projectile->x, projectile->x + 3);
      body.insert(body.end(), projectile->v, projectile->v + 3);
      body.insert(body.end(), projectile->f, projectile->f + 3);
      a.array("projectile", body);
      if (body.size() != 9) throw CheckpointError("the checkpoint's projectile is not 9 numbers");
      std::copy(body.begin(), body.begin() + 3, projectile->x);
      std::copy(body.begin() + 3, body.begin() + 6, projectile->v);
      std::copy(body.begin() + 6, body.end(), projectile->f);
    }
    for (std::size_t c = 0; c < columns.size(); ++c) a.array("series_" + columns[c], series[c]);
    a.array("damage", damage);
    a.value("broken", broken);
    a.value("snapshots", snapshots);
    a.value("next_snapshot", nextSnapshot);
    a.value("next_output", nextOutput);
  });
  if (checkpoints.resuming()) checkpoints.restore();
  // Where the run is, for the watcher's status line: the crack's length as its headline.
  auto publishStatus = [&] {
    RunStatus now;
    now.step = static_cast<std::int64_t>(system.steps);
    now.time = system.time;
    now.headlineName = "crack length";
    now.headlineUnit = "m";
    now.headline = tracker.tip().distance;
    now.brokenBonds = static_cast<std::int64_t>(broken);
    now.particles = static_cast<double>(wholeCount);
    reportStatus(control, now);
  };
  enterPhase(control, kSteppingPhase);
  auto lastReport = Clock::now();
  // A checkpoint is taken after the step's row and snapshot, with next_output and next_snapshot
  // already past them: a resumed run does not take them again.
  while (true) {
    if (system.time >= nextOutput - 1e-12 * spec.endTime) {
      record();
      nextOutput = nextOutputTime(nextOutput, system.time + 1e-12 * spec.endTime, spec.interval());
    }
    if (nextSnapshot < spec.snapshotTimes.size() && system.time >= spec.snapshotTimes[nextSnapshot]) {
      snapshot("time " + formatNumber(spec.snapshotTimes[nextSnapshot]), damage);
      while (nextSnapshot < spec.snapshotTimes.size() && system.time >= spec.snapshotTimes[nextSnapshot]) ++nextSnapshot;
    }
    if (system.time >= spec.endTime * (1 - 1e-12)) break;
    // Collective on several ranks: a cancel on any rank stops every rank at this step.
    if (checkpoints.poll(system.steps, system.time) == RunCheckpoints::Action::Stop) {
      stopReason = "cancelled";
      break;
    }
    if (static_cast<std::int64_t>(system.steps) >= spec.maxSteps) { stopReason = "max_steps"; break; }
    if (projectile) {  // velocity Verlet for the projectile around the system's step
      Projectile& pr = *projectile;
      for (int a = 0; a < d; ++a) { pr.v[a] += 0.5 * dt * pr.f[a] / pr.spec.mass; pr.x[a] += dt * pr.v[a]; }
    }
    if (part) {
      part->system.step(dt);
      system.time = part->system.time;
      system.steps = part->system.steps;
    } else {
      system.step(dt);
      broken += system.brokenLastStep;
    }
    if (projectile)
      for (int a = 0; a < d; ++a) projectile->v[a] += 0.5 * dt * projectile->f[a] / projectile->spec.mass;
    if ((system.steps & 63) == 0 && Clock::now() - lastReport > std::chrono::milliseconds(100)) {
      lastReport = Clock::now();
      // The run ends at end_time or max_steps, whichever comes first.
      reportProgress(control, std::max(system.time / spec.endTime,
                                        static_cast<double>(system.steps) / static_cast<double>(spec.maxSteps)));
      publishStatus();
    }
  }
  publishStatus();
  gatherWhole();
  if (series[0].empty() || series[0].back() != system.time) record();
  snapshot("final", damage);
  const bool completed = stopReason != "cancelled";
  if (!writes) {  // the first rank writes the summary
    RunOutcome outcome = finishRun(result, {{"completed", completed ? 1 : 0}, {"stop_reason", stopReason}}, {},
                                   completed, stopReason, control);
    checkpoints.finished(completed);
    return outcome;
  }
  file.createGroup("/series");
  for (std::size_t c = 0; c < columns.size(); ++c)
    file.writeDataset("/series/" + columns[c], series[c], {series[c].size()}, units[c]);

  const double* v = projectile ? projectile->v : nullptr;
  nlohmann::json summary = {
      {"completed", completed ? 1 : 0},
      {"stop_reason", stopReason},
      {"crack_speed_max", tracker.maxSpeed()},
      {"crack_length", tracker.tip().distance},
      {"crack_jumps", tracker.jumps()},
      {"crack_jumped_length", tracker.jumpedLength()},
      {"crack_angle", nullIfNaN(crackAngleNow())},
      {"branches", countCrackBranches(p, damage, spec.damageThreshold, origin, spacing)},
      {"fragments", static_cast<std::int64_t>(countFragments(system.bonds, n))},
      {"broken_bonds", static_cast<std::int64_t>(system.bonds.size() - system.bonds.intactCount())},
      {"broken_bond_fraction", static_cast<double>(system.bonds.size() - system.bonds.intactCount()) / bondCount},
      {"kinetic_energy", system.kineticEnergy()},
      {"elastic_energy", system.elasticEnergy()},
      {"projectile_final_speed", v ? nlohmann::json(std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])) : nlohmann::json(nullptr)},
  };
  summary.update(bondedRunScalars(system, dt, criticalStep, report));
  summary["wall_time_s"] = std::chrono::duration<double>(Clock::now() - wallStart).count();
  RunOutcome outcome = finishRun(result, summary, declaredUnits<impactSummaryFields>(), completed, stopReason, control);
  checkpoints.finished(completed);
  return outcome;
}

Scenario impactScenario() {
  return withPreview(scenarioOf<ImpactSpec>("impact", impactSummaryFields(), impactSeriesFields(), parseImpactSpec,
                                estimateImpact, runImpact), previewImpact);
}

}  // namespace rupture
