// Specs that would pin a worker never get one (issue 7): runs above --max-elements are refused at
// POST with the estimate in the error, and DELETE frees a worker during the packing of a large
// sample. Issue 56: specs that could never finish (a strain rate of 1e20 /s, a density of 1e308
// kg/m^3, a beam modulus of 1e-300 Pa) are refused, so are runs longer than --max-run-steps, and
// the longest run still admitted stops within a second of DELETE or SIGTERM.
#include <signal.h>

#include <chrono>
#include <cmath>

#include <gtest/gtest.h>

#include "rupture/run.hpp"
#include "server_test_support.hpp"

namespace rupture::server {
namespace {


TEST(RunLimits, RunsAboveMaxElementsAreRefusedWithTheEstimate) {
  if (!test::scenarioAvailable()) GTEST_SKIP() << "scenario not registered";
  test::LiveServer server([](ServerConfig& c) { c.maxElements = 2000; });
  auto client = server.client();
  Json inputs = test::smallInputs();  // about 1,600 elements: accepted
  const auto ok = test::postJson(*client, test::kExecutePath, Json{{"inputs", inputs}});
  ASSERT_TRUE(ok);
  EXPECT_EQ(ok->status, 201) << ok->body;

  // Half the element radius: four times the elements, refused before anything is queued.
  const double radius = inputs["sample"]["element_radius"].get<double>();
  Json sweep = {{"sample.element_radius", {radius, radius / 2}}};
  const auto refused = test::postJson(*client, test::kExecutePath, Json{{"inputs", inputs}, {"sweep", sweep}});
  const Json doc = test::expectProblem(refused, 400, "sample.element_radius");
  EXPECT_EQ(doc.value("sweep_point", -1), 1) << doc.dump();
  EXPECT_NE(doc["detail"].get<std::string>().find("--max-elements"), std::string::npos) << doc.dump();
  EXPECT_NE(doc["detail"].get<std::string>().find("MiB of memory"), std::string::npos) << doc.dump();
  const Json jobs = test::getJson(*client, "/jobs");
  EXPECT_EQ(jobs["jobs"].size(), 1u) << "the refused sweep queued nothing";
}

/// The three runaway specs: the field each one sets and its value.
struct RunawaySpec {
  const char* pointer;
  double value;
  const char* field;
};
const RunawaySpec kRunawaySpecs[] = {{"/loading/strain_rate", 1e20, "loading.strain_rate"},
                                     {"/material/density", 1e308, "material.density"},
                                     {"/material/beam/young_modulus", 1e-300, "material.beam.young_modulus"}};

TEST(RunLimits, SpecsThatCouldNeverFinishAreRefused) {
  if (!test::scenarioAvailable()) GTEST_SKIP() << "scenario not registered";
  test::LiveServer server;
  auto client = server.client();
  for (const RunawaySpec& r : kRunawaySpecs) {
    Json inputs = test::smallInputs();
    inputs[Json::json_pointer(r.pointer)] = r.value;
    const Json doc = test::expectProblem(test::postJson(*client, test::kExecutePath, Json{{"inputs", inputs}}), 400, r.field);
    EXPECT_NE(doc.value("detail", std::string()).find("allowed"), std::string::npos) << doc.dump();
  }
  EXPECT_EQ(test::getJson(*client, "/jobs")["jobs"].size(), 0u) << "nothing was queued";
}

/// A long run of the small example: from rest at 1e3 /s (VL), tens of millions of steps (half an
/// hour of one core), still under run.max_steps.
Json longInputs(double strainRate = 1e3) {
  Json inputs = test::smallInputs();
  inputs["loading"]["strain_rate"] = strainRate;
  return inputs;
}

double estimatedSteps(const Json& inputs) {
  Json spec = inputs;
  spec["scenario"] = test::kScenario;
  return rupture::estimateRun(nlohmann::json(spec)).steps;
}

TEST(RunLimits, RunsAboveMaxRunStepsAreRefusedWithTheEstimate) {
  if (!test::scenarioAvailable()) GTEST_SKIP() << "scenario not registered";
  const double edge = std::ceil(estimatedSteps(longInputs()));
  ASSERT_GT(edge, 1e6);
  ASSERT_LE(edge, rupture::kDefaultMaxRunSteps) << "the default admits the long run";
  test::LiveServer server([&](ServerConfig& c) { c.maxRunSteps = static_cast<long long>(edge); });
  auto client = server.client();
  // At the limit: accepted (and dismissed at once: it would run for half an hour).
  const std::int64_t id = test::submit(*client, Json{{"inputs", longInputs()}});
  ASSERT_GT(id, 0);
  client->Delete(("/jobs/" + std::to_string(id)).c_str());
  // Half the strain rate: twice the steps, refused with the estimate.
  const Json doc = test::expectProblem(test::postJson(*client, test::kExecutePath, Json{{"inputs", longInputs(5e2)}}), 400,
                                       "loading.strain_rate");
  EXPECT_NE(doc.value("detail", std::string()).find("--max-run-steps"), std::string::npos) << doc.dump();
  EXPECT_NEAR(doc.value("estimated_steps", 0.0), 2 * edge, 0.01 * edge) << doc.dump();
  EXPECT_EQ(doc.value("max_run_steps", 0.0), edge) << doc.dump();
}

/// Waits until job `id`'s run is stepping (its stage is the main run's) and returns when it saw it.
bool waitUntilStepping(httplib::Client& client, std::int64_t id) {
  return test::waitFor(
      [&] {
        const Json job = test::getJson(client, "/jobs/" + std::to_string(id));
        return job.value("stage", std::string()).find("main run") != std::string::npos;
      },
      60);
}

/// DELETEs job `id` and returns the seconds until the worker is free (/health running 0), then
/// checks the freed worker runs the next job to its end.
double secondsToFreeTheWorker(httplib::Client& client, std::int64_t id) {
  const auto start = std::chrono::steady_clock::now();
  auto res = client.Delete(("/jobs/" + std::to_string(id)).c_str());
  EXPECT_TRUE(res);
  if (res) {
    EXPECT_EQ(res->status, 200) << res->body;
  }
  EXPECT_TRUE(test::waitFor([&] { return test::getJson(client, "/health")["running"] == 0; }, 30));
  const double freedAfter = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::int64_t next = test::submit(client, Json{{"inputs", test::smallInputs()}});
  EXPECT_EQ(test::waitForJob(client, next, {"successful", "failed"}, 120)["status"], "successful");
  return freedAfter;
}

TEST(RunLimits, DeleteStopsALongAdmittedRunWithinASecond) {
  if (!test::scenarioAvailable()) GTEST_SKIP() << "scenario not registered";
  test::LiveServer server([](ServerConfig& c) { c.workers = 1; });
  auto client = server.client();
  const std::int64_t id = test::submit(*client, Json{{"inputs", longInputs()}});
  ASSERT_GT(id, 0);
  ASSERT_TRUE(waitUntilStepping(*client, id));
  std::this_thread::sleep_for(std::chrono::milliseconds(500));  // well inside the stepping
  const double freedAfter = secondsToFreeTheWorker(*client, id);
  std::cout << "[ measured ] worker free " << freedAfter << " s after DELETE during stepping\n";
  EXPECT_LT(freedAfter, 2.0);  // the issue asks for 1 s; the margin is for a loaded CI machine
}

TEST(RunLimits, SigtermStopsTheServerWithinTwoSecondsWhileALongRunSteps) {
  if (!test::scenarioAvailable()) GTEST_SKIP() << "scenario not registered";
  test::TempDir dir;
  test::ChildServer server(dir.path());
  auto client = server.client();
  const std::int64_t id = test::submit(*client, Json{{"inputs", longInputs()}});
  ASSERT_GT(id, 0);
  ASSERT_TRUE(waitUntilStepping(*client, id));
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(server.stop(SIGTERM, 30), 0);
  const double stoppedAfter = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cout << "[ measured ] server exited " << stoppedAfter << " s after SIGTERM during stepping\n";
  EXPECT_LT(stoppedAfter, 3.0);  // 2 s plus the small sample's checkpoint, with a CI margin
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
  const double freedAfter = secondsToFreeTheWorker(*client, id);
  // Issue 7 asks for a second; before the fix this took 60-78 s. 3 s leaves room for a busy CI.
  std::cout << "[ measured ] worker free " << freedAfter << " s after DELETE during the packing\n";
  EXPECT_LT(freedAfter, 3.0);
  EXPECT_EQ(test::getJson(*client, "/jobs/" + std::to_string(id))["status"], "dismissed");
}

}  // namespace
}  // namespace rupture::server
