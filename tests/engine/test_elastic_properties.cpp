// The elastic-properties scenario: runSpec measures E and ν exactly as measureElasticProperties does
// on the same sample, writes every documented attribute, fits the beams to a target, rejects bad
// specs naming the field, leaves a valid incomplete file when cancelled, and works through the CLI.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "support/test_support.hpp"
#include "engine/test_elastic_properties_support.hpp"
#include "../cli/cli_runner.hpp"
#include "calibration/calibration.hpp"
#include "samples/sample_builder.hpp"
#include "bonded/bonded_spec.hpp"
#include "io/hdf5_file.hpp"
#include "io/spec_reader.hpp"
#include "rupture/run.hpp"
#include "scenarios/elastic_properties/elastic_properties.hpp"
#include "scenarios/elastic_properties/elastic_properties_results.hpp"

namespace rupture {
namespace {

namespace fs = std::filesystem;
using rupture::testing::ScratchDir;
using rupture::testing::rejectedField;

nlohmann::json smallSpec() { return test::smallBeamElasticPropertiesSpec(); }

const std::vector<std::string> kAlways = {"young_modulus", "poisson_ratio", "converged", "relaxation_steps",
                                          "elements",      "bonds",         "mean_coordination", "porosity",
                                          "wall_time_s",   "completed",     "tensile_strength",
                                          "crack_onset_strain", "strain_at_peak"};
const std::vector<std::string> kWithTarget = {"beam_young_modulus", "beam_radius_ratio", "target_young_modulus",
                                              "target_poisson_ratio", "evaluations"};

/// Every listed /summary attribute is there with its unit, and equals the returned summary.
void expectSummaryInFile(const io::Hdf5File& file, const nlohmann::json& summary,
                         const std::vector<std::string>& names) {
  const auto& units = declaredUnits<elasticPropertiesSummaryFields>();
  for (const std::string& name : names) {
    SCOPED_TRACE(name);
    ASSERT_TRUE(file.hasAttribute("/summary", name));
    ASSERT_TRUE(file.hasAttribute("/summary", name + "_unit"));
    ASSERT_TRUE(units.count(name));
    EXPECT_EQ(file.readAttributeString("/summary", name + "_unit"), units.at(name));
    ASSERT_TRUE(summary.contains(name));
    if (summary[name].is_number()) {
      EXPECT_DOUBLE_EQ(file.readAttributeDouble("/summary", name), summary[name].get<double>());
    }
  }
}

TEST(ElasticPropertiesScenario, IsRegisteredWithItsSchema) {
  bool found = false;
  for (const ScenarioInfo& s : listScenarios()) found = found || s.name == "elastic-properties";
  EXPECT_TRUE(found);
  const nlohmann::json schema = scenarioSchema("elastic-properties");
  EXPECT_EQ(schema["$schema"], "https://json-schema.org/draft/2020-12/schema");
  EXPECT_EQ(schema["properties"]["scenario"]["const"], "elastic-properties");
  EXPECT_FALSE(schema["additionalProperties"].get<bool>());
  // The bonded part is the same text as dynamic-tension's.
  const nlohmann::json other = scenarioSchema("dynamic-tension");
  for (const char* key : {"dimension", "sample", "material", "description"}) {
    EXPECT_EQ(schema["properties"][key], other["properties"][key]) << key;
  }
  // The schema lists every key of the resolved spec, and its defaults are the parser's.
  nlohmann::json spec = smallSpec();
  spec["target"] = {{"young_modulus", 150e9}, {"poisson_ratio", 0.4}};
  const nlohmann::json resolved = toJson(parseElasticPropertiesSpec(spec));
  for (const auto& [key, value] : resolved.items()) {
    ASSERT_TRUE(schema["properties"].contains(key)) << key;
    if (!value.is_object()) continue;
    for (const auto& [sub, unused] : value.items()) {
      EXPECT_TRUE(schema["properties"][key]["properties"].contains(sub)) << key << "." << sub;
    }
  }
  for (const auto& [key, def] : schema["properties"]["calibration"]["properties"].items()) {
    EXPECT_EQ(def["default"], resolved["calibration"][key]) << key;
  }
  EXPECT_EQ(toJson(parseElasticPropertiesSpec(resolved)), resolved);  // round trip
}

TEST(ElasticPropertiesScenario, InvalidSpecsNameTheField) {
  EXPECT_EQ(rejectedField(smallSpec()), "");
  nlohmann::json s = smallSpec();
  s["bogus"] = 1;
  EXPECT_EQ(rejectedField(s), "bogus");
  s = smallSpec();
  s["target"] = {{"young_modulus", 150e9}};
  EXPECT_EQ(rejectedField(s), "target.poisson_ratio");
  s = smallSpec();
  s["target"] = {{"tensile_strength", -1.0}};
  EXPECT_EQ(rejectedField(s), "target.tensile_strength");
  s["target"] = nlohmann::json::object();
  EXPECT_EQ(rejectedField(s), "target");
  s["target"] = {{"young_modulus", 150e9}, {"poisson_ratio", 0.4}, {"extra", 1}};
  EXPECT_EQ(rejectedField(s), "target.extra");
  s = smallSpec();
  s["target"] = {{"young_modulus", -1.0}, {"poisson_ratio", 0.4}};
  EXPECT_EQ(rejectedField(s), "target.young_modulus");
  s = smallSpec();
  s["target"] = {{"young_modulus", 150e9}, {"poisson_ratio", 0.5}};
  EXPECT_EQ(rejectedField(s), "target.poisson_ratio");
  s = smallSpec();
  s["sample"]["porosity"] = 0.9;
  EXPECT_EQ(rejectedField(s), "sample.porosity");
  s = smallSpec();
  s["calibration"] = {{"strain", 0.0}};
  EXPECT_EQ(rejectedField(s), "calibration.strain");
  s = smallSpec();
  s["calibration"] = {{"damping", 0.7}, {"steps", 10}};
  EXPECT_EQ(rejectedField(s), "calibration.steps");
  s = smallSpec();
  s["material"]["beam"]["colour"] = "red";
  EXPECT_EQ(rejectedField(s), "material.beam.colour");
  // runSpec validates too, and writes nothing.
  ScratchDir dir;
  RunControl control;
  s = smallSpec();
  s["sample"]["porosity"] = 0.9;
  EXPECT_THROW(runSpec(s, (dir.path() / "bad.h5").string(), control), SpecError);
  EXPECT_FALSE(fs::exists(dir.path() / "bad.h5"));
  EXPECT_FALSE(fs::exists(dir.path() / "bad.h5.part"));
}

TEST(ElasticPropertiesScenario, MeasuresLikeTheCalibrationAndWritesEveryAttribute) {
  ScratchDir dir;
  const fs::path out = dir.path() / "ep.h5";
  RunControl control;
  const RunOutcome r = runSpec(smallSpec(), out.string(), control);
  EXPECT_TRUE(r.completed);
  EXPECT_DOUBLE_EQ(control.progress.load(), 1.0);
  const double E = r.summary["young_modulus"].get<double>(), nu = r.summary["poisson_ratio"].get<double>();
  EXPECT_GT(E, 0);
  EXPECT_GT(nu, 0);
  EXPECT_LT(nu, 1);
  EXPECT_EQ(r.summary["converged"], 1);
  EXPECT_EQ(r.summary["completed"], 1);
  EXPECT_FALSE(r.summary.contains("evaluations"));

  // The same sample measured directly.
  const nlohmann::json spec = smallSpec();
  const io::SpecReader root(spec, "");
  const SampleSpec sampleSpec = io::parseSample(root);
  const MaterialSpec material = io::parseMaterial(root);
  BondedSystem sample;
  const SampleReport report = buildSample(sampleSpec, material, sample);
  const ElasticProperties direct = measureElasticProperties(sample, sampleSpec);
  EXPECT_NEAR(E, direct.youngModulus, 1e-9 * std::abs(direct.youngModulus));
  EXPECT_NEAR(nu, direct.poissonRatio, 1e-9 * std::abs(direct.poissonRatio));
  EXPECT_EQ(r.summary["relaxation_steps"].get<std::int64_t>(), static_cast<std::int64_t>(direct.steps));
  EXPECT_EQ(r.summary["elements"].get<std::int64_t>(), static_cast<std::int64_t>(report.elements));
  EXPECT_EQ(r.summary["bonds"].get<std::int64_t>(), static_cast<std::int64_t>(report.bonds));
  // The strength figures are those of the quasi-static strength test on the same sample.
  const StrengthResult strength = measureTensileStrength(sample, sampleSpec);
  EXPECT_NEAR(r.summary["tensile_strength"].get<double>(), strength.tensileStrength, 1e-9 * strength.tensileStrength);
  EXPECT_NEAR(r.summary["crack_onset_strain"].get<double>(), strength.crackOnsetStrain, 1e-9 * strength.crackOnsetStrain);
  EXPECT_GT(strength.tensileStrength, 0.9 * E * strength.crackOnsetStrain);

  ASSERT_TRUE(fs::exists(out));
  EXPECT_FALSE(fs::exists(out.string() + ".part"));
  const io::Hdf5File file = io::Hdf5File::openReadOnly(out.string());
  EXPECT_EQ(file.readAttributeString("/", "scenario"), "elastic-properties");
  EXPECT_EQ(file.readAttributeString("/", "rupture_version"), RUPTURE_VERSION);
  EXPECT_EQ(file.readAttributeInt("/", "completed"), 1);
  EXPECT_EQ(file.readAttributeInt("/summary", "completed"), 1);
  EXPECT_EQ(file.readAttributeInt("/summary", "converged"), 1);
  const nlohmann::json resolved = nlohmann::json::parse(file.readAttributeString("/spec", "json"));
  EXPECT_EQ(resolved, toJson(parseElasticPropertiesSpec(spec)));
  EXPECT_EQ(resolved["calibration"]["strain"], 1e-4);
  EXPECT_EQ(nlohmann::json::parse(file.readAttributeString("/spec", "input")), spec);
  expectSummaryInFile(file, r.summary, kAlways);
  for (const std::string& name : kWithTarget) {
    EXPECT_FALSE(file.hasAttribute("/summary", name)) << name;
  }
}

TEST(ElasticPropertiesScenario, FitsTheBeamsToATarget) {
  ScratchDir dir;
  const fs::path out = dir.path() / "fit.h5";
  nlohmann::json spec = smallSpec();
  spec["target"] = {{"young_modulus", 150e9}, {"poisson_ratio", 0.4}};
  RunControl control;
  const RunOutcome r = runSpec(spec, out.string(), control);
  ASSERT_TRUE(r.completed);
  EXPECT_NEAR(r.summary["young_modulus"].get<double>(), 150e9, 0.05 * 150e9);
  EXPECT_NEAR(r.summary["poisson_ratio"].get<double>(), 0.4, 0.05 * 0.4);
  EXPECT_GT(r.summary["beam_young_modulus"].get<double>(), 0);
  EXPECT_GT(r.summary["beam_radius_ratio"].get<double>(), 0.02);
  EXPECT_LE(r.summary["beam_radius_ratio"].get<double>(), 1.0);
  EXPECT_EQ(r.summary["target_young_modulus"], 150e9);
  EXPECT_EQ(r.summary["target_poisson_ratio"], 0.4);
  EXPECT_GE(r.summary["evaluations"].get<int>(), 2);
  EXPECT_LE(r.summary["evaluations"].get<int>(), kMaxFitEvaluations);
  EXPECT_DOUBLE_EQ(control.progress.load(), 1.0);
  const io::Hdf5File file = io::Hdf5File::openReadOnly(out.string());
  EXPECT_EQ(file.readAttributeInt("/", "completed"), 1);
  expectSummaryInFile(file, r.summary, kAlways);
  expectSummaryInFile(file, r.summary, kWithTarget);
}

TEST(ElasticPropertiesScenario, CancelledRunLeavesAValidIncompleteFile) {
  for (const bool withTarget : {false, true}) {
    SCOPED_TRACE(withTarget ? "fit" : "measurement");
    ScratchDir dir;
    const fs::path out = dir.path() / "cancelled.h5";
    nlohmann::json spec = smallSpec();
    if (withTarget) spec["target"] = {{"young_modulus", 150e9}, {"poisson_ratio", 0.4}};
    RunControl control;
    control.cancel = true;
    const RunOutcome r = runSpec(spec, out.string(), control);
    EXPECT_FALSE(r.completed);
    EXPECT_EQ(r.summary["completed"], 0);
    EXPECT_EQ(r.summary["converged"], 0);
    ASSERT_TRUE(fs::exists(out));
    EXPECT_FALSE(fs::exists(out.string() + ".part"));
    const io::Hdf5File file = io::Hdf5File::openReadOnly(out.string());
    EXPECT_EQ(file.readAttributeString("/", "scenario"), "elastic-properties");
    EXPECT_EQ(file.readAttributeInt("/", "completed"), 0);
    EXPECT_EQ(file.readAttributeInt("/summary", "completed"), 0);
    EXPECT_TRUE(file.hasAttribute("/spec", "json"));
    for (const std::string& name : kAlways) {
      EXPECT_TRUE(file.hasAttribute("/summary", name)) << name;
    }
    if (!withTarget) continue;
    for (const std::string& name : kWithTarget) {
      EXPECT_TRUE(file.hasAttribute("/summary", name)) << name;
    }
  }
}

TEST(ElasticPropertiesScenario, CancelStopsAMeasurementAndAFit) {
  nlohmann::json spec = smallSpec();
  const io::SpecReader root(spec, "");
  const SampleSpec sampleSpec = io::parseSample(root);
  BondedSystem sample;
  buildSample(sampleSpec, io::parseMaterial(root), sample);
  std::atomic<bool> cancel{true};
  CalibrationOptions options;
  options.cancel = &cancel;
  const ElasticProperties m = measureElasticProperties(sample, sampleSpec, options);
  EXPECT_FALSE(m.converged);
  EXPECT_EQ(m.steps, sample.steps);  // not one relaxation step
  const BeamFit fit = fitBeamParameters(sample, sampleSpec, 150e9, 0.4, options);
  EXPECT_TRUE(fit.cancelled);
  EXPECT_EQ(fit.evaluations, 0);
  // Cancelled from the progress callback during the first test: the fit stops after it.
  cancel = false;
  int calls = 0;
  options.progress = [&](double f) {
    EXPECT_GE(f, 0.0);
    EXPECT_LE(f, 1.0);
    ++calls;
    cancel = true;
  };
  const BeamFit stopped = fitBeamParameters(sample, sampleSpec, 150e9, 0.4, options);
  EXPECT_TRUE(stopped.cancelled);
  EXPECT_EQ(stopped.evaluations, 1);
  EXPECT_GE(calls, 1);
  EXPECT_FALSE(stopped.achieved.converged);
}

TEST(ElasticPropertiesScenario, RunsThroughTheCli) {
  using rupture::testing::runCli;
  ScratchDir dir;
  const std::string specPath = rupture::testing::writeSpec(smallSpec(), "elastic-properties-cli.json");
  const fs::path out = dir.path() / "cli.h5";
  const auto r = runCli("run " + specPath + " -o " + out.string() + " --threads 1 --json");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const nlohmann::json summary = nlohmann::json::parse(r.out);
  EXPECT_EQ(summary["completed"], 1);
  EXPECT_GT(summary["young_modulus"].get<double>(), 0);
  ASSERT_TRUE(fs::exists(out));
  EXPECT_FALSE(fs::exists(dir.path() / "cli.xdmf2"));  // no particle snapshots, no ParaView sidecar
  const io::Hdf5File file = io::Hdf5File::openReadOnly(out.string());
  EXPECT_DOUBLE_EQ(file.readAttributeDouble("/summary", "young_modulus"), summary["young_modulus"].get<double>());

  const auto schema = runCli("schema elastic-properties");
  ASSERT_EQ(schema.exitCode, 0) << schema.err;
  const nlohmann::json printed = nlohmann::json::parse(schema.out);
  const fs::path schemas = fs::path(RUPTURE_SOURCE_DIR) / "api" / "schemas";
  nlohmann::json onDisk = nlohmann::json::parse(rupture::testing::readWhole(schemas / "elastic-properties.schema.json"));
  // The blocks bonded scenarios share are parts (api/schemas/parts/), inlined in what is printed.
  for (auto& [key, property] : onDisk["properties"].items())
    if (property.contains("$ref")) {
      property = nlohmann::json::parse(rupture::testing::readWhole(schemas / property["$ref"].get<std::string>()));
      for (const char* meta : {"$schema", "$id", "$comment"}) property.erase(meta);
    }
  EXPECT_EQ(printed, onDisk);

  const auto list = runCli("scenarios");
  ASSERT_EQ(list.exitCode, 0);
  EXPECT_NE(list.out.find("elastic-properties"), std::string::npos);

  nlohmann::json bad = smallSpec();
  bad["target"] = {{"young_modulus", 150e9}};
  const auto invalid = runCli("validate " + rupture::testing::writeSpec(bad, "elastic-properties-bad.json"));
  EXPECT_EQ(invalid.exitCode, 2);
  EXPECT_NE(invalid.err.find("target.poisson_ratio"), std::string::npos) << invalid.err;
}

}  // namespace
}  // namespace rupture
