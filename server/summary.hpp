#pragma once
// A job's summary table: one row per run with its swept values and the scalars the run reported
// (peak_stress, strain_at_peak, ...), rendered as JSON or CSV. Units are SI and named per column.
#include <functional>
#include <string>
#include <vector>

#include "job_store.hpp"

namespace rupture::server {

/// Unit of a column (a swept dotted path or a summary scalar), "" when dimensionless or unknown.
using UnitLookup = std::function<std::string(const std::string& column)>;

struct SummaryRow {
  int run = 0;
  Status status = Status::Accepted;
  Json swept;    ///< array aligned with SummaryTable::sweptPaths
  Json scalars;  ///< flat object name -> value (nested objects flattened with dots)
  std::string error;
  int replicate = 0;  ///< replicate index within the sweep point (replicate_statistics.hpp)
};

struct SummaryTable {
  std::int64_t jobId = 0;
  std::vector<std::string> sweptPaths;
  std::vector<std::string> scalarNames;  ///< the well-known ones first, then the rest as they appear
  std::vector<SummaryRow> rows;
  bool replicated = false;  ///< the job runs replicates: rows carry a "replicate" column

  /// The value of a column (swept path or scalar) in a row; null when absent.
  Json value(const SummaryRow& row, const std::string& column) const;
  bool hasColumn(const std::string& column) const;
};

SummaryTable buildSummary(const JobRecord& job, const std::vector<RunRecord>& runs);

/// {"jobID", "columns": [{name, kind, unit}], "rows": [{run, status, <columns>..., error?}]}
Json summaryJson(const SummaryTable& table, const UnitLookup& unitOf);

/// RFC 4180 CSV: header run,status,<swept paths>,<scalars>,error; one line per run.
std::string summaryCsv(const SummaryTable& table);

/// True for the scalars every scenario reports (peak_stress, strain_at_peak, ...).
bool isKnownScalar(const std::string& name);

/// Units of the scalars every scenario reports (peak_stress -> "Pa", wall_time_s -> "s", ...).
std::string knownScalarUnit(const std::string& name);

/// Formats a number the way JSON would (shortest round-trip form); "" for NaN and infinities.
std::string formatNumber(double value);

/// A CSV (RFC 4180) cell holding text: quoted when needed, and neutralised against formula
/// injection (a leading = + - @ gets an apostrophe) unless it is a plain number.
std::string csvTextCell(const std::string& text);

}  // namespace rupture::server
