#pragma once
// The job store: one SQLite database (WAL) holding jobs, their runs, statuses, progress, summaries
// and result-file paths. It is the only state that survives a restart; files under the data
// directory are referenced from it. All methods are thread-safe (one connection behind a mutex).
#include <cstdint>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/problem.hpp"
#include "common/utc_time.hpp"

struct sqlite3;

namespace rupture::server {

/// The store could not write because its disk (or a quota) is full: nothing was changed, and the
/// same write can succeed once space is freed (the HTTP API answers 507 with Retry-After).
class StoreFullError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

/// OGC API - Processes status codes, used for jobs and for their runs alike.
enum class Status { Accepted, Running, Successful, Failed, Dismissed };

const char* toString(Status status);
std::optional<Status> parseStatus(const std::string& text);
inline bool isTerminal(Status s) { return s == Status::Successful || s == Status::Failed || s == Status::Dismissed; }

struct RunKey {
  std::int64_t job = 0;
  int index = 0;
  bool operator==(const RunKey&) const = default;
};

struct RunRecord {
  RunKey key;
  Json swept;           ///< array of swept values, aligned with JobRecord::sweptPaths
  /// The full spec this run executes. run(key) always fills it; runs(jobId) leaves it null for a run
  /// stored as a patch (every run since the store keeps each job's inputs once): use runSpec().
  Json spec;
  /// The run's spec as a JSON Patch (RFC 6902) against its job's base spec (jobBaseSpec); null for a
  /// run stored whole by an older server.
  Json specPatch;
  Status status = Status::Accepted;
  double progress = 0;  ///< [0, 1]
  Json summary;         ///< object of scalars once successful, else null
  std::string error;    ///< message once failed
  std::string resultPath;  ///< relative to the data directory, once successful
  std::string started, finished, updated;
  std::string stage;    ///< the run's last stage message ("sample: 1625 elements, ..."), "" before any
  int attempts = 0;     ///< times the run was started (> 1 after a crash or restart)
  int replicate = 0;    ///< replicate index within its sweep point (0 without replicates)
  /// The rate anchor: when the run first reported progress above 0, and that progress ("" and 0
  /// before); its ETA is the rate since then (rupture::remainingSeconds).
  std::string rateFrom;
  double rateFromProgress = 0;
  /// Times the run continued from its checkpoint (docs/checkpoints.md), and the step it last
  /// continued from (−1: never).
  int resumes = 0;
  std::int64_t resumedFromStep = -1;
};

struct JobRecord {
  std::int64_t id = 0;
  std::string processId;
  std::string name;
  Status status = Status::Accepted;
  std::string sweepMode;
  Json sweptPaths;  ///< array of dotted paths, in request order
  Json inputs;      ///< the base inputs as posted
  Json sweep;       ///< the sweep object as posted
  std::string message;
  std::string created, started, finished, updated;
  int runsTotal = 0;
  int runsAccepted = 0, runsRunning = 0, runsSuccessful = 0, runsFailed = 0, runsDismissed = 0;
  double progress = 0;  ///< [0, 1]: successful runs count fully, running, failed and dismissed runs by the progress they reached
  std::string runsUpdated;  ///< the latest `updated` of its runs (progress changes it), "" without runs
  /// The study plan and its record, null for a plain sweep: {"replicates": {count, vary},
  /// "refine": {...}, "refinement": {"state": "pending"|"done", "rounds", "runs_added", "points", "stopped"}}
  Json study;
  /// What the job was submitted to: the server's build and host (io/provenance.hpp), its executor
  /// and threads per run; null for a job from before it was recorded. Each run's file has its own.
  Json provenance;
  /// The POST body as sent, less "inputs" (kept once, above); null for a job from before it was
  /// kept. submittedRequest() gives the whole body.
  Json request;
};

/// A job and its runs as one read: its counts, progress and `updated` agree with the runs listed
/// (two separate reads can straddle a progress write).
struct JobWithRuns {
  JobRecord job;
  std::vector<RunRecord> runs;
};

/// The spec every run of a job starts from: {"scenario": processId} followed by the inputs as
/// posted (without their own "scenario"). Sweeps, replicates and refinement change it by paths.
Json jobBaseSpec(const std::string& processId, const Json& inputs);

/// The body of the POST that made `job` (what "Submit a variant" starts from): as posted, or for a
/// job from before bodies were kept, rebuilt from its inputs, sweep, name and study.
Json submittedRequest(const JobRecord& job);

/// The full spec of `run` of `job`: its stored spec, or the job's base spec with the run's patch.
Json runSpec(const JobRecord& job, const RunRecord& run);

/// A running run's progress as its watcher sees it.
struct RunProgress {
  RunKey key;
  double fraction = 0;  ///< [0, 1]
  std::string stage;    ///< last stage message; "" keeps the stored one
};

struct NewJob {
  std::string processId;
  std::string name;
  std::string sweepMode;
  Json sweptPaths;
  Json inputs;
  Json sweep;
  /// (swept values, full spec) per run, in run order. The store keeps the inputs once and each
  /// run's difference from them (a JSON Patch), so a large description is not stored per run.
  std::vector<std::pair<Json, Json>> runs;
  /// When set (one per run): each run's spec as the text of its JSON Patch against the job's base
  /// spec (jobBaseSpec), and runs[k].second is not read. A large sweep is planned one spec at a time
  /// (routes/process_handlers.cpp), so its specs are never held whole.
  std::vector<std::string> runPatches;
  std::vector<int> replicates;  ///< replicate index per run (empty: all 0)
  Json study;                   ///< JobRecord::study (null: none)
  Json provenance;              ///< JobRecord::provenance
  Json request;                 ///< the POST body as sent (JobRecord::request)
  std::string idempotencyKey;  ///< the POST's Idempotency-Key header, "" when none
  std::string requestHash;     ///< identifies the request body sent with that key
};

/// What createJobOnce() did: created `id`, or found the job an earlier request with the same
/// Idempotency-Key created (with that request's hash).
struct CreatedJob {
  std::int64_t id = 0;
  bool created = false;
  std::string requestHash;
};

struct IdempotentJob {
  std::int64_t id = 0;
  std::string requestHash;
};

struct JobFilter {
  std::vector<Status> statuses;  ///< empty = any
  std::string processId;         ///< empty = any
  std::string nameContains;      ///< empty = any; else jobs whose name contains it (case-insensitive for ASCII)
  int limit = 50;
  std::int64_t offset = 0;
};

class JobStore {
public:
  /// Opens (creating if needed) the database file and its schema.
  explicit JobStore(const std::string& path);
  ~JobStore();
  JobStore(const JobStore&) = delete;
  JobStore& operator=(const JobStore&) = delete;

