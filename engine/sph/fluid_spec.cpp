#include "sph/fluid_spec.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/format_number.hpp"
#include "io/run_estimate.hpp"
#include "io/run_length.hpp"
#include "io/physical_ranges.hpp"

namespace rupture::io {

RunEstimate estimateFluidRun(double particles) {
  RunEstimate e;
  e.particles = particles;
  e.memoryBytes = kRunBaseBytes + kFluidBytesPerParticle * particles;
  e.field = "resolution.spacing";
  e.basis = formatNumber(kRunBaseBytes / 1048576.0) + " MiB and " + formatNumber(kFluidBytesPerParticle) +
            " B per fluid and wall particle";
  return e;
}

double estimatedFluidStep(const ResolutionSpec& r, const FluidRunSpec& run, double soundSpeed, double gravity) {
  if (run.timeStep) return *run.timeStep;
  const double h = r.smoothingRatio * r.spacing;
  const double force = gravity > 0 ? std::sqrt(h / gravity) : std::numeric_limits<double>::infinity();
  return run.cfl * std::min(h / soundSpeed, force);
}

void addFluidRunLength(RunEstimate& e, const ResolutionSpec& r, const FluidRunSpec& run, double soundSpeed,
                       double gravity) {
  const std::string rule =
      run.timeStep ? std::string("the fixed run.time_step")
                   : "time step run.cfl x min(h / c0, sqrt(h / g)) (h = resolution.smoothing_length_ratio x "
                     "resolution.spacing, c0 the sound speed, g the gravity), which the flow only lowers";
  addRunLength(e, {{run.endTime, estimatedFluidStep(r, run, soundSpeed, gravity), static_cast<double>(run.maxSteps),
                    "run.end_time", "run.end_time"}},
               run.timeStep ? "run.time_step" : "fluid.sound_speed", rule);
}

FluidSpec parseFluid(const SpecReader& root, double defaultAlpha) {
  FluidSpec f;
  f.alpha = defaultAlpha;
  const auto fluid = root.optionalObject("fluid");
  if (!fluid) return f;
  f.density = fluid->number("density", physical::density(), "kg/m^3", f.density);
  if (fluid->has("sound_speed")) f.soundSpeed = fluid->number("sound_speed", physical::speed(), "m/s");
  f.equationOfState =
      fluid->choice("equation_of_state", {"tait", "acoustic"}, "tait") == "tait" ? sph::EosKind::Tait : sph::EosKind::Acoustic;
  if (const auto visc = fluid->optionalObject("artificial_viscosity")) {
    f.alpha = visc->number("alpha", Range::closed(0.0, 10.0), "1", f.alpha);
    f.beta = visc->number("beta", Range::closed(0.0, 10.0), "1", f.beta);
    visc->finish();
  }
  if (const auto diff = fluid->optionalObject("density_diffusion")) {
    const std::string model = diff->choice("model", {"fourtakas", "molteni_colagrossi", "off"}, "fourtakas");
    f.diffusion = model == "off"         ? sph::DiffusionModel::Off
                  : model == "fourtakas" ? sph::DiffusionModel::Fourtakas
                                         : sph::DiffusionModel::MolteniColagrossi;
    f.delta = diff->number("delta", Range::closed(0.0, 1.0), "1", f.delta);
    diff->finish();
  }
  fluid->finish();
  return f;
}

ResolutionSpec parseResolution(const SpecReader& root) {
  ResolutionSpec r;
  const SpecReader res = root.object("resolution");
  r.spacing = res.number("spacing", Range::positive(), "m");
  r.smoothingRatio = res.number("smoothing_length_ratio", Range::closed(1.0, 2.0), "1", r.smoothingRatio);
  // The walls must fill the kernel support of a fluid particle touching them: layers dx >= 2h.
  const auto minLayers = static_cast<std::int64_t>(std::ceil(2.0 * r.smoothingRatio - 1e-9));
  if (res.has("wall_layers")) {
    const std::int64_t layers = res.integer("wall_layers", 1, 10);
    if (layers < minLayers)
      throw SpecError(res.pathOf("wall_layers"), std::to_string(layers),
                      "an integer in [" + std::to_string(minLayers) + ", 10]: the layers must span the kernel support 2h = " +
                          std::to_string(2.0 * r.smoothingRatio) + " dx");
    r.wallLayers = static_cast<int>(layers);
  } else {
    r.wallLayers = static_cast<int>(std::max<std::int64_t>(3, minLayers));
  }
  res.finish();
  return r;
}

FluidRunSpec parseFluidRun(const SpecReader& root, double defaultEndTime) {
  FluidRunSpec r;
  r.endTime = defaultEndTime;
  const auto run = root.optionalObject("run");
  if (run) {
    r.endTime = run->number("end_time", Range::positive(), "s", defaultEndTime);
    if (run->has("time_step")) r.timeStep = run->number("time_step", Range::positive(), "s");
    r.cfl = run->number("cfl", {0.0, 1.0, true, false}, "1", r.cfl);
    if (run->has("output_interval")) r.outputInterval = run->number("output_interval", Range::positive(), "s");
    if (run->has("snapshot_times")) r.snapshotTimes = run->numbers("snapshot_times", 0, 1000, Range::nonNegative(), "s");
    r.maxSteps = run->integer("max_steps", 1, std::int64_t{1} << 40, r.maxSteps);
    r.checkpointInterval =
        run->number("checkpoint_interval_s", Range::closed(0.0, 1e7), "s", r.checkpointInterval);
    run->finish();
  }
  if (!run || !run->has("snapshot_times")) r.snapshotTimes = {0.0, r.endTime};
  std::sort(r.snapshotTimes.begin(), r.snapshotTimes.end());
  r.snapshotTimes.erase(std::unique(r.snapshotTimes.begin(), r.snapshotTimes.end()), r.snapshotTimes.end());
  if (r.timeStep && *r.timeStep > r.endTime)
    throw SpecError("run.time_step", std::to_string(*r.timeStep), "a time step <= run.end_time (" + std::to_string(r.endTime) + " s)");
  return r;
}

nlohmann::json withoutPointArrays(const nlohmann::json& spec, std::initializer_list<const char*> pointKeys) {
  if (!spec.is_object()) throw SpecError("(root)", describeValue(spec), "a JSON object");
  nlohmann::json rest = spec;
  for (const char* key : pointKeys) rest.erase(key);
  return rest;
}

std::vector<std::array<double, 3>> parseProbes(const nlohmann::json& spec, int dimension) {
  std::vector<std::array<double, 3>> out;
  auto it = spec.find("probes");
  if (it == spec.end()) return out;
  const std::string allowed = "an array of points, each an array of " + std::to_string(dimension) + " coordinates (m)";
  if (!it->is_array() || it->size() > 1000) throw SpecError("probes", describeValue(*it), allowed + ", at most 1000");
  for (std::size_t k = 0; k < it->size(); ++k) {
    const nlohmann::json wrapper = {{std::to_string(k), (*it)[k]}};
    const SpecReader point(wrapper, "probes");
    const std::vector<double> c =
        point.numbers(std::to_string(k), static_cast<std::size_t>(dimension), static_cast<std::size_t>(dimension), Range(), "m");
    out.push_back({c[0], c[1], dimension == 3 ? c[2] : 0.0});
  }
  return out;
}

nlohmann::json toJson(const FluidSpec& f, double soundSpeed) {
  return {{"density", f.density},
          {"sound_speed", soundSpeed},
          {"equation_of_state", sph::toString(f.equationOfState)},
          {"artificial_viscosity", {{"alpha", f.alpha}, {"beta", f.beta}}},
          {"density_diffusion", {{"model", sph::toString(f.diffusion)}, {"delta", f.delta}}}};
}

nlohmann::json toJson(const ResolutionSpec& r) {
  return {{"spacing", r.spacing}, {"smoothing_length_ratio", r.smoothingRatio}, {"wall_layers", r.wallLayers}};
}

nlohmann::json toJson(const FluidRunSpec& r) {
  nlohmann::json j = {{"end_time", r.endTime},
                      {"cfl", r.cfl},
                      {"output_interval", r.outputIntervalOrDefault()},
                      {"snapshot_times", r.snapshotTimes},
                      {"max_steps", r.maxSteps},
                      {"checkpoint_interval_s", r.checkpointInterval}};
  if (r.timeStep) j["time_step"] = *r.timeStep;
  return j;
}

nlohmann::json probesJson(const std::vector<std::array<double, 3>>& probes, int dimension) {
  nlohmann::json j = nlohmann::json::array();
  for (const auto& p : probes)
    j.push_back(dimension == 3 ? nlohmann::json{p[0], p[1], p[2]} : nlohmann::json{p[0], p[1]});
  return j;
}

sph::FluidModel fluidModel(const FluidSpec& f, const ResolutionSpec& r, int dimension, double soundSpeed,
                           double gravity) {
  sph::FluidModel m;
  m.dimension = dimension;
  m.spacing = r.spacing;
  m.smoothingRatio = r.smoothingRatio;
  m.eos = {f.equationOfState, f.density, soundSpeed, 7.0};
  m.alpha = f.alpha;
  m.beta = f.beta;
  m.diffusion = f.diffusion;
  m.delta = f.delta;
  m.gravity = {0, 0, 0};
  m.gravity[dimension - 1] = -gravity;
  return m;
}

}  // namespace rupture::io
