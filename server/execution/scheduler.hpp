#pragma once
// The scheduler: a FIFO of runs (job order, then run index) served by a pool of worker threads.
// Each run gets its own engine call with its own RunControl (cancel flag + progress); a monitor
// copies progress into the store at most once a second. A run that throws marks only itself failed.
//
// Result files: <data-dir>/jobs/<id>/run-<k>.h5 exists only for a finished, complete run. The engine
// writes run-<k>.h5.part and leaves it there, with the run's checkpoint (io::ResultFile: a ".part"
// result is the caller's to commit); on success the .part is synced, the summary is written to
// run-<k>.summary.json.tmp and renamed to run-<k>.summary.json, the .part is renamed to run-<k>.h5,
// the checkpoint run-<k>.h5.checkpoint is removed, then the store is updated, each step durable
// (fsync) before the next. A kill before the summary's rename leaves the checkpoint: the restart
// continues from it (at most one checkpoint interval lost). A kill after it leaves a summary beside
// a complete result: the start-up repair renames the result into place (if it was not yet), removes
// the checkpoint and records the run from its files, so a finished result is never recomputed.
// Tests kill the server at each step (RUPTURE_TEST_KILL_AT, execution/kill_points.hpp).
//
// The files are the truth about a run's outcome, the store a record of it: an outcome the store
// cannot take (disk full, database locked) is kept in memory and retried every second, and the
// start-up repair records as successful every run, failed or unfinished in the store, whose
// result and summary files are complete. Below the disk-space floor (setMinFreeBytes) no run
// starts; a run that fails because the disk filled up is re-queued with its last good checkpoint
// and set aside until the disk has room for twice its partial result (or checkpoint) and the
// floor; only three such failures in a row without its checkpoint advancing fail it.
//
// A run whose spec asks for N > 1 ranks (run.ranks) runs under mpirun (execution/mpi_launch.hpp)
// and takes N of the workers' places: the workers are slots, and the run at the head of the queue
// waits until it has its slots (first come, first served: a wide run is never overtaken for ever).
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "execution/executor.hpp"
#include "execution/mpi_launch.hpp"
#include "io/status_line.hpp"
#include "jobs/job_store.hpp"
#include "rupture/progress.hpp"
#include "rupture/run.hpp"

namespace rupture::server {

/// How a run is executed: rupture::runSpec in production.
using RunExecutor = std::function<rupture::RunOutcome(const nlohmann::json& spec, const std::string& resultPath,
                                                      rupture::RunControl& control, int threads)>;

/// The local executor.
class Scheduler : public Executor {
public:
  Scheduler(JobStore& store, std::filesystem::path dataDir, int workers, int threadsPerRun,
            RunExecutor executor = {});
  ~Scheduler() override;
  Scheduler(const Scheduler&) = delete;
  Scheduler& operator=(const Scheduler&) = delete;

  /// Repairs and re-queues what a crash left behind, queues every accepted run, starts the threads.
  void start() override;
  /// Queues the runs 0..runs-1 of a new job.
  void enqueue(std::int64_t jobId, int runs) override;
  /// Queues runs put back to accepted by a retry.
  void resubmit(std::int64_t jobId, const std::vector<int>& indices) override;
  /// Cancels a job: queued runs never start, running ones are told to stop (within a second).
  /// Returns the job after the change, or nullopt when there is no such job.
  std::optional<JobRecord> dismiss(std::int64_t jobId) override;
  /// Stops the workers: running runs are cancelled and re-queued for the next start. Idempotent.
  void shutdown() override;
  /// Free bytes the data directory must keep for a run to start (0: no floor). Call before start().
  void setMinFreeBytes(std::uintmax_t bytes) { m_minFreeBytes = bytes; }
  /// Seconds between the status lines each running run writes to the log (io::StatusLine), as
  /// `rupture run` prints them off a terminal. Call before start().
  void setStatusInterval(double seconds) { m_statusInterval = seconds; }
  /// How runs of several ranks start (nullopt: they are refused, for the reason `why`). Call before start().
  void setMpiLauncher(std::optional<MpiLauncher> launcher, std::string why);
  /// True while queued runs wait for disk space (the floor, or a run re-queued for a full disk
  /// waiting for the room it needs).
  bool waitingForDisk() const override;
  /// Outcomes finished on disk that the store has not taken yet (retried every second).
  int unrecordedOutcomes() const override;
  /// The first half of shutdown(), without waiting: no run starts from now on and running runs are
  /// told to stop (they are re-queued as they end). shutdown() then waits for them.
  void requestStop() override;

