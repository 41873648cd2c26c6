// The HTTP surface on a real loopback server: discovery documents, and every kind of bad request
// answered with its 4xx problem document while the server keeps serving.
#include <gtest/gtest.h>

#include "server_test_support.hpp"

namespace rupture::server {
namespace {

using test::expectProblem;
using test::getJson;
using test::LiveServer;



TEST(HttpApi, LandingHealthConformanceAndOpenApi) {
  LiveServer live;
  auto client = live.client();
  Json landing = getJson(*client, "/");
  std::set<std::string> hrefs;
  for (const auto& l : landing["links"]) hrefs.insert(l["href"].get<std::string>());
  for (const char* h : {"/openapi.yaml", "/processes", "/jobs", "/conformance", "/health"}) {
    EXPECT_TRUE(hrefs.count(h)) << h;
  }
  Json health = getJson(*client, "/health");
  EXPECT_EQ(health["status"], "ok");
  EXPECT_EQ(health["workers"], 2);
  EXPECT_EQ(health["queue_depth"], 0);
  EXPECT_TRUE(health["version"].is_string());
  Json conformance = getJson(*client, "/conformance");
  EXPECT_GE(conformance["conformsTo"].size(), 4u);

  auto yaml = client->Get("/openapi.yaml");
  ASSERT_TRUE(yaml);
  EXPECT_EQ(yaml->status, 200);
  EXPECT_EQ(yaml->body.rfind("openapi: 3.0", 0), 0u) << yaml->body.substr(0, 80);
  for (const char* path : {"/processes/{processID}/execution:", "/jobs/{jobID}:", "/jobs/{jobID}/results:",
                           "/jobs/{jobID}/runs/{runIndex}/series:", "/jobs/{jobID}/summary.svg:", "/health:"}) {
    EXPECT_NE(yaml->body.find(path), std::string::npos) << path;
  }
  // HEAD works wherever GET does; OPTIONS lists the methods.
  auto head = client->Head("/health");
  ASSERT_TRUE(head);
  EXPECT_EQ(head->status, 200);
  auto options = client->Options("/jobs/1");
  ASSERT_TRUE(options);
  EXPECT_EQ(options->status, 204);
  EXPECT_NE(options->get_header_value("Allow").find("DELETE"), std::string::npos);
}

TEST(HttpApi, ProcessesListAndDescribeTheScenario) {
  ASSERT_TRUE(test::scenarioAvailable()) << "the dynamic-tension scenario or its small example is missing";
  LiveServer live;
  auto client = live.client();
  Json list = getJson(*client, "/processes");
  bool found = false;
  for (const auto& p : list["processes"]) found = found || p["id"] == test::kScenario;
  EXPECT_TRUE(found) << list.dump();
  Json desc = getJson(*client, std::string("/processes/") + test::kScenario);
  EXPECT_EQ(desc["id"], test::kScenario);
  EXPECT_EQ(desc["jobControlOptions"], Json::array({"async-execute"}));
  EXPECT_TRUE(desc["inputs"].contains("loading")) << desc["inputs"].dump();
  EXPECT_FALSE(desc["inputs"].contains("scenario"));
  EXPECT_TRUE(desc["inputsSchema"].is_object());
  expectProblem(client->Get("/processes/no-such-scenario"), 404, "processID");
}

TEST(HttpApi, BadSubmissionsGetProblemDocumentsAndNoJob) {
  ASSERT_TRUE(test::scenarioAvailable()) << "the dynamic-tension scenario or its small example is missing";
  LiveServer live([](ServerConfig& c) { c.maxRuns = 20; });
  auto client = live.client();
  const Json inputs = test::smallInputs();
  auto post = [&](const std::string& body, const std::string& path = test::kExecutePath) {
    return client->Post(path.c_str(), body, "application/json");
  };
  auto withInputs = [&](const Json& in, const Json& extra = Json::object()) {
    Json body = extra;
    body["inputs"] = in;
    return body.dump();
  };

  // Malformed JSON, empty body, wrong top-level shapes.
  Json p = expectProblem(post("{\"inputs\": {"), 400);
  EXPECT_NE(p["detail"].get<std::string>().find("not valid JSON"), std::string::npos);
  expectProblem(post(""), 400);
  expectProblem(post("[1, 2]"), 400);
  expectProblem(post("{}"), 400, "inputs");
  expectProblem(post(R"({"inputs": 5})"), 400, "inputs");
  expectProblem(post(withInputs(inputs, {{"sweeep", Json::object()}})), 400, "sweeep");
  expectProblem(post(withInputs(inputs, {{"sweep_mode", "diagonal"}})), 400, "sweep_mode");
  expectProblem(post(withInputs(inputs, {{"name", 42}})), 400, "name");

  // Unknown scenario: 404 (the URL names it).
  expectProblem(post(withInputs(inputs), "/processes/no-such-scenario/execution"), 404, "processID");
  // A scenario in the inputs that disagrees with the URL.
  Json other = inputs;
  other["scenario"] = "something-else";
  expectProblem(post(withInputs(other)), 400, "scenario");

  // Unknown field and wrong type inside the spec: the dotted path of the field.
  Json unknown = inputs;
  unknown["loading"]["bogus_knob"] = 1;
  Json doc = expectProblem(post(withInputs(unknown)), 400, "loading.bogus_knob");
  EXPECT_EQ(doc["type"], problem::kInvalidSpec);
  Json wrongType = inputs;
  wrongType["loading"]["strain_rate"] = "fast";
  expectProblem(post(withInputs(wrongType)), 400, "loading.strain_rate");

  // Sweeps: over a path whose parent does not exist; too many runs; empty list.
  expectProblem(post(withInputs(inputs, {{"sweep", {{"loadin.strain_rate", {1e5, 1e6}}}}})), 400,
                "loadin.strain_rate");
  Json many = Json::array();
  for (int i = 1; i <= 21; ++i) many.push_back(1e5 * i);
  Json tooMany = expectProblem(post(withInputs(inputs, {{"sweep", {{"loading.strain_rate", many}}}})), 400, "sweep");
  EXPECT_EQ(tooMany["type"], problem::kTooManyRuns);
  expectProblem(post(withInputs(inputs, {{"sweep", {{"loading.strain_rate", Json::array()}}}})), 400,
                "loading.strain_rate");

  // Pathologically deep nesting is refused before parsing (it would overflow the parser's stack).
  const std::string deep = "{\"inputs\": " + std::string(400000, '[') + std::string(400000, ']') + "}";
  expectProblem(post(deep), 400);
  test::expectStillServing(*client);

  // Form-encoded bodies (curl -d without --json) are refused: a web page can send those cross-site.
  auto form = client->Post(test::kExecutePath.c_str(), "{\"inputs\": {", "application/x-www-form-urlencoded");
  expectProblem(form, 415, "Content-Type");

  // Nothing above created a job.
  Json jobs = getJson(*client, "/jobs");
  EXPECT_EQ(jobs["numberMatched"], 0);
  test::expectStillServing(*client);
}

TEST(HttpApi, UnknownJobsRunsAndPathLikeIds) {
  LiveServer live;
  auto client = live.client();
  expectProblem(client->Get("/jobs/1"), 404, "jobID");
  expectProblem(client->Get("/jobs/999999999999999999999"), 404, "jobID");
  expectProblem(client->Get("/jobs/0"), 404, "jobID");
  expectProblem(client->Get("/jobs/-1"), 404, "jobID");
  expectProblem(client->Get("/jobs/1e3/summary"), 404, "jobID");
  expectProblem(client->Get("/jobs/1/runs/0/results"), 404);
  expectProblem(client->Delete("/jobs/abc"), 404, "jobID");
  expectProblem(client->Get("/no/such/route"), 404);

  // Path-like ids, sent byte for byte (a client library might normalise them).
  for (const char* target : {"/jobs/../etc/passwd", "/jobs/..", "/jobs/..%2F..%2Fetc%2Fpasswd", "/jobs/%2e%2e/results",
                             "/jobs/1/runs/../../../rupture.sqlite/results", "/jobs/./1", "/jobs/1%00"}) {
    const std::string response = test::rawExchange(
        live.port(), std::string("GET ") + target + " HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n");
    const int status = test::rawStatus(response);
    EXPECT_TRUE(status == 404 || status == 400) << target << " -> " << response.substr(0, 200);
    EXPECT_NE(response.find("application/problem+json"), std::string::npos) << target;
    EXPECT_EQ(response.find("SQLite format"), std::string::npos) << target;
  }
  const std::string del = test::rawExchange(
      live.port(), "DELETE /jobs/../../x HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n");
  EXPECT_EQ(test::rawStatus(del), 404) << del;
  test::expectStillServing(*client);
}

TEST(HttpApi, WrongMethodsAre405WithAllow) {
  LiveServer live;
  auto client = live.client();
  auto put = client->Put("/jobs/1", "{}", "application/json");
  expectProblem(put, 405);
  EXPECT_NE(put->get_header_value("Allow").find("GET"), std::string::npos);
  EXPECT_NE(put->get_header_value("Allow").find("DELETE"), std::string::npos);
  expectProblem(client->Delete("/processes"), 405);
  expectProblem(client->Post("/jobs", "{}", "application/json"), 405);
  expectProblem(client->Get(test::kExecutePath.c_str()), 405);
  expectProblem(client->Patch("/health", "{}", "application/json"), 405);
  test::expectStillServing(*client);
}

TEST(HttpApi, OversizedAndChunkedBodiesAreRefused) {
  LiveServer live([](ServerConfig& c) { c.maxRequestBytes = 64 * 1024; });
  auto client = live.client();
  const std::string big = "{\"inputs\": {\"pad\": \"" + std::string(100 * 1024, 'x') + "\"}}";
  expectProblem(client->Post(test::kExecutePath.c_str(), big, "application/json"), 413);
  test::expectStillServing(*client);

  // Chunked bodies escape cpp-httplib's size limit, so they are refused before being read: 411.
  const std::string chunked =
      "POST " + test::kExecutePath + " HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: application/json\r\n"
      "Transfer-Encoding: chunked\r\n\r\n" "5\r\n{\"inp\r\n0\r\n\r\n";
  const std::string response = test::rawExchange(live.port(), chunked);
  EXPECT_EQ(test::rawStatus(response), 411) << response;
  EXPECT_NE(response.find("application/problem+json"), std::string::npos);
  test::expectStillServing(*client);
}

TEST(HttpApi, TokenGuardsPostAndDeleteOnly) {
  LiveServer live([](ServerConfig& c) { c.token = "s3cret-token"; });
  auto client = live.client();
  auto missing = client->Post(test::kExecutePath.c_str(), "{}", "application/json");
  expectProblem(missing, 401);
  EXPECT_EQ(missing->get_header_value("WWW-Authenticate"), "Bearer realm=\"rupture\"");
  expectProblem(client->Post(test::kExecutePath.c_str(), httplib::Headers{{"Authorization", "Bearer wrong"}}, "{}",
                             "application/json"),
                401);
  expectProblem(client->Post(test::kExecutePath.c_str(), httplib::Headers{{"Authorization", "s3cret-token"}}, "{}",
                             "application/json"),
                401);
  expectProblem(client->Delete("/jobs/1"), 401);
  // With the token the request gets past authentication (and fails on its body or the job id).
  const httplib::Headers auth{{"Authorization", "Bearer s3cret-token"}};
  EXPECT_NE(client->Post(test::kExecutePath.c_str(), auth, "{}", "application/json")->status, 401);
  expectProblem(client->Delete("/jobs/1", auth), 404);
  // Reading needs no token.
  getJson(*client, "/jobs");
  test::expectStillServing(*client);
}

TEST(HttpApi, InvalidQueryParametersAre400) {
  LiveServer live;
  auto client = live.client();
  expectProblem(client->Get("/jobs?status=done"), 400, "status");
  expectProblem(client->Get("/jobs?limit=0"), 400, "limit");
  expectProblem(client->Get("/jobs?limit=ten"), 400, "limit");
  expectProblem(client->Get("/jobs?offset=-3"), 400, "offset");
  Json ok = getJson(*client, "/jobs?status=running,successful&limit=5&offset=0");
  EXPECT_EQ(ok["numberReturned"], 0);
}

}  // namespace
}  // namespace rupture::server
