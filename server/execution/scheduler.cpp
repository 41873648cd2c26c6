#include "execution/scheduler.hpp"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <exception>
#include <system_error>

#include <fcntl.h>
#include <unistd.h>

#include "common/files.hpp"
#include "execution/kill_points.hpp"
#include "io/checkpoint_file.hpp"
#include "io/hdf5_file.hpp"
#include "rupture/state_archive.hpp"
#include "common/log.hpp"

namespace rupture::server {
namespace fs = std::filesystem;
namespace {

std::string describe(RunKey key) {
  return "job " + std::to_string(key.job) + " run " + std::to_string(key.index);
}

/// The run file while the engine writes it: a ".part" the engine leaves for us to rename once the
/// summary is recorded (io::ResultFile), the one rename a result goes through.
fs::path partialFile(const fs::path& runFile) { return runFile.string() + ".part"; }

/// The names older servers wrote a run under (run-k.partial.h5 and its own .part): removed as
/// leftovers like any other.
std::vector<fs::path> legacyPartialFiles(const fs::path& runFile) {
  fs::path p = runFile;
  const fs::path partial = p.replace_extension(".partial.h5");
  return {partial, fs::path(partial.string() + ".part")};
}

fs::path summaryFile(const fs::path& runFile) {
  fs::path p = runFile;
  return p.replace_extension(".summary.json");
}

fs::path temporaryOf(const fs::path& file) { return file.string() + ".tmp"; }

void removeQuietly(const fs::path& p) {
  std::error_code ec;
  fs::remove(p, ec);
}

/// A run's checkpoint, and those of the other ranks of a run on several (io::rankCheckpointPath).
void removeCheckpoint(const fs::path& checkpoint) {
  removeQuietly(checkpoint);
  const std::string siblings = checkpoint.filename().string() + ".rank-";
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(checkpoint.parent_path(), ec))
    if (entry.path().filename().string().rfind(siblings, 0) == 0) removeQuietly(entry.path());
}

/// The directory's entries on the disk (a removal or rename that must survive a power cut).
void syncDirectory(const fs::path& dir) {
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  [[maybe_unused]] const int rc = ::fsync(fd);
  ::close(fd);
}

/// The engine's partial file says the run completed (ResultFile::finish wrote completed = 1 and
/// closed it): what a commit interrupted after the summary was kept leaves.
bool isCompleteResult(const fs::path& file) {
  try {
    const rupture::io::Hdf5File h5 = rupture::io::Hdf5File::openReadOnly(file.string());
    return h5.hasAttribute("/", "completed") && h5.readAttributeInt("/", "completed") == 1;
  } catch (const std::exception&) {
    return false;
  }
}

/// The step of the run's checkpoint (−1: none or unreadable).
std::int64_t checkpointStepOf(const fs::path& checkpoint) {
  std::error_code ec;
  if (!fs::exists(checkpoint, ec)) return -1;
  try {
    return rupture::io::readCheckpointHeader(checkpoint.string()).step;
  } catch (const std::exception&) {
    return -1;
  }
}

// A run that fails because the disk filled up goes back to the queue and waits there for room;
// this many such failures in a row without its checkpoint advancing (each after room had come
// back) say that the run itself needs more than the disk has: it is then recorded failed.
constexpr int kDiskFullAttempts = 3;
// The least free space such a run waits for, whatever its files' size (one that failed before it
// wrote anything, on a server without a floor).
constexpr std::uintmax_t kLeastRoomAfterFullDisk = 1u << 20;

}  // namespace

Scheduler::Scheduler(JobStore& store, fs::path dataDir, int workers, int threadsPerRun, RunExecutor executor)
    : m_store(store), m_dataDir(std::move(dataDir)), m_workerCount(std::max(1, workers)),
      m_threadsPerRun(std::max(1, threadsPerRun)), m_executor(std::move(executor)) {
  if (!m_executor) {
    m_executor = [](const nlohmann::json& spec, const std::string& path, rupture::RunControl& control,
                    int threads) { return rupture::runSpec(spec, path, control, threads); };
  }
}

Scheduler::~Scheduler() { shutdown(); }

void Scheduler::setMpiLauncher(std::optional<MpiLauncher> launcher, std::string why) {
  m_mpi = std::move(launcher);
  m_mpiMissing = std::move(why);
}

