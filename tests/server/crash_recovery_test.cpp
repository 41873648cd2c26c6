// Crash safety with the real rupture-server binary: SIGKILL mid-sweep, restart on the same data
// directory, every run finishes, and runs finished before the kill are byte-identical afterwards.
// Also: SIGTERM stops it gracefully (exit 0) and the interrupted run is re-queued.
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <map>

#include <gtest/gtest.h>

#include "server_test_support.hpp"

namespace rupture::server {
namespace {

using test::getJson;

using test::ChildServer;

std::map<int, std::string> downloadFinishedRuns(httplib::Client& client, const std::string& job, const Json& doc) {
  std::map<int, std::string> out;
  for (const auto& run : doc["runs"]) {
    if (run["status"] != "successful") continue;
    const int k = run["index"];
    auto res = client.Get((job + "/runs/" + std::to_string(k) + "/results").c_str());
    EXPECT_TRUE(res && res->status == 200);
    if (res) out[k] = res->body;
  }
  return out;
}

/// Polls the job until `done(doc)`; returns whether it happened, leaving the last document in doc.
bool waitForDoc(httplib::Client& client, const std::string& job, Json& doc, const std::function<bool(const Json&)>& done,
                double seconds) {
  return test::waitFor([&] {
    auto res = client.Get(job.c_str());
    if (!res || res->status != 200) return false;
    doc = Json::parse(res->body);
    return done(doc);
  }, seconds);
}

TEST(CrashRecovery, KilledMidSweepRestartsFinishesEveryRunAndNeverRecomputes) {
  ASSERT_TRUE(test::scenarioAvailable()) << "the dynamic-tension scenario or its small example is missing";
  test::TempDir data;
  const auto knob = test::runLengthKnob();
  // Four runs on one worker, one after the other; the last two last a few seconds, so that the
  // kill and the stop land while one runs.
  Json body = {{"inputs", test::smallInputs()},
               {"sweep", {{knob.path, {knob.quick, knob.quick, knob.medium, knob.medium}}}},
               {"sweep_mode", "zip"}};
  std::string job;
  std::int64_t id = 0;
  std::map<int, std::string> before;
  std::map<int, std::filesystem::file_time_type> mtimes;
  auto runFile = [&](int k) {
    return data.path() / "jobs" / std::to_string(id) / ("run-" + std::to_string(k) + ".h5");
  };

  // 1. SIGKILL while run 2 runs, after runs 0 and 1 finished.
  {
    ChildServer server(data.path());
    auto client = server.client();
    id = test::submit(*client, body);
    job = "/jobs/" + std::to_string(id);
    Json doc;
    ASSERT_TRUE(waitForDoc(*client, job, doc, [](const Json& d) {
      return d["runs"][1]["status"] == "successful" && d["runs"][2]["status"] == "running";
    }, 120)) << doc.dump(2);
    before = downloadFinishedRuns(*client, job, doc);
    ASSERT_EQ(before.size(), 2u);
    for (const auto& [k, bytes] : before) {
      EXPECT_EQ(test::readText(runFile(k)), bytes);
      mtimes[k] = std::filesystem::last_write_time(runFile(k));
    }
    EXPECT_EQ(server.stop(SIGKILL, 5), 128 + SIGKILL);
  }

  // 2. Restart: finished runs are kept as they are, the killed run starts again. Then SIGTERM while
  //    a run is running: a graceful stop (exit 0, promptly) that puts the run back in the queue.
  {
    ChildServer server(data.path());
    auto client = server.client();
    Json doc = getJson(*client, job);
    EXPECT_EQ(doc["runs"][0]["status"], "successful");
    EXPECT_EQ(doc["runs"][1]["status"], "successful");
    EXPECT_NE(doc["runs"][2]["status"], "failed");
    EXPECT_EQ(downloadFinishedRuns(*client, job, doc).at(1), before.at(1));
    ASSERT_TRUE(waitForDoc(*client, job, doc, [](const Json& d) {
      return d["runs"][2]["status"] == "successful" && d["runs"][3]["status"] == "running";
    }, 120)) << doc.dump(2);
    EXPECT_EQ(doc["runs"][2]["attempts"], 2);
    const auto t0 = std::chrono::steady_clock::now();
    EXPECT_EQ(server.stop(SIGTERM, 10), 0);
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 5.0);
  }

  // 3. Restart again: the job finishes; results from before the kill are byte-identical and their
  //    files were never rewritten.
  {
    ChildServer server(data.path());
    auto client = server.client();
    Json doc = test::waitForJob(*client, id, {"successful", "failed", "dismissed"}, 120);
    ASSERT_EQ(doc["status"], "successful") << doc.dump(2);
    for (const auto& run : doc["runs"]) EXPECT_EQ(run["status"], "successful");
    EXPECT_FALSE(doc["runs"][0].contains("attempts"));  // ran once
    EXPECT_EQ(doc["runs"][3]["attempts"], 2);
    auto after = downloadFinishedRuns(*client, job, doc);
    ASSERT_EQ(after.size(), 4u);
    for (const auto& [k, bytes] : before) {
      EXPECT_EQ(after.at(k), bytes) << "run " << k << " changed after the crash";
      EXPECT_EQ(std::filesystem::last_write_time(runFile(k)), mtimes.at(k)) << "run " << k << " was rewritten";
    }
    EXPECT_EQ(getJson(*client, "/jobs")["numberMatched"], 1);
    EXPECT_EQ(server.stop(SIGTERM, 10), 0);
  }
}

}  // namespace
}  // namespace rupture::server
