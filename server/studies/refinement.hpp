#pragma once
// Adaptive refinement of a swept axis: the request's
//   "refine": {"path": "loading.strain_rate", "quantity": "peak_stress", "max_runs": 8,
//              "tolerance": 0.1, "spacing": "auto", "per_round": 1}
// adds points between neighbouring values of `path` where `quantity` changes most, once the runs
// already queued have finished, round after round, until `max_runs` runs have been added or every
// neighbour change is at most `tolerance`.
//
//   change of a neighbour pair (a, b) = |q(b) - q(a)| / max(|q(a)|, |q(b)|)   (relative, 0 when both are 0)
// with q the mean of the quantity over the successful runs of a point (its replicates). Each round
// adds, in every series (combination of the other swept values), up to `per_round` points, between
// the pairs with the largest change above the tolerance, largest first across series while the
// budget lasts. The new value is the geometric mean sqrt(a b) on a log-spaced path, the arithmetic
// mean (a + b) / 2 otherwise ("auto": log when every initial value is > 0 and the largest is at
// least 10 x the smallest), rounded for an integer field. A pair closer than 0.1 % of its larger
// value is not split. A new point runs once per replicate; its runs count against max_runs.
//
// The plan and the record of every added point live in the job's study record in the job store,
// written in the same transaction as the new runs, so a server stopped mid-refinement resumes it.
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <limits>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "execution/executor.hpp"
#include "jobs/job_store.hpp"
#include "jobs/replicates.hpp"
#include "jobs/sweep.hpp"

namespace rupture::server {

inline constexpr int kMaxRefinePerRound = 16;
inline constexpr double kDefaultRefineTolerance = 0.1;
/// Pairs closer than this (relative to the larger value) are not split.
inline constexpr double kRefineResolution = 1e-3;

struct RefinePlan {
  std::string path;
  std::string quantity;
  int maxRuns = 0;
  double tolerance = kDefaultRefineTolerance;
  bool logSpacing = false;  ///< resolved from "spacing" at submission
  bool integer = false;     ///< the path is an integer field: midpoints are rounded
  int perRound = 1;

  Json toJson() const;
  static RefinePlan fromJson(const Json& doc);
};

/// Reads the request's "refine" member (null or absent: none). Throws ApiError(400) naming
/// refine.<field>, the value and what is allowed: path one of the swept paths with numeric values
/// (at least two), quantity a result scalar name, max_runs an integer >= the runs of one point
/// (replicates) with initialRuns + max_runs <= the server's maxRuns, tolerance in (0, 1), spacing
/// auto|log|linear (log needs values > 0), per_round 1..kMaxRefinePerRound; grid sweeps only
/// (or zip over one path).
std::optional<RefinePlan> parseRefinePlan(const Json* member, const std::string& scenario, const SweepPlan& sweep,
                                          int runsPerPoint, std::size_t initialRuns, std::size_t maxRuns);

/// A run's part in the planning: its swept values, whether it succeeded, and its quantity.
struct RefinementObservation {
  Json swept;
  bool successful = false;
  std::optional<double> quantity;
};

struct RefinementPoint {
  Json swept;         ///< the new point's swept values (the refined axis set to `value`)
  double value = 0;
  double a = 0, b = 0;  ///< the neighbours it splits
  double change = 0;    ///< their relative change
};

struct RefinementRound {
  std::vector<RefinementPoint> points;  ///< empty when refinement is over
  std::string stopReason;               ///< why it is over ("" while points are added)
};

/// Plans the next round (pure: no store, no specs). `axis` is the refined path's index in the
/// swept values; `runsAdded` the runs refinement added so far; a point costs `runsPerPoint` runs.
RefinementRound planRefinementRound(const RefinePlan& plan, std::size_t axis,
                                    const std::vector<RefinementObservation>& observations, int runsAdded,
                                    int runsPerPoint);

/// Runs the rounds of every job whose refinement is due: plans, builds and validates the new
/// runs, appends them with their record, and hands them to the executor. A thread that looks
/// every half second; stop() before the executor stops.
class RefinementDriver {
public:
  RefinementDriver(JobStore& store, Executor& executor, double maxElements,
                   double maxMemoryBytes = std::numeric_limits<double>::infinity(),
                   double maxSteps = std::numeric_limits<double>::infinity());
  ~RefinementDriver();
  RefinementDriver(const RefinementDriver&) = delete;
  RefinementDriver& operator=(const RefinementDriver&) = delete;

  void start();
  void stop();
  /// One pass over the jobs that are due (what the thread does every half second).
  void refineDueJobs();

private:
  void refineJob(std::int64_t jobId);
  void loop();

  JobStore& m_store;
  Executor& m_executor;
  double m_maxElements;
  double m_maxMemoryBytes;
  double m_maxSteps;
  std::mutex m_mutex;
  std::condition_variable m_wake;
  bool m_stopping = false;
  std::thread m_thread;
};

}  // namespace rupture::server
