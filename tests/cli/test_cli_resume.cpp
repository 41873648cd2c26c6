// `rupture run` stopped by SIGTERM (what Slurm and service managers send) writes a checkpoint and
// says how to continue; `--resume` continues it to the same result file, bit for bit, as a run
// never stopped; a fresh run over an interrupted one is refused unless --force; a damaged or
// foreign checkpoint is refused with exit 2 naming the reason.
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include <gtest/gtest.h>

#include "cli_runner.hpp"
#include "io/checkpoint_file.hpp"
#include "io/hdf5_file.hpp"
#include "support/hdf5_compare.hpp"
#include "support/test_support.hpp"

namespace {

namespace fs = std::filesystem;
using rupture::testing::readWhole;
using rupture::testing::runCli;
using rupture::testing::ScratchDir;
using rupture::testing::smallExampleSpec;
using rupture::testing::writeSpec;

nlohmann::json longRun() {
  nlohmann::json spec = smallExampleSpec();
  // From rest at 1e5 /s without a preliminary run: a few seconds of stepping to interrupt.
  spec["loading"] = {{"strain_rate", 1e5}, {"initial_velocity", "V0"}, {"ramp_time", 1e-9}};
  return spec;
}

/// Starts `rupture run SPEC -o OUT --threads 1 --json`, waits for its main run, sends SIGTERM and
/// returns the exit status; stderr goes to `err`.
int runAndTerminate(const std::string& specPath, const fs::path& out, const fs::path& err) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int devnull = ::open("/dev/null", O_WRONLY);
    const int e = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(devnull, 1);
    ::dup2(e, 2);
    ::execl(RUPTURE_CLI, RUPTURE_CLI, "run", specPath.c_str(), "-o", out.c_str(), "--threads", "1", "--json",
            static_cast<char*>(nullptr));
    ::_exit(127);
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (readWhole(err).find("main run") == std::string::npos && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  ::kill(pid, SIGTERM);
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(CliResume, SigtermCheckpointsAndResumeFinishesTheSameFile) {
  ScratchDir dir;
  const std::string specPath = writeSpec(longRun(), "cli-resume.json");
  const fs::path whole = dir.path() / "whole.h5", cut = dir.path() / "cut.h5", err = dir.path() / "err.txt";
  const fs::path checkpoint = rupture::io::checkpointPathFor(cut.string());

  ASSERT_EQ(runAndTerminate(specPath, cut, err), 130) << readWhole(err);
  const std::string said = readWhole(err);
  EXPECT_NE(said.find("checkpoint at step"), std::string::npos) << said;
  EXPECT_NE(said.find("--resume"), std::string::npos) << said;
  ASSERT_TRUE(fs::exists(checkpoint)) << said;
  const std::int64_t stoppedAt = rupture::io::readCheckpointHeader(checkpoint.string()).step;
  EXPECT_GT(stoppedAt, 0);

  // Starting afresh over an interrupted run is asked for, never a side effect.
  const auto fresh = runCli("run " + specPath + " -o " + cut.string() + " --threads 1");
  EXPECT_EQ(fresh.exitCode, 2);
  EXPECT_NE(fresh.err.find("holds an interrupted run"), std::string::npos) << fresh.err;

  const auto resumed = runCli("run " + specPath + " -o " + cut.string() + " --threads 1 --json --resume");
  ASSERT_EQ(resumed.exitCode, 0) << resumed.err;
  EXPECT_NE(resumed.err.find("resumed from the checkpoint at step " + std::to_string(stoppedAt)), std::string::npos)
      << resumed.err;
  EXPECT_FALSE(fs::exists(checkpoint)) << "a completed run removes its checkpoint";

  const auto plain = runCli("run " + specPath + " -o " + whole.string() + " --threads 1 --json");
  ASSERT_EQ(plain.exitCode, 0) << plain.err;
  EXPECT_EQ(rupture::testing::hdf5Differences(whole.string(), cut.string(),
                                              rupture::testing::howARunRan()),
            "");
  const rupture::io::Hdf5File file = rupture::io::Hdf5File::openReadOnly(cut.string());
  EXPECT_EQ(file.readAttributeString("/", "resumed_from_steps"), "[" + std::to_string(stoppedAt) + "]");
}

TEST(CliResume, DamagedForeignOrMissingCheckpointsAreRefusedWithExitTwo) {
  ScratchDir dir;
  const std::string specPath = writeSpec(longRun(), "cli-resume-refused.json");
  const fs::path cut = dir.path() / "cut.h5", err = dir.path() / "err.txt";
  const std::string checkpoint = rupture::io::checkpointPathFor(cut.string());

  const auto none = runCli("run " + specPath + " -o " + cut.string() + " --threads 1 --resume");
  EXPECT_EQ(none.exitCode, 2);
  EXPECT_NE(none.err.find("no checkpoint at"), std::string::npos) << none.err;

  ASSERT_EQ(runAndTerminate(specPath, cut, err), 130) << readWhole(err);
  ASSERT_TRUE(fs::exists(checkpoint));

  // Another spec: a different strain rate is another run.
  nlohmann::json other = longRun();
  other["loading"]["strain_rate"] = 2e5;
  const auto foreign = runCli("run " + writeSpec(other, "cli-resume-other.json") + " -o " + cut.string() + " --resume");
  EXPECT_EQ(foreign.exitCode, 2);
  EXPECT_NE(foreign.err.find("belongs to another spec"), std::string::npos) << foreign.err;
  EXPECT_NE(foreign.err.find("loading.strain_rate"), std::string::npos) << foreign.err;

  // How often to checkpoint is not part of the run's identity.
  nlohmann::json interval = longRun();
  interval["run"]["checkpoint_interval_s"] = 60;
  const std::string intervalPath = writeSpec(interval, "cli-resume-interval.json");

  // Damaged: the file cut in half.
  const std::string bytes = readWhole(checkpoint);
  { std::ofstream(checkpoint, std::ios::binary | std::ios::trunc) << bytes.substr(0, bytes.size() / 2); }
  const auto damaged = runCli("run " + intervalPath + " -o " + cut.string() + " --resume");
  EXPECT_EQ(damaged.exitCode, 2);
  EXPECT_NE(damaged.err.find("cannot be read"), std::string::npos) << damaged.err;
  EXPECT_TRUE(fs::exists(checkpoint)) << "a refused checkpoint is left for the user";

  // Starting afresh is there when asked for.
  const auto again = runCli("run " + intervalPath + " -o " + cut.string() + " --threads 1 --force");
  EXPECT_EQ(again.exitCode, 0) << again.err;
  EXPECT_FALSE(fs::exists(checkpoint));
}

}  // namespace
