// A full disk everywhere (docs/server.md, "A full disk"), on a real tmpfs filled to the last block:
// every write of the job store (POST of a job, POST of a retry) is a 507 with Retry-After that
// changes nothing and succeeds once space returns; a running run whose checkpoints find no room
// is never failed, and once space returns it ends with the result of a run that never met a full
// disk.
#include <fcntl.h>
#include <unistd.h>

#include <filesystem>
#include <vector>

#include <gtest/gtest.h>

#include "io/checkpoint_file.hpp"
#include "jobs/job_store.hpp"
#include "rupture/run.hpp"
#include "server_test_support.hpp"
#include "support/hdf5_compare.hpp"
#include "support/small_filesystem.hpp"

namespace rupture::server {
namespace {

namespace fs = std::filesystem;
using rupture::testing::SmallFilesystem;
using test::expectProblem;
using test::getJson;
using test::kExecutePath;
using test::LiveServer;

/// Fills the file system to its last block: fillUp leaves less than a block, which a small write
/// of the database could still use; this writes until the file system refuses even a byte.
void fillToTheLastByte(const fs::path& file) {
  SmallFilesystem::fillUp(file);
  const int fd = ::open((file.string() + ".last").c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  ASSERT_GE(fd, 0);
  const std::vector<char> block(4096, 'x');
  for (std::size_t size : {block.size(), std::size_t{512}, std::size_t{1}})
    while (::write(fd, block.data(), size) == static_cast<ssize_t>(size)) {
    }
  ::close(fd);
}

void unfill(const fs::path& file) {
  fs::remove(file);
  fs::remove(file.string() + ".last");
}

/// A job of one run that already failed, written to the store before the server starts.
std::int64_t failedJobIn(const fs::path& dataDir) {
  fs::create_directories(dataDir);
  JobStore store((dataDir / "rupture.sqlite").string());
  NewJob job;
  job.processId = test::kScenario;
  job.sweepMode = "grid";
  job.sweptPaths = Json::array();
  job.inputs = test::smallInputs();
  job.sweep = Json::object();
  job.runs.emplace_back(Json::array(), jobBaseSpec(job.processId, job.inputs));
  const std::int64_t id = store.createJob(job);
  store.startRun({id, 0});
  store.finishFailed({id, 0}, "failed for the test");
  return id;
}

void expect507WithRetryAfter(const httplib::Result& res, const std::string& what) {
  SCOPED_TRACE(what);
  expectProblem(res, 507);
  ASSERT_TRUE(res);
  EXPECT_EQ(res->get_header_value("Retry-After"), "60");
  EXPECT_NE(res->body.find("disk is full"), std::string::npos) << res->body;
}

TEST(FullDisk, WritesOfTheJobStoreAre507WithRetryAfterAndSucceedOnceSpaceReturns) {
  ASSERT_TRUE(test::scenarioAvailable());
  SmallFilesystem small(32u << 20);
  if (!small.mounted()) GTEST_SKIP() << small.whyNot();
  const fs::path data = small.path() / "data";
  const std::int64_t failed = failedJobIn(data);
  LiveServer live([](ServerConfig& c) { c.minFreeBytes = 0; }, data);
  auto client = live.client();
  const Json before = getJson(*client, "/jobs");

  // A job whose inputs (a long description, stored once) outgrow what the database has free.
  Json inputs = test::smallInputs();
  inputs["description"] = std::string(300'000, 'd');
  const Json body = {{"inputs", inputs}, {"name", "full disk"}};
  const fs::path filler = small.path() / "filler";
  fillToTheLastByte(filler);
  expect507WithRetryAfter(client->Post(("/jobs/" + std::to_string(failed) + "/retry").c_str(), "", "application/json"),
                          "POST of a retry");
  for (int attempt = 0; attempt < 3; ++attempt)  // the old answer was a 500, 3 times out of 3
    expect507WithRetryAfter(test::postJson(*client, kExecutePath, body), "POST of a job, attempt " + std::to_string(attempt));
  expect507WithRetryAfter(test::postJson(*client, kExecutePath, body, {{"Idempotency-Key", "full-disk-1"}}),
                          "POST of a job with an Idempotency-Key");
  auto health = client->Get("/health");
  ASSERT_TRUE(health) << "the server died";
  EXPECT_EQ(health->status, 200);
  EXPECT_EQ(getJson(*client, "/jobs")["numberMatched"], before["numberMatched"]) << "a refused POST created no job";
  EXPECT_EQ(getJson(*client, "/jobs/" + std::to_string(failed))["status"], "failed") << "a refused retry changed nothing";

  unfill(filler);
  const std::int64_t id = test::submit(*client, body, {{"Idempotency-Key", "full-disk-1"}});
  EXPECT_GT(id, 0) << "the same POST succeeds once space is back";
  auto retry = client->Post(("/jobs/" + std::to_string(failed) + "/retry").c_str(), "", "application/json");
  ASSERT_TRUE(retry);
  EXPECT_EQ(retry->status, 200) << retry->body;
  client->Delete(("/jobs/" + std::to_string(id)).c_str());
  client->Delete(("/jobs/" + std::to_string(failed)).c_str());
}

TEST(FullDisk, ARunWhoseCheckpointsFindNoRoomIsNeverFailedAndEndsWithTheUninterruptedResult) {
  ASSERT_TRUE(test::scenarioAvailable());
  SmallFilesystem small(96u << 20);
  if (!small.mounted()) GTEST_SKIP() << small.whyNot();
  const fs::path data = small.path() / "data";
  Json inputs = test::smallInputs();
  inputs["loading"]["strain_rate"] = 1e5;        // a few seconds of stepping
  inputs["run"]["checkpoint_interval_s"] = 0.1;  // checkpoints while the disk is full
  LiveServer live([](ServerConfig& c) { c.minFreeBytes = 0; }, data);
  auto client = live.client();
  const std::int64_t id = test::submit(*client, {{"inputs", inputs}});
  ASSERT_GT(id, 0);
  const std::string job = "/jobs/" + std::to_string(id);
  const fs::path checkpoint = data / "jobs" / std::to_string(id) / "run-0.h5.checkpoint";
  ASSERT_TRUE(test::waitFor([&] { return fs::exists(checkpoint); }, 120)) << getJson(*client, job).dump(2);
  const std::int64_t lastGood = io::readCheckpointHeader(checkpoint.string()).step;

  // Full for a few checkpoint intervals: the run is never failed, its last good checkpoint stays.
  const fs::path filler = small.path() / "filler";
  fillToTheLastByte(filler);
  const auto fullUntil = std::chrono::steady_clock::now() + std::chrono::milliseconds(1000);
  while (std::chrono::steady_clock::now() < fullUntil) {
    auto res = client->Get(job.c_str());
    ASSERT_TRUE(res && res->status == 200);
    const Json doc = Json::parse(res->body);
    ASSERT_NE(doc["runs"][0]["status"], "failed") << "a full disk failed the run: " << doc.dump(2);
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  ASSERT_TRUE(fs::exists(checkpoint)) << "the last good checkpoint is kept";
  EXPECT_GE(io::readCheckpointHeader(checkpoint.string()).step, lastGood);

  unfill(filler);
  const Json done = test::waitForJob(*client, id, {"successful", "failed", "dismissed"}, 180);
  ASSERT_EQ(done["status"], "successful") << done.dump(2);
  EXPECT_FALSE(fs::exists(checkpoint));

  Json spec = inputs;
  spec["scenario"] = test::kScenario;
  test::TempDir scratch;
  RunControl control;
  ASSERT_TRUE(runSpec(spec, (scratch.path() / "whole.h5").string(), control, 1).completed);
  EXPECT_EQ(rupture::testing::hdf5Differences((scratch.path() / "whole.h5").string(),
                                              (data / "jobs" / std::to_string(id) / "run-0.h5").string(),
                                              rupture::testing::howARunRan()),
            "");
}

}  // namespace
}  // namespace rupture::server
