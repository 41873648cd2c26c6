// The tank-impact spec (issue 11): the seed's defaults, the overrides, the errors that name their
// field, the schema's documented defaults against the parser's, and every example file.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "io/unknown_keys.hpp"
#include "rupture/spec_error.hpp"
#include "scenarios/scenario.hpp"
#include "scenarios/tank_impact/tank_impact_spec.hpp"

namespace rupture {
namespace {

nlohmann::json minimal() { return {{"scenario", "tank-impact"}, {"resolution", {{"spacing", 0.004}}}}; }

nlohmann::json schema() { return nlohmann::json::parse(embeddedSchema("tank-impact")); }

std::string fieldOf(const nlohmann::json& spec) {
  try {
    parseTankImpactSpec(spec);
  } catch (const SpecError& e) {
    return e.field();
  }
  return "(no error)";
}

TEST(TankImpactSpec, DefaultsAreTheSeedsTest) {
  const TankImpactSpec s = parseTankImpactSpec(minimal());
  EXPECT_DOUBLE_EQ(s.innerDiameter, 0.08);                       // D_cyl = 80 mm
  EXPECT_DOUBLE_EQ(s.plate.diameter, 0.08);                      // spot face Ø 80 mm
  EXPECT_DOUBLE_EQ(s.plate.shell.thickness, 0.002);              // thin specimen
  EXPECT_NEAR(s.waterHeight, 0.203, 1e-15);                      // H = 205 mm − e_p
  EXPECT_DOUBLE_EQ(s.impactor.mass, 245.0);
  EXPECT_DOUBLE_EQ(s.impactor.speed, 5.0);
  EXPECT_DOUBLE_EQ(s.soundSpeed, 1450.0);                        // Table 3
  EXPECT_DOUBLE_EQ(s.fluid.density, 1000.0);
  EXPECT_DOUBLE_EQ(s.fluid.alpha, 0.3);
  EXPECT_DOUBLE_EQ(s.run.endTime, 3e-3);
  EXPECT_EQ(s.contact.method, ContactMethod::Pinball);
  EXPECT_EQ(s.plate.materialPreset, "au4g_2024_t351_seed");
  EXPECT_DOUBLE_EQ(s.plate.shell.density, 2780.0);               // Table 1
  EXPECT_DOUBLE_EQ(s.plate.shell.material.youngModulus, 73.1e9);
  EXPECT_DOUBLE_EQ(s.plate.shell.material.poissonRatio, 0.33);
  EXPECT_DOUBLE_EQ(s.plate.shell.damageLaw.thresholdPlasticStrain, 0.03);  // Table 6
  EXPECT_DOUBLE_EQ(s.plate.shell.damageLaw.criticalPlasticStrain, 0.25);
  EXPECT_DOUBLE_EQ(s.plate.shell.damageLaw.criticalDamage, 0.23);
  EXPECT_DOUBLE_EQ(s.plate.shell.damageLaw.delayTime, 1e-7);
  EXPECT_DOUBLE_EQ(s.plate.shell.damageLaw.delaySharpness, 2.0);
  EXPECT_TRUE(s.plate.shell.damage);
  EXPECT_EQ(s.plate.shell.thicknessPoints, 5);
  EXPECT_DOUBLE_EQ(s.plate.shell.fractureLayerFraction, 1.0);  // every layer, "fully damaged" (§5.3.1)
  EXPECT_DOUBLE_EQ(s.plate.shell.stepRotaryInertia, 1.0);      // the least that keeps the step's time step
  // The shell's step from its measured spectrum, at the single rate (the faster with it).
  EXPECT_EQ(s.plate.shell.stepEstimate, ShellParameters::StepEstimate::Spectral);
  EXPECT_FALSE(s.plate.shell.subcycling);
  EXPECT_DOUBLE_EQ(s.plate.spacing, 0.004);  // the fluid spacing
  EXPECT_EQ(s.plate.precrack.shape, PrecrackShape::None);
  EXPECT_DOUBLE_EQ(s.gauge[0], 0.035);
  EXPECT_DOUBLE_EQ(s.gauge[2], 0.001 + 0.010);  // 10 mm above the plate's upper face z = t/2
  // Particles: the column π R² H / dx³ = 15,944, plus wall layers and plate nodes.
  const double column = std::numbers::pi * 0.04 * 0.04 * 0.203 / std::pow(0.004, 3);
  EXPECT_GT(s.estimatedParticles, column);
  EXPECT_LT(s.estimatedParticles, 3.0 * column);
}

TEST(TankImpactSpec, WaterHeightFollowsThePlateThickness) {
  nlohmann::json j = minimal();
  j["plate"] = {{"thickness", 0.025}};  // the thick E specimens
  EXPECT_NEAR(parseTankImpactSpec(j).waterHeight, 0.180, 1e-15);
  EXPECT_NEAR(parseTankImpactSpec(j).gauge[2], 0.0125 + 0.010, 1e-15);
  j["probes"] = {{0.0, 0.0, 0.010}};  // inside the 25 mm plate (its upper face is at z = 12.5 mm)
  EXPECT_EQ(fieldOf(j), "probes[0]");
  j.erase("probes");
  j["tank"] = {{"water_height", 0.15}};
  EXPECT_DOUBLE_EQ(parseTankImpactSpec(j).waterHeight, 0.15);
}

TEST(TankImpactSpec, MaterialOverridesAndPrecrackDefaults) {
  nlohmann::json j = minimal();
  j["plate"] = {{"material", {{"preset", "au4g_2024_t351"}, {"young_modulus", 70e9}, {"critical_damage", 0.4},
                              {"delay_time", 2e-7}, {"hardening", "linear"}, {"hardening_exponent", 1.0}}},
                {"layers", 3},
                {"fracture_layer_fraction", 0.4},
                {"step_rotary_inertia", 0.04},
                {"spacing", 0.001},
                {"precrack", {{"shape", "hole+cracks"}}}};
  const TankImpactSpec s = parseTankImpactSpec(j);
  EXPECT_DOUBLE_EQ(s.plate.shell.density, 2770.0);  // the preset's
  EXPECT_DOUBLE_EQ(s.plate.shell.material.youngModulus, 70e9);
  EXPECT_DOUBLE_EQ(s.plate.shell.damageLaw.criticalDamage, 0.4);
  EXPECT_DOUBLE_EQ(s.plate.shell.damageLaw.delayTime, 2e-7);
  EXPECT_DOUBLE_EQ(s.plate.shell.damageLaw.criticalPlasticStrain, 0.21);  // the preset's
  EXPECT_EQ(s.plate.shell.material.hardening.kind, HardeningKind::linear);
  EXPECT_EQ(s.plate.shell.thicknessPoints, 3);
  EXPECT_DOUBLE_EQ(s.plate.shell.fractureLayerFraction, 0.4);
  EXPECT_DOUBLE_EQ(s.plate.shell.stepRotaryInertia, 0.04);
  EXPECT_EQ(layersToFracture(s.plate.shell.fractureLayerFraction, s.plate.shell.thicknessPoints), 2);  // ⌈1.2⌉
  EXPECT_DOUBLE_EQ(s.plate.precrack.holeDiameter, 0.014);  // F14E3A5: hole 14 mm, two 3 mm cracks
  EXPECT_DOUBLE_EQ(s.plate.precrack.length, 0.003);
  EXPECT_EQ(s.plate.precrack.crackCount, 2);
  j["plate"]["precrack"] = {{"shape", "U"}};
  const TankImpactSpec u = parseTankImpactSpec(j);
  EXPECT_DOUBLE_EQ(u.plate.precrack.length, 0.020);
  EXPECT_DOUBLE_EQ(u.plate.precrack.width, 0.020);
  j["plate"]["precrack"] = {{"shape", "X"}};
  EXPECT_DOUBLE_EQ(parseTankImpactSpec(j).plate.precrack.length, 0.030);
}

TEST(TankImpactSpec, ErrorsNameTheField) {
  auto with = [](const nlohmann::json& patch) {
    nlohmann::json j = minimal();
    j.merge_patch(patch);
    return j;
  };
  EXPECT_EQ(fieldOf(with({{"plate", {{"precrack", {{"shape", "X"}, {"width", 0.01}}}}}})), "plate.precrack.width");
  EXPECT_EQ(fieldOf(with({{"plate", {{"precrack", {{"shape", "V"}}}}}})), "plate.precrack.shape");
  EXPECT_EQ(fieldOf(with({{"plate", {{"precrack", {{"shape", "I"}, {"length", 0.09}}}}}})), "plate.precrack.length");
  EXPECT_EQ(fieldOf(with({{"plate", {{"precrack", {{"shape", "hole"}, {"hole_diameter", 0.08}}}}}})),
            "plate.precrack.hole_diameter");
  EXPECT_EQ(fieldOf(with({{"plate", {{"material", {{"preset", "aluminium"}}}}}})), "plate.material.preset");
  EXPECT_EQ(fieldOf(with({{"plate", {{"material", {{"poisson_ratio", 0.5}}}}}})), "plate.material.poisson_ratio");
  EXPECT_EQ(fieldOf(with({{"plate", {{"material", {{"critical_plastic_strain", 0.01}}}}}})),
            "plate.material.critical_plastic_strain");  // below the threshold 0.03 (validateDamage)
  EXPECT_EQ(fieldOf(with({{"plate", {{"material", {{"initial_yield_stress", 0.0}}}}}})), "plate.material.initial_yield_stress");
  EXPECT_EQ(fieldOf(with({{"plate", {{"plasticity", false}}}})), "plate.damage");
  EXPECT_EQ(fieldOf(with({{"plate", {{"fracture_layer_fraction", 0.0}}}})), "plate.fracture_layer_fraction");
  EXPECT_EQ(fieldOf(with({{"plate", {{"fracture_layer_fraction", 1.5}}}})), "plate.fracture_layer_fraction");
  EXPECT_EQ(fieldOf(with({{"plate", {{"step_rotary_inertia", 0.0}}}})), "plate.step_rotary_inertia");
  EXPECT_EQ(fieldOf(with({{"plate", {{"step_rotary_inertia", -1.0}}}})), "plate.step_rotary_inertia");
  EXPECT_EQ(fieldOf(with({{"plate", {{"diameter", 0.1}}}})), "plate.diameter");
  EXPECT_EQ(fieldOf(with({{"plate", {{"spacing", 0.02}}}})), "plate.spacing");
  EXPECT_EQ(fieldOf(with({{"plate", {{"clamp", "edge"}}}})), "plate.clamp");
  EXPECT_EQ(fieldOf(with({{"plate", {{"clamp", "rim"}, {"bottom", {{"thickness", 0.025}}}}}})), "plate.bottom");
  EXPECT_EQ(fieldOf(with({{"plate", {{"bottom", {{"thickness", 0.001}}}}}})), "plate.bottom.thickness");  // below e_p
  EXPECT_EQ(fieldOf(with({{"plate", {{"bottom", {{"clamp_diameter", 0.085}}}}}})), "plate.bottom.clamp_diameter");
  EXPECT_EQ(fieldOf(with({{"plate", {{"spacing", 0.002}, {"bottom", {{"step_spacing", 0.003}}}}}})), "plate.bottom.step_spacing");
  // A plate refined at the step needs the master–slave surface (the pinballs are one spacing wide).
  EXPECT_EQ(fieldOf(with({{"plate", {{"spacing", 0.002}, {"bottom", {{"step_spacing", 0.001}}}}}})), "plate.bottom.step_spacing");
  EXPECT_NO_THROW(parseTankImpactSpec(with({{"plate", {{"spacing", 0.002}, {"bottom", {{"step_spacing", 0.001}}}}},
                                            {"contact", {{"method", "master_slave"}}}})));
  EXPECT_EQ(fieldOf(with({{"resolution", {{"spacing", 0.0003}}}})), "resolution.spacing");  // ~1e8 particles
  EXPECT_EQ(fieldOf(with({{"gauge", {0.05, 0.0, 0.01}}})), "gauge");                        // in the wall
  EXPECT_EQ(fieldOf(with({{"probes", {{0.0, 0.0, 0.5}}}})), "probes[0]");                   // above the water
  EXPECT_EQ(fieldOf(with({{"contact", {{"method", "penalty"}}}})), "contact.method");
  EXPECT_EQ(fieldOf(with({{"impactor", {{"mass", -1.0}}}})), "impactor.mass");
  // Unknown keys: from the schema, with the nearest allowed key.
  try {
    io::rejectUnknownKeys(with({{"plate", {{"thicknes", 0.002}}}}), schema());
    FAIL() << "no error";
  } catch (const SpecError& e) {
    EXPECT_EQ(e.field(), "plate.thicknes");
    EXPECT_NE(e.allowed().find("thickness"), std::string::npos) << e.allowed();
  }
  EXPECT_EQ(fieldOf(with({{"plate", {{"thicknes", 0.002}}}})), "plate.thicknes");
}

// `specimen` (Table 4): the specimen's plate and speed under the spec's own keys.
TEST(TankImpactSpec, SpecimenSetsItsTestUnderTheSpecsKeys) {
  nlohmann::json spec = minimal();
  spec["specimen"] = "E14A5";
  TankImpactSpec s = parseTankImpactSpec(spec);
  EXPECT_EQ(s.specimen, "E14A5");
  EXPECT_DOUBLE_EQ(s.plate.shell.thickness, 0.025);
  EXPECT_NEAR(s.waterHeight, 0.180, 1e-15);  // 205 mm − e_p
  EXPECT_EQ(s.plate.precrack.shape, PrecrackShape::Hole);
  EXPECT_DOUBLE_EQ(s.plate.precrack.holeDiameter, 0.014);
  EXPECT_DOUBLE_EQ(s.impactor.speed, 5.0);
  // The spec's values win; a pre-crack it gives replaces the specimen's whole.
  spec["impactor"] = {{"speed", 3.0}};
  spec["plate"] = {{"precrack", {{"shape", "U"}}}, {"spacing", 0.002}};
  s = parseTankImpactSpec(spec);
  EXPECT_DOUBLE_EQ(s.impactor.speed, 3.0);
  EXPECT_DOUBLE_EQ(s.plate.shell.thickness, 0.025);
  EXPECT_EQ(s.plate.precrack.shape, PrecrackShape::U);
  EXPECT_DOUBLE_EQ(s.plate.precrack.width, 0.020);
  // F14E3A5's 3 mm cracks need the 1 mm plate spacing; TFA5 has no pre-crack; FUA2 is at 2 m/s.
  spec = minimal();
  spec["specimen"] = "F14E3A5";
  s = parseTankImpactSpec(spec);
  EXPECT_DOUBLE_EQ(s.plate.spacing, 0.001);
  EXPECT_EQ(s.plate.precrack.shape, PrecrackShape::HoleAndCracks);
  spec["specimen"] = "TFA5";
  s = parseTankImpactSpec(spec);
  EXPECT_EQ(s.plate.precrack.shape, PrecrackShape::None);
  EXPECT_DOUBLE_EQ(s.plate.shell.thickness, 0.001);
  spec["specimen"] = "FUA2";
  EXPECT_DOUBLE_EQ(parseTankImpactSpec(spec).impactor.speed, 2.0);
  // The resolved spec names the specimen and reads back to itself.
  const nlohmann::json resolved = toJson(parseTankImpactSpec(spec));
  EXPECT_EQ(resolved["specimen"], "FUA2");
  EXPECT_EQ(toJson(parseTankImpactSpec(resolved)), resolved);
  // An unknown one names the field and lists the specimens.
  spec["specimen"] = "E14A9";
  EXPECT_EQ(fieldOf(spec), "specimen");
  try {
    parseTankImpactSpec(spec);
  } catch (const SpecError& e) {
    EXPECT_NE(std::string(e.what()).find("TF14A5"), std::string::npos) << e.what();
  }
  spec["specimen"] = 3;
  EXPECT_EQ(fieldOf(spec), "specimen");
}

// The impactor's keys within the tank's spec: the model, the piston, their errors.
TEST(TankImpactSpec, ImpactorModelAndPiston) {
  nlohmann::json spec = minimal();
  EXPECT_EQ(parseTankImpactSpec(spec).impactor.model, fsi::ImpactorModel::ElasticPiston);
  EXPECT_DOUBLE_EQ(parseTankImpactSpec(spec).impactor.pistonDiameter, 0.08);  // the bore
  spec["tank"] = {{"inner_diameter", 0.06}};
  EXPECT_DOUBLE_EQ(parseTankImpactSpec(spec).impactor.pistonDiameter, 0.06);
  spec["impactor"] = {{"model", "rigid"}};
  EXPECT_EQ(parseTankImpactSpec(spec).impactor.model, fsi::ImpactorModel::Rigid);
  spec["impactor"]["piston"] = {{"length", 0.1}};
  EXPECT_EQ(fieldOf(spec), "impactor.piston");
  spec["impactor"] = {{"piston", {{"length", 0.0}}}};
  EXPECT_EQ(fieldOf(spec), "impactor.piston.length");
  // The default impactor is checked as a given one: a run it could not finish names the run's length.
  spec = minimal();
  spec["run"] = {{"end_time", 1e4}};
  EXPECT_EQ(fieldOf(spec), "run.end_time");
}

TEST(TankImpactSpec, ResolvedSpecReadsBackToItself) {
  nlohmann::json j = minimal();
  j["description"] = "FXA5";
  j["plate"] = {{"spacing", 0.002}, {"precrack", {{"shape", "X"}}}};
  j["probes"] = {{0.0, 0.0, 0.1}};
  j["contact"] = {{"method", "master_slave"}};
  const nlohmann::json resolved = toJson(parseTankImpactSpec(j));
  EXPECT_EQ(toJson(parseTankImpactSpec(resolved)), resolved);
  EXPECT_NO_THROW(io::rejectUnknownKeys(resolved, schema()));
}

// ---- The schema against the parser ------------------------------------------------------------

/// Every "default" the schema documents (inside objects reached through "properties"), with its path.
void collectDefaults(const nlohmann::json& node, const std::string& path, std::vector<std::pair<std::string, nlohmann::json>>& out) {
  if (node.contains("default") && !path.empty()) out.emplace_back(path, node["default"]);
  if (node.contains("properties"))
    for (auto it = node["properties"].begin(); it != node["properties"].end(); ++it)
      collectDefaults(it.value(), path + "/" + it.key(), out);
}

TEST(TankImpactSchema, DocumentedDefaultsAreTheParsersDefaults) {
  std::vector<std::pair<std::string, nlohmann::json>> defaults;
  collectDefaults(schema(), "", defaults);
  ASSERT_GT(defaults.size(), 20u);
  // The precrack's sizes depend on the shape: resolve them with the shape that has each.
  nlohmann::json withCracks = minimal();
  withCracks["plate"] = {{"spacing", 0.001}, {"precrack", {{"shape", "hole+cracks"}}}};
  const nlohmann::json plain = toJson(parseTankImpactSpec(minimal())), cracked = toJson(parseTankImpactSpec(withCracks));
  for (const auto& [path, value] : defaults) {
    SCOPED_TRACE(path);
    const nlohmann::json& resolved = path.rfind("/plate/precrack/", 0) == 0 ? cracked : plain;
    const nlohmann::json::json_pointer pointer(path);
    ASSERT_TRUE(resolved.contains(pointer));
    if (value.is_number())
      EXPECT_DOUBLE_EQ(resolved[pointer].get<double>(), value.get<double>());
    else
      EXPECT_EQ(resolved[pointer], value);
  }
}

/// Every number (or array of numbers) in the schema states its unit.
void expectUnits(const nlohmann::json& node, const std::string& path) {
  const auto type = node.value("type", std::string());
  const bool numeric = type == "number" || type == "integer" ||
                       (type == "array" && node.contains("items") && node["items"].value("type", std::string()) != "object");
  if (numeric) { EXPECT_TRUE(node.contains("x-unit")) << path; }
  if (numeric) { EXPECT_TRUE(node.contains("description")) << path; }
  if (node.contains("properties"))
    for (auto it = node["properties"].begin(); it != node["properties"].end(); ++it) expectUnits(it.value(), path + "." + it.key());
}

TEST(TankImpactSchema, EveryNumberHasAUnitAndADescription) { expectUnits(schema(), ""); }

/// The subset of JSON Schema the scenario schemas use: type, const, enum, bounds, array lengths,
/// required, properties (additionalProperties false is rejectUnknownKeys' job).
void validate(const nlohmann::json& v, const nlohmann::json& s, const std::string& path) {
  SCOPED_TRACE(path);
  const std::string type = s.value("type", std::string());
  if (type == "object") {
    ASSERT_TRUE(v.is_object());
    for (const auto& key : s.value("required", nlohmann::json::array())) EXPECT_TRUE(v.contains(key.get<std::string>())) << key;
    for (auto it = v.begin(); it != v.end(); ++it)
      if (s.contains("properties") && s["properties"].contains(it.key())) validate(it.value(), s["properties"][it.key()], path + "." + it.key());
  }
  if (type == "number") { EXPECT_TRUE(v.is_number()); }
  if (type == "integer") { EXPECT_TRUE(v.is_number_integer()); }
  if (type == "boolean") { EXPECT_TRUE(v.is_boolean()); }
  if (type == "string") { EXPECT_TRUE(v.is_string()); }
  if (type == "array") {
    ASSERT_TRUE(v.is_array());
    if (s.contains("minItems")) { EXPECT_GE(v.size(), s["minItems"].get<std::size_t>()); }
    if (s.contains("maxItems")) { EXPECT_LE(v.size(), s["maxItems"].get<std::size_t>()); }
    if (s.contains("items"))
      for (std::size_t k = 0; k < v.size(); ++k) validate(v[k], s["items"], path + "." + std::to_string(k));
  }
  if (s.contains("const")) { EXPECT_EQ(v, s["const"]); }
  if (s.contains("enum")) { EXPECT_NE(std::find(s["enum"].begin(), s["enum"].end(), v), s["enum"].end()) << v; }
  if (v.is_number()) {
    const double x = v.get<double>();
    if (s.contains("minimum")) { EXPECT_GE(x, s["minimum"].get<double>()); }
    if (s.contains("maximum")) { EXPECT_LE(x, s["maximum"].get<double>()); }
    if (s.contains("exclusiveMinimum")) { EXPECT_GT(x, s["exclusiveMinimum"].get<double>()); }
    if (s.contains("exclusiveMaximum")) { EXPECT_LT(x, s["exclusiveMaximum"].get<double>()); }
  }
}

// Every examples/tank-impact-*.json has only keys the schema knows, meets the schema's types and
// bounds, parses, and its resolved spec does too.
TEST(TankImpactSchema, EveryExampleValidatesAndParses) {
  const std::filesystem::path dir = std::filesystem::path(RUPTURE_SOURCE_DIR) / "examples";
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("tank-impact-", 0) != 0 || entry.path().extension() != ".json") continue;
    SCOPED_TRACE(name);
    std::ifstream in(entry.path());
    const nlohmann::json spec = nlohmann::json::parse(in);
    EXPECT_NO_THROW(io::rejectUnknownKeys(spec, schema()));
    validate(spec, schema(), "");
    TankImpactSpec parsed;
    ASSERT_NO_THROW(parsed = parseTankImpactSpec(spec));
    validate(toJson(parsed), schema(), "(resolved)");
    EXPECT_LE(parsed.estimatedParticles, 5e6);
    ++count;
  }
  EXPECT_GE(count, 8);
}

}  // namespace
}  // namespace rupture
