// The Slurm executor against a real one-node Slurm (deploy/slurm/test-cluster.sh; ctest label
// "slurm"; skipped with a message where no cluster answers): the same sweep gives the same results
// as the local executor, DELETE cancels the cluster's runs, a run killed by scancel from outside is
// failed with Slurm's reason and can be retried, a restarted server re-attaches to the runs in
// the queue instead of submitting them twice, and a run longer than its time limit checkpoints before
// the limit and finishes through several allocations with the result of an uninterrupted run.
#include <cmath>
#include <chrono>
#include <fstream>

#include <gtest/gtest.h>

#include <thread>

#include "execution/command.hpp"
#include "rupture/run.hpp"
#include "support/hdf5_compare.hpp"
#include "common/files.hpp"
#include "server_test_support.hpp"

namespace rupture::server {
namespace {

namespace fs = std::filesystem;
const std::string kExecute = std::string("/processes/") + test::kScenario + "/execution";

bool clusterAvailable(std::string& why) {
  const CommandResult r = runCommand({"sinfo", "-h", "-o", "%T"}, std::chrono::seconds(10));
  if (r.ok() && !r.output.empty()) return true;
  why = "no Slurm cluster answers (start one with deploy/slurm/test-cluster.sh and export SLURM_CONF): " + r.error;
  return false;
}

#define REQUIRE_CLUSTER()                                     \
  do {                                                        \
    std::string why;                                          \
    if (!clusterAvailable(why)) GTEST_SKIP() << why;          \
    if (!test::scenarioAvailable()) GTEST_SKIP() << "no scenario"; \
  } while (0)

std::function<void(ServerConfig&)> slurmConfig(const fs::path& shared) {
  return [shared](ServerConfig& c) {
    c.executor = "slurm";
    c.sharedDir = shared.string();
  };
}

std::string arrayOf(const fs::path& shared, std::int64_t job, int run) {
  auto text = readFile(shared / "jobs" / std::to_string(job) / ("run-" + std::to_string(run) + ".slurm"));
  return text ? text->substr(0, text->find('\n')) : "";
}

bool inQueue(const std::string& array) {
  const CommandResult r = runCommand({"squeue", "-h", "-j", array, "-o", "%i"});
  return r.ok() && !r.output.empty();
}

Json summaryRows(httplib::Client& client, std::int64_t job) {
  Json rows = test::getJson(client, "/jobs/" + std::to_string(job) + "/summary")["rows"];
  for (Json& row : rows) row.erase("wall_time_s");  // the only value that depends on the machine's load
  return rows;
}

TEST(SlurmExecutor, SameSweepSameResultsAsTheLocalExecutor) {
  REQUIRE_CLUSTER();
  const Json body = {{"inputs", test::smallInputs()}, {"sweep", {{"loading.strain_rate", test::twoStrainRates()}}}};
  Json local, cluster;
  {
    test::LiveServer server;
    auto client = server.client();
    const auto id = test::submit(*client, body);
    ASSERT_EQ(test::waitForJob(*client, id, {"successful", "failed"}, 120)["status"], "successful");
    local = summaryRows(*client, id);
  }
  test::TempDir shared;
  test::LiveServer server(slurmConfig(shared.path()));
  auto client = server.client();
  EXPECT_EQ(test::getJson(*client, "/health")["executor"], "slurm");
  const auto id = test::submit(*client, body);
  const Json done = test::waitForJob(*client, id, {"successful", "failed"}, 120);
  ASSERT_EQ(done["status"], "successful") << done.dump();
  cluster = summaryRows(*client, id);
  ASSERT_EQ(local.size(), 2u);
  // The same specs give the same numbers on the cluster. Which run packs the sample and which reads
  // it from the sample cache depends on timing, and a run on a cached sample agrees with one on a
  // freshly packed sample to round-off (docs/dynamic-tension.md, "Sample cache"), not bit for bit.
  for (std::size_t r = 0; r < local.size(); ++r) {
    ASSERT_EQ(cluster[r].size(), local[r].size()) << r;
    for (const auto& [key, value] : local[r].items()) {
      if (key == "sample_from_cache") continue;
      SCOPED_TRACE("run " + std::to_string(r) + " " + key);
      ASSERT_TRUE(cluster[r].contains(key));
      if (value.is_number_float() && cluster[r][key].is_number())
        EXPECT_NEAR(cluster[r][key].get<double>(), value.get<double>(), 1e-9 * std::abs(value.get<double>()));
      else
        EXPECT_EQ(cluster[r][key], value);
    }
  }
  // The run files are served from the shared directory like local ones.
  auto file = client->Get(("/jobs/" + std::to_string(id) + "/runs/0/results").c_str());
  ASSERT_TRUE(file);
  EXPECT_EQ(file->status, 200);
  EXPECT_EQ(file->body.substr(1, 3), "HDF");
  EXPECT_TRUE(fs::exists(shared.path() / "jobs" / std::to_string(id) / "run-1.h5"));
}

// run.ranks on the cluster (docs/distributed.md): a job whose runs ask for 1 and 2 ranks becomes one
// array per rank count, the 2-rank one of 2 tasks started by srun; both files are the local 2-rank
// result bit for bit (series, snapshots, sample), and a run asking for more than --slurm-max-ranks
// gets a 400 naming run.ranks.
TEST(SlurmExecutor, TwoRankRunGivesTheLocalTwoRankResult) {
  REQUIRE_CLUSTER();
#ifndef RUPTURE_HAVE_MPI
  GTEST_SKIP() << "built without MPI";
#endif
  const Json spec = Json::parse(test::readText(fs::path(RUPTURE_SOURCE_DIR) / "tests" / "distributed" / "impact_pmb_projectile.json"));
  const Json body = {{"inputs", spec}, {"sweep", {{"run.ranks", {1, 2}}}}};
  test::LiveServer local;
  auto localClient = local.client();
  const auto localId = test::submit(*localClient, body, {}, "impact");
  ASSERT_EQ(test::waitForJob(*localClient, localId, {"successful", "failed"}, 300)["status"], "successful");
  const fs::path localTwoRanks = local.dataDir() / "jobs" / std::to_string(localId) / "run-1.h5";

  test::TempDir shared;
  test::LiveServer server([&](ServerConfig& c) {
    slurmConfig(shared.path())(c);
    c.slurmMaxRanks = 2;
  });
  auto client = server.client();
  Json tooWide = spec;
  tooWide["run"]["ranks"] = 3;
  test::expectProblem(test::postJson(*client, "/processes/impact/execution", {{"inputs", tooWide}}), 400, "run.ranks");
  const auto id = test::submit(*client, body, {}, "impact");
  const Json done = test::waitForJob(*client, id, {"successful", "failed"}, 300);
  ASSERT_EQ(done["status"], "successful") << done.dump(2);
  const fs::path dir = shared.path() / "jobs" / std::to_string(id);
  EXPECT_NE(arrayOf(shared.path(), id, 0), arrayOf(shared.path(), id, 1)) << "one array per rank count";
  bool srunScript = false;
  for (const auto& entry : fs::directory_iterator(dir / "slurm")) {
    const std::string script = test::readText(entry.path());
    if (script.find("#SBATCH --ntasks=2") != std::string::npos && script.find("srun --mpi=") != std::string::npos) srunScript = true;
  }
  EXPECT_TRUE(srunScript) << "no batch script asks for 2 tasks and starts them with srun";
  // Two ranks of one run, not two one-rank runs (which `rupture run` would say in the log).
  const std::string log = test::readText(dir / "run-1.log");
  EXPECT_EQ(log.find("this run has 1"), std::string::npos) << log;
  for (int k = 0; k < 2; ++k) {
    for (const char* group : {"/series", "/snapshots", "/sample"}) {
      const CommandResult diff = runCommand({"h5diff", "-r", localTwoRanks.string(), (dir / ("run-" + std::to_string(k) + ".h5")).string(), group});
      EXPECT_EQ(diff.exitCode, 0) << "run " << k << " " << group << " differs from the local 2-rank run:\n" << diff.output.substr(0, 4000);
    }
  }
}

TEST(SlurmExecutor, ReplicatesAndRefinementRunOnTheClusterAsLocally) {
  REQUIRE_CLUSTER();
  // 2 rates x 2 replicates, then one refined point (2 more runs, a second array submission).
  const Json body = {{"inputs", test::smallInputs()},
                     {"sweep", {{"loading.strain_rate", test::twoStrainRates()}}},
                     {"replicates", {{"count", 2}, {"vary", "sample.seed"}}},
                     {"refine", {{"path", "loading.strain_rate"}, {"quantity", "peak_stress"}, {"max_runs", 2}, {"tolerance", 0.01}}}};
  test::TempDir shared;
  test::LiveServer server(slurmConfig(shared.path()));
  auto client = server.client();
  const auto id = test::submit(*client, body);
  const Json done = test::waitForJob(*client, id, {"successful", "failed", "dismissed"}, 240);
  ASSERT_EQ(done["status"], "successful") << done.dump();
  ASSERT_EQ(done["runs_total"], 6);
  ASSERT_EQ(done["refinement"]["points"].size(), 1u);
  EXPECT_EQ(done["refinement"]["points"][0]["runs"], Json::array({4, 5}));
  const long long seed = test::smallInputs()["sample"]["seed"].get<long long>();
  for (int k = 0; k < 6; ++k) {
    EXPECT_EQ(done["runs"][k]["replicate"], k % 2);
    const Json spec = test::getJson(*client, "/jobs/" + std::to_string(id) + "/runs/" + std::to_string(k))["spec"];
    EXPECT_EQ(spec["sample"]["seed"], seed + k % 2);
    // What the cluster ran is the spec the store holds.
    const auto written = readFile(shared.path() / "jobs" / std::to_string(id) / ("run-" + std::to_string(k) + ".spec.json"));
    ASSERT_TRUE(written);
    EXPECT_EQ(Json::parse(*written), spec);
  }
  EXPECT_EQ(test::getJson(*client, "/jobs/" + std::to_string(id) + "/summary?aggregate=replicates")["rows"][2]["peak_stress"]["n"], 2);
}

TEST(SlurmExecutor, DeleteCancelsTheClusterRuns) {
  REQUIRE_CLUSTER();
  test::TempDir shared;
  test::LiveServer server(slurmConfig(shared.path()));
  auto client = server.client();
  Json inputs = test::smallInputs();
  const auto knob = test::runLengthKnob();
  const auto id = test::submit(*client, Json{{"inputs", inputs}, {"sweep", {{knob.path, {knob.slow}}}}});
  ASSERT_TRUE(test::waitFor([&] { return test::getJson(*client, "/jobs/" + std::to_string(id))["status"] == "running"; }, 60));
  const std::string array = arrayOf(shared.path(), id, 0);
  ASSERT_FALSE(array.empty());
  auto res = client->Delete(("/jobs/" + std::to_string(id)).c_str());
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 200) << res->body;
  EXPECT_EQ(test::getJson(*client, "/jobs/" + std::to_string(id))["status"], "dismissed");
  EXPECT_TRUE(test::waitFor([&] { return !inQueue(array); }, 30)) << "scancel took the runs off the cluster";
}

TEST(SlurmExecutor, ARunKilledFromOutsideFailsWithTheReasonAndCanBeRetried) {
  REQUIRE_CLUSTER();
  test::TempDir shared;
  test::LiveServer server(slurmConfig(shared.path()));
  auto client = server.client();
  const auto knob = test::runLengthKnob();
  // A run of a few seconds, cancelled by hand as soon as it runs.
  const auto id = test::submit(*client, Json{{"inputs", test::smallInputs()}, {"sweep", {{knob.path, {knob.medium}}}}});
  ASSERT_TRUE(test::waitFor([&] { return test::getJson(*client, "/jobs/" + std::to_string(id))["status"] == "running"; }, 60));
  const std::string array = arrayOf(shared.path(), id, 0);
  ASSERT_TRUE(runCommand({"scancel", array + "_0"}).ok());
  const Json failed = test::waitForJob(*client, id, {"failed", "successful"}, 60);
  ASSERT_EQ(failed["status"], "failed") << failed.dump();
  const Json run = test::getJson(*client, "/jobs/" + std::to_string(id) + "/runs/0");
  EXPECT_NE(run["error"].get<std::string>().find("CANCELLED"), std::string::npos) << run.dump();

  // Retry: the failed run goes back to the cluster as a new submission and succeeds.
  auto retried = client->Post(("/jobs/" + std::to_string(id) + "/retry").c_str(), "", "application/json");
  ASSERT_TRUE(retried);
  EXPECT_EQ(retried->status, 200) << retried->body;
  EXPECT_EQ(test::parseJson(retried->body)["retried_runs"], Json::array({0}));
  const Json again = test::waitForJob(*client, id, {"failed", "successful"}, 300);
  EXPECT_EQ(again["status"], "successful") << again.dump();
  EXPECT_NE(arrayOf(shared.path(), id, 0), array) << "a new submission";
  // Nothing left to retry.
  auto none = client->Post(("/jobs/" + std::to_string(id) + "/retry").c_str(), "", "application/json");
  test::expectProblem(none, 409);
}

TEST(SlurmExecutor, ARestartedServerReattachesInsteadOfSubmittingAgain) {
  REQUIRE_CLUSTER();
  test::TempDir data, shared;
  const auto knob = test::runLengthKnob();
  std::int64_t id = -1;
  std::string array;
  {
    test::LiveServer server(slurmConfig(shared.path()), data.path());
    auto client = server.client();
    id = test::submit(*client, Json{{"inputs", test::smallInputs()}, {"sweep", {{knob.path, {knob.medium, knob.quick}}}}});
    ASSERT_TRUE(test::waitFor([&] { return !arrayOf(shared.path(), id, 1).empty(); }, 30));
    array = arrayOf(shared.path(), id, 0);
  }  // the server stops; the cluster's runs go on
  test::LiveServer server(slurmConfig(shared.path()), data.path());
  auto client = server.client();
  const Json done = test::waitForJob(*client, id, {"successful", "failed"}, 300);
  EXPECT_EQ(done["status"], "successful") << done.dump();
  EXPECT_EQ(arrayOf(shared.path(), id, 0), array);
  EXPECT_EQ(arrayOf(shared.path(), id, 1), array);
  std::size_t submissions = 0;
  for (const auto& e : fs::directory_iterator(shared.path() / "jobs" / std::to_string(id) / "slurm"))
    submissions += e.path().extension() == ".sbatch";
  EXPECT_EQ(submissions, 1u);
}

TEST(SlurmExecutor, ARunLongerThanItsTimeLimitFinishesThroughSeveralAllocations) {
  REQUIRE_CLUSTER();
  test::TempDir shared, scratch;
  // Two minutes per allocation, told to checkpoint and stop 30 s before the limit: Slurm may signal
  // up to 60 s early, so each allocation runs 30 to 90 s, never less than the run's set-up (with one
  // minute the signal once came 1 s in; such a run is now submitted again, but a test must not
  // depend on it happening once only). The run needs well over 90 s.
  test::LiveServer server([&](ServerConfig& c) {
    slurmConfig(shared.path())(c);
    c.slurmTime = "00:02:00";
    c.slurmCheckpointLead = 30;
  });
  auto client = server.client();
  Json inputs = test::smallInputs();
  inputs["loading"]["strain_rate"] = 3e3;  // about two minutes of one core: past any allocation (6e3 once fit in one)
  const auto id = test::submit(*client, Json{{"inputs", inputs}});
  // The same spec uninterrupted, on the other core meanwhile.
  Json spec = inputs;
  spec["scenario"] = test::kScenario;
  const fs::path whole = scratch.path() / "whole.h5";
  bool wholeCompleted = false;
  std::thread reference([&] {
    RunControl control;
    wholeCompleted = runSpec(spec, whole.string(), control, 1).completed;
  });
  const Json done = test::waitForJob(*client, id, {"successful", "failed", "dismissed"}, 900);
  reference.join();
  ASSERT_EQ(done["status"], "successful") << done.dump(2);
  const Json& run = done["runs"][0];
  EXPECT_GE(run.value("resumes", 0), 1) << "it fit one allocation: " << run.dump(2);
  EXPECT_GT(run.value("resumed_from_step", std::int64_t{0}), 0);
  EXPECT_GE(run.value("attempts", 0), 2);
  ASSERT_TRUE(wholeCompleted);
  const fs::path result = shared.path() / "jobs" / std::to_string(id) / "run-0.h5";
  EXPECT_EQ(testing::hdf5Differences(whole.string(), result.string(),
                                     rupture::testing::howARunRan()),
            "");
  EXPECT_FALSE(fs::exists(shared.path() / "jobs" / std::to_string(id) / "run-0.h5.checkpoint"));
}

}  // namespace
}  // namespace rupture::server
