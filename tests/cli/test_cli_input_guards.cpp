// Inputs that used to crash or mislead the CLI: JSON nested deep enough to overflow a recursive
// dump, numbers beyond the double range, a spec file that cannot be read, a result file on a
// full disk (HDF5 used to leave a half-closed file behind and segfault at exit), and specs that
// could never finish (issue 56: they spun at 100 % CPU and ignored Ctrl-C).
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <thread>

#include <gtest/gtest.h>

#include "cli_runner.hpp"
#include "rupture/run.hpp"
#include "support/small_filesystem.hpp"

namespace {

namespace fs = std::filesystem;
using rupture::testing::readWhole;
using rupture::testing::runCli;
using rupture::testing::SmallFilesystem;
using rupture::testing::smallExampleSpec;
using rupture::testing::writeSpec;

std::string writeText(const std::string& text, const std::string& name) {
  const auto path = fs::temp_directory_path() / ("rupture-cli-guards-" + name);
  std::ofstream(path, std::ios::binary) << text;
  return path.string();
}

TEST(CliInputGuards, DeeplyNestedJsonExits2) {
  const std::string deep = std::string(70000, '[') + std::string(70000, ']');
  const std::string file = writeText(deep, "deep.json");
  for (const std::string& args : {"validate " + file, "run " + file + " -o /dev/null"}) {
    const auto r = runCli(args);
    EXPECT_EQ(r.exitCode, 2) << args << r.err;
    EXPECT_NE(r.err.find("nested more than 64 levels"), std::string::npos) << r.err;
  }
}

TEST(CliInputGuards, NumbersBeyondTheDoubleRangeExit2NamingTheField) {
  nlohmann::json spec = smallExampleSpec();
  std::string text = spec.dump();
  const std::string key = "\"strain_rate\":";
  const auto at = text.find(key);
  ASSERT_NE(at, std::string::npos);
  const auto end = text.find_first_of(",}", at + key.size());
  text = text.substr(0, at + key.size()) + "1e400" + text.substr(end);
  const auto r = runCli("validate " + writeText(text, "huge.json"));
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_NE(r.err.find("'loading.strain_rate' = 1e400"), std::string::npos) << r.err;
}

TEST(CliInputGuards, AnUnreadableSpecFileSaysWhy) {
  const auto r = runCli("validate /nonexistent/spec.json");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("No such file or directory"), std::string::npos) << r.err;
}

