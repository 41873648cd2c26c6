// The dynamic-tension spec: validation (field paths in errors, unknown keys), defaults, the
// resolved-spec round trip, and agreement between the parser and the embedded JSON Schema.
#include <functional>

#include "scenarios/dynamic_tension/dynamic_tension_spec.hpp"
#include "test_dynamic_tension_support.hpp"

namespace rupture::test {
namespace {

nlohmann::json minimalSpec() {
  nlohmann::json spec = readJson(examplePath("dynamic-tension-small.json"));
  spec.erase("run");
  spec.erase("description");
  spec["loading"] = {{"strain_rate", 1e6}};
  return spec;
}

TEST(DynamicTensionSpec, ExamplesAreValid) {
  EXPECT_EQ(rejectedField(readJson(examplePath("dynamic-tension-small.json"))), "");
  EXPECT_EQ(rejectedField(readJson(examplePath("dynamic-tension-seed.json"))), "");
  EXPECT_EQ(rejectedField(minimalSpec()), "");
}

TEST(DynamicTensionSpec, ErrorsNameTheField) {
  auto with = [](const std::function<void(nlohmann::json&)>& edit) {
    nlohmann::json spec = minimalSpec();
    edit(spec);
    return rejectedField(spec);
  };
  EXPECT_EQ(with([](auto& s) { s.erase("scenario"); }), "scenario");
  EXPECT_EQ(with([](auto& s) { s["scenario"] = "tension"; }), "scenario");
  EXPECT_EQ(with([](auto& s) { s["loading"]["initial_velocity"] = "VX"; }), "loading.initial_velocity");
  EXPECT_EQ(with([](auto& s) { s["loading"]["strain_rate"] = -1e6; }), "loading.strain_rate");
  EXPECT_EQ(with([](auto& s) { s["loading"]["strain_rate"] = 0; }), "loading.strain_rate");
  EXPECT_EQ(with([](auto& s) { s["loading"].erase("strain_rate"); }), "loading.strain_rate");
  EXPECT_EQ(with([](auto& s) { s.erase("loading"); }), "loading");
  EXPECT_EQ(with([](auto& s) { s["loading"]["ramp_time"] = 0; }), "loading.ramp_time");
  EXPECT_EQ(with([](auto& s) { s["loading"]["vh_capture_strain"] = 0.5; }), "loading.vh_capture_strain");
  EXPECT_EQ(with([](auto& s) { s["loading"]["speed"] = 1; }), "loading.speed");
  EXPECT_EQ(with([](auto& s) { s["run"] = {{"stop_fraction", 1.0}}; }), "run.stop_fraction");
  EXPECT_EQ(with([](auto& s) { s["run"] = {{"settle_round_trips", -1}}; }), "run.settle_round_trips");
  EXPECT_EQ(with([](auto& s) { s["run"] = {{"unloaded_fraction", 1}}; }), "run.unloaded_fraction");
  EXPECT_EQ(with([](auto& s) { s["output"] = {{"fragment_min_fraction", 0}}; }), "output.fragment_min_fraction");
  EXPECT_EQ(with([](auto& s) { s["run"] = {{"max_steps", 0}}; }), "run.max_steps");
  EXPECT_EQ(with([](auto& s) { s["run"] = {{"snapshot_strains", {0.001, -1}}}; }), "run.snapshot_strains");
  EXPECT_EQ(with([](auto& s) { s["run"] = {{"every", 3}}; }), "run.every");
  EXPECT_EQ(with([](auto& s) { s["output"] = {{"cache_preliminary", "yes"}}; }), "output.cache_preliminary");
  EXPECT_EQ(with([](auto& s) { s["extra"] = 1; }), "extra");
  EXPECT_EQ(with([](auto& s) { s["sample"]["porosity"] = 0.9; }), "sample.porosity");
  EXPECT_EQ(with([](auto& s) { s["material"]["beam"]["failure_stress"] = -4e9; }), "material.beam.failure_stress");
  EXPECT_EQ(with([](auto& s) { s["material"]["local_damping"] = -0.5; }), "material.local_damping");
  EXPECT_EQ(with([](auto& s) { s["run"]["ranks"] = 0; }), "run.ranks");
  EXPECT_EQ(with([](auto& s) { s["run"]["ranks"] = 5000; }), "run.ranks");
  EXPECT_EQ(with([](auto& s) { s["run"]["ranks"] = 2; }), "");
  // Silling's damping is not decomposed: refused on several ranks, naming run.ranks.
  EXPECT_EQ(with([](auto& s) {
              s["run"]["ranks"] = 2;
              s["material"]["local_damping"] = 0.5;
            }),
            "run.ranks");
  EXPECT_EQ(with([](auto& s) { s["sample"]["grains"] = {{"count", 1}}; }), "sample.grains.count");
  EXPECT_EQ(with([](auto& s) { s["sample"]["grains"] = {{"boundary_factor", 0.5}}; }), "sample.grains.count");
  EXPECT_EQ(with([](auto& s) { s["sample"]["grains"] = {{"count", 8}, {"boundary_factor", 0}}; }),
            "sample.grains.boundary_factor");
  EXPECT_EQ(with([](auto& s) { s["sample"]["grains"] = {{"count", 8}, {"factor", 0.5}}; }), "sample.grains.factor");
  EXPECT_EQ(with([](auto& s) { s["sample"]["inclusions"] = {{"volume_fraction", 0.2}}; }), "sample.inclusions.radius");
  EXPECT_EQ(with([](auto& s) { s["sample"]["inclusions"] = {{"volume_fraction", 0.7}, {"radius", {2e-8, 3e-8}}}; }),
            "sample.inclusions.volume_fraction");
  EXPECT_EQ(with([](auto& s) { s["sample"]["inclusions"] = {{"volume_fraction", 0.2}, {"radius", {3e-8, 2e-8}}}; }),
            "sample.inclusions.radius");
  // Beams take a per-bond factor on E_mu: stiffer inclusions are allowed.
  EXPECT_EQ(with([](auto& s) {
              s["sample"]["inclusions"] = {{"volume_fraction", 0.2}, {"radius", {2e-8, 3e-8}}, {"stiffness_factor", 2}};
            }),
            "");
  // material.disorder: each bad field is named.
  EXPECT_EQ(with([](auto& s) { s["material"]["disorder"] = nlohmann::json::object(); }), "material.disorder");
  EXPECT_EQ(with([](auto& s) { s["material"]["disorder"] = {{"seed", 3}}; }), "material.disorder");
  EXPECT_EQ(with([](auto& s) { s["material"]["disorder"] = {{"strength", {{"distribution", "gamma"}}}}; }),
            "material.disorder.strength.distribution");
  EXPECT_EQ(with([](auto& s) { s["material"]["disorder"] = {{"strength", {{"distribution", "weibull"}}}}; }),
            "material.disorder.strength.modulus");
  EXPECT_EQ(with([](auto& s) { s["material"]["disorder"] = {{"strength", {{"distribution", "weibull"}, {"modulus", 0.1}}}}; }),
            "material.disorder.strength.modulus");
  EXPECT_EQ(with([](auto& s) { s["material"]["disorder"] = {{"stiffness", {{"distribution", "normal"}, {"cv", 0.5}}}}; }),
            "material.disorder.stiffness.cv");
  EXPECT_EQ(with([](auto& s) {
              s["material"]["disorder"] = {{"stiffness", {{"distribution", "normal"}, {"cv", 0.1}, {"modulus", 4}}}};
            }),
            "material.disorder.stiffness.modulus");
  EXPECT_EQ(with([](auto& s) { s["material"]["disorder"] = {{"seed", -1}, {"strength", {{"distribution", "normal"}, {"cv", 0.1}}}}; }),
            "material.disorder.seed");
  // material.anisotropic_damage: each bad field is named.
  EXPECT_EQ(with([](auto& s) { s["material"]["anisotropic_damage"] = nlohmann::json::object(); }),
            "material.anisotropic_damage.critical_factors");
  EXPECT_EQ(with([](auto& s) { s["material"]["anisotropic_damage"] = {{"critical_factors", {1, 0.5, 0.2}}}; }),
            "material.anisotropic_damage.critical_factors");  // 2D: two axes
  EXPECT_EQ(with([](auto& s) { s["material"]["anisotropic_damage"] = {{"critical_factors", {1, 0}}}; }),
            "material.anisotropic_damage.critical_factors");
  EXPECT_EQ(with([](auto& s) { s["material"]["anisotropic_damage"] = {{"critical_factors", {1, 0.5}}, {"angles", {10, 20}}}; }),
            "material.anisotropic_damage.angles");
  EXPECT_EQ(with([](auto& s) { s["material"]["anisotropic_damage"] = {{"critical_factors", {1, 0.5}}, {"angles", {400}}}; }),
            "material.anisotropic_damage.angles");
  EXPECT_EQ(with([](auto& s) {
              s["material"]["anisotropic_damage"] = {{"critical_factors", {1, 0.5}}, {"block_angles", {{"x", {30}}}}};
            }),
            "material.anisotropic_damage.block_angles.x");
  EXPECT_EQ(with([](auto& s) {
              s["material"]["anisotropic_damage"] = {{"critical_factors", {1, 0.5}}, {"block_angles", {{"2", {30, 1}}}}};
            }),
            "material.anisotropic_damage.block_angles[2]");  // the reader names numeric keys as indices
  EXPECT_EQ(with([](auto& s) {
              s["material"]["anisotropic_damage"] = {{"critical_factors", {1, 0.5}}, {"grain_frames", "random"}};
            }),
            "material.anisotropic_damage.grain_frames");  // no grains
  EXPECT_EQ(with([](auto& s) {
              s["sample"]["grains"] = {{"count", 8}, {"boundary_factor", 0.5}};
              s["material"]["anisotropic_damage"] = {{"critical_factors", {1, 0.5}}, {"grain_frames", "random"},
                                                     {"angles", {30}}};
            }),
            "material.anisotropic_damage.grain_frames");
  EXPECT_EQ(with([](auto& s) {
              s["sample"]["grains"] = {{"count", 8}, {"boundary_factor", 0.5}};
              s["material"]["anisotropic_damage"] = {{"critical_factors", {1, 0.5}}, {"grain_frames", "random"}};
            }),
            "");
  EXPECT_EQ(with([](auto& s) {
              s["material"]["anisotropic_damage"] = {{"critical_factors", {1, 0.5}}, {"angles", {30}},
                                                     {"block_angles", {{"2", {-45}}}}};
            }),
            "");
  EXPECT_EQ(with([](auto& s) {
              s["material"]["disorder"] = {{"seed", 9}, {"strength", {{"distribution", "weibull"}, {"modulus", 6}}},
                                           {"stiffness", {{"distribution", "normal"}, {"cv", 0.2}}}};
            }),
            "");
  EXPECT_EQ(with([](auto& s) {
              s["sample"]["inclusions"] = {{"volume_fraction", 0.2}, {"radius", {2e-8, 3e-8}}, {"strength_factor", 2}};
            }),
            "");
  EXPECT_EQ(with([](auto& s) {
              s["sample"]["grains"] = {{"count", 8}, {"boundary_factor", 0.5}};
              s["material"]["local_damping"] = 1.0;
            }),
            "");

  try {
    nlohmann::json spec = minimalSpec();
    spec["loading"]["initial_velocity"] = "VX";
    validateSpec(spec);
    FAIL() << "accepted";
  } catch (const SpecError& e) {
    EXPECT_EQ(e.value(), "\"VX\"");
    EXPECT_NE(std::string(e.what()).find("\"V0\", \"VL\", \"VH\""), std::string::npos) << e.what();
  }
}

TEST(DynamicTensionSpec, DefaultsAndResolvedRoundTrip) {
  const DynamicTensionSpec s = parseDynamicTensionSpec(minimalSpec());
  EXPECT_EQ(s.loading.initialVelocity, InitialVelocityField::VH);
  EXPECT_DOUBLE_EQ(s.loading.rampWaveRoundTrips, 3.0);
  EXPECT_DOUBLE_EQ(s.loading.vhPreliminaryStrainRate, 1e5);
  EXPECT_FALSE(s.loading.rampTime);
  EXPECT_FALSE(s.loading.waveSpeed);
  EXPECT_FALSE(s.loading.vhCaptureStrain);
  EXPECT_DOUBLE_EQ(s.run.maxStrain, 0.01);
  EXPECT_DOUBLE_EQ(s.run.settleRoundTrips, 1.0);
  EXPECT_DOUBLE_EQ(s.run.unloadedFraction, 0.1);
  EXPECT_FALSE(s.run.stopFraction);  // the stop rule is separation unless a post-peak drop is asked for
  EXPECT_DOUBLE_EQ(s.output.fragmentMinFraction, 0.01);
  EXPECT_DOUBLE_EQ(s.run.timeStepSafety, 0.15);
  EXPECT_DOUBLE_EQ(s.outputInterval(), 5e-6 / 1e6);
  EXPECT_TRUE(s.run.snapshotStrains.empty());
  EXPECT_TRUE(s.output.cachePreliminary);

  const nlohmann::json resolved = toJson(s);
  EXPECT_EQ(resolved["loading"]["initial_velocity"], "VH");
  EXPECT_FALSE(resolved["loading"].contains("ramp_time"));
  EXPECT_EQ(toJson(parseDynamicTensionSpec(resolved)), resolved);

  nlohmann::json full = readJson(examplePath("dynamic-tension-seed.json"));
  full["loading"]["ramp_time"] = 2e-9;
  full["loading"]["wave_speed"] = 5000.0;
  full["loading"]["vh_capture_strain"] = 1e-4;
  full["run"]["snapshot_strains"] = {4e-4, 0.0, 4e-4};
  full["run"]["stop_fraction"] = 0.2;
  const DynamicTensionSpec f = parseDynamicTensionSpec(full);
  EXPECT_EQ(f.run.snapshotStrains, (std::vector<double>{0.0, 4e-4}));  // sorted, duplicates dropped
  const nlohmann::json fr = toJson(f);
  EXPECT_EQ(fr["loading"]["ramp_time"], 2e-9);
  EXPECT_EQ(fr["run"]["stop_fraction"], 0.2);
  EXPECT_EQ(toJson(parseDynamicTensionSpec(fr)), fr);
}

// Every property the schema declares is accepted by the parser (with its default, or a valid
// value), and the schema lists every key the resolved spec has.
TEST(DynamicTensionSpec, SchemaAgreesWithTheParser) {
  const nlohmann::json schema = scenarioSchema("dynamic-tension");
  EXPECT_EQ(schema["$schema"], "https://json-schema.org/draft/2020-12/schema");
  EXPECT_FALSE(schema["additionalProperties"].get<bool>());
  const nlohmann::json& props = schema["properties"];
  const nlohmann::json valid = {{"ramp_time", 1e-9},  {"wave_speed", 5000.0}, {"vh_capture_strain", 1e-4},
                                {"output_interval", 1e-12}, {"snapshot_strains", {1e-4}}, {"stop_fraction", 0.1}};
  for (const char* section : {"loading", "run", "output"}) {
    const nlohmann::json& sectionProps = props[section]["properties"];
    EXPECT_FALSE(props[section]["additionalProperties"].get<bool>()) << section;
    for (const auto& [key, def] : sectionProps.items()) {
      SCOPED_TRACE(std::string(section) + "." + key);
      EXPECT_NE(def["description"].get<std::string>(), "");
      nlohmann::json spec = minimalSpec();
      if (def.contains("default")) spec[section][key] = def["default"];
      else if (valid.contains(key)) spec[section][key] = valid[key];
      else if (key == "strain_rate") spec[section][key] = 1e6;
      else FAIL() << "no test value";
      EXPECT_EQ(rejectedField(spec), "");
    }
  }
  nlohmann::json resolved = toJson(parseDynamicTensionSpec(readJson(examplePath("dynamic-tension-seed.json"))));
  for (const auto& [key, value] : resolved.items()) {
    EXPECT_TRUE(props.contains(key)) << key;
    if (!value.is_object()) continue;
    for (const auto& [sub, unused] : value.items()) {
      EXPECT_TRUE(props[key]["properties"].contains(sub)) << key << "." << sub;
    }
  }
}

}  // namespace
}  // namespace rupture::test