  const char* name() const override { return "local"; }
  int workers() const override { return m_workerCount; }
  int threadsPerRun() const override { return m_threadsPerRun; }
  RankLimit rankLimit() const override;
  int running() const;

  /// <data-dir>/jobs/<id>/run-<k>.h5
  std::filesystem::path runFile(RunKey key) const;
  std::filesystem::path jobDir(std::int64_t jobId) const override;

private:
  /// How a run ended, to be written to the store.
  struct Outcome {
    enum class Kind { Successful, Failed, Dismissed, Requeued } kind;
    RunKey key;
    Json summary;         ///< Successful
    std::string message;  ///< Failed
  };
  void workerLoop();
  /// The slots (workers' places) a queued run takes: its ranks, read from its spec once (under m_mutex).
  int slotsOf(RunKey key);
  bool diskHasRoom() const;
  bool hasFreeBytes(std::uintmax_t bytes) const;
  /// Writes an outcome to the store; if the store fails, keeps it for the monitor to retry.
  void record(const Outcome& outcome);
  bool tryRecord(const Outcome& outcome);
  void retryUnrecorded();
  void monitorLoop();
  /// The status line of each active run that is due (one per m_statusInterval), to log.
  std::vector<std::string> dueStatusLines();
  void execute(RunKey key, const std::shared_ptr<rupture::RunControl>& control);
  void recoverFinishedFiles();

  JobStore& m_store;
  std::filesystem::path m_dataDir;
  int m_workerCount;
  int m_threadsPerRun;
  RunExecutor m_executor;
  std::optional<MpiLauncher> m_mpi;
  std::string m_mpiMissing;  ///< why runs of several ranks are refused when m_mpi is empty

  mutable std::mutex m_mutex;
  std::condition_variable m_wake;         // workers: queue or stop
  std::condition_variable m_monitorWake;  // monitor: stop
  std::deque<RunKey> m_queue;
  struct RunKeyLess {
    bool operator()(const RunKey& a, const RunKey& b) const {
      return a.job != b.job ? a.job < b.job : a.index < b.index;
    }
  };
  std::map<RunKey, std::shared_ptr<rupture::RunControl>, RunKeyLess> m_active;
  std::map<RunKey, std::string, RunKeyLess> m_stages;  ///< last stage message of each active run
  std::map<RunKey, int, RunKeyLess> m_slots;            ///< slots of each run read so far (its ranks)
  int m_busySlots = 0;                                  ///< slots the active runs hold
  std::set<RunKey, RunKeyLess> m_resumeRecorded;        ///< active runs whose resume the store has
  /// What the periodic status line of an active run needs between lines (guarded by m_mutex).
  struct StatusWatch {
    io::StatusLine line;
    RemainingTime remaining;
    std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now(), lastLine = start;
  };
  std::map<RunKey, StatusWatch, RunKeyLess> m_statusWatches;
  double m_statusInterval = 10;
  bool m_stopping = false;
  bool m_started = false;
  std::vector<Outcome> m_unrecorded;  // guarded by m_mutex
  /// Runs re-queued for a full disk, waiting for `bytes` free (guarded by m_mutex).
  struct SpaceWait {
    RunKey key;
    std::uintmax_t bytes;
  };
  std::vector<SpaceWait> m_waitingForSpace;
  /// Full-disk failures in a row of each run, and its checkpoint's step at the last (guarded by m_mutex).
  struct DiskFullHistory {
    int strikes = 0;
    std::int64_t checkpointStep = -1;
  };
  std::map<RunKey, DiskFullHistory, RunKeyLess> m_diskFull;
  std::uintmax_t m_minFreeBytes = 0;
  std::atomic<bool> m_waitingForDisk{false};
  std::vector<std::thread> m_threads;
  std::thread m_monitor;
};

}  // namespace rupture::server