Executor::RankLimit Scheduler::rankLimit() const {
  if (!m_mpi) return {1, m_mpiMissing.empty() ? std::string("this server runs each run in one process") : m_mpiMissing};
  return {m_workerCount, "a run of N ranks takes N of this server's " + std::to_string(m_workerCount) +
                             " workers (--workers), each rank with " + std::to_string(m_threadsPerRun) +
                             " thread(s) (--threads-per-run)"};
}

int Scheduler::slotsOf(RunKey key) {
  if (auto it = m_slots.find(key); it != m_slots.end()) return it->second;
  int ranks = 1;
  try {
    if (auto run = m_store.run(key)) ranks = requestedRanks(nlohmann::json(run->spec));
  } catch (const std::exception& e) {
    logLine(describe(key) + ": cannot read its ranks (" + e.what() + "); it takes one worker");
  }
  // Never more than there are: a spec admitted by a server with more workers still runs here.
  ranks = std::clamp(ranks, 1, m_workerCount);
  m_slots.emplace(key, ranks);
  return ranks;
}

fs::path Scheduler::jobDir(std::int64_t jobId) const { return m_dataDir / "jobs" / std::to_string(jobId); }

fs::path Scheduler::runFile(RunKey key) const {
  return jobDir(key.job) / ("run-" + std::to_string(key.index) + ".h5");
}

int Scheduler::running() const {
  std::lock_guard lock(m_mutex);
  return static_cast<int>(m_active.size());
}

void Scheduler::recoverFinishedFiles() {
  // A run whose result and summary files are complete finished, whatever the store says: it may
  // have stopped before the store took the outcome, or the store may have taken a wrong one (a
  // full disk once made the success unrecordable and the failure recordable). A commit
  // interrupted between the summary's rename and the result's is finished here (the summary is
  // kept only once the engine has closed its complete file), and a checkpoint the commit did not
  // get to remove is removed: nothing is recomputed.
  std::vector<RunKey> candidates = m_store.unfinishedRuns();
  const std::vector<RunKey> failed = m_store.failedRuns();
  candidates.insert(candidates.end(), failed.begin(), failed.end());
  for (RunKey key : candidates) {
    const bool wasFailed = std::find(failed.begin(), failed.end(), key) != failed.end();
    const fs::path file = runFile(key);
    const fs::path partial = partialFile(file);
    const bool committedSummary = regularFileSize(summaryFile(file)).has_value();
    if (!regularFileSize(file) && committedSummary && regularFileSize(partial) && isCompleteResult(partial)) {
      try {
        renameDurable(partial, file);
        logLine(describe(key) + ": its result was complete beside its summary; renamed into place");
      } catch (const std::exception& e) {
        logLine(describe(key) + ": cannot rename its complete result into place: " + e.what());
      }
    }
    if (!regularFileSize(file)) continue;
    auto text = readFile(summaryFile(file));
    Json summary;
    try {
      if (text) summary = Json::parse(*text);
    } catch (const std::exception&) {
      summary = Json();
    }
    if (!summary.is_object()) {
      if (!wasFailed) removeQuietly(file);  // not recorded as complete: it runs again
      continue;
    }
    const fs::path checkpoint = rupture::io::checkpointPathFor(partial.string());
    if (fs::exists(checkpoint)) {
      removeCheckpoint(checkpoint);
      syncDirectory(file.parent_path());
    }
    m_store.finishSuccessful(key, summary, fs::relative(file, m_dataDir).string());
    logLine(describe(key) + (wasFailed ? " was recorded failed but its files are complete; recorded successful"
                                       : " had finished before the last stop; recorded from its files"));
  }
}

void Scheduler::start() {
  std::lock_guard startLock(m_mutex);
  if (m_started) return;
  m_started = true;
  recoverFinishedFiles();
  if (int n = m_store.requeueInterrupted(); n > 0) {
    logLine("re-queued " + std::to_string(n) + " run(s) interrupted by the last stop");
  }
  for (RunKey key : m_store.queuedRuns()) m_queue.push_back(key);
  for (int i = 0; i < m_workerCount; ++i) m_threads.emplace_back([this] { workerLoop(); });
  m_monitor = std::thread([this] { monitorLoop(); });
}

void Scheduler::enqueue(std::int64_t jobId, int runs) {
  {
    std::lock_guard lock(m_mutex);
    for (int k = 0; k < runs; ++k) m_queue.push_back({jobId, k});
  }
  m_wake.notify_all();
}

