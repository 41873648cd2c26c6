// rupture run SPEC.json -o RUN.h5 [--threads N] [--progress-file FILE] [--json] [--force] [--resume]
//                                 [--status-interval SECONDS]
//
// Validates the spec (exit 2 naming the field), refuses to replace an existing RUN.h5 unless
// --force, runs the spec on a worker thread through rupture::runSpec while this thread shows the
// progress on stderr (a bar with an ETA on a terminal; otherwise a status line every
// --status-interval seconds, as LAMMPS' thermo output: time, strain or step, the scenario's
// headline quantity, broken bonds, speed; io/status_line.hpp), then the run's timing breakdown,
// writes RUN.xdmf2 beside RUN.h5 for ParaView, and prints the summary once on stdout: a table in
// engineering units for a reader, or with --json the JSON at full precision for scripts. Ctrl-C (SIGINT) or SIGTERM (what Slurm's scancel sends) asks the run to stop:
// a checkpoint of the state is written first (RUN.h5.checkpoint, docs/checkpoints.md), then the file,
// marked incomplete (/summary completed = 0), the summary is printed and the exit code is 130;
// --resume continues from the checkpoint, bit for bit, and refuses (exit 2) a missing, damaged or
// foreign one. A second signal kills the process at once. --progress-file keeps a small
// JSON file up to date (about once a second), for watchers on other machines (the Slurm executor).
#include <omp.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <chrono>
#include <cstdio>
#include <exception>
#include <limits>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <mutex>
#include <thread>

#include "cli/cli.hpp"
#include "cli/interrupt_guard.hpp"
#include "cli/progress_view.hpp"
#include "cli/spec_file.hpp"
#include "distributed/communicator.hpp"
#include "io/checkpoint_file.hpp"
#include "io/hdf5_file.hpp"
#include "io/status_line.hpp"
#include "io/xdmf_writer.hpp"
#include "rupture/quantity_text.hpp"
#include "rupture/progress.hpp"
#include "rupture/run.hpp"

