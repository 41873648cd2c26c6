// `rupture run` through the real binary: a run writes RUN.h5 + RUN.xdmf2 and prints the summary
// once (a table, or with --json the JSON); it never replaces a file without --force; invalid specs
// exit 2 naming the field; Ctrl-C (SIGINT) leaves a valid file marked incomplete and exits 130.
// Also: --help lists every option the CLI accepts, and `validate` knows a server request file.
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <set>
#include <filesystem>
#include <random>
#include <regex>
#include <thread>

#include <gtest/gtest.h>

#include "support/test_support.hpp"
#include "cli_runner.hpp"
#include "io/hdf5_file.hpp"

namespace {

namespace fs = std::filesystem;
using rupture::testing::readWhole;
using rupture::testing::runCli;
using rupture::testing::smallExampleSpec;
using rupture::testing::writeSpec;
using rupture::testing::ScratchDir;

TEST(CliRun, WritesResultSidecarAndSummary) {
  ScratchDir dir;
  nlohmann::json spec = smallExampleSpec();
  spec["loading"] = {{"strain_rate", 1e7}, {"initial_velocity", "VL"}};
  spec["run"]["snapshot_strains"] = {0.0, 3e-4};
  const fs::path out = dir.path() / "run.h5";
  const auto r = runCli("run " + writeSpec(spec, "cli-run-ok.json") + " -o " + out.string() + " --threads 1 --json");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const nlohmann::json summary = nlohmann::json::parse(r.out);  // stdout is exactly the summary
  EXPECT_EQ(summary["completed"], 1);
  EXPECT_GT(summary["peak_stress"].get<double>(), 1e7);
  EXPECT_TRUE(summary.contains("crack_onset_strain"));
  EXPECT_TRUE(fs::exists(out));
  EXPECT_FALSE(fs::exists(out.string() + ".part"));
  // Not a terminal: plain progress lines, no bar.
  EXPECT_NE(r.err.find("100 %"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find('\r'), std::string::npos);

  const fs::path sidecar = dir.path() / "run.xdmf2";
  ASSERT_TRUE(fs::exists(sidecar));
  const std::string xml = readWhole(sidecar);
  rupture::io::Hdf5File file = rupture::io::Hdf5File::openReadOnly(out.string());
  const std::regex ref(R"(>\s*([^<>:\s]+\.h5):(/[^<\s]+)\s*<)");
  int refs = 0;
  for (auto it = std::sregex_iterator(xml.begin(), xml.end(), ref); it != std::sregex_iterator(); ++it, ++refs)
    EXPECT_TRUE(file.exists((*it)[2].str())) << (*it)[2].str();
  // Snapshots at 0, 3e-4 and the final one; per snapshot 5 particle datasets and 5 of the bond grid
  // (pairs, positions, bond_intact, bond_load, bond_equivalent_stress).
  EXPECT_EQ(refs, 3 * (5 + 5));
  EXPECT_DOUBLE_EQ(file.readAttributeDouble("/summary", "peak_stress"), summary["peak_stress"].get<double>());
}

struct BadRunSpec {
  const char* name;
  const char* pointer;
  nlohmann::json value;  // null: remove the field
  const char* field;
};

void PrintTo(const BadRunSpec& bad, std::ostream* os) { *os << bad.name; }

class CliRunBadSpec : public ::testing::TestWithParam<BadRunSpec> {};

TEST_P(CliRunBadSpec, ExitsTwoNamingTheField) {
  const BadRunSpec& bad = GetParam();
  nlohmann::json spec = smallExampleSpec();
  const nlohmann::json::json_pointer pointer(bad.pointer);
  if (bad.value.is_null()) spec[pointer.parent_pointer()].erase(pointer.back());
  else spec[pointer] = bad.value;
  ScratchDir dir;
  const fs::path out = dir.path() / "never.h5";
  const auto r = runCli("run " + writeSpec(spec, std::string("cli-run-") + bad.name + ".json") + " -o " + out.string());
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_NE(r.err.find(std::string("field '") + bad.field + "'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("allowed"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty());
  EXPECT_FALSE(fs::exists(out));
}

INSTANTIATE_TEST_SUITE_P(
    Specs, CliRunBadSpec,
    ::testing::Values(BadRunSpec{"unknown-field", "/loading/initial_velocity", "VZ", "loading.initial_velocity"},
                      BadRunSpec{"negative-rate", "/loading/strain_rate", -1e6, "loading.strain_rate"},
                      BadRunSpec{"missing-scenario", "/scenario", nullptr, "scenario"},
                      BadRunSpec{"unknown-key", "/run/snapshots", 3, "run.snapshots"}),
    [](const auto& info) {
      std::string n = info.param.name;
      for (char& c : n) if (c == '-') c = '_';
      return n;
    });

TEST(CliRun, UsageErrorsExitTwo) {
  EXPECT_EQ(runCli("run").exitCode, 2);
  EXPECT_EQ(runCli("run " + writeSpec(smallExampleSpec(), "cli-run-noout.json")).exitCode, 2);  // no -o
  EXPECT_EQ(runCli("run a.json -o x.h5 --threads 0").exitCode, 2);
  EXPECT_EQ(runCli("run a.json -o x.h5 --fast").exitCode, 2);
  const auto missing = runCli("run /nonexistent/spec.json -o x.h5");
  EXPECT_EQ(missing.exitCode, 2);
}

TEST(CliRun, InterruptLeavesAValidIncompleteFile) {
  ScratchDir dir;
  nlohmann::json spec = smallExampleSpec();
  // A long run without preliminary: from rest at 2e4 /s (about 15 s of computing).
  spec["loading"] = {{"strain_rate", 2e4}, {"initial_velocity", "V0"}, {"ramp_time", 1e-9}};
  const std::string specPath = writeSpec(spec, "cli-run-interrupt.json");
  const fs::path out = dir.path() / "cut.h5";
  const fs::path stdoutPath = dir.path() / "stdout.txt", stderrPath = dir.path() / "stderr.txt";

  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    const int o = ::open(stdoutPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int e = ::open(stderrPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(o, 1);
    ::dup2(e, 2);
    ::execl(RUPTURE_CLI, RUPTURE_CLI, "run", specPath.c_str(), "-o", out.c_str(), "--threads", "1",
            "--json", static_cast<char*>(nullptr));
    ::_exit(127);
  }
  // Wait until the main run has started, then press Ctrl-C.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (readWhole(stderrPath).find("main run") == std::string::npos && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  ::kill(pid, SIGINT);
  int status = 0;
  ::waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status)) << readWhole(stderrPath);
  EXPECT_EQ(WEXITSTATUS(status), 130) << readWhole(stderrPath);

  const nlohmann::json summary = nlohmann::json::parse(readWhole(stdoutPath));
  EXPECT_EQ(summary["completed"], 0);
  EXPECT_EQ(summary["stop_reason"], "cancelled");
  rupture::io::Hdf5File file = rupture::io::Hdf5File::openReadOnly(out.string());
  EXPECT_EQ(file.readAttributeInt("/summary", "completed"), 0);
  EXPECT_GT(file.datasetDims("/series/time")[0], 1u);
  EXPECT_TRUE(fs::exists(dir.path() / "cut.xdmf2"));
  EXPECT_FALSE(fs::exists(out.string() + ".part"));
}

TEST(CliRun, PrintsOneTableAndNeverReplacesAFileUnasked) {
  ScratchDir dir;
  nlohmann::json spec = smallExampleSpec();
  spec["loading"] = {{"strain_rate", 1e7}, {"initial_velocity", "VL"}};
  const std::string specPath = writeSpec(spec, "cli-run-table.json");
  const fs::path out = dir.path() / "run.h5";
  const auto r = runCli("run " + specPath + " -o " + out.string() + " --threads 1");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  // The summary once, on stdout, as a table in engineering units; none of it on stderr.
  EXPECT_NE(r.out.find("Peak stress"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(" MPa\n"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find('{'), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("e+"), std::string::npos) << "no e-notation for a reader: " << r.out;
  EXPECT_EQ(r.err.find("Peak stress"), std::string::npos) << r.err;

  // A second run to the same file is refused before any work, and the file is left as it was.
  const auto sizeBefore = fs::file_size(out);
  const auto timeBefore = fs::last_write_time(out);
  const auto again = runCli("run " + specPath + " -o " + out.string() + " --threads 1");
  EXPECT_EQ(again.exitCode, 2) << again.err;
  EXPECT_NE(again.err.find("exists"), std::string::npos) << again.err;
  EXPECT_NE(again.err.find("--force"), std::string::npos) << again.err;
  EXPECT_EQ(fs::file_size(out), sizeBefore);
  EXPECT_EQ(fs::last_write_time(out), timeBefore);

  // --force replaces it; --json prints the JSON instead of the table.
  const auto forced = runCli("run " + specPath + " -o " + out.string() + " --threads 1 --force --json");
  ASSERT_EQ(forced.exitCode, 0) << forced.err;
  EXPECT_EQ(nlohmann::json::parse(forced.out)["completed"], 1);
  EXPECT_EQ(forced.out.find("Peak stress"), std::string::npos);
}

TEST(CliHelp, ListsEveryOptionTheCommandsAccept) {
  // Every "--option" string in the CLI's sources (an argument compared with it, or a table of
  // accepted options) is in `rupture --help`, and every option of `run` in `rupture run --help`.
  const auto help = runCli("--help");
  ASSERT_EQ(help.exitCode, 0);
  const auto runHelp = runCli("run --help");
  ASSERT_EQ(runHelp.exitCode, 0);
  const std::regex option(R"re("(--[a-z][a-z-]*)")re");
  std::set<std::string> seen;
  for (const auto& entry : fs::directory_iterator(fs::path(RUPTURE_SOURCE_DIR) / "engine" / "cli")) {
    const std::string text = readWhole(entry.path());
    for (auto it = std::sregex_iterator(text.begin(), text.end(), option); it != std::sregex_iterator(); ++it) {
      const std::string name = (*it)[1].str();
      seen.insert(name);
      EXPECT_NE(help.out.find(name), std::string::npos) << name << " (" << entry.path().filename() << ")";
      if (entry.path().filename() == "command_run.cpp") {
        EXPECT_NE(runHelp.out.find(name), std::string::npos) << name;
      }
    }
  }
  for (const char* name : {"--progress-file", "--json", "--force", "--scenario", "--target-tensile-strength", "--series",
                           "--slice"})
    EXPECT_TRUE(seen.count(name)) << name << " is accepted but the scan did not find it";
  // A subcommand's --help is help, not an error.
  EXPECT_EQ(runCli("calibrate --help").exitCode, 0);
  EXPECT_EQ(runCli("validate -h").exitCode, 0);
  EXPECT_NE(runCli("plot --help").out.find("--bonds"), std::string::npos);
}

TEST(CliValidate, RecognisesAServerRequestFile) {
  nlohmann::json inputs = smallExampleSpec();
  inputs.erase("scenario");
  const nlohmann::json request = {{"name", "rate sweep"}, {"inputs", inputs},
                                  {"sweep", {{"loading.strain_rate", {1e6, 1e7}}}}};
  const std::string path = writeSpec(request, "request.json");
  // Without the scenario (the URL names it) it says what the file is and what to add.
  const auto unnamed = runCli("validate " + path);
  EXPECT_EQ(unnamed.exitCode, 2);
  EXPECT_NE(unnamed.err.find("server request file"), std::string::npos) << unnamed.err;
  EXPECT_NE(unnamed.err.find("--scenario"), std::string::npos) << unnamed.err;
  const auto named = runCli("validate " + path + " --scenario dynamic-tension");
  EXPECT_EQ(named.exitCode, 0) << named.err;
  EXPECT_NE(named.out.find("POST /processes/dynamic-tension/execution"), std::string::npos) << named.out;
  // Its inputs are checked as the spec, naming the field.
  nlohmann::json bad = request;
  bad["inputs"]["sample"]["porosity"] = 2;
  const auto invalid = runCli("validate " + writeSpec(bad, "request-bad.json") + " --scenario dynamic-tension");
  EXPECT_EQ(invalid.exitCode, 2);
  EXPECT_NE(invalid.err.find("sample.porosity"), std::string::npos) << invalid.err;
  // A scenario that does not exist is named with the allowed ones.
  const auto unknown = runCli("validate " + path + " --scenario no-such");
  EXPECT_EQ(unknown.exitCode, 2);
  EXPECT_NE(unknown.err.find("dynamic-tension"), std::string::npos) << unknown.err;
}

}  // namespace
