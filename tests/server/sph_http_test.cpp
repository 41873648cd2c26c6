// The SPH scenarios over HTTP on a real loopback server: they are listed, a bad spec gets a 400
// problem document naming the field, and a small dam-break job runs to a summary.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "server_test_support.hpp"

namespace rupture::server {
namespace {

using test::expectProblem;
using test::getJson;
using test::LiveServer;

Json smallDamBreak() {
  return {{"dimension", 2},
          {"geometry", {{"column_width", 0.057}, {"column_height", 0.114}, {"tank_length", 0.2}, {"tank_height", 0.15}}},
          {"resolution", {{"spacing", 0.005}}},
          {"probes", {{0.01, 0.005}}},
          {"run", {{"end_time", 0.02}}}};
}

TEST(SphHttp, ScenariosAreServedAndBadSpecsGet400NamingTheField) {
  LiveServer live;
  auto client = live.client();
  for (const char* name : {"dam-break", "piston-column"}) {
    Json desc = getJson(*client, std::string("/processes/") + name);
    EXPECT_EQ(desc["id"], name);
    EXPECT_TRUE(desc["inputs"].contains("fluid")) << desc["inputs"].dump();
  }
  auto post = [&](const std::string& scenario, const Json& inputs) {
    return test::postJson(*client, "/processes/" + scenario + "/execution", Json{{"inputs", inputs}});
  };
  Json bad = smallDamBreak();
  bad["resolution"]["spacing"] = 0.0;
  Json doc = expectProblem(post("dam-break", bad), 400, "resolution.spacing");
  EXPECT_NE(doc["detail"].get<std::string>().find("> 0"), std::string::npos) << doc.dump();
  bad = smallDamBreak();
  bad["fluid"] = {{"sound_speed", -3.0}};
  expectProblem(post("dam-break", bad), 400, "fluid.sound_speed");
  bad = smallDamBreak();
  bad["probes"] = {{0.3, 0.01}};
  expectProblem(post("dam-break", bad), 400, "probes[0]");
  bad = smallDamBreak();
  bad["run"]["end_time"] = -1.0;
  expectProblem(post("dam-break", bad), 400, "run.end_time");
  const Json piston = {{"geometry", {{"diameter", 0.08}, {"column_height", 0.203}}}, {"resolution", {{"spacing", 0.3}}}};
  expectProblem(post("piston-column", piston), 400, "resolution.spacing");
}

TEST(SphHttp, SmallDamBreakJobRunsToASummary) {
  LiveServer live;
  auto client = live.client();
  auto res = test::postJson(*client, "/processes/dam-break/execution", Json{{"inputs", smallDamBreak()}});
  ASSERT_TRUE(res);
  ASSERT_EQ(res->status, 201) << res->body;
  const std::string id = Json::parse(res->body)["jobID"].get<std::string>();
  const Json done = test::waitForJob(*client, std::stoll(id), {"successful", "failed", "dismissed"}, 120);
  ASSERT_EQ(done["status"], "successful") << done.dump();
  const Json summary = getJson(*client, "/jobs/" + id + "/summary");
  ASSERT_EQ(summary["rows"].size(), 1u) << summary.dump();
  const std::string text = summary.dump();
  EXPECT_NE(text.find("front_position_final"), std::string::npos) << text.substr(0, 500);
  // The series of the run, as the API serves them.
  const Json series = getJson(*client, "/jobs/" + id + "/runs/0/series?names=time,front_position");
  EXPECT_NE(series.dump().find("front_position"), std::string::npos) << series.dump().substr(0, 300);
  // A body the run does not have is a 400 naming the parameter and the bodies it has, not an
  // empty picture (issue 56).
  const Json problem = expectProblem(client->Get(("/jobs/" + id + "/runs/0/field?body=999").c_str()), 400, "body");
  EXPECT_NE(problem.value("detail", "").find("allowed: all, fluid"), std::string::npos) << problem.dump();
  auto fluid = client->Get(("/jobs/" + id + "/runs/0/field?body=fluid&thumbnail=1").c_str());
  ASSERT_TRUE(fluid);
  EXPECT_EQ(fluid->status, 200) << fluid->body;
}

TEST(SphHttp, ProgressReaches100OnlyOnceTheRunHasFinished) {
  LiveServer live;
  auto client = live.client();
  Json inputs = smallDamBreak();
  inputs["resolution"]["spacing"] = 0.004;
  inputs["run"]["end_time"] = 0.3;  // a second or two: polled many times while it runs
  const std::string id = std::to_string(test::submit(*client, Json{{"inputs", inputs}}, {}, "dam-break"));
  int polledWhileRunning = 0;
  bool ended = false;
  for (int k = 0; k < 1200; ++k) {
    const Json job = getJson(*client, "/jobs/" + id);
    const std::string status = job["status"].get<std::string>();
    if (status == "successful" || status == "failed" || status == "dismissed") {
      EXPECT_EQ(status, "successful");
      EXPECT_EQ(job["progress"], 100);
      EXPECT_EQ(job["runs"][0]["progress"], 100);
      ended = true;
      break;
    }
    EXPECT_LT(job["progress"].get<int>(), 100) << "job " << status;
    if (job["runs"][0]["status"] == "running") {
      ++polledWhileRunning;
      EXPECT_LT(job["runs"][0]["progress"].get<int>(), 100) << job["runs"][0].dump();
      if (!job["runs"][0]["eta_s"].is_null()) {
        EXPECT_GE(job["runs"][0]["eta_s"].get<double>(), 0.0);
      }
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(25));
  }
  EXPECT_TRUE(ended) << "the job finished within the 30 s of polling";
  EXPECT_GT(polledWhileRunning, 0) << "the run was seen running";
}

TEST(SphHttp, ADamBreakSweepHasADefaultPlotWithoutAPeakStress) {
  LiveServer live;
  auto client = live.client();
  const Json body = {{"inputs", smallDamBreak()}, {"sweep", {{"resolution.spacing", {0.006, 0.005}}}}};
  const std::string id = std::to_string(test::submit(*client, body, {}, "dam-break"));
  ASSERT_EQ(test::waitForJob(*client, std::stoll(id), {"successful", "failed", "dismissed"}, 120)["status"], "successful");
  auto plot = client->Get(("/jobs/" + id + "/summary.svg").c_str());
  ASSERT_TRUE(plot);
  EXPECT_EQ(plot->status, 200) << "the plot nobody tuned works for every scenario: " << plot->body.substr(0, 300);
  EXPECT_NE(plot->body.find("Final front position"), std::string::npos) << "its first declared result";
  auto page = client->Get(("/jobs/" + id + "?f=html").c_str());
  ASSERT_TRUE(page);
  EXPECT_NE(page->body.find("summary.svg?x=resolution.spacing&amp;y=front_position_final"), std::string::npos);
}

}  // namespace
}  // namespace rupture::server
