#pragma once
// The preliminary run of the heterogeneous initial velocity field VH (Longchamp et al., CSMA 2024,
// section 3.2, eq. 9): a tension test of the same sample from rest (V0) at a low strain rate ε̇⁰,
// whose velocity field V_i⁰ is recorded once the response is quasi-stationary and still elastic.
// The main run then starts from V_i(0) = V_i⁰ × V_max / V_max⁰, V_max⁰ being the X_max face
// velocity at capture.
//
// Capture rule:
// - loading.vh_capture_strain given: the field at the first step with ε ≥ that strain. If a bond
//   breaks before, the run fails with a SpecError naming that field.
// - absent (default): the run goes on until the first bond breaks, at strain ε_onset, and the field
//   captured is the one at ½ ε_onset (within 5 %: fields are kept at strains 5 % apart, after the
//   end of the ramp). Elastic by construction, and late enough to be quasi-stationary at a rate
//   well below eq. 7's limit.
//
// The same run measures the sample's macroscopic modulus E (least-squares slope through the origin
// of σ̄ against ε over [½ ε_capture, ε_capture]) and its bar wave speed C0 = √(E / ρ) with ρ the
// porous sample's density: the seed's Table 2 "porous" row, used by eq. 6 for the V0 ramp time.
// The run's own ramp time is eq. 6 with the affine (upper-bound) wave speed of the bond network.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "bonded/bonded_system.hpp"
#include "distributed/communicator.hpp"
#include "rupture/run.hpp"
#include "scenarios/dynamic_tension/tension_loading.hpp"

namespace rupture {

/// Velocities and angular velocities of every element (m/s, rad/s).
struct VelocityField {
  std::vector<double> vx, vy, vz, wx, wy, wz;
};

struct PreliminaryParameters {
  double strainRate = 1e5;               ///< ε̇⁰ (1/s)
  std::optional<double> captureStrain;   ///< explicit capture strain (1); nullopt: ½ ε_onset
  double rampTime = 0;                   ///< Δt of this run (s)
  double timeStep = 0;                   ///< dt (s)
  double maxStrain = 0.01;               ///< guard (1): reaching it without a capture is an error
  std::int64_t maxSteps = 50'000'000;    ///< guard, likewise (so guards never change a result)
};

struct PreliminaryResult {
  VelocityField field;                 ///< V_i⁰ at capture (not yet scaled)
  double faceVelocity = 0;             ///< V_max⁰: X_max face velocity at capture (m/s)
  double strainRate = 0;               ///< ε̇⁰ (1/s)
  double rampTime = 0;                 ///< Δt of the preliminary run (s)
  double timeStep = 0;                 ///< dt (s)
  double captureStrain = 0;            ///< ε at capture (1)
  double captureTime = 0;              ///< t at capture (s)
  std::int64_t captureSteps = 0;       ///< steps at capture
  std::int64_t steps = 0;              ///< steps run in total
  double onsetStrain = 0;              ///< ε at the first broken bond (1); NaN if none was reached
  double modulus = 0;                  ///< E of the sample (Pa)
  double waveSpeed = 0;                ///< C0 = √(E / ρ) (m/s)
  double equilibriumRatio = 0;         ///< mean |σ_Xmin − σ_Xmax| / mean σ̄ over the fit window (1)
  double wallTime = 0;                 ///< s spent computing it (in the run that computed it)
};

/// What the preliminary run reports as it goes: its simulated time, the time it is estimated to
/// end at, and the strain it runs to (the first break's, extrapolated from the worst bond, or the
/// capture strain when given), for the share of the progress bar it takes.
struct PreliminaryProgress {
  double time = 0, endTime = 0, targetStrain = 0;
};

/// Runs the preliminary test on a copy of `initial` (a freshly built sample at rest, initialised),
/// or, on several ranks, on this rank's sub-domain of it (collective; the same result on every
/// rank, the one-process result bit for bit). Returns nullopt if control.cancel was set (on any
/// rank: every rank stops at the same step). `progress` receives where it is about every 0.1 s of
/// wall time, and once at its end (endTime = time).
/// Throws SpecError (field loading.vh_capture_strain: a bond broke before it, or it is reached
/// before the end of the ramp) or std::runtime_error (no bond broke within the guards, or the first
/// break came before a post-ramp field below half its strain was kept).
std::optional<PreliminaryResult> runPreliminary(const BondedSystem& initial, const TensionGeometry& geometry,
                                                const PreliminaryParameters& params, RunControl& control,
                                                const std::function<void(const PreliminaryProgress&)>& progress,
                                                const Communicator& comm = Communicator::world());

}  // namespace rupture
