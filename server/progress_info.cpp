#include "progress_info.hpp"

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

bool isFinal(Status s) { return s == Status::Successful || s == Status::Failed || s == Status::Dismissed; }

}  // namespace

double secondsBetween(const std::string& from, const std::string& to) {
  const double a = epochSeconds(from), b = epochSeconds(to);
  if (a < 0 || b < 0) return -1;
  return std::max(0.0, b - a);
}

void addRunProgress(Json& doc, const RunRecord& run, const std::string& now) {
  double elapsed = -1;
  if (!run.started.empty()) elapsed = secondsBetween(run.started, isFinal(run.status) && !run.finished.empty() ? run.finished : now);
  double eta = -1;
  if (run.status == Status::Running) eta = estimateRemainingSeconds(elapsed, run.progress);
  if (run.status == Status::Successful) eta = 0;
  std::string stage = toString(run.status);
  if (run.status == Status::Accepted) stage = "queued";
  if (run.status == Status::Running) stage = run.stage.empty() ? "starting" : run.stage;
  if (run.status == Status::Dismissed && !run.started.empty() && !run.stage.empty()) stage = "dismissed during: " + run.stage;
  doc["stage"] = stage;
  doc["elapsed_s"] = secondsOrNull(elapsed);
  doc["eta_s"] = secondsOrNull(eta);
  doc["updated"] = run.updated;
}

void addJobProgress(Json& doc, const JobRecord& job, const std::vector<RunRecord>* runs, const std::string& now) {
  double elapsed = -1;
  if (!job.started.empty()) elapsed = secondsBetween(job.started, isFinal(job.status) && !job.finished.empty() ? job.finished : now);
  double eta = -1;
  if (job.status == Status::Running) eta = estimateRemainingSeconds(elapsed, job.progress);
  if (job.status == Status::Successful) eta = 0;
  std::string stage = toString(job.status);
  if (job.status == Status::Accepted) stage = "queued";
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
  doc["elapsed_s"] = secondsOrNull(elapsed);
  doc["eta_s"] = secondsOrNull(eta);
  doc["updated"] = std::max(job.updated, job.runsUpdated);
}

}  // namespace rupture::server
