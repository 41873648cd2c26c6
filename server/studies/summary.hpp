#pragma once
// A job's summary table: one row per run with its swept values and the scalars the run reported
// (peak_stress, strain_at_peak, ...), rendered as JSON or CSV. Every column carries its SI unit and
// a human label from one source: the scenario's declared result fields (rupture/result_fields.hpp)
// for scalars, the schema keyword "x-unit" (and "title") for swept spec fields.
#include <map>
#include <string>
#include <vector>

#include "jobs/job_store.hpp"

namespace rupture::server {

/// What a column means: its SI unit ("1" dimensionless, "" text or undeclared), label, description.
struct ColumnInfo {
  std::string unit;
  std::string label;
  std::string description;
};

struct SummaryRow {
  int run = 0;
  Status status = Status::Accepted;
  Json swept;    ///< array aligned with SummaryTable::sweptPaths
  Json inputs;   ///< array aligned with SummaryTable::inputPaths
  Json scalars;  ///< flat object name -> value (nested objects flattened with dots)
  std::string error;
  int replicate = 0;  ///< replicate index within the sweep point (replicate_statistics.hpp)
};

struct SummaryTable {
  std::int64_t jobId = 0;
  std::vector<std::string> sweptPaths;
  /// Inputs each run resolved that the sweep does not name, one column each: the sample seed the
  /// run used ("sample.seed": its spec's, a replicate's base + r, else the schema's default), in
  /// scenarios that have one.
  std::vector<std::string> inputPaths;
  /// Result scalars: the scenario's declared ones in declaration order, then undeclared ones as
  /// they appear. A scalar that repeats a swept value (strain_rate when loading.strain_rate is
  /// swept, same value in every row) is left out.
  std::vector<std::string> scalarNames;
  std::vector<SummaryRow> rows;
  bool replicated = false;  ///< the job runs replicates: rows carry a "replicate" column
  std::vector<std::string> declaredScalars;  ///< every scalar the scenario may report (a plot may name one before any run has it)
  std::map<std::string, ColumnInfo> info;  ///< per column (swept path, scalar or declared scalar)

  /// The column's unit, label and description (name as label, no unit, when unknown).
  ColumnInfo columnInfo(const std::string& column) const;

  /// The value of a column (swept path or scalar) in a row; null when absent.
  Json value(const SummaryRow& row, const std::string& column) const;
  bool hasColumn(const std::string& column) const;
  /// The y of a plot nobody chose: peak_stress where the runs report it (the seeds' headline), else
  /// the first scalar, in declaration order, that some row holds as a number; before any run has
  /// reported, the declared peak_stress or first declared number; "" when there is none.
  std::string headlineQuantity() const;
};

SummaryTable buildSummary(const JobRecord& job, const std::vector<RunRecord>& runs);

/// {"jobID", "columns": [{name, kind, unit, label, description}], "units": {name: unit},
///  "rows": [{run, status, <columns>..., error?}]}; kind "swept", "input" (inputPaths) or "result".
Json summaryJson(const SummaryTable& table);

/// RFC 4180 CSV: header run,status,<swept paths>,<input paths>,<scalars>,error, each column named
/// "name [unit]" (rupture::nameWithUnit: "peak_stress [Pa]", "fragments [1]", text columns bare);
/// one line per run.
std::string summaryCsv(const SummaryTable& table);

/// {"a": {"mean": 1}} -> {"a.mean": 1}, added to `out` under `prefix`; `arrays` false leaves
/// arrays out (a CSV cell cannot hold a list of runs).
void flattenInto(const Json& value, const std::string& prefix, Json& out, bool arrays = true);

/// Formats a number the way JSON would (shortest round-trip form); "" for NaN and infinities.
std::string formatNumber(double value);

/// A CSV (RFC 4180) cell holding text: quoted when needed, neutralised against formula injection
/// (a leading = + - @ gets an apostrophe) unless it is a plain number, and without raw control
/// bytes (each but tab, CR and LF becomes U+FFFD).
std::string csvTextCell(const std::string& text);

/// A JSON value as a CSV cell: numbers as written, null empty, text through csvTextCell.
std::string csvCell(const Json& v);

}  // namespace rupture::server
