#include "scenarios/dynamic_tension/preliminary_velocity_field.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "distributed/coordinate_bisection.hpp"
#include "distributed/subdomain.hpp"
#include "scenarios/bonded/intact_network.hpp"
#include "scenarios/dynamic_tension/tension_step_observables.hpp"
#include "scenarios/run_support.hpp"

namespace rupture {

namespace {

/// Fields kept during the run, at strains a factor kLadder apart.
constexpr double kLadder = 1.05;

struct SavedField {
  VelocityField field;
  double strain, time, faceVelocity;
  std::int64_t steps;
};

/// The velocities of every element of the sample: the system's own on one process, gathered from
/// the ranks' owned elements on several (collective).
VelocityField copyVelocities(const BondedSystem& stepped, const Subdomain* part) {
  const ParticleStore& p = stepped.particles;
  if (!part) return {p.vx, p.vy, p.vz, p.wx, p.wy, p.wz};
  return {part->gather(p.vx), part->gather(p.vy), part->gather(p.vz),
          part->gather(p.wx), part->gather(p.wy), part->gather(p.wz)};
}

}  // namespace

std::optional<PreliminaryResult> runPreliminary(const BondedSystem& initial, const TensionGeometry& geometry,
                                                const PreliminaryParameters& params, RunControl& control,
                                                const std::function<void(const PreliminaryProgress&)>& progress,
                                                const Communicator& comm) {
  const auto wallStart = std::chrono::steady_clock::now();
  // On several ranks, each steps its sub-domain, cut from the sample at rest as the main run's is
  // (its loads at t = 0 evaluated again, as the builder evaluated the whole sample's), and every
  // step's strain, face stresses and breaks are gathered in the whole sample's order: the run, its
  // capture and its fit are the one-process ones bit for bit (docs/distributed.md).
  // (No copy of the whole sample there: a rank holds its part beside `initial`.)
  TensionLoading loading(geometry, params.strainRate, params.rampTime);
  std::optional<Subdomain> part;
  std::optional<BondedSystem> copy;  // one process: the sample pulled
  if (comm.size() > 1) {
    part.emplace(initial, bisectCoordinates(initial.particles, initial.bonds, comm.size()), comm);
    part->system.initialize();
    loading.setReference(initial.particles);
    loading.prescribeFaces(part->system, part->localMembers(geometry.xmin), part->localMembers(geometry.xmax));
  } else {
    copy.emplace(initial);
    loading.install(*copy);
  }
  BondedSystem& stepped = part ? part->system : *copy;
  const Subdomain* const partHere = part ? &*part : nullptr;
  const TensionStepObservables observe(loading, partHere);
  const double dt = params.timeStep;

  // Per-step record after the ramp, for the modulus fit and the equilibrium check.
  struct Sample { double strain, xmin, xmax, mean; };
  std::vector<Sample> record;
  std::deque<SavedField> ladder;
  double nextLevel = 0;  // strain at which the next field is kept (0: at the first post-ramp step)

  std::size_t broken = 0;
  double onset = std::numeric_limits<double>::quiet_NaN();
  std::optional<SavedField> captured;
  auto lastReport = wallStart;

  while (true) {
    stepped.step(dt);
    const TensionStep now = observe.measure(stepped, control.cancel.load(std::memory_order_relaxed));
    if (now.cancelled) return std::nullopt;
    const double strain = now.strain;
    const double time = stepped.time;
    broken += now.brokenBonds;
    const auto steps = static_cast<std::int64_t>(stepped.steps);

    if (broken > 0) {
      onset = strain;
      if (params.captureStrain)
        throw SpecError("loading.vh_capture_strain", formatNumber(*params.captureStrain),
                        "a strain below the first bond break of the VH preliminary run (a bond broke at strain " +
                            formatNumber(strain) + " at " + formatNumber(params.strainRate) + " /s)");
      break;
    }
    const bool afterRamp = time >= params.rampTime;
    if (afterRamp) record.push_back({strain, now.stress.xmin, now.stress.xmax, now.stress.mean});
    if (params.captureStrain) {
      if (strain >= *params.captureStrain) {
        captured = SavedField{copyVelocities(stepped, partHere), strain, time,
                              loading.ramp().velocity(time), steps};
        break;
      }
    } else if (afterRamp && strain >= nextLevel) {
      ladder.push_back({copyVelocities(stepped, partHere), strain, time,
                        loading.ramp().velocity(time), steps});
      nextLevel = strain * kLadder;
      // The target ½ ε_onset is at least ½ ε now: keep the largest field below ½ ε and those above.
      while (ladder.size() > 1 && ladder[1].strain <= 0.5 * strain) ladder.pop_front();
    }
    if (strain >= params.maxStrain || steps >= params.maxSteps)
      throw std::runtime_error("VH preliminary run: " +
                               (params.captureStrain ? "the capture strain was not reached"
                                                     : std::string("no bond broke")) +
                               " within run.max_strain = " + formatNumber(params.maxStrain) + " and run.max_steps = " +
                               std::to_string(params.maxSteps) + " (reached strain " + formatNumber(strain) + ")" +
                               (params.captureStrain ? "" : "; set loading.vh_capture_strain"));

    const auto wallNow = std::chrono::steady_clock::now();
    if (progress && wallNow - lastReport > std::chrono::milliseconds(100)) {
      lastReport = wallNow;
      // Target strain: the capture strain, or the first break, extrapolated from the worst bond
      // (its stress grows about linearly with ε); the run ends about when it is reached.
      double target = params.captureStrain ? *params.captureStrain : 0.0;
      if (!params.captureStrain) {
        // (On several ranks, of this rank's bonds: an estimate, and no rank waits for another.)
        const double ratio = stepped.maxFailureRatio();
        target = ratio > 1e-3 ? strain / ratio : params.maxStrain;
      }
      progress({time, loading.ramp().timeToReach(target * geometry.gaugeLength), target});
    }
  }

  if (captured && captured->time < params.rampTime)
    throw SpecError("loading.vh_capture_strain", formatNumber(*params.captureStrain),
                    "a strain reached after the end of the VH preliminary run's ramp (ramp time " +
                        formatNumber(params.rampTime) + " s, face displacement strain " +
                        formatNumber(0.5 * params.strainRate * params.rampTime) + " at its end)");
  if (!captured) {
    // Default rule: the field nearest below ½ ε_onset.
    const double target = 0.5 * onset;
    for (const SavedField& f : ladder)
      if (f.strain <= target) captured = f;
    if (!captured)
      throw std::runtime_error(
          "VH preliminary run: the first bond broke at strain " + formatNumber(onset) +
          " before a post-ramp field below half that strain could be kept (ramp time " + formatNumber(params.rampTime) +
          " s); lower loading.vh_preliminary_strain_rate or set loading.vh_capture_strain");
  }

  PreliminaryResult r;
  r.field = std::move(captured->field);
  r.faceVelocity = captured->faceVelocity;
  r.strainRate = params.strainRate;
  r.rampTime = params.rampTime;
  r.timeStep = dt;
  r.captureStrain = captured->strain;
  r.captureTime = captured->time;
  r.captureSteps = captured->steps;
  r.steps = static_cast<std::int64_t>(stepped.steps);
  r.onsetStrain = onset;

  // Modulus: σ̄ = E ε fitted through the origin over [½ ε_c, ε_c]; equilibrium over the same window.
  double sxy = 0, sxx = 0, gap = 0, mean = 0;
  std::size_t count = 0;
  for (const Sample& s : record) {
    if (s.strain < 0.5 * r.captureStrain || s.strain > r.captureStrain) continue;
    sxy += s.mean * s.strain;
    sxx += s.strain * s.strain;
    gap += std::abs(s.xmin - s.xmax);
    mean += s.mean;
    ++count;
  }
  if (count == 0 || !(sxx > 0) || !(sxy > 0))
    throw std::runtime_error("VH preliminary run: no post-ramp stress record to measure the sample's modulus");
  r.modulus = sxy / sxx;
  r.waveSpeed = std::sqrt(r.modulus / geometry.bulkDensity);
  r.equilibriumRatio = gap / std::abs(mean);
  r.wallTime = std::chrono::duration<double>(std::chrono::steady_clock::now() - wallStart).count();
  if (progress) progress({stepped.time, stepped.time, onset});
  return r;
}

}  // namespace rupture
