#include "execution/slurm_executor.hpp"

#include <algorithm>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "execution/command.hpp"
#include "execution/mpi_launch.hpp"
#include "common/files.hpp"
#include "io/checkpoint_file.hpp"
#include "rupture/run.hpp"
#include "common/log.hpp"

namespace rupture::server {
namespace fs = std::filesystem;
namespace {

std::string shellQuote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::string trim(std::string s) {
  const auto first = s.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return "";
  return s.substr(first, s.find_last_not_of(" \t\r\n") - first + 1);
}

/// "0-3,5,7-8" from sorted indices: sbatch's --array syntax.
std::string arraySpec(std::vector<int> indices) {
  std::sort(indices.begin(), indices.end());
  std::ostringstream out;
  for (std::size_t i = 0; i < indices.size();) {
    std::size_t j = i;
    while (j + 1 < indices.size() && indices[j + 1] == indices[j] + 1) ++j;
    if (i > 0) out << ',';
    out << indices[i];
    if (j > i) out << '-' << indices[j];
    i = j + 1;
  }
  return out.str();
}

std::string lastLine(const fs::path& file) {
  auto text = readFile(file);
  if (!text) return "";
  std::istringstream lines(*text);
  std::string line, last;
  while (std::getline(lines, line))
    if (!trim(line).empty()) last = trim(line);
  for (const char* prefix : {"rupture run: failed: ", "rupture run: "})
    if (last.rfind(prefix, 0) == 0) return last.substr(std::string(prefix).size());
  return last;
}

/// "Key=Value" of `scontrol show job -o` output.
std::string field(const std::string& line, const std::string& key) {
  const std::string marker = key + "=";
  std::size_t at = 0;
  while ((at = line.find(marker, at)) != std::string::npos) {
    if (at == 0 || line[at - 1] == ' ') {
      const auto end = line.find(' ', at);
      return line.substr(at + marker.size(), end == std::string::npos ? std::string::npos : end - at - marker.size());
    }
    at += marker.size();
  }
  return "";
}

bool isPendingOrRunning(const std::string& state) {
  return state == "PENDING" || state == "RUNNING" || state == "COMPLETING" || state == "CONFIGURING" ||
         state == "SUSPENDED" || state == "REQUEUED" || state == "RESIZING";
}

}  // namespace

SlurmExecutor::SlurmExecutor(JobStore& store, SlurmSettings settings)
    : m_store(store), m_settings(std::move(settings)) {
  fs::create_directories(m_settings.sharedDir / "jobs");
  fs::create_directories(m_settings.sharedDir / "cache");
}

SlurmExecutor::~SlurmExecutor() { shutdown(); }

fs::path SlurmExecutor::jobDir(std::int64_t jobId) const { return m_settings.sharedDir / "jobs" / std::to_string(jobId); }

fs::path SlurmExecutor::runPath(RunKey key, const std::string& suffix) const {
  return jobDir(key.job) / ("run-" + std::to_string(key.index) + suffix);
}

std::string SlurmExecutor::batchScript(std::int64_t jobId, int ranks) const {
  const fs::path dir = jobDir(jobId);
  std::ostringstream s;
  s << "#!/bin/bash\n"
    << "#SBATCH --job-name=rupture-job-" << jobId << "\n"
    << "#SBATCH --cpus-per-task=" << m_settings.cpusPerRun << "\n";
  // A run of several ranks (run.ranks): that many tasks, anywhere in the cluster, started by srun
  // through Slurm's PMIx plugin, which Debian's Open MPI speaks (docs/distributed.md).
  if (ranks > 1) s << "#SBATCH --ntasks=" << ranks << "\n";
  s
    << "#SBATCH --output=" << (dir / "slurm" / "%A_%a.out").string() << "\n"
    // The time limit's warning goes to this script (B:), which passes it on to rupture run.
    << "#SBATCH --signal=B:TERM@" << m_settings.checkpointLead << "\n";
  if (!m_settings.partition.empty()) s << "#SBATCH --partition=" << m_settings.partition << "\n";
  if (!m_settings.account.empty()) s << "#SBATCH --account=" << m_settings.account << "\n";
  if (!m_settings.time.empty()) s << "#SBATCH --time=" << m_settings.time << "\n";
  for (const std::string& option : m_settings.options) s << "#SBATCH " << option << "\n";
  s << "# Written by rupture-server for job " << jobId << ": array task k runs run-k.spec.json.\n"
    << "# run-k.h5 appears only for a complete run; run-k.status (the exit code) is written last.\n"
    << "k=\"$SLURM_ARRAY_TASK_ID\"\n"
    << "cd " << shellQuote(dir.string()) << " || exit 1\n"
    << "export RUPTURE_CACHE_DIR=" << shellQuote((m_settings.sharedDir / "cache").string()) << "\n"
    << "# The server removed run-k.h5 and run-k.summary.json when it submitted this run: both here mean that this\n"
    << "# task ran before (Slurm requeued it) and committed its result; a summary beside the .part, that it was\n"
    << "# stopped between the two renames. Either way the result is complete: finish the commit, do not rerun.\n"
    << "if [ -f \"run-$k.summary.json\" ] && [ -f \"run-$k.h5.part\" ] && [ ! -f \"run-$k.h5\" ]; then mv -f \"run-$k.h5.part\" \"run-$k.h5\"; fi\n"
    << "if [ -f \"run-$k.summary.json\" ] && [ -f \"run-$k.h5\" ]; then\n"
    << "  rm -f \"run-$k.h5.checkpoint\" \"run-$k.h5.checkpoint\".rank-*\n"
    << "  echo 0 > \"run-$k.status.tmp\" && mv -f \"run-$k.status.tmp\" \"run-$k.status\"\n"
    << "  exit 0\n"
    << "fi\n"
    << "rm -f \"run-$k.h5\" \"run-$k.h5.part\" \"run-$k.summary.json\" \"run-$k.status\"\n"
    << "# A run stopped before (its time limit, a preemption) continues from its checkpoint.\n"
    << "resume=\"\"\n"
    << "if [ -f \"run-$k.h5.checkpoint\" ]; then resume=\"--resume\"; fi\n"
    << "# The engine leaves a result named *.part for its caller to rename: this script, once the summary is kept.\n"
    << (ranks > 1 ? "srun --mpi=" + shellQuote(m_settings.mpiPlugin) + " --ntasks=" + std::to_string(ranks) +
                        " --cpus-per-task=" + std::to_string(m_settings.cpusPerRun) + " --kill-on-bad-exit=1 "
                  : std::string())
    << shellQuote(m_settings.cli) << " run \"run-$k.spec.json\" -o \"run-$k.h5.part\" --threads "
    << m_settings.cpusPerRun << " --progress-file \"run-$k.progress.json\" --json $resume > \"run-$k.summary.tmp\" 2> \"run-$k.log\" &\n"
    << "pid=$!\n"
    << "# SIGTERM before the time limit (--signal): rupture run writes a checkpoint and exits 130.\n"
    // srun answers a SIGTERM by killing its tasks (SIGKILL after KillWait): the ranks of a run of
    // several get it from scancel instead, as a signal to the step, and write their checkpoints.
    << (ranks > 1 ? "trap 'scancel --signal=TERM \"${SLURM_JOB_ID}.0\" 2>/dev/null' TERM\n"
                  : "trap 'kill -TERM \"$pid\" 2>/dev/null' TERM\n")
    << "wait \"$pid\"\n"
    << "code=$?\n"
    << "while kill -0 \"$pid\" 2>/dev/null; do wait \"$pid\"; code=$?; done\n"
    << "# A checkpoint refused (exit 2) would be refused again: removed, so that a retry starts afresh.\n"
    << "if [ \"$code\" -eq 2 ] && grep -q \"cannot resume\" \"run-$k.log\"; then rm -f \"run-$k.h5.checkpoint\" \"run-$k.h5.checkpoint\".rank-*; fi\n"
    << "rm -f \"run-$k.h5.part.xdmf2\"\n"
    << "# The commit: the result and the summary on the disk, the summary renamed, the result renamed, and only\n"
    << "# then the checkpoint removed (rupture run keeps it for a *.part result), so that a kill at any point\n"
    << "# leaves a checkpoint to continue from or a complete result.\n"
    << "if [ \"$code\" -eq 0 ]; then\n"
    << "  sync \"run-$k.h5.part\" \"run-$k.summary.tmp\" 2>/dev/null || sync\n"
    << "  mv -f \"run-$k.summary.tmp\" \"run-$k.summary.json\" && mv -f \"run-$k.h5.part\" \"run-$k.h5\" && rm -f \"run-$k.h5.checkpoint\" \"run-$k.h5.checkpoint\".rank-* || code=74\n"
    << "else\n"
    << "  rm -f \"run-$k.h5.part\" \"run-$k.summary.tmp\"\n"
    << "fi\n"
    << "echo \"$code\" > \"run-$k.status.tmp\" && mv -f \"run-$k.status.tmp\" \"run-$k.status\"\n"
    << "exit \"$code\"\n";
  return s.str();
}

void SlurmExecutor::submit(std::int64_t jobId, const std::vector<int>& indices) {
  if (indices.empty()) return;
  std::lock_guard lock(m_submitMutex);
  std::map<int, std::vector<int>> byRanks;  // run indices by the ranks their specs ask for
  try {
    const fs::path dir = jobDir(jobId);
    fs::create_directories(dir / "slurm");
    for (int k : indices) {
      const RunKey key{jobId, k};
      for (const char* stale : {".slurm", ".status", ".h5", ".h5.part", ".summary.json", ".partial.h5", ".progress.json", ".log"}) {
        std::error_code ec;
        fs::remove(runPath(key, stale), ec);
      }
      const std::optional<RunRecord> run = m_store.run(key);  // one spec in memory at a time
      if (!run) throw std::runtime_error("run " + std::to_string(k) + " of job " + std::to_string(jobId) + " is not in the store");
      writeFileAtomic(runPath(key, ".spec.json"), run->spec.dump(2) + "\n");  // in the order it was sent
      byRanks[requestedRanks(nlohmann::json(run->spec))].push_back(k);
    }
    std::size_t count = 0;
    for (const auto& entry : fs::directory_iterator(dir / "slurm")) count += entry.path().extension() == ".sbatch";
    // One array per rank count: an array's tasks share one allocation shape.
    for (const auto& [ranks, group] : byRanks) {
      try {
        const fs::path script = dir / "slurm" / ("submission-" + std::to_string(++count) + ".sbatch");
        writeFileAtomic(script, batchScript(jobId, ranks));
        const CommandResult r = runCommand({"sbatch", "--parsable", "--array=" + arraySpec(group), script.string()});
        const std::string id = trim(r.output.substr(0, r.output.find(';')));
        if (!r.ok() || id.empty() || id.find_first_not_of("0123456789") != std::string::npos)
          throw std::runtime_error("sbatch failed: " + trim(r.error.empty() ? r.output : r.error));
        for (int k : group) writeFileAtomic(runPath({jobId, k}, ".slurm"), id + "\n");
        logLine("job " + std::to_string(jobId) + ": runs " + arraySpec(group) + " submitted as Slurm array job " + id +
                (ranks > 1 ? " (" + std::to_string(ranks) + " ranks each)" : std::string()));
      } catch (const std::exception& e) {
        failRuns(jobId, group, e.what());
      }
    }
  } catch (const std::exception& e) {
    failRuns(jobId, indices, e.what());
  }
}

void SlurmExecutor::failRuns(std::int64_t jobId, const std::vector<int>& indices, const std::string& why) {
  logLine("job " + std::to_string(jobId) + ": " + why);
  for (int k : indices) {
    try {
      m_store.finishFailed({jobId, k}, why);
    } catch (const std::exception&) {
    }
  }
}

void SlurmExecutor::enqueue(std::int64_t jobId, int runs) {
  std::vector<int> indices(static_cast<std::size_t>(runs));
  for (int k = 0; k < runs; ++k) indices[static_cast<std::size_t>(k)] = k;
  submit(jobId, indices);
}

void SlurmExecutor::resubmit(std::int64_t jobId, const std::vector<int>& indices) { submit(jobId, indices); }

std::optional<JobRecord> SlurmExecutor::dismiss(std::int64_t jobId) {
  auto job = m_store.dismissJob(jobId);
  if (!job || job->status != Status::Dismissed) return job;
  std::set<std::string> arrays;
  std::vector<RunKey> running;
  for (const RunRecord& run : m_store.runs(jobId)) {
    if (auto id = readFile(runPath(run.key, ".slurm"))) arrays.insert(trim(*id));
    if (run.status == Status::Running) running.push_back(run.key);
  }
  for (const std::string& id : arrays) {
    const CommandResult r = runCommand({"scancel", id});
    if (!r.ok()) logLine("job " + std::to_string(jobId) + ": scancel " + id + ": " + trim(r.error));
  }
  for (RunKey key : running) m_store.finishDismissed(key);
  return m_store.job(jobId);
}

void SlurmExecutor::start() {
  {
    std::lock_guard lock(m_mutex);
    if (m_started) return;
    m_started = true;
  }
  // Runs recorded failed whose files say they succeeded (the store missed the outcome).
  for (RunKey key : m_store.failedRuns()) {
    auto status = readFile(runPath(key, ".status"));
    if (status && trim(*status) == "0") recordFinished(key, 0, "");
  }
  // Unfinished runs with no Slurm id: adopt a submission made just before a stop, else submit.
  std::map<std::int64_t, std::vector<int>> unsubmitted;
  for (RunKey key : m_store.unfinishedRuns())
    if (!fs::exists(runPath(key, ".slurm"))) unsubmitted[key.job].push_back(key.index);
  for (const auto& [jobId, indices] : unsubmitted) {
    const CommandResult r = runCommand({"squeue", "-h", "-n", "rupture-job-" + std::to_string(jobId), "-o", "%F"});
    const std::string existing = trim(r.output.substr(0, r.output.find('\n')));
    if (r.ok() && !existing.empty()) {
      for (int k : indices) writeFileAtomic(runPath({jobId, k}, ".slurm"), existing + "\n");
      logLine("job " + std::to_string(jobId) + ": re-attached to Slurm array job " + existing);
    } else {
      submit(jobId, indices);
    }
  }
  m_tracker = std::thread([this] { trackLoop(); });
}

void SlurmExecutor::shutdown() {
  {
    std::lock_guard lock(m_mutex);
    if (m_stopping) return;
    m_stopping = true;
  }
  m_wake.notify_all();
  if (m_tracker.joinable()) m_tracker.join();
}

void SlurmExecutor::trackLoop() {
  std::unique_lock lock(m_mutex);
  while (!m_stopping) {
    lock.unlock();
    try {
      poll();
    } catch (const std::exception& e) {
      logLine(std::string("slurm tracker: ") + e.what());
    }
    lock.lock();
    m_wake.wait_for(lock, m_settings.pollInterval, [this] { return m_stopping; });
  }
}

std::string SlurmExecutor::slurmStateOf(const std::string& taskId, std::string& reason) const {
  const CommandResult r = runCommand({"scontrol", "-o", "show", "job", taskId});
  if (!r.ok()) return "";
  reason = field(r.output, "Reason");
  return field(r.output, "JobState");
}

bool SlurmExecutor::continueInNextAllocation(RunKey key, std::string& why) {
  // No checkpoint: stopped in its set-up, before its first step (Slurm may signal up to a minute
  // early): submitted again to start afresh, like a run that gained steps, once.
  std::int64_t step = -1;
  const fs::path checkpoint = runPath(key, ".h5.checkpoint");
  if (fs::exists(checkpoint)) {
    try {
      step = rupture::io::readCheckpointHeader(checkpoint.string()).step;
    } catch (const std::exception& e) {
      why = e.what();
      return false;
    }
  }
  const std::string stepText = step < 0 ? "none" : std::to_string(step);
  if (auto last = readFile(runPath(key, ".resumed-step")); last && trim(*last) == stepText) {
    why = (step < 0 ? std::string("stopped twice before its first checkpoint (in its set-up)")
                    : "no step was gained in an allocation (the checkpoint is still at step " + stepText + ")") +
          ": the time limit leaves no time to run; raise --slurm-time or lower --slurm-checkpoint-lead";
    return false;
  }
  writeFileAtomic(runPath(key, ".resumed-step"), stepText + "\n");
  m_store.requeueRun(key);
  if (step >= 0) m_store.recordResume(key, step);
  logLine("job " + std::to_string(key.job) + " run " + std::to_string(key.index) +
          (step < 0 ? " stopped in its set-up, before a checkpoint; submitted again to start afresh"
                    : " stopped with a checkpoint at step " + stepText + "; submitted again to continue"));
  submit(key.job, {key.index});
  return true;
}

void SlurmExecutor::recordFinished(RunKey key, int exitCode, const std::string& slurmState) {
  const fs::path file = runPath(key, ".h5");
  // Stopped by its time limit's warning or a preemption, not cancelled by hand (scancel: failed,
  // with Slurm's reason; a retry continues from the checkpoint).
  std::string why;  // why a stopped run cannot continue
  if (exitCode == kExitInterrupted && slurmState.rfind("CANCELLED", 0) != 0 && continueInNextAllocation(key, why))
    return;
  if (exitCode == 0 && regularFileSize(file)) {
    Json summary;
    try {
      if (auto text = readFile(runPath(key, ".summary.json"))) summary = Json::parse(*text);
    } catch (const std::exception&) {
    }
    if (summary.is_object()) {
      std::error_code ec;
      fs::remove(runPath(key, ".h5.checkpoint"), ec);  // a commit stopped before it removed it
      m_store.finishSuccessful(key, summary, fs::relative(file, m_settings.sharedDir).string());
      logLine("job " + std::to_string(key.job) + " run " + std::to_string(key.index) + " successful (Slurm)");
      return;
    }
  }
  std::string message = lastLine(runPath(key, ".log"));
  if (message.empty()) message = "rupture run exited with code " + std::to_string(exitCode);
  if (!why.empty()) message = "stopped and cannot continue: " + why + "; last output: " + message;
  if (!slurmState.empty() && slurmState != "COMPLETED" && slurmState != "FAILED") message += " (Slurm: " + slurmState + ")";
  m_store.finishFailed(key, message);
  logLine("job " + std::to_string(key.job) + " run " + std::to_string(key.index) + " failed: " + message);
}

void SlurmExecutor::poll() {
  const std::vector<RunKey> runs = m_store.unfinishedRuns();
  std::map<std::string, RunKey> tasks;  // "array_k" -> run
  std::set<std::string> arrays;
  for (RunKey key : runs) {
    auto id = readFile(runPath(key, ".slurm"));
    if (!id) continue;  // being submitted
    arrays.insert(trim(*id));
    tasks[trim(*id) + "_" + std::to_string(key.index)] = key;
  }
  if (tasks.empty()) return;
  std::string list;
  for (const std::string& a : arrays) list += (list.empty() ? "" : ",") + a;
  const CommandResult q = runCommand({"squeue", "-h", "-r", "-j", list, "-o", "%i|%T|%r"});
  std::map<std::string, std::string> queued;  // task -> state
  if (q.ok()) {
    std::istringstream lines(q.output);
    for (std::string line; std::getline(lines, line);) {
      const auto bar = line.find('|');
      if (bar == std::string::npos) continue;
      queued[trim(line.substr(0, bar))] = trim(line.substr(bar + 1, line.find('|', bar + 1) - bar - 1));
    }
  }
  std::vector<RunProgress> progress;
  for (const auto& [task, key] : tasks) {
    if (auto status = readFile(runPath(key, ".status"))) {
      int code = -1;
      try {
        code = std::stoi(trim(*status));
      } catch (const std::exception&) {
      }
      std::string reason;
      const std::string state = code == 0 ? "" : slurmStateOf(task, reason);
      recordFinished(key, code, state);
      m_missingStatusPolls.erase(task);
      continue;
    }
    auto it = queued.find(task);
    std::string state = it != queued.end() ? it->second : "";
    std::string reason;
    if (state.empty()) {
      if (!q.ok()) continue;  // the controller did not answer: look again next time
      state = slurmStateOf(task, reason);
    }
    if (state == "RUNNING" || state == "COMPLETING") {
      if (auto run = m_store.run(key); run && run->status == Status::Accepted) m_store.startRun(key);
      if (auto text = readFile(runPath(key, ".progress.json"))) {
        try {
          const Json doc = Json::parse(*text);
          progress.push_back({key, doc.value("progress", 0.0), doc.value("stage", std::string())});
        } catch (const std::exception&) {
        }
      }
    }
    if (it != queued.end() || (isPendingOrRunning(state) && state != "COMPLETING")) continue;
    // Gone from the queue without a status file: give the shared filesystem a few polls to show
    // it, then believe Slurm.
    if (++m_missingStatusPolls[task] < (state == "COMPLETED" || state.empty() ? 10 : 3)) continue;
    m_missingStatusPolls.erase(task);
    std::string message = state.empty() ? "the Slurm job " + task + " is no longer known to Slurm and left no status file"
                                        : "Slurm: " + state + (reason.empty() || reason == "None" ? "" : " (" + reason + ")");
    if (const std::string log = lastLine(runPath(key, ".log")); !log.empty()) message += "; last output: " + log;
    m_store.finishFailed(key, message);
    logLine("job " + std::to_string(key.job) + " run " + std::to_string(key.index) + " failed: " + message);
  }
  if (!progress.empty()) m_store.setProgress(progress);
}

}  // namespace rupture::server
