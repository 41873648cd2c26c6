#pragma once
// Runs an external program (sbatch, squeue, scontrol, scancel) without a shell: argv as given,
// stdout and stderr captured, a time limit after which it is killed. Safe to call from any thread.
#include <chrono>
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

}  // namespace rupture::server
