// `rupture calibrate` and `rupture bench` through the real binary: documented output keys, and
// exit code 2 with the field named for bad specs.
#include <gtest/gtest.h>

#include <cmath>

#include "cli_runner.hpp"

using rupture::testing::runCli;
using rupture::testing::writeSpec;

namespace {

nlohmann::json calibrationSpec() {
  return {{"dimension", 2},
          {"sample", {{"size", {0.15e-6, 0.15e-6}}, {"element_radius", 3.3e-9}, {"seed", 5}}},
          {"material",
           {{"model", "beam"},
            {"density", 6060},
            {"beam", {{"young_modulus", 2865e9}, {"poisson_ratio", 0.3}, {"radius_ratio", 0.3}, {"failure_stress", 4e9}}}}}};
}

TEST(CliCalibrate, MeasuresYoungModulusAndPoissonRatio) {
  const auto r = runCli("calibrate " + writeSpec(calibrationSpec(), "good.json"));
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto out = nlohmann::json::parse(r.out);
  EXPECT_GT(out.at("young_modulus").get<double>(), 1e10);
  EXPECT_GT(out.at("poisson_ratio").get<double>(), 0.0);
  EXPECT_LT(out.at("poisson_ratio").get<double>(), 1.0);
  EXPECT_GT(out.at("sample").at("elements").get<int>(), 100);
  // What it is doing goes to stderr as it happens: the sample once built, then what it measured,
  // in engineering units (the JSON on stdout keeps full precision).
  EXPECT_NE(r.err.find("building the sample"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(std::to_string(out["sample"]["elements"].get<int>()) + " elements"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("GPa"), std::string::npos) << r.err;
}

TEST(CliCalibrate, WithoutTargetsAlsoPrintsStrengthAndOnset) {
  const auto r = runCli("calibrate " + writeSpec(calibrationSpec(), "strength.json"));
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto out = nlohmann::json::parse(r.out);
  const double strength = out.at("tensile_strength").get<double>();
  const double onset = out.at("crack_onset_strain").get<double>();
  // Before the first break the sample is linear: the peak lies at or above E × onset strain, below
  // the stress the beams would carry with no pore at all (σ_f × section fraction is far above it).
  EXPECT_GT(onset, 0.0);
  EXPECT_LT(onset, 0.01);
  EXPECT_GE(strength, 0.97 * out.at("young_modulus").get<double>() * onset);
  EXPECT_GE(out.at("strain_at_peak").get<double>(), onset * 0.97);
}

// Round trip (issue 13): fit σ_f to a strength S, then the plain test with the fitted σ_f gives S
// within 5 %, on two sample seeds and two targets below and above the Table 3 beams' strength.
TEST(CliCalibrate, TensileStrengthRoundTrip) {
  const std::pair<int, double> cases[] = {{3, 60e6}, {8, 150e6}};
  for (const auto& [seed, target] : cases) {
    nlohmann::json spec = calibrationSpec();
    spec["sample"]["size"] = {0.1e-6, 0.1e-6};
    spec["sample"]["seed"] = seed;
    const auto fit = runCli("calibrate " + writeSpec(spec, "fit" + std::to_string(seed) + ".json") +
                            " --target-tensile-strength " + std::to_string(target));
    ASSERT_EQ(fit.exitCode, 0) << fit.err;
    const auto fitted = nlohmann::json::parse(fit.out);
    const double sigmaF = fitted.at("beam").at("failure_stress").get<double>();
    EXPECT_NEAR(fitted.at("achieved").at("tensile_strength").get<double>(), target, 0.05 * target);
    EXPECT_EQ(fitted.at("target").at("tensile_strength").get<double>(), target);
    spec["material"]["beam"]["failure_stress"] = sigmaF;
    const auto check = runCli("calibrate " + writeSpec(spec, "check" + std::to_string(seed) + ".json"));
    ASSERT_EQ(check.exitCode, 0) << check.err;
    EXPECT_NEAR(nlohmann::json::parse(check.out).at("tensile_strength").get<double>(), target, 0.05 * target)
        << "seed " << seed << ", fitted failure stress " << sigmaF;
  }
}

// With elastic and strength targets together, what the fit reports is what a spec holding the
// fitted beams gives: the contact law whose defaults follow the beams (E_μ r_μ², ν_μ) follows the
// fitted ones too, not the beams the spec started from. The sample has a notch along the tension:
// the pairs across it overlap as packed and touch from the start, so the contact law matters.
TEST(CliCalibrate, FullFitReportsWhatTheFittedSpecGives) {
  nlohmann::json spec = calibrationSpec();
  spec["sample"]["size"] = {0.1e-6, 0.1e-6};
  spec["sample"]["notches"] = {{{"start", {0.0, 0.05e-6}}, {"end", {0.05e-6, 0.05e-6}}}};
  const auto fit = runCli("calibrate " + writeSpec(spec, "fullfit.json") +
                          " --target-young-modulus 150e9 --target-poisson-ratio 0.35 --target-tensile-strength 80e6");
  ASSERT_EQ(fit.exitCode, 0) << fit.err;
  const auto fitted = nlohmann::json::parse(fit.out);
  const auto& beam = fitted.at("beam");
  ASSERT_NE(beam.at("young_modulus").get<double>(), 2865e9);  // the fit changed the beams
  spec["material"]["beam"]["young_modulus"] = beam.at("young_modulus");
  spec["material"]["beam"]["radius_ratio"] = beam.at("radius_ratio");
  spec["material"]["beam"]["failure_stress"] = beam.at("failure_stress");
  const auto check = runCli("calibrate " + writeSpec(spec, "fullfit-check.json"));
  ASSERT_EQ(check.exitCode, 0) << check.err;
  const auto measured = nlohmann::json::parse(check.out);
  const auto& achieved = fitted.at("achieved");
  for (const char* key : {"young_modulus", "tensile_strength", "crack_onset_strain", "strain_at_peak"})
    EXPECT_NEAR(measured.at(key).get<double>(), achieved.at(key).get<double>(),
                1e-9 * std::abs(achieved.at(key).get<double>()))
        << key;
}

TEST(CliCalibrate, BadStrengthTargetExitsTwoNamingTheOption) {
  const std::string spec = writeSpec(calibrationSpec(), "badtarget.json");
  for (const char* value : {"-5e6", "0", "abc", "inf"}) {
    const auto r = runCli("calibrate " + spec + " --target-tensile-strength " + value);
    EXPECT_EQ(r.exitCode, 2) << value;
    EXPECT_NE(r.err.find("--target-tensile-strength"), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
}

struct BadSpec {
  const char* name;
  nlohmann::json::json_pointer pointer;
  nlohmann::json value;  // null: remove the field
  const char* field;     // must appear in the message
};

class CliBadSpec : public ::testing::TestWithParam<BadSpec> {};

TEST_P(CliBadSpec, ExitsTwoNamingTheField) {
  const BadSpec& bad = GetParam();
  nlohmann::json spec = calibrationSpec();
  if (bad.value.is_null()) {
    const auto parent = bad.pointer.parent_pointer();
    spec[parent].erase(bad.pointer.back());
  } else {
    spec[bad.pointer] = bad.value;
  }
  const auto r = runCli("calibrate " + writeSpec(spec, std::string(bad.name) + ".json"));
  EXPECT_EQ(r.exitCode, 2) << r.out << r.err;
  EXPECT_NE(r.err.find(bad.field), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("allowed"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
}

INSTANTIATE_TEST_SUITE_P(
    Specs, CliBadSpec,
    ::testing::Values(
        BadSpec{"missing_radius", nlohmann::json::json_pointer("/sample/element_radius"), nullptr, "sample.element_radius"},
        BadSpec{"negative_radius", nlohmann::json::json_pointer("/sample/element_radius"), -1e-9, "sample.element_radius"},
        BadSpec{"porosity_09", nlohmann::json::json_pointer("/sample/porosity"), 0.9, "sample.porosity"},
        BadSpec{"dimension_4", nlohmann::json::json_pointer("/dimension"), 4, "dimension"},
        BadSpec{"missing_failure", nlohmann::json::json_pointer("/material/beam/failure_stress"), nullptr, "material.beam.failure_stress"},
        BadSpec{"unknown_key", nlohmann::json::json_pointer("/sample/colour"), "red", "sample.colour"},
        BadSpec{"wrong_type", nlohmann::json::json_pointer("/material/density"), "heavy", "material.density"}),
    [](const auto& info) { return std::string(info.param.name); });

TEST(CliCalibrate, UnreadableOrMalformedSpecExitsTwo) {
  EXPECT_EQ(runCli("calibrate /nonexistent/spec.json").exitCode, 2);
  const auto path = rupture::testing::writeSpec(nullptr, "null.json");
  std::ofstream(path) << "{ not json";
  const auto r = runCli("calibrate " + path);
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("not valid JSON"), std::string::npos);
}

TEST(CliBench, PrintsOneJsonLineWithTheDocumentedKeys) {
  const auto r = runCli("bench W1 --particles 2000 --steps 20 --threads 1");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto out = nlohmann::json::parse(r.out);
  for (const char* key : {"workload", "particles", "bonds", "steps", "threads", "seconds", "particle_steps_per_s", "bond_steps_per_s"})
    EXPECT_TRUE(out.contains(key)) << key;
  EXPECT_EQ(out["workload"], "W1");
  EXPECT_EQ(out["steps"], 20);
  // fcc: 4 spheres per cell and about 6 bonds per sphere (12 neighbours, each bond counted once).
  const double bondsPerSphere = out["bonds"].get<double>() / out["particles"].get<double>();
  EXPECT_GT(bondsPerSphere, 4.5);
  EXPECT_LT(bondsPerSphere, 6.0);
  EXPECT_NEAR(out["particle_steps_per_s"].get<double>(),
              out["particles"].get<double>() * 20 / out["seconds"].get<double>(), 1e-6 * out["particle_steps_per_s"].get<double>());
  EXPECT_EQ(runCli("bench W9").exitCode, 2);
  EXPECT_EQ(runCli("bench W1 --threads 0").exitCode, 2);
}

}  // namespace
