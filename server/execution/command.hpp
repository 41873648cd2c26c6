#pragma once
// Runs an external program (sbatch, squeue, scontrol, scancel, mpirun) without a shell: argv as
// given, stdout and stderr captured, a time limit after which it is killed. Safe to call from any thread.
#include <chrono>
#include <functional>
#include <string>
#include <vector>

namespace rupture::server {

struct CommandResult {
  int exitCode = -1;    ///< the program's exit status; -1 if it could not start, was killed or timed out
  std::string output;   ///< stdout
  std::string error;    ///< stderr, or why it could not run
  bool ok() const { return exitCode == 0; }
};

CommandResult runCommand(const std::vector<std::string>& argv,
                         std::chrono::milliseconds timeout = std::chrono::seconds(30));

/// A long-running program (a run under mpirun): no time limit; `watch` is called about every
/// 0.2 s while it runs, and once it returns true the program gets SIGTERM, then SIGKILL if it
/// has not ended 10 s later. Only the last `keepErrorBytes` of stderr are kept.
CommandResult runWatchedCommand(const std::vector<std::string>& argv, const std::function<bool()>& watch,
                                std::size_t keepErrorBytes = 64 * 1024);

}  // namespace rupture::server
