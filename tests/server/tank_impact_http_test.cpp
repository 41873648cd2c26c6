// The tank-impact scenario over HTTP on a real loopback server: it is listed with its inputs, a bad
// field gets a 400 problem document naming it, and a tiny job swept over the carriage speed runs to
// a summary with the documented columns and units.
#include <gtest/gtest.h>

#include "server_test_support.hpp"

namespace rupture::server {
namespace {

using test::expectProblem;
using test::getJson;
using test::LiveServer;

/// A 40 mm tank, 30 mm of water over a 2 mm plate with a 12 mm hole, 20 µs of impact.
Json tinyTank() {
  return {{"tank", {{"inner_diameter", 0.04}, {"water_height", 0.03}}},
          {"impactor", {{"mass", 5.0}, {"speed", 2.0}}},
          {"plate", {{"thickness", 0.002}, {"spacing", 0.004}, {"precrack", {{"shape", "hole"}, {"hole_diameter", 0.012}}}}},
          {"resolution", {{"spacing", 0.005}}},
          {"run", {{"end_time", 2e-5}}}};
}

TEST(TankImpactHttp, IsServedAndBadFieldsGet400NamingThem) {
  LiveServer live;
  auto client = live.client();
  const Json desc = getJson(*client, "/processes/tank-impact");
  EXPECT_EQ(desc["id"], "tank-impact");
  for (const char* input : {"plate", "impactor", "contact"})
    EXPECT_TRUE(desc["inputs"].contains(input)) << input << ": " << desc["inputs"].dump().substr(0, 300);
  auto post = [&](const Json& inputs) {
    return test::postJson(*client, "/processes/tank-impact/execution", Json{{"inputs", inputs}});
  };
  Json bad = tinyTank();
  bad["impactor"]["speed"] = -5.0;
  expectProblem(post(bad), 400, "impactor.speed");
  bad = tinyTank();
  bad["contact"] = {{"method", "glue"}};
  const Json doc = expectProblem(post(bad), 400, "contact.method");
  EXPECT_NE(doc["detail"].get<std::string>().find("master_slave"), std::string::npos) << doc.dump();
}

TEST(TankImpactHttp, TinyJobSweptOverTheCarriageSpeedReportsTheDocumentedSummary) {
  LiveServer live;
  auto client = live.client();
  const Json body = {{"inputs", tinyTank()}, {"sweep", {{"impactor.speed", {2.0, 5.0}}}}};
  auto res = test::postJson(*client, "/processes/tank-impact/execution", body);
  ASSERT_TRUE(res);
  ASSERT_EQ(res->status, 201) << res->body;
  const std::string id = Json::parse(res->body)["jobID"].get<std::string>();
  const Json done = test::waitForJob(*client, std::stoll(id), {"successful", "failed", "dismissed"}, 120);
  ASSERT_EQ(done["status"], "successful") << done.dump();
  const Json summary = getJson(*client, "/jobs/" + id + "/summary");
  ASSERT_EQ(summary["rows"].size(), 2u) << summary.dump().substr(0, 500);
  const std::map<std::string, std::string> documented = {
      {"first_pressure_peak", "Pa"}, {"peak_gauge_pressure", "Pa"}, {"max_jet_speed", "m/s"},
      {"max_deflection", "m"},       {"time_to_fracture", "s"},     {"cracked_length", "m"},
      {"final_tongue_angle", "rad"}, {"carriage_final_speed", "m/s"}};
  for (const auto& [name, unit] : documented) EXPECT_EQ(summary["units"][name], unit) << name;
}

// The campaign as one job (docs/tank-impact.md#the-campaign): a sweep over the seed's specimens, each
// row with the seed's measurements beside ours (coarse and 20 µs here: the columns, not the physics).
TEST(TankImpactHttp, CampaignSweptOverSpecimensCarriesTheSeedsMeasurements) {
  LiveServer live;
  auto client = live.client();
  const Json inputs = {{"plate", {{"spacing", 0.004}}}, {"resolution", {{"spacing", 0.01}}}, {"run", {{"end_time", 2e-5}}}};
  const Json body = {{"inputs", inputs}, {"sweep", {{"specimen", {"E14A5", "E20A2", "FUA5", "TF14A5"}}}}};
  auto res = test::postJson(*client, "/processes/tank-impact/execution", body);
  ASSERT_TRUE(res);
  ASSERT_EQ(res->status, 201) << res->body;
  const std::string id = Json::parse(res->body)["jobID"].get<std::string>();
  const Json done = test::waitForJob(*client, std::stoll(id), {"successful", "failed", "dismissed"}, 180);
  ASSERT_EQ(done["status"], "successful") << done.dump();
  const Json summary = getJson(*client, "/jobs/" + id + "/summary");
  ASSERT_EQ(summary["rows"].size(), 4u) << summary.dump().substr(0, 500);
  std::map<std::string, Json> bySpecimen;
  for (const Json& row : summary["rows"]) {
    const Json& values = row.contains("summary") ? row["summary"] : row;
    bySpecimen[values["specimen"].get<std::string>()] = values;
  }
  ASSERT_EQ(bySpecimen.size(), 4u);
  EXPECT_DOUBLE_EQ(bySpecimen["E14A5"]["seed_first_peak_low"].get<double>(), 210e5);   // §3.1.1
  EXPECT_DOUBLE_EQ(bySpecimen["E14A5"]["seed_first_peak_high"].get<double>(), 277e5);
  EXPECT_TRUE(bySpecimen["E14A5"]["seed_jet_speed"].is_null());
  EXPECT_DOUBLE_EQ(bySpecimen["E20A2"]["seed_jet_speed"].get<double>(), 45.0);         // §5.1
  EXPECT_NEAR(bySpecimen["FUA5"]["seed_tongue_angle"].get<double>(), 50.0 * 3.14159265358979 / 180, 1e-12);
  EXPECT_DOUBLE_EQ(bySpecimen["TF14A5"]["seed_time_to_fracture"].get<double>(), 1.5e-3); // §5.3.2
  EXPECT_NE(bySpecimen["TF14A5"]["seed_outcome"].get<std::string>().find("rim"), std::string::npos);
  EXPECT_DOUBLE_EQ(bySpecimen["E20A2"]["carriage_initial_speed"].get<double>(), 2.0);  // the specimen's speed
  EXPECT_EQ(summary["units"]["seed_first_peak_low"], "Pa");
  EXPECT_EQ(summary["units"]["seed_tongue_angle"], "rad");
}

}  // namespace
}  // namespace rupture::server