namespace rupture::cli {
namespace {

/// The summary for a reader: each declared scalar with its label and unit, in the scenario's order.
void printReadableSummary(std::ostream& out, const nlohmann::json& spec, const nlohmann::json& summary) {
  const ScenarioInfo* scenario = spec.contains("scenario") && spec["scenario"].is_string()
                                     ? findScenario(spec["scenario"].get<std::string>())
                                     : nullptr;
  if (!scenario || !summary.is_object()) return;
  const int dimension = specDimension(scenarioSchema(scenario->name), spec);
  std::size_t width = 0;
  for (const ResultField& f : scenario->summary)
    if (summary.contains(f.name)) width = std::max(width, f.label.size());
  for (const ResultField& f : scenario->summary) {
    auto it = summary.find(f.name);
    if (it == summary.end()) continue;
    // As people read them (rupture/quantity_text.hpp); the JSON on stdout keeps full precision.
    const std::string value = it->is_number() && f.isFlag() ? formatFlag(it->get<double>() != 0)
                              : it->is_number()   ? formatQuantity(it->get<double>(), f.unitFor(dimension))
                              : it->is_string() ? it->get<std::string>()
                              : it->is_null()   ? "n/a"
                                                : it->dump();
    out << "  " << f.label << std::string(width - f.label.size(), ' ') << "  " << value << "\n";
  }
}

/// A rank of a decomposed run other than the first: the same run on this thread, in silence (the
/// first rank shows the progress and writes the file); only a failure of its own is told.
int runQuietRank(const ParsedSpec& parsed, const std::string& specPath, const std::string& output,
                 RunControl& control, int threads, int rank) {
  InterruptGuard guard(control.cancel);
  // The first rank tells the run's story; the others speak only of their own trouble: a checkpoint
  // of theirs that could not be written leaves the run without a resumable checkpoint.
  control.log = [rank](const std::string& text) {
    if (text.find("checkpoint") != std::string::npos && (text.find("cannot") != std::string::npos || text.find("no room") != std::string::npos))
      std::cerr << "rupture run (rank " << rank << "): " << text << "\n";
  };
  try {
    const RunOutcome outcome = runSpec(parsed, output, control, threads);
    return outcome.completed ? 0 : kExitInterrupted;
  } catch (const SpecError&) {
    return 2;  // the first rank reports it
  } catch (const std::exception& e) {
    std::cerr << "rupture run (rank " << rank << "): failed on " << specPath << ": " << e.what() << "\n";
    return 1;
  }
}

/// Seconds between status lines off a terminal unless --status-interval says otherwise: often
/// enough to see a run is healthy, rarely enough that a day's log stays readable.
constexpr double kDefaultStatusInterval = 10.0;
constexpr double kLongestStatusInterval = 86400.0;

/// --status-interval: seconds in (0, 1 day]; prints why and returns false otherwise.
bool parseStatusInterval(const std::string& text, double& seconds) {
  try {
    std::size_t used = 0;
    const double value = std::stod(text, &used);
    if (used == text.size() && value > 0 && value <= kLongestStatusInterval) {
      seconds = value;
      return true;
    }
  } catch (const std::exception&) {  // not a number: said below
  }
  std::cerr << "rupture: option --status-interval = '" << text << "'; allowed: seconds in (0, "
            << kLongestStatusInterval << "], e.g. 10\n";
  return false;
}


/// {"progress": 0.42, "stage": "...", "elapsed_s": 12.3, "completed": false} written to a temporary
/// name and renamed, so a reader on another node sees a whole document or the previous one.
class ProgressFile {
public:
  explicit ProgressFile(std::string path) : m_path(std::move(path)), m_start(std::chrono::steady_clock::now()) {}
  void stage(const std::string& text) {
    std::lock_guard lock(m_mutex);
    m_stage = text;
  }
  void write(double fraction, bool finished = false) {
    if (m_path.empty()) return;
    std::lock_guard lock(m_mutex);
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - m_start).count();
    m_remaining.observe(elapsed, fraction);
    const double eta = finished ? 0.0 : m_remaining.at(elapsed);
    const nlohmann::json doc = {{"progress", fraction}, {"stage", m_stage}, {"elapsed_s", elapsed},
                                {"eta_s", eta >= 0 ? nlohmann::json(eta) : nlohmann::json()}, {"finished", finished}};
    const std::string temporary = m_path + ".tmp";
    {
      std::ofstream out(temporary, std::ios::trunc);
      out << doc.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
      if (!out) return;  // a watcher's convenience: never a reason to fail the run
    }
    std::error_code ec;
    std::filesystem::rename(temporary, m_path, ec);
  }

private:
  std::string m_path;
  std::chrono::steady_clock::time_point m_start;
  std::mutex m_mutex;
  std::string m_stage;
  RemainingTime m_remaining;
};

std::string sidecarPath(const std::string& h5Path) {
  std::filesystem::path p(h5Path);
  if (p.extension() == ".h5" || p.extension() == ".hdf5") return p.replace_extension(".xdmf2").string();
  return h5Path + ".xdmf2";
}

constexpr const char* kRunUsage =
    "usage: rupture run SPEC.json -o RUN.h5 [--threads N] [--progress-file FILE] [--json] [--force] [--resume]\n"
    "                  [--max-run-steps N] [--status-interval S] [--stop-at-step N]\n"
    "  -o, --output RUN.h5     the result file (HDF5; RUN.xdmf2 is written beside it for ParaView)\n"
    "  --threads N             OpenMP threads (default: all cores)\n"
    "  --progress-file FILE    keep FILE up to date (about once a second) with the progress as JSON\n"
    "  --json                  print the summary as JSON at full precision instead of the table\n"
    "  --force                 overwrite RUN.h5 if it exists (otherwise: exit 2), and start afresh\n"
    "                          even if RUN.h5.checkpoint exists\n"
    "  --resume                continue the run from RUN.h5.checkpoint (written every\n"
    "                          run.checkpoint_interval_s and when Ctrl-C or SIGTERM stops it)\n"
    "  --max-run-steps N       refuse (exit 2) a spec whose estimated time steps exceed N\n"
    "                          (default 100000000, as rupture-server's --max-run-steps)\n"
    "  --status-interval S     when stderr is not a terminal (a log, nohup, Slurm), print a status\n"
    "                          line every S seconds (default 10): progress, ETA, step, time, strain,\n"
    "                          the headline quantity, broken bonds and speed\n"
    "  --stop-at-step N        stop after step N with a checkpoint, as an interrupted run (exit 130),\n"
    "                          for --resume to continue (to try a resume, or to split a run)\n"
    "  -h, --help              this text\n"
    "Under mpirun -np N (N > 1) the N processes step one impact or dynamic-tension run together and\n"
    "the first writes RUN.h5, the same file as one process writes (docs/distributed.md). Each rank\n"
    "keeps its own checkpoint (RUN.h5.checkpoint, RUN.h5.checkpoint.rank-1, ...): --resume on as many ranks.\n";

}  // namespace

