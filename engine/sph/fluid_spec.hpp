#pragma once
// Parsing and validation of the parts every SPH scenario's spec shares (fluid, resolution, run,
// probes), and their resolved JSON (defaults filled in) for the result file. Units: SI, stated in
// api/schemas/{dam-break,piston-column}.schema.json.
#include <array>
#include <cstdint>
#include <initializer_list>
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "rupture/run.hpp"

#include "io/spec_reader.hpp"
#include "sph/fluid_model.hpp"

namespace rupture::io {

/// The "fluid" block.
struct FluidSpec {
  double density = 1000.0;                ///< ρ0 (kg/m³)
  std::optional<double> soundSpeed;       ///< c0 (m/s); absent: the scenario's default
  sph::EosKind equationOfState = sph::EosKind::Tait;
  double alpha = 0.1, beta = 0.0;         ///< artificial_viscosity.{alpha, beta} (1)
  sph::DiffusionModel diffusion = sph::DiffusionModel::Fourtakas;
  double delta = 0.1;                     ///< density_diffusion.delta (1)
};

/// The "resolution" block.
struct ResolutionSpec {
  double spacing = 0;           ///< initial particle spacing dx (m), required
  double smoothingRatio = 1.3;  ///< h/dx (1)
  int wallLayers = 3;           ///< layers of boundary particles, must cover the support 2h
};

/// The "run" block.
struct FluidRunSpec {
  double endTime = 0;                   ///< s
  std::optional<double> timeStep;       ///< fixed dt (s); absent: Monaghan & Kos with `cfl`
  double cfl = 0.2;                     ///< Courant number of the variable step (1)
  std::optional<double> outputInterval; ///< s between series rows; absent: end_time/500
  std::vector<double> snapshotTimes;    ///< s; absent: {0, end_time}
  std::int64_t maxSteps = 50'000'000;
  double checkpointInterval = 300;      ///< wall time between checkpoints (s; 0: none)

  double outputIntervalOrDefault() const { return outputInterval ? *outputInterval : endTime / 500.0; }
};

/// defaultAlpha: the scenario's default Monaghan α (free-surface flows 0.1, pressure waves 0.3).
/// Peak resident memory per particle of an SPH run: measured at 0.87 kB on a 3D dam break
/// (69,628 particles, 70.5 MB), rounded up to 1 kB.
inline constexpr double kFluidBytesPerParticle = 1e3;
/// The RunEstimate of an SPH scenario with `particles` fluid and wall particles (field
/// "resolution.spacing").
RunEstimate estimateFluidRun(double particles);
/// The step of an SPH run, estimated from the spec (s): run.time_step when fixed, else the bound
/// the Monaghan & Kos rule (SphSystem::stableTimeStep) starts from, C min(h / c0, √(h / g)), which
/// the flow's own speeds, accelerations and viscosity only lower.
double estimatedFluidStep(const ResolutionSpec& resolution, const FluidRunSpec& run, double soundSpeed, double gravity);
/// Adds the length of an SPH run to its estimate: run.end_time over that step, capped by run.max_steps.
void addFluidRunLength(RunEstimate& e, const ResolutionSpec& resolution, const FluidRunSpec& run, double soundSpeed,
                       double gravity);
/// The same for a scenario's spec that holds `estimatedParticles`, `resolution`, `run`,
/// `soundSpeed` and `gravity` (a Scenario's estimate).
template <class Spec>
RunEstimate estimateFluidSpec(const Spec& spec) {
  RunEstimate e = estimateFluidRun(spec.estimatedParticles);
  addFluidRunLength(e, spec.resolution, spec.run, spec.soundSpeed, spec.gravity);
  return e;
}

FluidSpec parseFluid(const SpecReader& root, double defaultAlpha);
ResolutionSpec parseResolution(const SpecReader& root);
FluidRunSpec parseFluidRun(const SpecReader& root, double defaultEndTime);
/// "probes": an optional array of points, each `dimension` numbers (m); read from the raw spec
/// (the root reader is given a copy without the key). Bounds are checked by the scenario.
std::vector<std::array<double, 3>> parseProbes(const nlohmann::json& spec, int dimension);

/// The spec without its arrays of points (`pointKeys`, read separately by parseProbes), for the
/// SpecReader of the rest; SpecError("(root)") unless `spec` is a JSON object.
nlohmann::json withoutPointArrays(const nlohmann::json& spec, std::initializer_list<const char*> pointKeys);

/// The head a 2D-or-3D fluid scenario's spec opens with, read in this order into `spec`:
/// "scenario" (which must be `scenario`), "description" and "dimension" (2 or 3, default 2).
template <class Spec>
void parseFluidHead(const SpecReader& root, const std::string& scenario, Spec& spec) {
  root.choice("scenario", {scenario});
  spec.description = root.string("description", "");
  spec.dimension = static_cast<int>(root.integer("dimension", 2, 3, 2));
}

nlohmann::json toJson(const FluidSpec& f, double soundSpeed);
nlohmann::json toJson(const ResolutionSpec& r);
nlohmann::json toJson(const FluidRunSpec& r);
nlohmann::json probesJson(const std::vector<std::array<double, 3>>& probes, int dimension);

/// The model a scenario runs: fluid + resolution, its sound speed, gravity magnitude g (m/s²)
/// acting along −y (2D) or −z (3D).
sph::FluidModel fluidModel(const FluidSpec& f, const ResolutionSpec& r, int dimension, double soundSpeed,
                           double gravity);

}  // namespace rupture::io