void Scheduler::resubmit(std::int64_t jobId, const std::vector<int>& indices) {
  {
    std::lock_guard lock(m_mutex);
    for (int k : indices) m_queue.push_back({jobId, k});
  }
  m_wake.notify_all();
}

std::optional<JobRecord> Scheduler::dismiss(std::int64_t jobId) {
  // Under m_mutex, so that a worker between "registered" and "started in the store" sees either the
  // store's dismissal (startRun fails) or the cancel flag.
  std::lock_guard lock(m_mutex);
  auto job = m_store.dismissJob(jobId);
  if (job && job->status == Status::Dismissed) {
    for (auto& [key, control] : m_active) {
      if (key.job == jobId) control->cancel = true;
    }
  }
  return job;
}

void Scheduler::requestStop() {
  {
    std::lock_guard lock(m_mutex);
    m_stopping = true;
    for (auto& [key, control] : m_active) {
      control->checkpointOnCancel = true;  // the next start continues from here (docs/checkpoints.md)
      control->cancel = true;
    }
  }
  m_wake.notify_all();
  m_monitorWake.notify_all();
}

void Scheduler::shutdown() {
  requestStop();
  for (std::thread& t : m_threads) {
    if (t.joinable()) t.join();
  }
  if (m_monitor.joinable()) m_monitor.join();
  retryUnrecorded();  // what still fails is repaired from the files on the next start
}

bool Scheduler::diskHasRoom() const { return m_minFreeBytes == 0 || hasFreeBytes(m_minFreeBytes); }

bool Scheduler::waitingForDisk() const {
  if (m_waitingForDisk.load()) return true;
  std::lock_guard lock(m_mutex);
  return !m_waitingForSpace.empty();
}

int Scheduler::unrecordedOutcomes() const {
  std::lock_guard lock(m_mutex);
  return static_cast<int>(m_unrecorded.size());
}

bool Scheduler::tryRecord(const Outcome& o) {
  try {
    switch (o.kind) {
      case Outcome::Kind::Successful:
        m_store.finishSuccessful(o.key, o.summary, fs::relative(runFile(o.key), m_dataDir).string());
        break;
      case Outcome::Kind::Failed: m_store.finishFailed(o.key, o.message); break;
      case Outcome::Kind::Dismissed: m_store.finishDismissed(o.key); break;
      case Outcome::Kind::Requeued: m_store.requeueRun(o.key); break;
    }
    return true;
  } catch (const std::exception& e) {
    logLine(describe(o.key) + ": cannot record the outcome yet (" + e.what() + "); retrying every second");
    return false;
  }
}

void Scheduler::record(const Outcome& outcome) {
  if (tryRecord(outcome)) return;
  std::lock_guard lock(m_mutex);
  m_unrecorded.push_back(outcome);
}

void Scheduler::retryUnrecorded() {
  std::vector<Outcome> pending;
  {
    std::lock_guard lock(m_mutex);
    pending.swap(m_unrecorded);
  }
  std::vector<Outcome> still;
  for (const Outcome& o : pending) {
    if (tryRecord(o)) logLine(describe(o.key) + ": outcome recorded");
    else still.push_back(o);
  }
  if (still.empty()) return;
  std::lock_guard lock(m_mutex);
  m_unrecorded.insert(m_unrecorded.begin(), still.begin(), still.end());
}

void Scheduler::workerLoop() {
  while (true) {
    RunKey key;
    auto control = std::make_shared<rupture::RunControl>();
    // The VH preliminary-run cache lives with the data unless the operator chose a place: a sweep
    // over one sample then runs its preliminary run once, and the cache leaves with the data dir.
    if (const char* env = std::getenv("RUPTURE_CACHE_DIR"); env == nullptr || *env == '\0')
      control->cacheDirectory = (m_dataDir / "cache").string();
    {
      std::unique_lock lock(m_mutex);
      // The head of the queue starts when its slots are free (first come, first served).
      m_wake.wait(lock, [this] {
        return m_stopping || (!m_queue.empty() && m_busySlots + slotsOf(m_queue.front()) <= m_workerCount);
      });
      if (m_stopping) return;
      if (!diskHasRoom()) {  // leave the run queued; look again in a second
        if (!m_waitingForDisk.exchange(true))
          logLine("less than " + std::to_string(m_minFreeBytes) + " bytes free in " + m_dataDir.string() +
                  ": queued runs wait for disk space");
        m_wake.wait_for(lock, std::chrono::seconds(1), [this] { return m_stopping; });
        continue;
      }
      if (m_waitingForDisk.exchange(false)) logLine("disk space is back: runs start again");
      key = m_queue.front();
      m_queue.pop_front();
      m_active.emplace(key, control);
      m_busySlots += slotsOf(key);
    }
    bool started = false;
    try {
      started = m_store.startRun(key);
    } catch (const std::exception& e) {
      logLine(describe(key) + ": cannot start: " + e.what());
    }
    if (started) execute(key, control);
    {
      std::lock_guard lock(m_mutex);
      m_active.erase(key);
      m_stages.erase(key);
      m_resumeRecorded.erase(key);
      m_statusWatches.erase(key);
      m_busySlots -= slotsOf(key);
      if (std::find(m_queue.begin(), m_queue.end(), key) == m_queue.end()) m_slots.erase(key);
    }
    m_wake.notify_all();  // its slots may let the head of the queue start
  }
}

