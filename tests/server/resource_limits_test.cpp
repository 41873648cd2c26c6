// What a client sends cannot exhaust the server (issue 25): the merged file on a full disk, memory
// in admission, the server-wide queue bound, and the small deviations the outside probe found, each
// on a real loopback server. What is bounded in time (fan-out, renders, cancel) is tested alone in
// tests/latency/.
#include <algorithm>

#include <gtest/gtest.h>

#include "common/config.hpp"
#include "rupture/run.hpp"
#include "server_test_support.hpp"
#include "support/small_filesystem.hpp"

namespace rupture::server {
namespace {

namespace fs = std::filesystem;
using test::expectProblem;
using test::kExecutePath;
using test::getJson;
using test::LiveServer;

// -- 1. the merged file on a full disk --------------------------------------------------------------

TEST(ResourceLimits, MergedFileOnAFullDiskIs507LeavesNoPartAndComesOnceSpaceReturns) {
  ASSERT_TRUE(test::scenarioAvailable());
  rupture::testing::SmallFilesystem small(96u << 20);
  if (!small.mounted()) GTEST_SKIP() << small.whyNot();
  const fs::path data = small.path() / "data";
  LiveServer live([](ServerConfig& c) { c.minFreeBytes = 0; }, data);
  auto client = live.client();
  Json body = {{"inputs", test::smallInputs()}, {"name", "full disk"}};
  const std::int64_t id = test::submit(*client, body);
  ASSERT_GT(id, 0);
  const Json done = test::waitForJob(*client, id, {"successful", "failed"}, 120);
  ASSERT_EQ(done["status"], "successful") << done.dump();

  const fs::path filler = small.path() / "filler";
  rupture::testing::SmallFilesystem::fillUp(filler);
  const std::string results = "/jobs/" + std::to_string(id) + "/results";
  for (int attempt = 0; attempt < 3; ++attempt) {  // the old crash came 6 times out of 6
    auto res = client->Get(results.c_str());
    const Json problem = expectProblem(res, 507);
    ASSERT_TRUE(res);
    EXPECT_FALSE(res->get_header_value("Retry-After").empty());
    EXPECT_GT(problem.value("needed_bytes", 0.0), 0.0) << res->body;
  }
  auto health = client->Get("/health");
  ASSERT_TRUE(health) << "the server died";
  EXPECT_EQ(health->status, 200);
  for (const auto& entry : fs::directory_iterator(data / "jobs" / std::to_string(id)))
    EXPECT_EQ(entry.path().filename().string().find("results.h5"), std::string::npos) << entry.path();

  fs::remove(filler);
  auto res = client->Get(results.c_str());
  ASSERT_TRUE(res);
  ASSERT_EQ(res->status, 200) << res->body.substr(0, 300);
  EXPECT_EQ(res->body.substr(0, 8), std::string("\x89HDF\r\n\x1a\n", 8));
}

// -- 2. memory in admission -------------------------------------------------------------------------

/// A 3D bond-based peridynamic sample with the widest horizon: hundreds of bonds per site.
Json widePmbInputs() {
  return {{"dimension", 3},
          {"sample", {{"lattice", "simple-cubic"}, {"size", {0.04, 0.02, 0.02}}, {"spacing", 6e-4}}},
          {"material",
           {{"model", "pmb"}, {"density", 2440}, {"pmb", {{"young_modulus", 72e9}, {"horizon_factor", 6}, {"fracture_energy", 3.8}}}}},
          {"loading", {{"strain_rate", 1e3}, {"initial_velocity", "VL"}}},
          {"run", {{"max_strain", 0.002}}}};
}

double estimatedBytes(const Json& inputs, const std::string& scenario) {
  Json spec = inputs;
  spec["scenario"] = scenario;
  return rupture::estimateRun(nlohmann::json(spec)).memoryBytes;
}

TEST(ResourceLimits, AdmissionRefusesARunWhoseMemoryEstimateExceedsTheLimitNamingTheBytes) {
  ASSERT_TRUE(test::scenarioAvailable());
  const Json wide = widePmbInputs();
  const double wideBytes = estimatedBytes(wide, test::kScenario);
  // Bonds dominate: hundreds per site at horizon factor 6 on a cubic lattice.
  EXPECT_GT(wideBytes, 2e9);
  {
    LiveServer live([](ServerConfig& c) { c.maxRunMemory = 1LL << 30; });
    auto client = live.client();
    const Json problem = expectProblem(test::postJson(*client, kExecutePath, Json{{"inputs", wide}}), 400, "sample.spacing");
    EXPECT_EQ(problem.value("estimated_memory_bytes", 0LL), std::llround(wideBytes)) << problem.dump();
    EXPECT_EQ(problem.value("max_run_memory_bytes", 0LL), 1LL << 30);
    EXPECT_NE(problem.value("detail", "").find("--max-run-memory"), std::string::npos) << problem.dump();
  }
  // Just below and just above the limit, on the small example: accepted, then refused.
  const Json small = test::smallInputs();
  const double smallBytes = estimatedBytes(small, test::kScenario);
  ASSERT_GT(smallBytes, 0);
  {
    LiveServer live([&](ServerConfig& c) {
      c.maxRunMemory = static_cast<long long>(smallBytes * 1.01);
      c.minFreeBytes = std::numeric_limits<long long>::max();  // nothing starts: admission only
    });
    auto client = live.client();
    auto accepted = test::postJson(*client, kExecutePath, Json{{"inputs", small}});
    ASSERT_TRUE(accepted);
    EXPECT_EQ(accepted->status, 201) << accepted->body;
  }
  {
    LiveServer live([&](ServerConfig& c) { c.maxRunMemory = static_cast<long long>(smallBytes * 0.99); });
    auto client = live.client();
    const Json problem = expectProblem(test::postJson(*client, kExecutePath, Json{{"inputs", small}}), 400, "sample.element_radius");
    EXPECT_EQ(problem.value("estimated_memory_bytes", 0LL), std::llround(smallBytes));
  }
}

TEST(ResourceLimits, TheDefaultMemoryLimitIsTheMachinesShareAndIsDocumentedInHelp) {
  ServerConfig config;
  config.workers = 2;
  const long long share = effectiveRunMemory(config);
  config.workers = 1;
  EXPECT_NEAR(static_cast<double>(effectiveRunMemory(config)), 2.0 * static_cast<double>(share), 2.0);
  config.maxRunMemory = 12345678;
  EXPECT_EQ(effectiveRunMemory(config), 12345678);
  EXPECT_NE(helpText().find("--max-run-memory"), std::string::npos);
  EXPECT_NE(helpText().find("--max-queued-runs"), std::string::npos);
  EXPECT_NE(helpText().find("--max-render-pixels"), std::string::npos);
}

// -- 3. the queue bound ---------------------------------------------------------------------------------

TEST(ResourceLimits, QueuedRunsAreBoundedForTheWholeServer) {
  ASSERT_TRUE(test::scenarioAvailable());
  LiveServer live([](ServerConfig& c) {
    c.minFreeBytes = std::numeric_limits<long long>::max();  // nothing starts: the queue only grows
    c.maxQueuedRuns = 5;
  });
  auto client = live.client();
  Json rates = Json::array({1e5, 2e5, 3e5});
  const Json body = {{"inputs", test::smallInputs()}, {"sweep", {{"loading.strain_rate", rates}}}};
  auto first = test::postJson(*client, kExecutePath, body);
  ASSERT_TRUE(first);
  EXPECT_EQ(first->status, 201);
  auto second = test::postJson(*client, kExecutePath, body);  // 3 + 3 > 5: wait for room
  const Json problem = expectProblem(second, 503);
  EXPECT_EQ(second->get_header_value("Retry-After"), "60");
  EXPECT_EQ(problem.value("queued_runs", 0), 3);
  Json six = Json::array({1e5, 2e5, 3e5, 4e5, 5e5, 6e5});
  expectProblem(test::postJson(*client, kExecutePath, Json{{"inputs", test::smallInputs()}, {"sweep", {{"loading.strain_rate", six}}}}),
                400, "sweep");  // could never fit
}

TEST(ResourceLimits, StoredInputsOfUnfinishedJobsAreBoundedForTheWholeServer) {
  ASSERT_TRUE(test::scenarioAvailable());
  Json inputs = test::smallInputs();
  inputs["description"] = std::string(100'000, 'd');
  const auto bytes = static_cast<long long>(inputs.dump().size());
  LiveServer live([&](ServerConfig& c) {
    c.minFreeBytes = std::numeric_limits<long long>::max();  // nothing starts: the jobs stay unfinished
    c.maxQueuedBytes = bytes * 3 / 2;
  });
  auto client = live.client();
  auto first = test::postJson(*client, kExecutePath, Json{{"inputs", inputs}});
  ASSERT_TRUE(first);
  EXPECT_EQ(first->status, 201) << first->body;
  auto second = test::postJson(*client, kExecutePath, Json{{"inputs", inputs}});
  const Json problem = expectProblem(second, 503);
  EXPECT_EQ(second->get_header_value("Retry-After"), "60");
  EXPECT_EQ(problem.value("queued_bytes", 0LL), bytes);
  inputs["description"] = std::string(200'000, 'd');  // larger than the bound itself
  expectProblem(test::postJson(*client, kExecutePath, Json{{"inputs", inputs}}), 400, "inputs");
  // A dismissed job no longer counts: its inputs leave the bound.
  const std::string job = "/jobs/" + Json::parse(first->body)["jobID"].get<std::string>();
  ASSERT_EQ(client->Delete(job.c_str())->status, 200);
  inputs["description"] = std::string(100'000, 'd');
  auto third = test::postJson(*client, kExecutePath, Json{{"inputs", inputs}});
  ASSERT_TRUE(third);
  EXPECT_EQ(third->status, 201) << third->body;
}

// -- 3b. memory per request ------------------------------------------------------------------------

long long residentMemory(httplib::Client& client) {
  const Json health = getJson(client, "/health");
  return health.value("resident_memory_bytes", 0LL);
}

// Issue 56: one POST under 1 MiB (1,000 runs, a 900 KB description) took the server from 24 MB to
// 901 MB and it stayed there. Now the sweep is planned one spec at a time and the freed heap goes
// back to the system.
TEST(ResourceLimits, AThousandRunSweepOfALargeDescriptionLeavesTheResidentMemoryWhereItWas) {
  ASSERT_TRUE(test::scenarioAvailable());
  LiveServer live([](ServerConfig& c) {
    c.minFreeBytes = std::numeric_limits<long long>::max();  // nothing starts: admission only
    c.maxRuns = 1000;
    c.maxQueuedRuns = 100000;
    c.maxRequestBytes = 1 << 20;
  });
  auto client = live.client();
  ASSERT_EQ(test::postJson(*client, kExecutePath, Json{{"inputs", test::smallInputs()}})->status, 201);  // warm
  const long long before = residentMemory(*client);
  ASSERT_GT(before, 0) << "/health gives no resident_memory_bytes";

  Json inputs = test::smallInputs();
  inputs["description"] = std::string(900'000, 'd');
  Json rates = Json::array();
  for (int k = 0; k < 1000; ++k) rates.push_back(1e5 + 100.0 * k);
  const Json body{{"inputs", inputs}, {"sweep", {{"loading.strain_rate", rates}}}, {"name", "amplification"}};
  ASSERT_LT(body.dump().size(), 1u << 20);
  auto res = test::postJson(*client, kExecutePath, body);
  ASSERT_TRUE(res);
  ASSERT_EQ(res->status, 201) << res->body.substr(0, 400);
  const std::string job = "/jobs/" + Json::parse(res->body)["jobID"].get<std::string>();
  const long long after = residentMemory(*client);
  EXPECT_LT(after - before, 50LL << 20) << "before " << before << " B, after " << after << " B";

  // Each run still holds the whole spec: its swept value and the description.
  const Json last = getJson(*client, job + "/runs/999")["spec"];
  EXPECT_EQ(last["loading"]["strain_rate"], rates[999]) << last.dump().substr(0, 300);
  EXPECT_EQ(last.value("description", "").size(), 900'000u);
  ASSERT_EQ(client->Delete(job.c_str())->status, 200);
  EXPECT_LT(residentMemory(*client) - before, 50LL << 20);
}

// -- 4. the small deviations -------------------------------------------------------------------------

std::string rawRequest(const std::string& head) { return head + "\r\n"; }

TEST(ResourceLimits, HeaderNulsDuplicateHostsAndEmptyIdempotencyKeysAre400) {
  LiveServer live([](ServerConfig& c) { c.token = "s3cret"; });
  const int port = live.port();
  auto status = [&](const std::string& head) { return test::rawStatus(test::rawExchange(port, rawRequest(head))); };
  // A NUL in a header value: the bearer token followed by a NUL and junk is not the token.
  const std::string nulToken("Authorization: Bearer s3cret\0x\r\n", 31);
  EXPECT_EQ(status("DELETE /jobs/1 HTTP/1.1\r\nHost: 127.0.0.1\r\n" + nulToken), 400);
  const std::string nulKey("Idempotency-Key: k\0y\r\n", 22);
  const std::string response = test::rawExchange(port, rawRequest("GET /health HTTP/1.1\r\nHost: 127.0.0.1\r\n" + nulKey));
  EXPECT_EQ(test::rawStatus(response), 400);
  EXPECT_NE(test::rawBody(response).find("NUL"), std::string::npos) << response;
  EXPECT_EQ(status("GET /health HTTP/1.1\r\nHost: 127.0.0.1\r\nHost: 127.0.0.1\r\n"), 400);
  EXPECT_EQ(status("GET /health HTTP/1.1\r\nHost: 127.0.0.1\r\nIdempotency-Key:\r\n"), 400);
  EXPECT_EQ(status("GET /health HTTP/1.1\r\nHost: 127.0.0.1\r\nIdempotency-Key:   \r\n"), 400);
  // Each names the header at fault, as the handlers' header problems do (issue 56).
  auto fieldOf = [&](const std::string& head) {
    const Json problem = Json::parse(test::rawBody(test::rawExchange(port, rawRequest(head))));
    EXPECT_EQ(problem.value("in", ""), "header") << problem.dump();
    return problem.value("field", "");
  };
  EXPECT_EQ(fieldOf("POST /processes/dynamic-tension/execution HTTP/1.1\r\nHost: 127.0.0.1\r\nIdempotency-Key:\r\n"),
            "Idempotency-Key");
  EXPECT_EQ(fieldOf("GET /health HTTP/1.1\r\nHost: 127.0.0.1\r\nHost: 127.0.0.1\r\n"), "Host");
  EXPECT_EQ(fieldOf("GET /health HTTP/1.1\r\nHost: 127.0.0.1\r\n" + nulKey), "Idempotency-Key");
  EXPECT_EQ(status("GET /health HTTP/1.1\r\nHost: 127.0.0.1\r\n"), 200);  // and the server is fine
  // The documented 414: a request target over 8 KiB.
  EXPECT_EQ(status("GET /jobs?name=" + std::string(9000, 'a') + " HTTP/1.1\r\nHost: 127.0.0.1\r\n"), 414);
}

TEST(ResourceLimits, NanAndInfinityLiteralsAre400NamingThePositionAndTheField) {
  LiveServer live;
  const int port = live.port();
  for (const std::string literal : {"NaN", "Infinity", "-Infinity"}) {
    const std::string body = "{\"inputs\": {\"loading\": {\"strain_rate\": " + literal + "}}}";
    const std::string response = test::rawExchange(
        port, "POST " + kExecutePath + " HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: application/json\r\nContent-Length: " +
                  std::to_string(body.size()) + "\r\nConnection: close\r\n\r\n" + body);
    EXPECT_EQ(test::rawStatus(response), 400) << response;
    const Json problem = Json::parse(test::rawBody(response));
    EXPECT_EQ(problem["field"], "loading.strain_rate") << problem.dump();
    EXPECT_EQ(problem["byte"], body.find(literal)) << problem.dump();
    EXPECT_NE(problem["detail"].get<std::string>().find("JSON has no NaN or Infinity"), std::string::npos) << problem.dump();
  }
}

}  // namespace
}  // namespace rupture::server
