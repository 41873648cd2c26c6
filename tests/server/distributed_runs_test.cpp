// Runs of several MPI ranks through the local executor (docs/distributed.md): a spec's run.ranks
// makes the server start `mpirun -np N rupture run`, holding N of its workers; the file is the
// one-rank file bit for bit; a cancel ends every rank; a server stopped half way continues the run
// from its ranks' checkpoints to the uninterrupted file; a spec asking for more ranks than the
// server has workers, or for ranks with what is not decomposed yet, gets a 400 naming run.ranks.
#include <fstream>

#include <gtest/gtest.h>

#include "execution/command.hpp"
#include "server_test_support.hpp"

namespace rupture::server {
namespace {

namespace fs = std::filesystem;

/// The 3D PMB block under a projectile that the distributed engine tests run (contact on).
Json pmbImpact() {
  return Json::parse(test::readText(fs::path(RUPTURE_SOURCE_DIR) / "tests" / "distributed" / "impact_pmb_projectile.json"));
}

fs::path runFile(const test::LiveServer& server, std::int64_t job, int run) {
  return server.dataDir() / "jobs" / std::to_string(job) / ("run-" + std::to_string(run) + ".h5");
}

#ifdef RUPTURE_HAVE_MPI

TEST(DistributedRuns, TwoRanksWriteTheOneRankFileAndSummary) {
  test::LiveServer server;  // two workers
  auto client = server.client();
  const Json body = {{"inputs", pmbImpact()}, {"sweep", {{"run.ranks", {1, 2}}}}};
  const auto id = test::submit(*client, body, {}, "impact");
  ASSERT_GT(id, 0);
  const Json done = test::waitForJob(*client, id, {"successful", "failed"}, 300);
  ASSERT_EQ(done["status"], "successful") << done.dump(2);
  for (const char* group : {"/series", "/snapshots", "/sample"}) {
    const CommandResult diff = runCommand({"h5diff", "-r", runFile(server, id, 0).string(), runFile(server, id, 1).string(), group});
    EXPECT_EQ(diff.exitCode, 0) << group << " differs between 1 and 2 ranks:\n" << diff.output.substr(0, 4000);
  }
  Json rows = test::getJson(*client, "/jobs/" + std::to_string(id) + "/summary")["rows"];
  ASSERT_EQ(rows.size(), 2u);
  Json one = rows[0], two = rows[1];
  EXPECT_GT(one.value("broken_bonds", 0.0), 0.0) << "nothing broke: the comparison would prove little";
  for (Json* row : {&one, &two}) {
    row->erase("wall_time_s");
    row->erase("run");
    row->erase("run.ranks");
  }
  for (auto it = one.begin(); it != one.end(); ++it) {
    if (it.value().is_number()) {
      EXPECT_EQ(it.value(), two[it.key()]) << it.key();
    }
  }
  // What the launch adds beside the result is gone.
  for (const char* leftover : {"run-1.h5.part.spec.json", "run-1.h5.part.progress.json", "run-1.h5.part.xdmf2"}) {
    EXPECT_FALSE(fs::exists(server.dataDir() / "jobs" / std::to_string(id) / leftover)) << leftover;
  }
}

TEST(DistributedRuns, CancelEndsEveryRank) {
  test::LiveServer server;
  auto client = server.client();
  Json spec = pmbImpact();
  // About 24,000 steps, far longer than the test waits; its first 1 % (the progress the test waits
  // for) in a second or two.
  spec["run"]["end_time"] = 2e-3;
  spec["run"]["ranks"] = 2;
  const auto id = test::submit(*client, {{"inputs", spec}}, {}, "impact");
  ASSERT_GT(id, 0);
  // Cancelled once the ranks are stepping (the progress file says so).
  ASSERT_TRUE(test::waitFor([&] {
    const Json job = test::getJson(*client, "/jobs/" + std::to_string(id));
    return job.value("progress", 0) > 0;
  }, 120)) << "the 2-rank run never reported progress";
  // mpirun and its ranks run the spec the launch wrote beside the partial result: found by its path.
  const std::string launchedSpec = runFile(server, id, 0).string() + ".part.spec.json";
  EXPECT_EQ(runCommand({"pgrep", "-f", launchedSpec}).exitCode, 0) << "no process runs " << launchedSpec;
  const auto t0 = std::chrono::steady_clock::now();
  auto res = client->Delete(("/jobs/" + std::to_string(id)).c_str());
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 200) << res->body;
  ASSERT_TRUE(test::waitFor([&] { return !fs::exists(runFile(server, id, 0).string() + ".part"); }, 30))
      << "the 2-rank run's partial file is still there 30 s after the cancel";
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_LT(seconds, 15.0) << "mpirun and its ranks took " << seconds << " s to stop";
  const Json run = test::waitForJob(*client, id, {"dismissed"}, 30);
  EXPECT_EQ(run["status"], "dismissed");
  EXPECT_FALSE(fs::exists(runFile(server, id, 0)));
  EXPECT_NE(runCommand({"pgrep", "-f", launchedSpec}).exitCode, 0) << "a rank or mpirun outlived the cancel";
}

TEST(DistributedRuns, AStoppedServerContinuesATwoRankRunFromItsRanksCheckpoints) {
  Json spec = pmbImpact();
  spec["run"]["end_time"] = 2e-4;  // about 2,400 steps: long enough to stop it half way
  spec["run"]["ranks"] = 2;
  test::TempDir data;
  std::int64_t id = -1;
  {
    test::LiveServer server({}, data.path());
    auto client = server.client();
    id = test::submit(*client, {{"inputs", spec}}, {}, "impact");
    ASSERT_GT(id, 0);
    ASSERT_TRUE(test::waitFor([&] { return test::getJson(*client, "/jobs/" + std::to_string(id)).value("progress", 0) >= 20; }, 120))
        << "the 2-rank run never got to 20 %";
  }  // the server stops: the ranks write their checkpoints and the run goes back to the queue
  const fs::path checkpoint = data.path() / "jobs" / std::to_string(id) / "run-0.h5.checkpoint";
  ASSERT_TRUE(fs::exists(checkpoint)) << "no checkpoint of the first rank after the stop";
  ASSERT_TRUE(fs::exists(checkpoint.string() + ".rank-1")) << "no checkpoint of the second rank after the stop";
  test::LiveServer server({}, data.path());
  auto client = server.client();
  const Json done = test::waitForJob(*client, id, {"successful", "failed"}, 300);
  ASSERT_EQ(done["status"], "successful") << done.dump(2);
  const Json run = test::getJson(*client, "/jobs/" + std::to_string(id) + "/runs/0");
  EXPECT_EQ(run.value("resumes", 0), 1) << run.dump(2);
  EXPECT_GT(run.value("resumed_from_step", 0), 0) << run.dump(2);
  EXPECT_FALSE(fs::exists(checkpoint));
  EXPECT_FALSE(fs::exists(checkpoint.string() + ".rank-1"));
  // The uninterrupted run on one process: the same series, snapshots and sample.
  const fs::path whole = data.path() / "whole.h5";
  const fs::path specFile = data.path() / "whole.json";
  std::ofstream(specFile) << spec.dump();
  const std::string cli = (fs::read_symlink("/proc/self/exe").parent_path().parent_path() / "engine" / "rupture").string();
  const CommandResult one = runCommand({cli, "run", specFile.string(), "-o", whole.string(), "--threads", "1"}, std::chrono::minutes(5));
  ASSERT_EQ(one.exitCode, 0) << one.error;
  for (const char* group : {"/series", "/snapshots", "/sample"}) {
    const CommandResult diff = runCommand({"h5diff", "-r", whole.string(), runFile(server, id, 0).string(), group});
    EXPECT_EQ(diff.exitCode, 0) << group << " differs from the uninterrupted run:\n" << diff.output.substr(0, 4000);
  }
}

TEST(DistributedRuns, ADryRunTimesARunOfNRanksOnNWorkers) {
  test::LiveServer server;  // two workers, one thread each
  auto client = server.client();
  const Json body = {{"inputs", pmbImpact()}, {"sweep", {{"run.ranks", {1, 2}}}}};
  auto res = test::postJson(*client, "/processes/impact/execution?dry_run=true", body);
  ASSERT_TRUE(res);
  ASSERT_EQ(res->status, 200) << res->body;
  const Json d = Json::parse(res->body);
  ASSERT_EQ(d["run_estimates"].size(), 2u);
  const Json one = d["run_estimates"][0], two = d["run_estimates"][1];
  EXPECT_EQ(one["ranks"], 1);
  EXPECT_EQ(two["ranks"], 2);
  EXPECT_EQ(one["elements"], two["elements"]);
  EXPECT_EQ(one["steps"], two["steps"]);
  // Ideal scaling over the ranks, as over threads (docs/server.md, "Preview and cost").
  const double seconds = one["estimated_run_s"].get<double>();
  EXPECT_NEAR(two["estimated_run_s"].get<double>(), seconds / 2, 1e-12 * seconds);
  // The 1-rank run holds one worker, then the 2-rank run both: one after the other.
  EXPECT_NEAR(d["estimated_wall_s"].get<double>(), 1.5 * seconds, 1e-12 * seconds);
}

#endif  // RUPTURE_HAVE_MPI

TEST(DistributedRuns, MoreRanksThanWorkersIs400NamingRunRanks) {
  test::LiveServer server;  // two workers
  auto client = server.client();
  Json spec = pmbImpact();
  spec["run"]["ranks"] = 3;
  const Json problem = test::expectProblem(test::postJson(*client, "/processes/impact/execution", {{"inputs", spec}}), 400, "run.ranks");
  EXPECT_NE(problem.value("detail", "").find("run.ranks"), std::string::npos) << problem.dump(2);
  EXPECT_EQ(test::getJson(*client, "/jobs")["numberMatched"], 0) << "no job for a refused submission";
}

TEST(DistributedRuns, RanksWithBondDampingIs400NamingRunRanks) {
  test::LiveServer server;
  auto client = server.client();
  Json spec = pmbImpact();
  spec["material"]["local_damping"] = 0.1;
  spec["run"]["ranks"] = 2;
  const Json problem = test::expectProblem(test::postJson(*client, "/processes/impact/execution", {{"inputs", spec}}), 400, "run.ranks");
  EXPECT_NE(problem.value("detail", "").find("material.local_damping"), std::string::npos) << problem.dump(2);
}

TEST(DistributedRuns, RanksOnAScenarioThatRunsOnOneRankIs400) {
  test::LiveServer server;
  auto client = server.client();
  Json spec = Json::parse(test::readText(fs::path(RUPTURE_SOURCE_DIR) / "examples" / "dam-break-2d.json"));
  spec["run"]["ranks"] = 2;
  test::expectProblem(test::postJson(*client, "/processes/" + spec["scenario"].get<std::string>() + "/execution",
                                     {{"inputs", spec}}),
                      400, "run.ranks");
}

TEST(DistributedRuns, ADynamicTensionSpecAsksForRanksLikeAnImpactSpec) {
  test::LiveServer server;  // two workers
  auto client = server.client();
  Json spec = test::smallInputs();
  spec["run"]["ranks"] = 3;
  const Json problem = test::expectProblem(test::postJson(*client, test::kExecutePath, {{"inputs", spec}}), 400, "run.ranks");
  EXPECT_NE(problem.value("detail", "").find("run.ranks"), std::string::npos) << problem.dump(2);
}

}  // namespace
}  // namespace rupture::server
