#include "execution/mpi_launch.hpp"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <system_error>
#include <thread>

#include <unistd.h>

#include "common/files.hpp"
#include "execution/command.hpp"
#include "rupture/run.hpp"
#include "rupture/state_archive.hpp"

namespace rupture::server {
namespace fs = std::filesystem;
namespace {

/// The first executable `name` on PATH, or empty.
std::string onPath(const std::string& name) {
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path ? path : "/usr/local/bin:/usr/bin:/bin");
  for (std::string dir; std::getline(dirs, dir, ':');) {
    if (dir.empty()) continue;
    const fs::path candidate = fs::path(dir) / name;
    if (::access(candidate.c_str(), X_OK) == 0) return candidate.string();
  }
  return {};
}

/// The last line of `text` that says something (the CLI's error).
std::string lastLine(const std::string& text) {
  std::istringstream lines(text);
  std::string last;
  for (std::string line; std::getline(lines, line);)
    if (line.find_first_not_of(" \t\r") != std::string::npos) last = line;
  return last;
}

/// Removes the files the launch adds beside the result, however the run ends.
struct LaunchFiles {
  fs::path spec, progress, sidecar;
  ~LaunchFiles() {
    std::error_code ec;
    for (const fs::path& p : {spec, progress, fs::path(progress.string() + ".tmp"), sidecar}) fs::remove(p, ec);
  }
};

}  // namespace

int requestedRanks(const nlohmann::json& spec) {
  const nlohmann::json::json_pointer at("/run/ranks");
  if (!spec.is_object() || !spec.contains(at) || !spec.at(at).is_number_integer()) return 1;
  return static_cast<int>(std::clamp<long long>(spec.at(at).get<long long>(), 1, rupture::kMaxRanks));
}

std::optional<MpiLauncher> MpiLauncher::find(const std::string& cli, std::string& why) {
#ifndef RUPTURE_HAVE_MPI
  (void)cli;
  why = "this server was built without MPI (RUPTURE_MPI off, or libopenmpi-dev missing)";
  return std::nullopt;
#else
  MpiLauncher launcher;
  launcher.mpirun = onPath("mpirun");
  if (launcher.mpirun.empty()) {
    why = "this server finds no mpirun on its PATH (Debian: apt-get install openmpi-bin)";
    return std::nullopt;
  }
  launcher.cli = cli.find('/') == std::string::npos ? onPath(cli) : cli;
  if (launcher.cli.empty() || ::access(launcher.cli.c_str(), X_OK) != 0) {
    why = "this server finds no rupture binary to start on the ranks ('" + cli + "'; --rupture-cli names it)";
    return std::nullopt;
  }
  return launcher;
#endif
}

rupture::RunOutcome MpiLauncher::run(const nlohmann::json& spec, const fs::path& resultPath, rupture::RunControl& control,
                                     int ranks, int threads) const {
  // The CLI's ParaView sidecar: RUN.xdmf2 beside RUN.h5, RESULT.xdmf2 beside any other name (a .part).
  const fs::path sidecar = resultPath.extension() == ".h5" ? fs::path(resultPath).replace_extension(".xdmf2")
                                                           : fs::path(resultPath.string() + ".xdmf2");
  LaunchFiles files{resultPath.string() + ".spec.json", resultPath.string() + ".progress.json", sidecar};
  writeFileAtomic(files.spec, spec.dump(2) + "\n");
  std::vector<std::string> argv{mpirun, "-np", std::to_string(ranks), "--bind-to", "none"};
  // The server's workers, not mpirun's count of cores, decide how many ranks this machine runs.
  if (ranks > static_cast<int>(std::thread::hardware_concurrency())) argv.push_back("--oversubscribe");
  if (::geteuid() == 0) argv.push_back("--allow-run-as-root");  // containers and CI run as root
  for (const std::string& a : {cli, std::string("run"), files.spec.string(), std::string("-o"), resultPath.string(),
                               std::string("--threads"), std::to_string(std::max(1, threads)), std::string("--progress-file"),
                               files.progress.string(), std::string("--json")})
    argv.push_back(a);
  // Every rank continues from its own checkpoint (the scheduler found the first rank's).
  argv.push_back(control.resume ? "--resume" : "--force");

  std::string stage;
  auto lastRead = std::chrono::steady_clock::now();
  auto watch = [&] {
    if (control.cancel.load()) return true;
    const auto now = std::chrono::steady_clock::now();
    if (now - lastRead < std::chrono::seconds(1)) return false;
    lastRead = now;
    try {  // the CLI renames a complete file into place: any read is whole or absent
      if (auto text = readFile(files.progress)) {
        const nlohmann::json doc = nlohmann::json::parse(*text);
        if (doc.contains("progress") && doc["progress"].is_number()) control.progress = doc["progress"].get<double>();
        if (doc.contains("stage") && doc["stage"].is_string() && doc["stage"].get<std::string>() != stage) {
          stage = doc["stage"].get<std::string>();
          if (control.log && !stage.empty()) control.log(stage);
          // The ranks continued from their checkpoints: the store records where, as for a run in process.
          constexpr std::string_view kResumed = "resumed from the checkpoint at step ";
          if (stage.rfind(kResumed, 0) == 0) control.resumedFromStep = std::atoll(stage.c_str() + kResumed.size());
        }
      }
    } catch (const std::exception&) {  // a watcher's convenience, never a reason to fail the run
    }
    return false;
  };
  const CommandResult r = runWatchedCommand(argv, watch);
  const std::string ranksText = std::to_string(ranks) + " ranks";
  if (r.exitCode == 0) {
    rupture::RunOutcome outcome;
    try {
      outcome.summary = nlohmann::json::parse(r.output);
    } catch (const std::exception& e) {
      throw std::runtime_error("rupture run on " + ranksText + " ended well but its summary is not JSON (" + e.what() + ")");
    }
    outcome.completed = true;
    return outcome;
  }
  if (control.cancel.load() || r.exitCode == kExitInterrupted) {
    rupture::RunOutcome outcome;
    outcome.completed = false;
    return outcome;
  }
  const std::string said = lastLine(r.error);
  // A checkpoint the ranks cannot take up (another rank count, a rank's file missing): the
  // scheduler removes it, and a retry starts afresh.
  if (control.resume && r.exitCode == 2 && said.find("cannot resume") != std::string::npos)
    throw rupture::CheckpointError("rupture run on " + ranksText + ": " + said);
  throw std::runtime_error("rupture run on " + ranksText + " (mpirun) failed" +
                           (r.exitCode >= 0 ? " with exit code " + std::to_string(r.exitCode) : std::string()) +
                           (said.empty() ? std::string() : ": " + said));
}

}  // namespace rupture::server
