#pragma once
// Statistics over the replicates of each sweep point: the runs that share their swept values
// (replicates, or a refined point) form one point; for every numeric scalar it reports the mean,
// the sample standard deviation (n - 1), the 95 % confidence interval of the mean
// (mean +- t(0.975, n - 1) sd / sqrt(n), Student t) and n. Only successful runs count: failed,
// dismissed and unfinished runs are listed as excluded, and n says how many values were used.
#include <optional>
#include <string>
#include <vector>

#include "studies/summary.hpp"

namespace rupture::server {

inline constexpr double kConfidenceLevel = 0.95;

struct ScalarStatistics {
  int n = 0;                  ///< successful runs that reported the scalar as a number
  double mean = 0;
  std::optional<double> sd;   ///< n >= 2
  std::optional<double> ciHalfWidth;  ///< n >= 2: t(0.975, n-1) sd / sqrt(n)
};

/// mean, sd, CI of a sample (empty: n = 0).
ScalarStatistics describeSample(const std::vector<double>& values);

struct PointAggregate {
  Json swept;                        ///< the point's swept values, aligned with the table's sweptPaths
  std::vector<int> runs;             ///< every run of the point, in order
  std::vector<int> successfulRuns;
  Json excluded = Json::array();     ///< [{run, status}] of the runs that did not count
  std::vector<std::pair<std::string, ScalarStatistics>> scalars;  ///< in the table's scalar order
  std::vector<std::vector<double>> values;  ///< per scalar, the values used (aligned with scalars)

  const ScalarStatistics* find(const std::string& name) const;
  const std::vector<double>* valuesOf(const std::string& name) const;
};

/// One point per distinct swept-value combination, in the order the points first appear.
std::vector<PointAggregate> aggregateReplicates(const SummaryTable& table);

/// {"jobID", "aggregate": "replicates", "confidence_level": 0.95, "columns": [...],
///  "rows": [{<swept>, n_runs, n_successful, runs, excluded, <scalar>: {mean, sd, ci95_low,
///  ci95_high, ci95_half_width, n}}]}
/// Each column carries unit, label and description from the table's column info.
Json aggregateJson(const SummaryTable& table, const std::vector<PointAggregate>& points);

/// CSV: <swept paths>,n_runs,n_successful,<s>.mean,<s>.sd,<s>.ci95_low,<s>.ci95_high,<s>.ci95_half_width,<s>.n per scalar,
/// each header "name [unit]" like the summary CSV (the statistics of s in s's unit, n in "1").
std::string aggregateCsv(const SummaryTable& table, const std::vector<PointAggregate>& points);

/// The column of a means table holding the 95 % confidence half-width of `scalar` ("<scalar>.ci95_half_width").
std::string ciHalfWidthColumn(const std::string& scalar);

/// The points as a summary table of means (one row per point; run = the point's first run): each
/// numeric scalar s holds its mean, and derived columns s.sd, s.ci95_half_width and s.n hold the
/// rest, with units and labels in the table's column info. A plot draws the 95 % intervals by
/// naming ciHalfWidthColumn(y) as PlotRequest::yError.
SummaryTable meansTable(const SummaryTable& table, const std::vector<PointAggregate>& points);

}  // namespace rupture::server
