// The bonded material options over HTTP. material.disorder: a bad distribution parameter is a 400
// naming the field, and a sweep over the disorder's seed runs, each run with its own bond strengths
// (different peaks) and its seed in its spec. material.anisotropic_damage: a bad field is a 400
// naming it, and a sweep over the frame's angle runs (a weak axis across the load lowers the peak).
#include <gtest/gtest.h>

#include "server_test_support.hpp"

namespace rupture::server {
namespace {

Json disorderedInputs() {
  Json inputs = test::smallInputs();
  inputs["material"]["disorder"] = {{"strength", {{"distribution", "weibull"}, {"modulus", 6}}}};
  return inputs;
}

TEST(BondDisorderHttp, BadParameterIs400NamingTheField) {
  ASSERT_TRUE(test::scenarioAvailable());
  test::LiveServer live;
  auto client = live.client();
  Json inputs = disorderedInputs();
  inputs["material"]["disorder"]["strength"] = {{"distribution", "normal"}, {"cv", 0.5}};
  const Json doc = test::expectProblem(test::postJson(*client, test::kExecutePath, {{"inputs", inputs}}), 400,
                                       "material.disorder.strength.cv");
  EXPECT_NE(doc.value("detail", "").find("0.3"), std::string::npos) << doc.dump();  // what is allowed
  EXPECT_EQ(test::getJson(*client, "/jobs")["numberMatched"], 0) << "no job for a bad submission";
}

TEST(BondDisorderHttp, SweepOverTheDisorderSeedGivesDifferentPeaks) {
  ASSERT_TRUE(test::scenarioAvailable());
  test::LiveServer live;
  auto client = live.client();
  const std::int64_t id =
      test::submit(*client, {{"inputs", disorderedInputs()}, {"sweep", {{"material.disorder.seed", {1, 2}}}}});
  ASSERT_GT(id, 0);
  const Json done = test::waitForJob(*client, id, {"successful", "failed", "dismissed"}, 150);
  ASSERT_EQ(done["status"], "successful") << done.dump(2);
  ASSERT_EQ(done["runs"].size(), 2u);
  const double a = done["runs"][0]["summary"]["peak_stress"].get<double>();
  const double b = done["runs"][1]["summary"]["peak_stress"].get<double>();
  EXPECT_GT(a, 0);
  EXPECT_GT(b, 0);
  EXPECT_NE(a, b) << "the two seeds drew the same bond strengths";
  for (int k = 0; k < 2; ++k) {
    const Json run = test::getJson(*client, "/jobs/" + std::to_string(id) + "/runs/" + std::to_string(k));
    EXPECT_EQ(run["spec"]["material"]["disorder"]["seed"], k + 1) << run.dump().substr(0, 400);
  }
}

Json anisotropicInputs() {
  Json inputs = test::smallInputs();
  inputs["material"]["anisotropic_damage"] = {{"critical_factors", {1.0, 0.5}}, {"angles", {0}}};
  return inputs;
}

TEST(AnisotropicDamageHttp, BadFieldIs400NamingIt) {
  ASSERT_TRUE(test::scenarioAvailable());
  test::LiveServer live;
  auto client = live.client();
  Json inputs = anisotropicInputs();
  inputs["material"]["anisotropic_damage"]["critical_factors"] = {1.0, 0.5, 0.5};
  test::expectProblem(test::postJson(*client, test::kExecutePath, {{"inputs", inputs}}), 400,
                      "material.anisotropic_damage.critical_factors");
  EXPECT_EQ(test::getJson(*client, "/jobs")["numberMatched"], 0) << "no job for a bad submission";
}

TEST(AnisotropicDamageHttp, SweepOverTheFrameAngle) {
  ASSERT_TRUE(test::scenarioAvailable());
  test::LiveServer live;
  auto client = live.client();
  // The dynamic-tension sample is pulled along x: with the weak axis along y (0°) the pull loads
  // the strong fibres; turned by 90°, the weak ones.
  const std::int64_t id = test::submit(
      *client, {{"inputs", anisotropicInputs()}, {"sweep", {{"material.anisotropic_damage.angles", {{0}, {90}}}}}});
  ASSERT_GT(id, 0);
  const Json done = test::waitForJob(*client, id, {"successful", "failed", "dismissed"}, 150);
  ASSERT_EQ(done["status"], "successful") << done.dump(2);
  ASSERT_EQ(done["runs"].size(), 2u);
  const double strong = done["runs"][0]["summary"]["peak_stress"].get<double>();
  const double weak = done["runs"][1]["summary"]["peak_stress"].get<double>();
  EXPECT_GT(weak, 0);
  EXPECT_LT(weak, strong);
}

}  // namespace
}  // namespace rupture::server
