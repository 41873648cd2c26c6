#pragma once
// Sweep expansion: a base spec ("inputs") plus swept dotted paths -> one full spec per run.
// grid = Cartesian product, the first swept path varying slowest (nested loops in the order given);
// zip = element-wise, all lists the same length. Every expanded spec is validated before a job is
// accepted, so a job is accepted whole or not at all.
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "common/problem.hpp"
#include "rupture/run.hpp"

namespace rupture::server {

enum class SweepMode { Grid, Zip };

const char* toString(SweepMode mode);

struct SweepAxis {
  std::string path;  ///< dotted path into the spec, e.g. "loading.strain_rate"
  Json values;       ///< non-empty array of values, in the order they run
};

struct SweepPlan {
  SweepMode mode = SweepMode::Grid;
  std::vector<SweepAxis> axes;  ///< in the order the request listed them
};

struct SweepPoint {
  Json spec;   ///< the full spec, with "scenario"
  Json swept;  ///< array of this point's values, aligned with SweepPlan::axes
};

/// Reads the request's "sweep" object and "sweep_mode" string (either may be null = absent).
/// Throws ApiError(400) naming the offending path: not an object, empty list, bad path, mode, or
/// zip lists of different lengths.
SweepPlan parseSweepPlan(const Json* sweep, const Json* mode);

/// Number of runs the plan expands to (1 without axes); saturates at SIZE_MAX instead of overflowing.
std::size_t runCount(const SweepPlan& plan);

/// Builds the plan's points over `inputs` (the spec without "scenario") one at a time, in run order,
/// and hands each to `visit`: a point's spec holds the whole inputs (a large description, many
/// probes), so a sweep of many runs is never held whole. Throws ApiError(400) when the runs would
/// exceed maxRuns (before building anything), or when a swept path's parent does not exist in the
/// inputs (the path is named).
void forEachSweepPoint(const std::string& scenario, const Json& inputs, const SweepPlan& plan, std::size_t maxRuns,
                       const std::function<void(SweepPoint&&)>& visit);

/// Every point of forEachSweepPoint, held at once (for a few points: refinement rounds, tests).
std::vector<SweepPoint> expandSweep(const std::string& scenario, const Json& inputs,
                                    const SweepPlan& plan, std::size_t maxRuns);

/// Validates every expanded spec with rupture::validateSpec, and its size (rupture::estimateRun)
/// against maxElements, its memory estimate against maxMemoryBytes and its step estimate against
/// maxSteps (rupture::checkRunSteps), and the ranks it asks for (run.ranks) against maxRanks
/// (ranksWhy says where that limit comes from). Throws ApiError(400) for the first bad point, naming the
/// field, the value, what is allowed (with the estimate in bytes or steps), the point's index and
/// its swept values.
void validateSweepPoints(const std::vector<SweepPoint>& points, const SweepPlan& plan, double maxElements,
                         double maxMemoryBytes, double maxSteps, int maxRanks, const std::string& ranksWhy);

/// validateSweepPoints for the one point at run index `index`; returns the estimate it checked
/// (the dry run of a submission reports it).
rupture::RunEstimate validateSweepPoint(const SweepPoint& point, std::size_t index, const SweepPlan& plan, double maxElements,
                                        double maxMemoryBytes, double maxSteps, int maxRanks, const std::string& ranksWhy);

/// "a.b.0.c" -> {"a","b","0","c"}; empty segments are an error (returns empty vector).
std::vector<std::string> splitPath(const std::string& path);

/// The value at a dotted path (object keys, or array indices for arrays), or nullptr.
const Json* findAtPath(const Json& root, const std::string& path);

}  // namespace rupture::server
