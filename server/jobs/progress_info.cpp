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

double elapsedOf(Status status, const std::string& started, const std::string& finished, const std::string& now) {
  if (started.empty()) return -1;
  return secondsBetween(started, isTerminal(status) && !finished.empty() ? finished : now);
}

/// A run's: its ETA from its own rate since its first progress (unknown before it has one).
Timing runTiming(const RunRecord& run, const std::string& now) {
  Timing t;
  t.elapsed = elapsedOf(run.status, run.started, run.finished, now);
  if (run.status == Status::Successful) t.eta = 0;
  if (run.status == Status::Running && !run.rateFrom.empty())
    t.eta = remainingSeconds(epochSeconds(run.rateFrom), run.rateFromProgress, epochSeconds(run.updated),
                             runningFraction(run.progress), epochSeconds(now));
  return t;
}

/// A job's, from its runs' measured rates: each running run ends after its own ETA, and each
/// queued run starts on the first of those slots to come free and lasts as long as its finished
/// runs took on average (before any has finished: as long as the running ones will have taken,
/// elapsed + ETA). The slots are the runs running now (the workers this job holds). A running run
/// whose own rate is not known yet (its first 2 s of progress) counts as a typical run less the
/// time it has run; unknown while nothing measures a typical run, or between runs.
Timing jobTiming(const JobRecord& job, const std::vector<RunRecord>* runs, const std::string& now) {
  Timing t;
  t.elapsed = elapsedOf(job.status, job.started, job.finished, now);
  if (job.status == Status::Successful) t.eta = 0;
  if (job.status != Status::Running || !runs) return t;
  double finishedTime = 0, projectedTime = 0;
  int queued = 0, finished = 0, projected = 0;
  std::vector<Timing> running;
  for (const RunRecord& r : *runs) {
    if (r.status == Status::Accepted) ++queued;
    if (r.status == Status::Successful && !r.started.empty() && !r.finished.empty()) {
      finishedTime += secondsBetween(r.started, r.finished);
      ++finished;
    }
    if (r.status != Status::Running) continue;
    const Timing rt = runTiming(r, now);
    running.push_back(rt);
    if (rt.eta >= 0) {
      projectedTime += std::max(rt.elapsed, 0.0) + rt.eta;
      ++projected;
    }
  }
  if (running.empty()) return t;  // between runs: nothing measures the rate
  double perRun = -1;
  if (finished > 0) perRun = finishedTime / finished;
  else if (projected > 0) perRun = projectedTime / projected;
  std::vector<double> slots;  // when each running run's worker comes free (s from now)
  for (const Timing& rt : running) {
    double eta = rt.eta;
    if (eta < 0 && perRun > 0 && rt.elapsed >= 0 && perRun > rt.elapsed) eta = perRun - rt.elapsed;
    if (eta < 0) return t;  // not known yet
    slots.push_back(eta);
  }
  if (queued > 0 && !(perRun > 0)) return t;
  for (int q = 0; q < queued; ++q) *std::min_element(slots.begin(), slots.end()) += perRun;
  t.eta = *std::max_element(slots.begin(), slots.end());
  return t;
}

}  // namespace

double jobProgress(const std::vector<RunRecord>& runs, const std::string& now) {
  std::vector<double> weight(runs.size(), -1), fraction(runs.size(), 0);
  double known = 0;
  int counted = 0;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const RunRecord& r = runs[i];
    fraction[i] = r.status == Status::Successful ? 1.0 : std::clamp(r.progress, 0.0, 1.0);  // failed: as far as it got
    if (r.status == Status::Dismissed && r.started.empty()) weight[i] = 0;  // never ran, never will
    if (isTerminal(r.status) && !r.started.empty() && !r.finished.empty()) weight[i] = secondsBetween(r.started, r.finished);
    if (r.status == Status::Running) {
      const Timing t = runTiming(r, now);
      if (t.eta >= 0 && t.elapsed >= 0) weight[i] = t.elapsed + t.eta;
    }
    if (weight[i] > 0) {
      known += weight[i];
      ++counted;
    }
  }
  const double typical = counted ? known / counted : 1.0;
  double total = 0, done = 0;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const double w = weight[i] < 0 ? typical : weight[i];
    total += w;
    done += w * fraction[i];
  }
  return total > 0 ? std::clamp(done / total, 0.0, 1.0) : 0.0;
}

void addRunProgress(Json& doc, const RunRecord& run, const std::string& now) {
  const Timing timing = runTiming(run, now);
  std::string stage = run.status == Status::Accepted ? "queued" : toString(run.status);
  if (run.status == Status::Running) stage = run.stage.empty() ? "starting" : run.stage;
  if (run.status == Status::Dismissed && !run.started.empty() && !run.stage.empty()) stage = "dismissed during: " + run.stage;
  doc["stage"] = stage;
  doc["elapsed_s"] = secondsOrNull(timing.elapsed);
  doc["eta_s"] = secondsOrNull(timing.eta);
  doc["updated"] = run.updated;
}

void addJobProgress(Json& doc, const JobRecord& job, const std::vector<RunRecord>* runs, const std::string& now) {
  const Timing timing = jobTiming(job, runs, now);
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
  // A running job's percentage weighs its runs by cost (at most 99 while it runs).
  if (job.status == Status::Running && runs && !runs->empty())
    doc["progress"] = static_cast<int>(std::floor(100 * runningFraction(jobProgress(*runs, now)) + 1e-9));
}

}  // namespace rupture::server
