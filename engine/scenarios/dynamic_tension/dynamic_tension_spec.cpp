#include "scenarios/dynamic_tension/dynamic_tension_spec.hpp"

#include <algorithm>

#include "bonded/bonded_spec.hpp"
#include "core/format_number.hpp"
#include "io/physical_ranges.hpp"
#include "io/run_length.hpp"
#include "io/spec_reader.hpp"
#include "rupture/run.hpp"

namespace rupture {

namespace {

constexpr const char* kScenarioName = "dynamic-tension";

TensionLoadingSpec parseLoading(const SpecReader& root) {
  TensionLoadingSpec l;
  const SpecReader loading = root.object("loading");
  l.strainRate = loading.number("strain_rate", io::physical::strainRate(), "1/s");
  const std::string field = loading.choice("initial_velocity", {"V0", "VL", "VH"}, "VH");
  l.initialVelocity = field == "V0" ? InitialVelocityField::V0
                      : field == "VL" ? InitialVelocityField::VL
                                      : InitialVelocityField::VH;
  // Optional numbers without a fixed default: absent = derived at run time (see the header).
  if (loading.has("ramp_time")) l.rampTime = loading.number("ramp_time", Range::positive(), "s");
  l.rampWaveRoundTrips = loading.number("ramp_wave_round_trips", Range::positive(), "1", l.rampWaveRoundTrips);
  if (loading.has("wave_speed")) l.waveSpeed = loading.number("wave_speed", io::physical::speed(), "m/s");
  l.vhPreliminaryStrainRate =
      loading.number("vh_preliminary_strain_rate", io::physical::strainRate(), "1/s", l.vhPreliminaryStrainRate);
  if (loading.has("vh_capture_strain"))
    l.vhCaptureStrain = loading.number("vh_capture_strain", {0.0, 1.0, true, true}, "1");
  loading.finish();
  return l;
}

TensionRunSpec parseRun(const SpecReader& root) {
  TensionRunSpec r;
  const auto run = root.optionalObject("run");
  if (!run) return r;
  r.maxStrain = run->number("max_strain", {0.0, 1.0, true, false}, "1", r.maxStrain);
  r.settleRoundTrips = run->number("settle_round_trips", Range::closed(0.0, 1e3), "1", r.settleRoundTrips);
  r.unloadedFraction = run->number("unloaded_fraction", {0.0, 1.0, false, true}, "1", r.unloadedFraction);
  if (run->has("stop_fraction")) r.stopFraction = run->number("stop_fraction", {0.0, 1.0, false, true}, "1");
  if (run->has("output_interval")) r.outputInterval = run->number("output_interval", Range::positive(), "s");
  if (run->has("snapshot_strains")) {
    r.snapshotStrains = run->numbers("snapshot_strains", 0, 1000, Range::closed(0.0, 1.0), "1");
    std::sort(r.snapshotStrains.begin(), r.snapshotStrains.end());
    r.snapshotStrains.erase(std::unique(r.snapshotStrains.begin(), r.snapshotStrains.end()),
                            r.snapshotStrains.end());
  }
  r.timeStepSafety = run->number("time_step_safety", {0.0, 1.0, true, false}, "1", r.timeStepSafety);
  r.maxSteps = run->integer("max_steps", 1, std::int64_t{1} << 40, r.maxSteps);
  r.checkpointInterval = run->number("checkpoint_interval_s", Range::closed(0.0, 1e7), "s", r.checkpointInterval);
  r.ranks = static_cast<int>(run->integer("ranks", 1, kMaxRanks, r.ranks));
  run->finish();
  return r;
}

TensionOutputSpec parseOutput(const SpecReader& root) {
  TensionOutputSpec o;
  if (const auto output = root.optionalObject("output")) {
    o.cachePreliminary = output->boolean("cache_preliminary", o.cachePreliminary);
    o.cacheSample = output->boolean("cache_sample", o.cacheSample);
    o.fragmentMinFraction =
        output->number("fragment_min_fraction", {0.0, 1.0, true, false}, "1", o.fragmentMinFraction);
    output->finish();
  }
  return o;
}

}  // namespace

std::string toString(InitialVelocityField field) {
  switch (field) {
    case InitialVelocityField::V0: return "V0";
    case InitialVelocityField::VL: return "VL";
    case InitialVelocityField::VH: return "VH";
  }
  return "?";
}

DynamicTensionSpec parseDynamicTensionSpec(const nlohmann::json& json) {
  const SpecReader root(json, "");
  DynamicTensionSpec s;
  io::parseBondedHead(root, kScenarioName, s);
  s.loading = parseLoading(root);
  s.run = parseRun(root);
  s.output = parseOutput(root);
  root.finish();

  // Cross-field checks.
  // The loaded faces are the elements within half an element radius of the sample's X extremes
  // (tension_loading.cpp): an element spanning the whole width would belong to both. Two of the
  // largest element diameters along X leave every element on at most one face.
  const bool lattice = s.sample.lattice != "random";
  const double largestDiameter = 2.0 * s.sample.elementRadius * (lattice ? 1.0 : 1.0 + s.sample.radiusDispersion);
  if (s.sample.size[0] < 2.0 * largestDiameter)
    throw SpecError("sample.size[0]", formatNumber(s.sample.size[0]),
                    "a gauge length of at least two of the largest element diameters, so that no element touches both "
                    "loaded faces (" +
                        std::string(lattice ? "2 x sample.spacing"
                                            : "4 x sample.element_radius x (1 + sample.radius_dispersion)") +
                        " = " + formatNumber(2.0 * largestDiameter) + " m)");
  if (s.loading.vhCaptureStrain && *s.loading.vhCaptureStrain >= s.run.maxStrain)
    throw SpecError("loading.vh_capture_strain", io::describeValue(*s.loading.vhCaptureStrain),
                    "a strain below run.max_strain (" + io::describeValue(s.run.maxStrain) + ")");
  // What a sub-domain cannot do yet (docs/distributed.md), refused where the field is named.
  if (s.run.ranks > 1 && s.material.localDamping > 0)
    throw SpecError("run.ranks", std::to_string(s.run.ranks),
                    "1 while material.local_damping is above 0: Silling's bond damping is not decomposed yet");
  return s;
}

RunEstimate estimateDynamicTension(const DynamicTensionSpec& s) {
  RunEstimate e = io::estimateBondedSpec(s);
  e.ranks = s.run.ranks;
  // Each rank builds the whole sample, then cuts its sub-domain from it (docs/distributed.md), as impact's.
  if (s.run.ranks > 1) e.memoryBytes *= s.run.ranks + 2.0;
  const double dt = s.run.timeStepSafety * io::estimatedCriticalStep(s.sample, s.material);
  const double gauge = s.sample.size[0];
  const double waveSpeed = s.loading.waveSpeed ? *s.loading.waveSpeed : s.material.dampingWaveSpeed;
  const double roundTrip = 2.0 * gauge / waveSpeed;  // eq. 6's 2 L0 / C0
  const auto maxSteps = static_cast<double>(s.run.maxSteps);
  const bool v0 = s.loading.initialVelocity == InitialVelocityField::V0;
  const double ramp = !v0 ? 0.0 : s.loading.rampTime ? *s.loading.rampTime : s.loading.rampWaveRoundTrips * roundTrip;
  std::vector<io::RunLoop> loops = {
      {ramp + s.run.maxStrain / s.loading.strainRate + s.run.settleRoundTrips * roundTrip, dt, maxSteps,
       "loading.strain_rate", "main run: run.max_strain / loading.strain_rate, ramp and settling"}};
  const bool preliminary = s.loading.initialVelocity == InitialVelocityField::VH ||
                           (v0 && !s.loading.rampTime && !s.loading.waveSpeed);
  if (preliminary)
    loops.push_back({s.loading.rampWaveRoundTrips * roundTrip + s.run.maxStrain / s.loading.vhPreliminaryStrainRate, dt,
                     maxSteps, "loading.vh_preliminary_strain_rate",
                     "preliminary run: run.max_strain / loading.vh_preliminary_strain_rate and its ramp"});
  io::addRunLength(e, loops, "material.density", io::bondedStepRule());
  return e;
}

nlohmann::json toJson(const DynamicTensionSpec& s) {
  nlohmann::json j = io::bondedSpecJson(kScenarioName, s.description, s.sample, s.material);
  j["loading"] = {{"strain_rate", s.loading.strainRate},
                  {"initial_velocity", toString(s.loading.initialVelocity)},
                  {"ramp_wave_round_trips", s.loading.rampWaveRoundTrips},
                  {"vh_preliminary_strain_rate", s.loading.vhPreliminaryStrainRate}};
  // Absent optional fields stay absent (their values are derived at run time and reported in
  // /summary and /preliminary), so the resolved spec parses back to the same struct.
  if (s.loading.rampTime) j["loading"]["ramp_time"] = *s.loading.rampTime;
  if (s.loading.waveSpeed) j["loading"]["wave_speed"] = *s.loading.waveSpeed;
  if (s.loading.vhCaptureStrain) j["loading"]["vh_capture_strain"] = *s.loading.vhCaptureStrain;
  j["run"] = {{"max_strain", s.run.maxStrain},
              {"settle_round_trips", s.run.settleRoundTrips},
              {"unloaded_fraction", s.run.unloadedFraction},
              {"output_interval", s.outputInterval()},
              {"snapshot_strains", s.run.snapshotStrains},
              {"time_step_safety", s.run.timeStepSafety},
              {"max_steps", s.run.maxSteps},
              {"checkpoint_interval_s", s.run.checkpointInterval},
              {"ranks", s.run.ranks}};
  if (s.run.stopFraction) j["run"]["stop_fraction"] = *s.run.stopFraction;
  j["output"] = {{"cache_preliminary", s.output.cachePreliminary},
                 {"cache_sample", s.output.cacheSample},
                 {"fragment_min_fraction", s.output.fragmentMinFraction}};
  return j;
}

}  // namespace rupture
