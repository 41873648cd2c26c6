// What keeps a spec from pinning a worker: samples that cannot be built are rejected at validation
// (pores smaller than an element, more pores than placement can handle, porosity beyond what
// non-overlapping pores reach), many small pores still build, the size estimate the server's
// --max-elements relies on is close to what gets built, and cancel stops the sample build
// (packing included) promptly.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <thread>

#include "samples/sample_builder.hpp"
#include "bonded/bonded_spec.hpp"
#include "sample_test_support.hpp"
#include "support/test_support.hpp"

using namespace rupture;
using rupture::testing::ceramic;
using rupture::testing::rejectedField;

namespace {

nlohmann::json tensionSpec(int dimension) {
  nlohmann::json spec = {
      {"scenario", "dynamic-tension"},
      {"dimension", dimension},
      {"sample", {{"size", dimension == 2 ? nlohmann::json{1e-6, 1e-6} : nlohmann::json{0.12e-6, 0.12e-6, 0.12e-6}},
                  {"element_radius", 3.3e-9},
                  {"porosity", 0.11},
                  {"pore_radius", {5e-8, 1.5e-7}}}},
      {"material", {{"model", "beam"}, {"density", 6060},
                    {"beam", {{"young_modulus", 2865e9}, {"poisson_ratio", 0.3}, {"radius_ratio", 0.3}, {"failure_stress", 4e9}}}}},
      {"loading", {{"strain_rate", 1e6}, {"initial_velocity", "VL"}}}};
  if (dimension == 3) spec["sample"]["pore_radius"] = {1.5e-8, 3e-8};
  return spec;
}

TEST(SampleLimits, TheSpecThatPinnedAWorkerIsRejected) {
  // Issue 7: porosity 0.6 with 1 pm pores passed validation and spun in pore placement forever.
  nlohmann::json spec = tensionSpec(2);
  spec["sample"]["porosity"] = 0.6;
  spec["sample"]["pore_radius"] = {1e-12, 1e-12};
  EXPECT_EQ(rejectedField(spec), "sample.porosity");
  spec["sample"]["porosity"] = 0.3;
  EXPECT_EQ(rejectedField(spec), "sample.pore_radius");  // smaller than an element
}

TEST(SampleLimits, PoresMustBeAtLeastAnElementAndFewEnoughToPlace) {
  nlohmann::json spec = tensionSpec(2);
  spec["sample"]["pore_radius"] = {3e-9, 1e-8};  // min below element_radius = 3.3 nm
  EXPECT_EQ(rejectedField(spec), "sample.pore_radius");
  // 10,000 pores is the placement bound: on 4 µm × 4 µm, radius 3.5 nm at 11 % needs about
  // 45,700 pores, radius 10 nm about 5,600.
  spec["sample"]["size"] = {4e-6, 4e-6};
  spec["sample"]["pore_radius"] = {3.5e-9, 3.5e-9};
  EXPECT_EQ(rejectedField(spec), "sample.pore_radius");
  spec["sample"]["pore_radius"] = {1e-8, 1e-8};
  EXPECT_EQ(rejectedField(spec), "");
}

TEST(SampleLimits, PorosityBelowTheJammingOfRandomPores) {
  nlohmann::json spec2 = tensionSpec(2);
  spec2["sample"]["porosity"] = 0.5;
  EXPECT_EQ(rejectedField(spec2), "");
  spec2["sample"]["porosity"] = 0.55;
  EXPECT_EQ(rejectedField(spec2), "sample.porosity");
  nlohmann::json spec3 = tensionSpec(3);
  spec3["sample"]["porosity"] = 0.35;
  EXPECT_EQ(rejectedField(spec3), "");
  spec3["sample"]["porosity"] = 0.4;
  EXPECT_EQ(rejectedField(spec3), "sample.porosity");
}

TEST(SampleLimits, ManySmallPoresAtTheLimitPorosityBuild) {
  // Thousands of pores of a few element radii at the largest accepted porosity: placement on a
  // grid and carving through a cell list keep this to seconds, and the porosity is reached.
  SampleSpec s;
  s.dimension = 2;
  s.size = {0.6e-6, 0.6e-6, 0};
  s.elementRadius = 3.3e-9;
  s.porosity = 0.5;
  s.poreRadius = {1e-8, 1.2e-8};
  BondedSystem system;
  const SampleReport report = buildSample(s, ceramic(), system);
  // porosity × area / mean pore area = 0.5 × 0.36 µm² / (π × 122 nm²) ≈ 470 pores
  EXPECT_GT(report.pores.size(), 400u);
  EXPECT_NEAR(report.porosity, s.porosity, 0.05 * s.porosity);
}

TEST(SampleLimits, SizeEstimateIsCloseToTheBuiltSample) {
  // The server refuses runs above --max-elements from this estimate: it must not be far off.
  for (const int dimension : {2, 3}) {
    SCOPED_TRACE(dimension);
    nlohmann::json spec = tensionSpec(dimension);
    if (dimension == 2) spec["sample"]["size"] = {0.5e-6, 0.5e-6};
    if (dimension == 3) spec["sample"]["element_radius"] = 5e-9;
    const io::SpecReader root(spec, "");
    const SampleSpec s = io::parseSample(root);
    BondedSystem system;
    const SampleReport report = buildSample(s, ceramic(), system);
    const RunEstimate estimate = estimateRun(spec);
    EXPECT_EQ(estimate.field, "sample.element_radius");
    EXPECT_NEAR(estimate.particles, static_cast<double>(report.elements), 0.1 * static_cast<double>(report.elements));
    EXPECT_GT(estimate.memoryBytes, 500.0 * estimate.particles);
  }
}

TEST(SampleLimits, CancelStopsTheBuildDuringPacking) {
  // 400,000 elements: placing them takes a fraction of a second, relaxing them tens of seconds.
  SampleSpec s;
  s.dimension = 2;
  s.size = {4.3e-6, 4.3e-6, 0};
  s.elementRadius = 3.3e-9;
  std::atomic<bool> cancel{false};
  std::chrono::steady_clock::time_point cancelledAt;
  std::thread watcher([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(1500));
    cancelledAt = std::chrono::steady_clock::now();
    cancel = true;
  });
  BondedSystem system;
  EXPECT_THROW(buildSample(s, ceramic(), system, &cancel), RunCancelled);
  const double afterCancel = std::chrono::duration<double>(std::chrono::steady_clock::now() - cancelledAt).count();
  watcher.join();
  // The contract is a look at the flag every 0.2 s at most; 2 s leaves room for a loaded machine.
  EXPECT_LT(afterCancel, 2.0);
}

}  // namespace
