// Specs that would pin a worker never get one (issue 7): runs above --max-elements are refused at
// POST with the estimate in the error, and DELETE frees a worker during the packing of a large
// sample.
#include <chrono>

#include <gtest/gtest.h>

#include "server_test_support.hpp"

namespace rupture::server {
namespace {

const std::string kExecute = std::string("/processes/") + test::kScenario + "/execution";

TEST(RunLimits, RunsAboveMaxElementsAreRefusedWithTheEstimate) {
  if (!test::scenarioAvailable()) GTEST_SKIP() << "scenario not registered";
  test::LiveServer server([](ServerConfig& c) { c.maxElements = 2000; });
  auto client = server.client();
  Json inputs = test::smallInputs();  // about 1,600 elements: accepted
  const auto ok = test::postJson(*client, kExecute, Json{{"inputs", inputs}});
  ASSERT_TRUE(ok);
  EXPECT_EQ(ok->status, 201) << ok->body;

  // Half the element radius: four times the elements, refused before anything is queued.
  const double radius = inputs["sample"]["element_radius"].get<double>();
  Json sweep = {{"sample.element_radius", {radius, radius / 2}}};
  const auto refused = test::postJson(*client, kExecute, Json{{"inputs", inputs}, {"sweep", sweep}});
  const Json doc = test::expectProblem(refused, 400, "sample.element_radius");
  EXPECT_EQ(doc.value("sweep_point", -1), 1) << doc.dump();
  EXPECT_NE(doc["detail"].get<std::string>().find("--max-elements"), std::string::npos) << doc.dump();
  EXPECT_NE(doc["detail"].get<std::string>().find("MiB of memory"), std::string::npos) << doc.dump();
  const Json jobs = test::getJson(*client, "/jobs");
  EXPECT_EQ(jobs["jobs"].size(), 1u) << "the refused sweep queued nothing";
}

TEST(RunLimits, DeleteFreesAWorkerDuringPacking) {
  if (!test::scenarioAvailable()) GTEST_SKIP() << "scenario not registered";
  test::LiveServer server([](ServerConfig& c) { c.workers = 1; });
  auto client = server.client();
  Json inputs = test::smallInputs();
  // About 400,000 elements: the packing alone takes tens of seconds on one core.
  inputs["sample"]["size"] = {4.3e-6, 4.3e-6};
  inputs["sample"]["element_radius"] = 3.3e-9;
  inputs["sample"]["porosity"] = 0;
  inputs["sample"].erase("pore_radius");
  const std::int64_t id = test::submit(*client, Json{{"inputs", inputs}});
  ASSERT_GT(id, 0);
  ASSERT_TRUE(test::waitFor([&] { return test::getJson(*client, "/health")["running"] == 1; }, 30));
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));  // well inside the packing
  const auto start = std::chrono::steady_clock::now();
  auto res = client->Delete(("/jobs/" + std::to_string(id)).c_str());
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 200) << res->body;
  ASSERT_TRUE(test::waitFor([&] { return test::getJson(*client, "/health")["running"] == 0; }, 30));
  const double freedAfter = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // Issue 7 asks for a second; before the fix this took 60-78 s. 3 s leaves room for a busy CI.
  EXPECT_LT(freedAfter, 3.0);
  EXPECT_EQ(test::getJson(*client, "/jobs/" + std::to_string(id))["status"], "dismissed");
}

}  // namespace
}  // namespace rupture::server
