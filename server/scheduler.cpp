#include "scheduler.hpp"

#include <cstdlib>
#include <chrono>
#include <exception>
#include <system_error>

#include "files.hpp"
#include "log.hpp"

namespace rupture::server {
namespace fs = std::filesystem;
namespace {

std::string describe(RunKey key) {
  return "job " + std::to_string(key.job) + " run " + std::to_string(key.index);
}

fs::path partialFile(const fs::path& runFile) {
  fs::path p = runFile;
  return p.replace_extension(".partial.h5");
}

fs::path summaryFile(const fs::path& runFile) {
  fs::path p = runFile;
  return p.replace_extension(".summary.json");
}

void removeQuietly(const fs::path& p) {
  std::error_code ec;
  fs::remove(p, ec);
}

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

fs::path Scheduler::jobDir(std::int64_t jobId) const { return m_dataDir / "jobs" / std::to_string(jobId); }

fs::path Scheduler::runFile(RunKey key) const {
  return jobDir(key.job) / ("run-" + std::to_string(key.index) + ".h5");
}

int Scheduler::running() const {
  std::lock_guard lock(m_mutex);
  return static_cast<int>(m_active.size());
}

void Scheduler::recoverFinishedFiles() {
  for (RunKey key : m_store.unfinishedRuns()) {
    const fs::path file = runFile(key);
    if (!regularFileSize(file)) continue;
    auto text = readFile(summaryFile(file));
    Json summary;
    try {
      if (text) summary = Json::parse(*text);
    } catch (const std::exception&) {
      summary = Json();
    }
    if (!summary.is_object()) {
      removeQuietly(file);  // not recorded as complete: it runs again
      continue;
    }
    m_store.finishSuccessful(key, summary, fs::relative(file, m_dataDir).string());
    logLine(describe(key) + " had finished before the last stop; recorded from its files");
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
    for (auto& [key, control] : m_active) control->cancel = true;
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
      m_wake.wait(lock, [this] { return m_stopping || !m_queue.empty(); });
      if (m_stopping) return;
      key = m_queue.front();
      m_queue.pop_front();
      m_active.emplace(key, control);
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
    }
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
  try {
    auto run = m_store.run(key);
    if (!run) throw std::runtime_error("run vanished from the store");
    fs::create_directories(file.parent_path());
    // Anything here is left over from an interrupted attempt.
    for (const fs::path& stale : {file, partial, fs::path(partial.string() + ".part"), summaryFile(file)}) {
      removeQuietly(stale);
    }
    logLine(describe(key) + " started");
    control->log = [key](const std::string& msg) { logLine(describe(key) + ": " + msg); };
    rupture::RunOutcome outcome = m_executor(nlohmann::json(run->spec), partial.string(), *control, m_threadsPerRun);
    if (outcome.completed) {
      Json summary = outcome.summary.is_object() ? Json(outcome.summary) : Json::object();
      writeFileAtomic(summaryFile(file), summary.dump(2) + "\n");
      renameDurable(partial, file);
      m_store.finishSuccessful(key, summary, fs::relative(file, m_dataDir).string());
      logLine(describe(key) + " successful after " + elapsed() + " s");
      return;
    }
    removeQuietly(partial);
    if (stopping()) {
      m_store.requeueRun(key);
      logLine(describe(key) + " interrupted by shutdown; re-queued");
    } else if (control->cancel) {
      m_store.finishDismissed(key);
      logLine(describe(key) + " cancelled after " + elapsed() + " s");
    } else {
      m_store.finishFailed(key, "the run ended without completing (nobody cancelled it)");
      logLine(describe(key) + " ended incomplete after " + elapsed() + " s");
    }
  } catch (const std::exception& e) {
    removeQuietly(partial);
    removeQuietly(fs::path(partial.string() + ".part"));
    try {
      if (control->cancel && stopping()) {
        m_store.requeueRun(key);
      } else if (control->cancel) {
        m_store.finishDismissed(key);
      } else {
        m_store.finishFailed(key, e.what());
        logLine(describe(key) + " failed: " + e.what());
      }
    } catch (const std::exception& e2) {
      logLine(describe(key) + ": cannot record the outcome: " + e2.what());
    }
  } catch (...) {
    removeQuietly(partial);
    try {
      m_store.finishFailed(key, "unknown error (non-standard exception)");
    } catch (...) {
    }
  }
}

void Scheduler::monitorLoop() {
  std::unique_lock lock(m_mutex);
  while (!m_stopping) {
    m_monitorWake.wait_for(lock, std::chrono::seconds(1), [this] { return m_stopping; });
    if (m_stopping) break;
    std::vector<std::pair<RunKey, double>> progress;
    for (const auto& [key, control] : m_active) progress.emplace_back(key, control->progress.load());
    lock.unlock();
    try {
      m_store.setProgress(progress);
    } catch (const std::exception& e) {
      logLine(std::string("cannot store progress: ") + e.what());
    }
    lock.lock();
  }
}

}  // namespace rupture::server