int runCommand(const Args& args) {
  std::string specPath, output, progressPath;
  long long threads = omp_get_max_threads();
  long long maxRunSteps = static_cast<long long>(kDefaultMaxRunSteps);
  long long stopAtStep = -1;
  double statusInterval = kDefaultStatusInterval;
  bool json = false, force = false, resume = false;
  for (std::size_t k = 0; k < args.size(); ++k) {
    const std::string& a = args[k];
    if (a == "--help" || a == "-h") {
      std::cout << kRunUsage;
      return 0;
    }
    if (a == "-o" || a == "--output" || a == "--threads" || a == "--progress-file" || a == "--max-run-steps" ||
        a == "--status-interval" || a == "--stop-at-step") {
      if (k + 1 >= args.size()) return usageError("run: option " + a + " needs a value; see rupture run --help");
      if (a == "--threads") {
        if (!parseIntOption("--threads", args[k + 1], 1, 1024, threads)) return 2;
      } else if (a == "--max-run-steps") {
        if (!parseIntOption("--max-run-steps", args[k + 1], 1, std::numeric_limits<long long>::max(), maxRunSteps))
          return 2;
      } else if (a == "--status-interval") {
        if (!parseStatusInterval(args[k + 1], statusInterval)) return 2;
      } else if (a == "--stop-at-step") {
        if (!parseIntOption("--stop-at-step", args[k + 1], 1, std::numeric_limits<long long>::max(), stopAtStep)) return 2;
      } else if (a == "--progress-file") {
        progressPath = args[k + 1];
      } else {
        output = args[k + 1];
      }
      ++k;
    } else if (a == "--json") {
      json = true;
    } else if (a == "--force") {
      force = true;
    } else if (a == "--resume") {
      resume = true;
    } else if (!a.empty() && a[0] == '-') {
      return usageError("run: unknown option '" + a +
                        "'; allowed: -o/--output, --threads, --progress-file, --json, --force, --resume, --max-run-steps, "
                        "--status-interval, --stop-at-step, --help");
    } else if (specPath.empty()) {
      specPath = a;
    } else {
      return usageError("run: more than one spec file; see rupture run --help");
    }
  }
  if (specPath.empty()) return usageError("run: missing SPEC.json; see rupture run --help");
  if (output.empty()) return usageError("run: missing -o RUN.h5; see rupture run --help");

  // Started by mpirun -np N (N > 1): one rank of a decomposed run (docs/distributed.md). Every rank
  // parses, checks and runs the same spec; the first writes the file and speaks.
  const Communicator ranks = Communicator::world();
  const bool firstRank = ranks.rank() == 0;
  nlohmann::json spec;
  if (int code = readSpecFile(specPath, spec)) return code;
  ParsedSpec parsed;  // parsed once: the run reads this value
  try {
    parsed = parseSpec(spec);
    checkRunSteps(spec, parsed.estimate(), static_cast<double>(maxRunSteps));
  } catch (const SpecError& e) {
    return firstRank ? reportSpecError(specPath, e) : 2;
  }
  if (ranks.size() > 1) {
    const auto refuse = [&](const std::string& message) { return firstRank ? usageError(message) : 2; };
    if (parsed.scenarioName() != "impact" && parsed.scenarioName() != "dynamic-tension")
      return refuse("run: the " + parsed.scenarioName() + " scenario runs on one rank; " +
                    std::to_string(ranks.size()) + " ranks (mpirun -np " + std::to_string(ranks.size()) +
                    ") run the impact and dynamic-tension scenarios only, so far (docs/distributed.md)");
  }

  // run.ranks is what a server gives the run; here mpirun decides, and the result is the same.
  if (const int asked = parsed.estimate().ranks;
      firstRank && asked != ranks.size() && spec.contains(nlohmann::json::json_pointer("/run/ranks")))
    std::cerr << "rupture run: the spec asks for " << asked << " rank(s) (run.ranks); this run has " << ranks.size()
              << (ranks.size() == 1 ? " (start it with mpirun -np " + std::to_string(asked) + " to decompose it)" : std::string())
              << ": the result is the same\n";

  // The output location is checked before any work: a missing directory fails now, not after the
  // sample is built.
  {
    const std::filesystem::path parent = std::filesystem::absolute(output).parent_path();
    std::error_code ec;
    if (!std::filesystem::is_directory(parent, ec)) {
      return usageError("run: cannot write '" + output + "': the directory '" + parent.string() +
                        (std::filesystem::exists(parent, ec) ? "' is not a directory" : "' does not exist"));
    }
    if (::access(parent.c_str(), W_OK) != 0) {
      return usageError("run: cannot write '" + output + "' in '" + parent.string() + "': " + std::strerror(errno));
    }
    if (std::filesystem::is_directory(output, ec)) {
      return usageError("run: cannot write '" + output + "': it is a directory; name the HDF5 file, e.g. " +
                        (std::filesystem::path(output) / "run.h5").string());
    }
    if (resume && force) return usageError("run: --resume continues RUN.h5, --force starts it afresh: pass one");
    // A finished result may be hours of work: replacing it is asked for, never a side effect. So is
    // a checkpoint of an interrupted one.
    const std::string checkpoint = io::checkpointPathFor(output);
    if (resume) {
      // Each rank continues from its own checkpoint (docs/distributed.md); all go on, or none.
      const std::string mine = io::rankCheckpointPath(checkpoint, ranks.rank());
      std::string refused;
      try {
        const io::CheckpointHeader header = io::readCheckpointHeader(mine);
        io::checkCheckpointFits(header, mine, parsed.scenarioName(), spec);
        if (header.ranks != ranks.size())
          throw CheckpointError("it was written by a run on " + std::to_string(header.ranks) + " rank(s), this one has " +
                                std::to_string(ranks.size()) + " (each rank saved its own part): resume it with mpirun -np " +
                                std::to_string(header.ranks));
        if (header.threads != threads && firstRank)
          std::cerr << "rupture run: the checkpoint was written with " << header.threads << " thread(s), this run has "
                    << threads << ": the result may differ from an uninterrupted run in the last digits\n";
      } catch (const CheckpointError& e) {
        refused = std::string("run: cannot resume: ") + e.what() + "; run without --resume (and with --force) to start afresh";
      }
      if (ranks.max(refused.empty() ? 0.0 : 1.0) > 0) return refused.empty() ? 2 : usageError(refused);
    } else if (std::filesystem::exists(checkpoint, ec)) {
      if (!force)
        return firstRank ? usageError("run: '" + checkpoint + "' holds an interrupted run; pass --resume to continue it, or --force to start afresh") : 2;
      ranks.barrier();  // every rank has looked before the first removes it
      std::filesystem::remove(io::rankCheckpointPath(checkpoint, ranks.rank()), ec);
    } else if (!force && std::filesystem::exists(std::filesystem::symlink_status(output, ec))) {
      return usageError("run: '" + output + "' exists; pass --force to overwrite it, or name another -o");
    }
  }

  RunControl control;
  control.resume = resume;
  control.checkpointOnCancel = true;  // Ctrl-C, SIGTERM: keep the work for --resume
  control.stopAtStep = stopAtStep;
  if (!firstRank) return runQuietRank(parsed, specPath, output, control, static_cast<int>(threads), ranks.rank());
  ProgressView view("rupture run", ::isatty(STDERR_FILENO) == 1, statusInterval);
  io::StatusLine statusLine;
  const auto runStart = std::chrono::steady_clock::now();
  auto observeStatus = [&] {
    statusLine.observe(control.status.latest(),
                       std::chrono::duration<double>(std::chrono::steady_clock::now() - runStart).count());
  };
  view.setLineText([&statusLine](double fraction, double eta) { return statusLine.line(fraction, eta); });
  ProgressFile progressFile(progressPath);
  // The interrupt notice comes before anything the run says about stopping: whichever thread sees
  // the cancel flag first prints it, once.
  std::atomic<bool> noticed{false};
  auto noticeInterrupt = [&] {
    if (control.cancel.load() && !noticed.exchange(true))
      view.message("interrupted: writing a checkpoint and an incomplete result file (Ctrl-C again to kill)");
  };
  control.log = [&view, &progressFile, &noticeInterrupt](const std::string& text) {
    noticeInterrupt();
    view.message(roundNumbersInText(text));  // for people; the progress file keeps the digits
    progressFile.stage(text);
  };
  RunOutcome outcome;
  std::exception_ptr failure;
  std::atomic<bool> finished{false};
  {
    InterruptGuard guard(control.cancel);
    std::thread worker([&] {
      try {
        outcome = runSpec(parsed, output, control, static_cast<int>(threads));
      } catch (...) {
        failure = std::current_exception();
      }
      finished.store(true);
    });
    auto lastProgressWrite = std::chrono::steady_clock::now() - std::chrono::seconds(1);
    // Looked at every 0.2 s, or at every status line when they are asked for more often.
    const auto poll = std::chrono::duration<double>(std::min(0.2, statusInterval));
    while (!finished.load()) {
      std::this_thread::sleep_for(poll);
      if (std::chrono::steady_clock::now() - lastProgressWrite >= std::chrono::seconds(1)) {
        lastProgressWrite = std::chrono::steady_clock::now();
        progressFile.write(runningFraction(control.progress.load()));
      }
      noticeInterrupt();
      // The progress first, then the status: the run reports its status just after its progress,
      // so the line's step is never older than its fraction.
      const double fraction = runningFraction(control.progress.load());
      observeStatus();
      if (!finished.load()) view.update(fraction);
    }
    worker.join();
    noticeInterrupt();
  }
  observeStatus();
  if (!failure) view.update(control.progress.load(), true);
  view.close();
  for (const std::string& line : io::timingBreakdown(control)) std::cerr << "rupture run: " << line << "\n";
  progressFile.write(control.progress.load(), true);

  if (failure) {
    try {
      std::rethrow_exception(failure);
    } catch (const SpecError& e) {
      return reportSpecError(specPath, e);
    } catch (const CheckpointError& e) {
      return usageError(std::string("run: cannot resume: ") + e.what());
    } catch (const std::exception& e) {
      std::cerr << "rupture run: failed: " << e.what() << "\n";
      return 1;
    }
  }

  int code = outcome.completed ? 0 : kExitInterrupted;
  // A ParaView sidecar only for results with particle snapshots (elastic-properties has none, nor
  // does a run cancelled while its sample was built).
  std::string sidecar;
  try {
    const io::Hdf5File result = io::Hdf5File::openReadOnly(output);
    if (result.exists("/snapshots") && !result.listGroup("/snapshots").empty()) {
      sidecar = sidecarPath(output);
      io::writeXdmfSidecar(output, sidecar);
    }
  } catch (const std::exception& e) {
    std::cerr << "rupture run: cannot write the ParaView sidecar '" << sidecar << "': " << e.what() << "\n";
    code = code == 0 ? 1 : code;
  }
  if (json) std::cout << outcome.summary.dump(2) << std::endl;
  else printReadableSummary(std::cout, spec, outcome.summary);
  std::cerr << "rupture run: " << (outcome.completed ? "done" : "interrupted, result marked incomplete") << ": "
            << output << (sidecar.empty() ? "" : " (+ " + sidecar + ")") << "\n";
  if (!outcome.completed && control.checkpointStep.load() >= 0)
    std::cerr << "rupture run: checkpoint at step " << control.checkpointStep.load() << " in "
              << io::checkpointPathFor(output) << "; continue with: rupture run " << specPath << " -o " << output
              << " --resume\n";
  return code;
}

}  // namespace rupture::cli
