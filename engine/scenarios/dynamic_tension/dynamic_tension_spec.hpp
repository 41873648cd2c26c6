#pragma once
// The spec of the dynamic-tension scenario (Longchamp et al., CSMA 2024, section 3): the common
// bonded sample + material, plus "loading", "run" and "output". Plain data in SI units; parsed and
// validated once (parseDynamicTensionSpec), serialised back with every default filled in (toJson)
// for the result file. The JSON Schema api/schemas/dynamic-tension.schema.json describes the same
// fields; docs/dynamic-tension.md explains them.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bonded/sample_spec.hpp"
#include "rupture/run.hpp"

namespace rupture {

/// Initial velocity field of the main run (section 3.2): at rest (eq. 5), linear (eq. 8),
/// heterogeneous from a preliminary low-rate run (eq. 9).
enum class InitialVelocityField { V0, VL, VH };

std::string toString(InitialVelocityField field);

struct TensionLoadingSpec {
  double strainRate = 0;                                     ///< ε̇ = V_max / L0 (1/s), eq. 3
  InitialVelocityField initialVelocity = InitialVelocityField::VH;
  std::optional<double> rampTime;                            ///< Δt of the V0 ramp (s); default eq. 6
  double rampWaveRoundTrips = 3;                             ///< n of eq. 6 (1)
  std::optional<double> waveSpeed;                           ///< C0 of eq. 6 (m/s); default measured
  double vhPreliminaryStrainRate = 1e5;                      ///< strain rate of the preliminary run (1/s)
  std::optional<double> vhCaptureStrain;                     ///< capture strain (1); default ½ × onset
};

struct TensionRunSpec {
  double maxStrain = 0.01;                   ///< strain limit: stop here if not separated before (1)
  double settleRoundTrips = 1;               ///< after separation, stop once no bond broke for this many
                                             ///< wave round trips 2 L0 / C0 (1)
  double unloadedFraction = 0.1;             ///< stop a broken, quiet sample whose averaged σ̄ is below
                                             ///< this fraction of the peak, even if still joined (1)
  std::optional<double> stopFraction;        ///< if set, also stop once σ̄ < stopFraction × peak after damage (1)
  std::optional<double> outputInterval;      ///< time between series rows (s); default 5e-6 / ε̇
  std::vector<double> snapshotStrains;       ///< strains at which snapshots are written (1), sorted
  double timeStepSafety = 0.15;              ///< dt = safety × critical step (1)
  std::int64_t maxSteps = 50'000'000;        ///< guard on the number of steps of one run
  double checkpointInterval = 300;           ///< wall time between checkpoints (s; 0: none)
  int ranks = 1;                             ///< MPI ranks a server runs it on (docs/distributed.md)
};

struct TensionOutputSpec {
  bool cachePreliminary = true;  ///< reuse / store the preliminary run in the cache directory
  bool cacheSample = true;       ///< reuse / store the packed sample in the cache directory (sample_cache.hpp)
  double fragmentMinFraction = 0.01;  ///< macroscopic fragment: at least this fraction of the elements (1)
};

struct DynamicTensionSpec {
  std::string description;  ///< free text, kept in the result file
  SampleSpec sample;
  MaterialSpec material;
  TensionLoadingSpec loading;
  TensionRunSpec run;
  TensionOutputSpec output;

  /// Strain increment between series rows used when run.output_interval is absent (1).
  static constexpr double kDefaultOutputStrainIncrement = 5e-6;
  /// Output interval actually used (s).
  double outputInterval() const {
    return run.outputInterval ? *run.outputInterval : kDefaultOutputStrainIncrement / loading.strainRate;
  }
};

/// Reads and checks a whole spec (with "scenario": "dynamic-tension"); throws SpecError naming the
/// first offending field (dotted path, value, what is allowed). Unknown keys are errors.
DynamicTensionSpec parseDynamicTensionSpec(const nlohmann::json& spec);

/// The run's size (the bonded estimate) and length: the main run to run.max_strain at
/// loading.strain_rate (plus a V0 ramp and the settling after separation) and, when the spec needs
/// one, the preliminary run to run.max_strain at loading.vh_preliminary_strain_rate, each over the
/// estimated stable step and capped by run.max_steps.
RunEstimate estimateDynamicTension(const DynamicTensionSpec& spec);

/// The resolved spec, in the same shape as the input: every default filled in, except the optional
/// fields derived at run time (ramp_time, wave_speed, vh_capture_strain), which stay absent when
/// they were absent. Parsing it back gives the same struct.
nlohmann::json toJson(const DynamicTensionSpec& spec);

}  // namespace rupture
