#pragma once
// Runs one run over several MPI ranks on this machine: `mpirun -np N rupture run SPEC -o RESULT`
// (docs/distributed.md), for the local executor, which runs one-rank runs in its own process.
// The child's progress file feeds the RunControl's progress and stages, the RunControl's cancel
// becomes a SIGTERM to mpirun (which ends every rank), and the CLI's exit code and last error line
// become the outcome, so that the scheduler treats both kinds of run alike.
#include <filesystem>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "rupture/run.hpp"

namespace rupture::server {

struct MpiLauncher {
  std::string mpirun;  ///< the mpirun that starts the ranks (Open MPI's)
  std::string cli;     ///< the rupture binary each rank runs

  /// mpirun on PATH and a CLI built with MPI beside this server, or nullopt with why not in `why`.
  static std::optional<MpiLauncher> find(const std::string& cli, std::string& why);

  /// Runs `spec` on `ranks` ranks of `threads` OpenMP threads each, writing `resultPath` (the
  /// engine's .part, as runSpec does), continuing from the ranks' checkpoints with control.resume.
  /// The spec is written beside it as <resultPath>.spec.json. Throws std::runtime_error with the
  /// CLI's error when the run fails (rupture::CheckpointError when the checkpoints cannot be taken
  /// up); completed = false when control.cancel stopped it.
  rupture::RunOutcome run(const nlohmann::json& spec, const std::filesystem::path& resultPath,
                          rupture::RunControl& control, int ranks, int threads) const;
};

/// The ranks a spec asks for (run.ranks; 1 when absent or not a positive integer).
int requestedRanks(const nlohmann::json& spec);

}  // namespace rupture::server
