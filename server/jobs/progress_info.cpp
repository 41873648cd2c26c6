#include "jobs/progress_info.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>

#include "rupture/progress.hpp"

namespace rupture::server {
namespace {

/// Seconds since the epoch of a store timestamp, or -1.
double epochSeconds(const std::string& text) {
  int y, mo, d, h, mi, s, ms = 0;
  if (std::sscanf(text.c_str(), "%4d-%2d-%2dT%2d:%2d:%2d.%3dZ", &y, &mo, &d, &h, &mi, &s, &ms) < 6) return -1;
  std::tm tm{};
  tm.tm_year = y - 1900;
  tm.tm_mon = mo - 1;
  tm.tm_mday = d;
  tm.tm_hour = h;
  tm.tm_min = mi;
  tm.tm_sec = s;
  return static_cast<double>(timegm(&tm)) + ms / 1000.0;
}

Json secondsOrNull(double seconds) { return seconds >= 0 ? Json(std::round(seconds * 10) / 10) : Json(); }

}  // namespace

double secondsBetween(const std::string& from, const std::string& to) {
  const double a = epochSeconds(from), b = epochSeconds(to);
  if (a < 0 || b < 0) return -1;
  return std::max(0.0, b - a);
}

namespace {

/// Elapsed time and the estimate of what remains (s; -1 for not known), for a run or a job alike.
struct Timing {
  double elapsed = -1, eta = -1;
};

Timing timingOf(Status status, const std::string& started, const std::string& finished, double progress,
                const std::string& now) {
  Timing t;
  if (!started.empty()) t.elapsed = secondsBetween(started, isTerminal(status) && !finished.empty() ? finished : now);
  if (status == Status::Running) t.eta = estimateRemainingSeconds(t.elapsed, runningFraction(progress));
  if (status == Status::Successful) t.eta = 0;
  return t;
}

}  // namespace

void addRunProgress(Json& doc, const RunRecord& run, const std::string& now) {
  const Timing timing = timingOf(run.status, run.started, run.finished, run.progress, now);
  std::string stage = run.status == Status::Accepted ? "queued" : toString(run.status);
  if (run.status == Status::Running) stage = run.stage.empty() ? "starting" : run.stage;
  if (run.status == Status::Dismissed && !run.started.empty() && !run.stage.empty()) stage = "dismissed during: " + run.stage;
  doc["stage"] = stage;
  doc["elapsed_s"] = secondsOrNull(timing.elapsed);
  doc["eta_s"] = secondsOrNull(timing.eta);
  doc["updated"] = run.updated;
}

void addJobProgress(Json& doc, const JobRecord& job, const std::vector<RunRecord>* runs, const std::string& now) {
  const Timing timing = timingOf(job.status, job.started, job.finished, job.progress, now);
  std::string stage = job.status == Status::Accepted ? "queued" : toString(job.status);
  if (job.status == Status::Running) {
    const int finished = job.runsSuccessful + job.runsFailed + job.runsDismissed;
    stage = std::to_string(finished) + " of " + std::to_string(job.runsTotal) + " runs finished, " +
            std::to_string(job.runsRunning) + " running";
    if (runs) {
      for (const RunRecord& r : *runs) {
        if (r.status == Status::Running && !r.stage.empty()) {
          stage += "; run " + std::to_string(r.key.index) + ": " + r.stage;
          break;
        }
      }
    }
  }
  doc["stage"] = stage;
  doc["elapsed_s"] = secondsOrNull(timing.elapsed);
  doc["eta_s"] = secondsOrNull(timing.eta);
  doc["updated"] = std::max(job.updated, job.runsUpdated);
}

}  // namespace rupture::server