void Scheduler::execute(RunKey key, const std::shared_ptr<rupture::RunControl>& control) {
  const fs::path file = runFile(key);
  const fs::path partial = partialFile(file);
  const auto t0 = std::chrono::steady_clock::now();
  auto elapsed = [&] {
    return std::to_string(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  };
  auto stopping = [this] {
    std::lock_guard lock(m_mutex);
    return m_stopping;
  };
  auto removeLeftovers = [&] {
    for (const fs::path& stale : {file, partial, summaryFile(file), temporaryOf(summaryFile(file))}) removeQuietly(stale);
    for (const fs::path& stale : legacyPartialFiles(file)) removeQuietly(stale);
  };
  Outcome outcome{Outcome::Kind::Failed, key, Json(), std::string()};
  std::uintmax_t roomNeeded = 0;  // free bytes a run re-queued for a full disk waits for
  try {
    auto run = m_store.run(key);
    if (!run) throw std::runtime_error("run vanished from the store");
    fs::create_directories(file.parent_path());
    removeLeftovers();  // anything here is left over from an interrupted attempt
    logLine(describe(key) + " started");
    control->log = [this, key](const std::string& msg) {
      logLine(describe(key) + ": " + msg);
      std::lock_guard lock(m_mutex);
      m_stages[key] = msg;
    };
    // A checkpoint left by a stop, a crash or a kill: the run continues from it, not from step 0.
    const fs::path checkpoint = rupture::io::checkpointPathFor(partial.string());
    control->resume = fs::exists(checkpoint);
    if (control->resume) logLine(describe(key) + " continues from its checkpoint");
    rupture::RunOutcome result;
    // The timing breakdown in the log however the run ends, as `rupture run` prints it.
    struct TimingLogger {
      RunKey key;
      const rupture::RunControl& control;
      ~TimingLogger() {
        try {
          if (control.phases.totals().empty()) return;  // an executor that keeps no phases
          for (const std::string& line : io::timingBreakdown(control)) logLine(describe(key) + ": " + line);
        } catch (...) {  // a log line is never a reason to end the server (this may run while unwinding)
        }
      }
    } timingLogger{key, *control};
    try {
      const nlohmann::json spec(run->spec);
      const int ranks = requestedRanks(spec);
      if (ranks > 1 && !m_mpi)
        throw std::runtime_error("the spec asks for " + std::to_string(ranks) + " ranks (run.ranks) and " + m_mpiMissing);
      result = ranks > 1 ? m_mpi->run(spec, partial, *control, std::min(ranks, m_workerCount), m_threadsPerRun)
                         : m_executor(spec, partial.string(), *control, m_threadsPerRun);
    } catch (const rupture::CheckpointError& e) {
      // Never mixed into another run, never kept to fail again: a retry starts afresh.
      removeCheckpoint(checkpoint);
      throw std::runtime_error(std::string("cannot continue from the run's checkpoint (") + e.what() +
                               "); it was removed: retry the run to start it afresh");
    }
    if (result.completed) {
      // The commit, each step durable before the next (docs/checkpoints.md): the engine's complete
      // .part, then the summary, then the result renamed into place, and only then the
      // checkpoint removed. A kill at any step leaves the checkpoint (the restart continues from
      // it) or a summary beside a complete result (the restart finishes the commit).
      killPointForTests(kill_point::kAfterEngine);
      Json summary = result.summary.is_object() ? Json(result.summary) : Json::object();
      syncFile(partial);  // its content on the disk before a summary that vouches for it
      const fs::path summaryPath = summaryFile(file);
      writeFileSynced(temporaryOf(summaryPath), summary.dump(2) + "\n");
      killPointForTests(kill_point::kAfterSummaryTmp);
      renameDurable(temporaryOf(summaryPath), summaryPath);
      killPointForTests(kill_point::kAfterSummaryRename);
      renameDurable(partial, file);
      killPointForTests(kill_point::kAfterResultRename);
      removeCheckpoint(checkpoint);
      syncDirectory(file.parent_path());
      killPointForTests(kill_point::kAfterCheckpointRemoval);
      // From here the files say the run succeeded, whatever happens to the store.
      outcome = {Outcome::Kind::Successful, key, summary, {}};
      logLine(describe(key) + " successful after " + elapsed() + " s");
    } else {
      removeQuietly(partial);
      if (stopping()) {
        outcome.kind = Outcome::Kind::Requeued;
        logLine(describe(key) + " interrupted by shutdown; re-queued");
      } else if (control->cancel) {
        outcome.kind = Outcome::Kind::Dismissed;
        removeCheckpoint(rupture::io::checkpointPathFor(partial.string()));  // nothing will continue it
        logLine(describe(key) + " cancelled after " + elapsed() + " s");
      } else {
        outcome.message = "the run ended without completing (nobody cancelled it)";
        logLine(describe(key) + " ended incomplete after " + elapsed() + " s");
      }
    }
  } catch (const std::bad_alloc&) {
    // Say where and how much, not a bare "std::bad_alloc": the estimate the admission check used.
    removeLeftovers();
    std::string stage;
    {
      std::lock_guard lock(m_mutex);
      if (auto it = m_stages.find(key); it != m_stages.end()) stage = it->second;
    }
    std::string estimate;
    try {
      if (auto run = m_store.run(key)) {
        const rupture::RunEstimate e = rupture::estimateRun(nlohmann::json(run->spec));
        if (e.memoryBytes > 0) estimate = "; the spec's estimate was " + formatBytes(e.memoryBytes) + " (set by " + e.field + ")";
      }
    } catch (const std::exception&) {
    }
    if (control->cancel) {
      outcome.kind = stopping() ? Outcome::Kind::Requeued : Outcome::Kind::Dismissed;
    } else {
      outcome.message = "out of memory" + (stage.empty() ? std::string(" while setting up the run") : " after the stage '" + stage + "'") +
                        estimate + "; the machine could not give the run the memory it asked for (other runs share it): "
                        "retry when fewer runs are running, or make the run smaller";
      logLine(describe(key) + " failed: " + outcome.message);
    }
  } catch (const std::exception& e) {
    const bool diskFull = isDiskFull(e.what()) || !diskHasRoom();
    const std::uintmax_t partialBytes = regularFileSize(partial).value_or(0);
    removeLeftovers();
    if (control->cancel && stopping()) {
      outcome.kind = Outcome::Kind::Requeued;
    } else if (control->cancel) {
      outcome.kind = Outcome::Kind::Dismissed;
    } else if (diskFull) {
      // Back to the queue with its last good checkpoint (kept: removeLeftovers leaves it), to start
      // again once the disk has room for its partial result and a checkpoint's copy of it.
      const fs::path checkpoint = rupture::io::checkpointPathFor(partial.string());
      const std::int64_t step = checkpointStepOf(checkpoint);
      int strikes = 0;
      {
        std::lock_guard lock(m_mutex);
        DiskFullHistory& h = m_diskFull[key];
        h.strikes = h.strikes == 0 || step > h.checkpointStep ? 1 : h.strikes + 1;
        h.checkpointStep = step;
        strikes = h.strikes;
      }
      if (strikes <= kDiskFullAttempts) {
        outcome.kind = Outcome::Kind::Requeued;
        roomNeeded = std::max({m_minFreeBytes, kLeastRoomAfterFullDisk,
                               2 * std::max(partialBytes, regularFileSize(checkpoint).value_or(0))});
        logLine(describe(key) + ": the disk is full (" + e.what() + "); re-queued " +
                (step >= 0 ? "with its checkpoint at step " + std::to_string(step) : std::string("(no checkpoint yet)")) +
                " to wait for space");
      } else {
        outcome.message = "the disk filled up " + std::to_string(strikes) +
                          " times in a row without the run's checkpoint advancing, each time after space had come back: "
                          "the run needs more space than the data disk has (" + std::string(e.what()) + ")";
        logLine(describe(key) + " failed: " + outcome.message);
      }
    } else {
      outcome.message = e.what();
      logLine(describe(key) + " failed: " + e.what());
    }
  } catch (...) {
    removeLeftovers();
    outcome.message = "unknown error (non-standard exception)";
  }
  // A run that ended before the monitor saw it resume: its resume in the store before its outcome,
  // so that a finished run's document always says it continued.
  bool resumeUnrecorded = false;
  {
    std::lock_guard lock(m_mutex);
    resumeUnrecorded = control->resumedFromStep.load() >= 0 && m_resumeRecorded.insert(key).second;
  }
  if (resumeUnrecorded) {
    try {
      m_store.recordResume(key, control->resumedFromStep.load());
    } catch (const std::exception& e) {
      logLine(describe(key) + ": cannot record its resume: " + e.what());
    }
  }
  record(outcome);
  std::lock_guard lock(m_mutex);
  if (outcome.kind != Outcome::Kind::Requeued) m_diskFull.erase(key);
  // Re-queued for the disk, not for a shutdown: back in this server's queue, behind the floor, or
  // aside until the disk has the room it needs (the monitor looks every second).
  if (outcome.kind == Outcome::Kind::Requeued && !m_stopping) {
    if (roomNeeded > 0 && !hasFreeBytes(roomNeeded)) {
      m_waitingForSpace.push_back({key, roomNeeded});
      std::erase(m_queue, key);  // not started from another place in the queue meanwhile
      logLine(describe(key) + " waits for " + formatBytes(static_cast<double>(roomNeeded)) + " free in " + m_dataDir.string());
    } else {
      m_queue.push_back(key);
    }
  }
}

bool Scheduler::hasFreeBytes(std::uintmax_t bytes) const {
  const std::optional<std::uintmax_t> available = availableBytes(m_dataDir);
  return !available || *available >= bytes;  // an unknown free space does not stop the queue
}

std::vector<std::string> Scheduler::dueStatusLines() {
  std::vector<std::string> lines;
  const auto now = std::chrono::steady_clock::now();
  for (const auto& [key, control] : m_active) {
    StatusWatch& watch = m_statusWatches[key];
    const double elapsed = std::chrono::duration<double>(now - watch.start).count();
    const double fraction = rupture::runningFraction(control->progress.load());
    watch.line.observe(control->status.latest(), elapsed);
    watch.remaining.observe(elapsed, fraction);
    if (std::chrono::duration<double>(now - watch.lastLine).count() < m_statusInterval) continue;
    watch.lastLine = now;
    lines.push_back(describe(key) + ": " + watch.line.line(fraction, watch.remaining.at(elapsed)));
  }
  return lines;
}

void Scheduler::monitorLoop() {
  std::unique_lock lock(m_mutex);
  while (!m_stopping) {
    m_monitorWake.wait_for(lock, std::chrono::seconds(1), [this] { return m_stopping; });
    if (m_stopping) break;
    std::vector<RunProgress> progress;
    std::vector<std::pair<RunKey, std::int64_t>> resumed;
    for (const auto& [key, control] : m_active) {
      auto stage = m_stages.find(key);
      progress.push_back({key, control->progress.load(), stage == m_stages.end() ? std::string() : stage->second});
      const std::int64_t from = control->resumedFromStep.load();
      if (from >= 0 && m_resumeRecorded.insert(key).second) resumed.emplace_back(key, from);
    }
    // Runs set aside for a full disk go back to the head of the queue once it has their room.
    bool room = false;
    for (auto it = m_waitingForSpace.begin(); it != m_waitingForSpace.end();) {
      if (!hasFreeBytes(it->bytes)) {
        ++it;
        continue;
      }
      logLine(describe(it->key) + ": disk space is back; queued again");
      m_queue.push_front(it->key);
      it = m_waitingForSpace.erase(it);
      room = true;
    }
    if (room) m_wake.notify_all();
    const bool retry = !m_unrecorded.empty();
    const std::vector<std::string> statusLines = dueStatusLines();
    lock.unlock();
    for (const std::string& line : statusLines) logLine(line);
    try {
      m_store.setProgress(progress);
      for (const auto& [key, step] : resumed) m_store.recordResume(key, step);
    } catch (const std::exception& e) {
      logLine(std::string("cannot store progress: ") + e.what());
    }
    if (retry) retryUnrecorded();
    lock.lock();
  }
}

}  // namespace rupture::server