TEST(CliInputGuards, AFullDiskFailsTheRunCleanly) {
  SmallFilesystem disk(200 * 1024);  // the small example's result file is several hundred kB
  if (!disk.mounted()) GTEST_SKIP() << disk.whyNot();
  nlohmann::json spec = smallExampleSpec();
  spec["loading"] = {{"strain_rate", 1e7}, {"initial_velocity", "VL"}};
  const fs::path out = disk.path() / "run.h5";
  const auto r = runCli("run " + writeSpec(spec, "full-disk.json") + " -o " + out.string() + " --threads 1");
  EXPECT_EQ(r.exitCode, 1) << "a crash shows as -1: " << r.err;  // not 139 (SIGSEGV in HDF5's exit handler)
  EXPECT_NE(r.err.find("No space left on device"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("0x"), std::string::npos) << "no buffer addresses in messages: " << r.err;
  EXPECT_TRUE(fs::is_empty(disk.path())) << "nothing half-written is left";
}

TEST(CliInputGuards, SpecsThatCouldNeverFinishExit2NamingTheField) {
  const std::pair<const char*, double> runaway[] = {{"/loading/strain_rate", 1e20},
                                                   {"/material/density", 1e308},
                                                   {"/material/beam/young_modulus", 1e-300}};
  for (const auto& [pointer, value] : runaway) {
    nlohmann::json spec = smallExampleSpec();
    spec[nlohmann::json::json_pointer(pointer)] = value;
    std::string field = std::string(pointer).substr(1);
    std::replace(field.begin(), field.end(), '/', '.');
    const std::string path = writeSpec(spec, "runaway.json");
    for (const std::string& command : {"validate " + path, "run " + path + " -o /dev/null"}) {
      const auto r = runCli(command);
      EXPECT_EQ(r.exitCode, 2) << command << ": " << r.err;
      EXPECT_NE(r.err.find("'" + field + "'"), std::string::npos) << r.err;
    }
  }
}

TEST(CliInputGuards, RunsAboveMaxRunStepsExit2WithTheEstimate) {
  nlohmann::json spec = smallExampleSpec();
  spec["loading"] = {{"strain_rate", 1e3}, {"initial_velocity", "VL"}};
  nlohmann::json full = spec;
  const double steps = rupture::estimateRun(full).steps;
  const std::string path = writeSpec(spec, "long.json");
  const std::string edge = std::to_string(static_cast<long long>(std::ceil(steps)));
  EXPECT_EQ(runCli("validate " + path).exitCode, 0) << "the default admits it";
  EXPECT_EQ(runCli("validate " + path + " --max-run-steps " + edge).exitCode, 0);
  const std::string below = std::to_string(static_cast<long long>(steps / 2));
  for (const std::string& command : {"validate " + path + " --max-run-steps " + below,
                                     "run " + path + " -o /dev/null --max-run-steps " + below}) {
    const auto r = runCli(command);
    EXPECT_EQ(r.exitCode, 2) << command << ": " << r.err;
    EXPECT_NE(r.err.find("'loading.strain_rate'"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("--max-run-steps"), std::string::npos) << r.err;
  }
}

/// Spawns `rupture run SPEC -o OUT`, waits until its stderr shows `stage`, presses Ctrl-C and
/// returns the seconds until it exited (its exit code in `code`), or -1 when it did not show it.
double secondsToStopOnSigint(const std::string& specPath, const fs::path& out, const std::string& stage, int& code,
                             std::string& err) {
  const fs::path stderrPath = out.string() + ".stderr";
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int e = ::open(stderrPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int o = ::open("/dev/null", O_WRONLY);
    ::dup2(o, 1);
    ::dup2(e, 2);
    ::execl(RUPTURE_CLI, RUPTURE_CLI, "run", specPath.c_str(), "-o", out.c_str(), "--threads", "1", "--force",
            static_cast<char*>(nullptr));
    ::_exit(127);
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (readWhole(stderrPath).find(stage) == std::string::npos && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  const bool seen = readWhole(stderrPath).find(stage) != std::string::npos;
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  const auto start = std::chrono::steady_clock::now();
  ::kill(pid, SIGINT);
  int status = 0;
  ::waitpid(pid, &status, 0);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  err = readWhole(stderrPath);
  return seen ? seconds : -1;
}

/// Runs `spec` with `rupture run`, presses Ctrl-C once its stderr shows `stage`, and expects it to
/// exit with 130 within 2 s (the checkpoint of the run so far included); removes what it wrote.
void expectCtrlCStopsWithinASecond(const nlohmann::json& spec, const std::string& name, const std::string& stage) {
  const fs::path out = fs::temp_directory_path() / ("rupture-cli-guards-" + name + "-" + std::to_string(::getpid()) + ".h5");
  int code = 0;
  std::string err;
  const double seconds = secondsToStopOnSigint(writeSpec(spec, name + ".json"), out, stage, code, err);
  std::cout << "[ measured ] rupture run exited " << seconds << " s after SIGINT during '" << stage << "'\n";
  EXPECT_GE(seconds, 0) << err;
  EXPECT_EQ(code, 130) << err;
  EXPECT_LT(seconds, 2.0) << err;  // the issue asks for 1 s; the margin is for a loaded CI machine
  for (const char* suffix : {"", ".checkpoint", ".stderr"}) fs::remove(out.string() + suffix);
  fs::remove(fs::path(out).replace_extension(".xdmf2"));
}

TEST(CliInputGuards, ALongAdmittedRunStopsOnCtrlCWithinASecond) {
  nlohmann::json spec = smallExampleSpec();
  spec["loading"] = {{"strain_rate", 1e3}, {"initial_velocity", "VL"}};  // half an hour of one core
  expectCtrlCStopsWithinASecond(spec, "long-run", "main run");
}

TEST(CliInputGuards, CtrlCStopsTheBuildingOfALargeSampleWithinASecond) {
  nlohmann::json spec = smallExampleSpec();
  // About 400,000 elements: the packing alone takes tens of seconds on one core.
  spec["sample"]["size"] = {4.3e-6, 4.3e-6};
  spec["sample"]["element_radius"] = 3.3e-9;
  spec["sample"]["porosity"] = 0;
  spec["sample"].erase("pore_radius");
  spec["loading"] = {{"strain_rate", 1e6}, {"initial_velocity", "VL"}};
  spec["output"] = {{"cache_sample", false}};
  expectCtrlCStopsWithinASecond(spec, "large-sample", "building the sample");
}

}  // namespace