  /// Inserts a job and all its runs (status accepted) in one transaction; returns the job id.
  std::int64_t createJob(const NewJob& job);
  /// createJob, unless a job was already created under job.idempotencyKey (then nothing is
  /// inserted and that job is returned). The key and the job are committed together.
  CreatedJob createJobOnce(const NewJob& job);
  /// The job created under an Idempotency-Key, if any.
  std::optional<IdempotentJob> jobForIdempotencyKey(const std::string& key);

  std::optional<JobRecord> job(std::int64_t id);
  /// Newest first. `total` receives the number of jobs matching the filter, before paging.
  std::vector<JobRecord> listJobs(const JobFilter& filter, std::int64_t& total);
  /// A job's runs in index order, without materialising their specs (RunRecord::spec is null for
  /// runs stored as patches: runSpec(job, run) gives it).
  std::vector<RunRecord> runs(std::int64_t jobId);
  /// job(id) and runs(id) under one lock, so that no write falls between them; nullopt for no job.
  std::optional<JobWithRuns> jobWithRuns(std::int64_t id);
  /// One run, its full spec included.
  std::optional<RunRecord> run(RunKey key);

  /// Accepted runs of jobs not dismissed, in execution order (job id, then run index).
  std::vector<RunKey> queuedRuns();
  /// Runs accepted or running, in any job (for crash recovery).
  std::vector<RunKey> unfinishedRuns();
  /// Runs recorded failed, in any job (for the start-up repair of outcomes recorded wrongly).
  std::vector<RunKey> failedRuns();
  /// After a crash: runs left `running` go back to `accepted` (or `dismissed` in a dismissed job).
  /// Returns how many.
  int requeueInterrupted();

  /// accepted -> running. False when the run is no longer accepted (dismissed meanwhile).
  bool startRun(RunKey key);
  /// Stores progress fractions of running runs, in one transaction.
  void setProgress(const std::vector<RunProgress>& progress);
  /// The running run continued from its checkpoint at `step`: resumes + 1, resumed_from_step.
  void recordResume(RunKey key, std::int64_t step);
  void finishSuccessful(RunKey key, const Json& summary, const std::string& resultPath);
  void finishFailed(RunKey key, const std::string& message);
  /// A running run stopped by cancellation.
  void finishDismissed(RunKey key);
  /// running -> accepted (the server is stopping; the run starts again on the next start).
  void requeueRun(RunKey key);
  /// failed -> accepted for every failed run of a job that is not dismissed (POST /jobs/{id}/retry);
  /// their errors are cleared. Returns the run indices, in order (empty: nothing to retry).
  std::vector<int> retryFailedRuns(std::int64_t jobId);
  /// Every run of a failed or dismissed (cancelled) job that did not succeed (failed, cancelled,
  /// never started) -> accepted, and the job runs again (POST /jobs/{id}/resume). Returns the run
  /// indices, in order; empty when the job has not ended, still has a run stopping, or has nothing
  /// left to run.
  std::vector<int> resumeUnfinishedRuns(std::int64_t jobId);

  /// Cancels a job: its accepted runs become dismissed and the job `dismissed`. Jobs already
  /// successful or failed are left as they are. Returns the job after the change, or nullopt.
  std::optional<JobRecord> dismissJob(std::int64_t id);

  /// Jobs whose refinement is pending and which have no accepted or running run (refinement's
  /// next round is due), dismissed ones included (their refinement is closed).
  std::vector<std::int64_t> jobsAwaitingRefinement();
  /// Appends runs (accepted) after the job's last index and stores its new study record, in one
  /// transaction: a stop between the two cannot lose or repeat a round. Returns the new indices.
  std::vector<int> appendRuns(std::int64_t jobId, const std::vector<std::pair<Json, Json>>& runs,
                              const std::vector<int>& replicates, const Json& study);
  /// Stores the job's study record (e.g. refinement done) and updates its status.
  void setStudy(std::int64_t jobId, const Json& study);

  /// Number of accepted runs in jobs not dismissed.
  int queueDepth();
  /// Bytes of the stored inputs of the jobs not finished yet (accepted or running).
  long long queuedInputBytes();
  /// Number of runs recorded as running.
  int runningCount();

private:
  void exec(const std::string& sql);
  void migrate();  // columns added after schema version 1
  bool hasColumn(const std::string& table, const std::string& column);
  void updateJobStatus(std::int64_t jobId, const std::string& now);  // caller holds m_mutex, in a transaction
  void finishRun(RunKey key, Status status, const Json* summary, const std::string* error,
                 const std::string* resultPath);
  std::optional<JobRecord> jobLocked(std::int64_t id);
  std::vector<RunRecord> runsLocked(std::int64_t jobId);

  std::mutex m_mutex;
  sqlite3* m_db = nullptr;
};

}  // namespace rupture::server
