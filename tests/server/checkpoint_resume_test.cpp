// A server that dies loses no running work (docs/checkpoints.md): SIGKILL after a run's first
// checkpoint, and the restarted server continues the run from it; SIGTERM writes a checkpoint as the
// server stops, and the next start continues from that. The job then says how many times the run
// was resumed and from which step (so does the run's page), and its result file equals an
// uninterrupted run's bit for bit.
#include <signal.h>

#include <filesystem>

#include <gtest/gtest.h>

#include "io/checkpoint_file.hpp"
#include "rupture/run.hpp"
#include "server_test_support.hpp"
#include "support/hdf5_compare.hpp"

namespace rupture::server {
namespace {

namespace fs = std::filesystem;
using test::ChildServer;
using test::getJson;

TEST(CheckpointResume, KilledAndStoppedServersContinueTheRunFromItsCheckpoint) {
  ASSERT_TRUE(test::scenarioAvailable()) << "the dynamic-tension scenario or its small example is missing";
  test::TempDir data;
  Json inputs = test::smallInputs();
  inputs["loading"]["strain_rate"] = 3e4;         // several seconds of stepping
  inputs["run"]["checkpoint_interval_s"] = 0.3;   // a checkpoint soon after the run starts
  const Json body = {{"inputs", inputs}};
  std::int64_t id = 0;
  fs::path checkpoint;
  auto run0 = [&](httplib::Client& client) { return getJson(client, "/jobs/" + std::to_string(id))["runs"][0]; };

  // 1. SIGKILL once the run has a checkpoint.
  {
    ChildServer server(data.path());
    auto client = server.client();
    id = test::submit(*client, body);
    checkpoint = data.path() / "jobs" / std::to_string(id) / "run-0.h5.checkpoint";
    ASSERT_TRUE(test::waitFor([&] { return fs::exists(checkpoint); }, 120)) << run0(*client).dump(2);
    EXPECT_EQ(server.stop(SIGKILL, 5), 128 + SIGKILL);
  }
  const std::int64_t killedAt = io::readCheckpointHeader(checkpoint.string()).step;
  EXPECT_GT(killedAt, 0);

  // 2. The restarted server continues from it; SIGTERM then stops it with a fresh checkpoint.
  std::int64_t stoppedAt = 0;
  {
    ChildServer server(data.path());
    auto client = server.client();
    Json run;
    ASSERT_TRUE(test::waitFor([&] {
      run = run0(*client);
      return run.value("resumes", 0) == 1;
    }, 120)) << run.dump(2);
    EXPECT_EQ(run["resumed_from_step"], killedAt);
    ASSERT_EQ(run["status"], "running") << "the run must still be running to be stopped";
    EXPECT_EQ(server.stop(SIGTERM, 20), 0);
    ASSERT_TRUE(fs::exists(checkpoint)) << "a graceful stop writes a checkpoint";
    stoppedAt = io::readCheckpointHeader(checkpoint.string()).step;
    EXPECT_GT(stoppedAt, killedAt);
  }

  // 3. The next start finishes the run from there, to the uninterrupted result.
  fs::path result;
  {
    ChildServer server(data.path());
    auto client = server.client();
    const Json doc = test::waitForJob(*client, id, {"successful", "failed", "dismissed"}, 180);
    ASSERT_EQ(doc["status"], "successful") << doc.dump(2);
    const Json& run = doc["runs"][0];
    EXPECT_EQ(run["resumes"], 2);
    EXPECT_EQ(run["resumed_from_step"], stoppedAt);
    EXPECT_EQ(run["attempts"], 3);
    EXPECT_FALSE(fs::exists(checkpoint)) << "a completed run removes its checkpoint";
    auto page = client->Get(("/jobs/" + std::to_string(id) + "/runs/0?f=html").c_str());
    ASSERT_TRUE(page);
    EXPECT_NE(page->body.find("Continued from its checkpoint 2 times, last from step " + std::to_string(stoppedAt)),
              std::string::npos);
    result = data.path() / "jobs" / std::to_string(id) / "run-0.h5";
    EXPECT_EQ(server.stop(SIGTERM, 10), 0);
  }
  Json spec = inputs;
  spec["scenario"] = test::kScenario;
  test::TempDir scratch;
  RunControl control;
  ASSERT_TRUE(runSpec(spec, (scratch.path() / "whole.h5").string(), control, 1).completed);
  EXPECT_EQ(testing::hdf5Differences((scratch.path() / "whole.h5").string(), result.string(),
                                     rupture::testing::howARunRan()),
            "");
}

}  // namespace
}  // namespace rupture::server
