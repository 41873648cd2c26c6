#pragma once
// The Slurm executor (--executor slurm): each job becomes one `sbatch --array` whose task ids are
// the run indices (one array per rank count when runs ask for several MPI ranks, run.ranks, which
// srun starts); a generated batch script runs `rupture run` on the run's spec file in the shared
// directory. The cluster's queue replaces the worker threads; a tracker thread follows the runs.
//
// Files of run k of job J, in <shared-dir>/jobs/J/ (the truth; the store is the record):
//   run-k.spec.json      the spec (written before submission)
//   run-k.slurm          the Slurm array job id the run was last submitted in
//   run-k.progress.json  written by `rupture run --progress-file` about once a second
//   run-k.log            the run's stderr (its last line is the error of a failed run)
//   run-k.h5.part        the run file while it is written; renamed to run-k.h5 only when complete,
//   run-k.summary.json   after the summary (the CLI's stdout) is in place
//   run-k.status         the exit code of `rupture run`, written last
//   run-k.h5.checkpoint  the run's checkpoint (docs/checkpoints.md): a run stopped by its time limit's
//                        warning (sbatch --signal) exits 130 with one, and is submitted again with
//                        --resume to continue in the next allocation
//   run-k.resumed-step   the step the last resubmission continued from (no step gained: failed)
//   slurm/<n>.sbatch     the batch script of each submission; slurm/%A_%a.out Slurm's own output
//
// Tracking (every second): a status file decides (0 = successful, with the summary; else failed
// with the log's last line and Slurm's state); without one, squeue says pending or running (progress
// from the progress file), and a task squeue no longer lists is asked of scontrol, whose state and
// reason (TIMEOUT, NODE_FAIL, CANCELLED, PREEMPTED, ...) make the failure message. Slurm accounting
// is never needed. Stopping the server leaves the cluster's runs alone; the next start re-attaches
// to them through run-k.slurm (or, for a submission whose ids were not written yet, through the
// job name rupture-job-J) instead of submitting twice.
#include <atomic>
#include <condition_variable>
#include <filesystem>
#include <map>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "execution/executor.hpp"

namespace rupture::server {

struct SlurmSettings {
  std::filesystem::path sharedDir;  ///< holds jobs/ and cache/
  std::string partition, account, time;
  int checkpointLead = 120;  ///< s before the time limit: SIGTERM, a checkpoint, a resubmission
  int cpusPerRun = 1;
  int maxRanks = 64;              ///< most ranks one run may ask for (run.ranks)
  std::string mpiPlugin = "pmix";  ///< srun --mpi for runs of several ranks
  std::vector<std::string> options;  ///< extra #SBATCH lines
  std::string cli;                   ///< the rupture binary on the compute nodes
  std::chrono::milliseconds pollInterval{1000};
};

class SlurmExecutor : public Executor {
public:
  SlurmExecutor(JobStore& store, SlurmSettings settings);
  ~SlurmExecutor() override;
  SlurmExecutor(const SlurmExecutor&) = delete;
  SlurmExecutor& operator=(const SlurmExecutor&) = delete;

  void start() override;
  void enqueue(std::int64_t jobId, int runs) override;
  void resubmit(std::int64_t jobId, const std::vector<int>& indices) override;
  std::optional<JobRecord> dismiss(std::int64_t jobId) override;
  /// The cluster's runs go on; only the tracker stops (the next start re-attaches).
  void requestStop() override {}
  void shutdown() override;

  const char* name() const override { return "slurm"; }
  int workers() const override { return 0; }
  int threadsPerRun() const override { return m_settings.cpusPerRun; }
  RankLimit rankLimit() const override {
    return {m_settings.maxRanks, "this server's --slurm-max-ranks; each rank takes --slurm-cpus-per-run " +
                                     std::to_string(m_settings.cpusPerRun) + " CPU(s)"};
  }
  bool waitingForDisk() const override { return false; }
  int unrecordedOutcomes() const override { return 0; }
  std::filesystem::path jobDir(std::int64_t jobId) const override;

  /// The batch script of a submission of runs of `ranks` ranks (also written under slurm/ for the record).
  std::string batchScript(std::int64_t jobId, int ranks = 1) const;

private:
  std::filesystem::path runPath(RunKey key, const std::string& suffix) const;
  /// Writes the specs and the script and calls sbatch; on failure the runs are recorded failed.
  void submit(std::int64_t jobId, const std::vector<int>& indices);
  /// Records the runs failed with the reason (a submission that did not happen).
  void failRuns(std::int64_t jobId, const std::vector<int>& indices, const std::string& why);
  void trackLoop();
  void poll();
  /// Records the outcome of a run whose status file exists. False if the files are not complete yet.
  void recordFinished(RunKey key, int exitCode, const std::string& slurmState);
  std::string slurmStateOf(const std::string& taskId, std::string& reason) const;
  /// A run that stopped with a checkpoint (exit 130) goes back to the queue to continue from it;
  /// false (with the reason in `why`) when it cannot: no checkpoint, or no step gained since the last time.
  bool continueInNextAllocation(RunKey key, std::string& why);

  JobStore& m_store;
  SlurmSettings m_settings;
  std::mutex m_submitMutex;  // one submission at a time (sbatch, files)
  std::mutex m_mutex;
  std::condition_variable m_wake;
  bool m_stopping = false;
  bool m_started = false;
  std::thread m_tracker;
  std::map<std::string, int> m_missingStatusPolls;  // task id -> polls since Slurm said it completed
};

}  // namespace rupture::server
