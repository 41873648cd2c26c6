#pragma once
// Where runs execute, behind one interface so the HTTP API does not change with it:
//   Scheduler      (scheduler.hpp)       worker threads of this process (--executor local)
//   SlurmExecutor  (slurm_executor.hpp)  one `sbatch --array` per job on a Slurm cluster (--executor slurm)
// Both keep the job store as the record and the run files as the truth: a run is successful when
// <jobs-dir>/<id>/run-<k>.h5 and its summary exist.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "jobs/job_store.hpp"

namespace rupture::server {

class Executor {
public:
  virtual ~Executor() = default;

  /// Repairs what a stop left behind, resumes unfinished runs, starts tracking. Called once.
  virtual void start() = 0;
  /// Runs 0..runs-1 of a new job (already in the store, accepted).
  virtual void enqueue(std::int64_t jobId, int runs) = 0;
  /// Runs of a job put back to accepted by JobStore::retryFailedRuns.
  virtual void resubmit(std::int64_t jobId, const std::vector<int>& indices) = 0;
  /// Cancels a job: queued runs never start, running ones are stopped. The job after the change.
  virtual std::optional<JobRecord> dismiss(std::int64_t jobId) = 0;
  /// No run starts from now on; runs this process executes are told to stop (re-queued as they
  /// end). Returns at once; shutdown() waits. Runs on a cluster are left running.
  virtual void requestStop() = 0;
  /// Stops this server's part (threads, trackers) and waits for it. Idempotent.
  virtual void shutdown() = 0;

  virtual const char* name() const = 0;  ///< "local" or "slurm"
  virtual int workers() const = 0;        ///< runs at a time (local), 0 when the cluster decides
  virtual int threadsPerRun() const = 0;
  /// The most MPI ranks one run may have here (run.ranks), and why not more, for the 400 that
  /// refuses a spec asking for more (docs/distributed.md).
  struct RankLimit {
    int ranks = 1;
    std::string why;
  };
  virtual RankLimit rankLimit() const = 0;
  virtual bool waitingForDisk() const = 0;
  virtual int unrecordedOutcomes() const = 0;

  /// <jobs-dir>/<id>: the run files of a job.
  virtual std::filesystem::path jobDir(std::int64_t jobId) const = 0;
};

}  // namespace rupture::server
