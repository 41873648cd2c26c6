#include "job_comparison.hpp"

#include <algorithm>
#include <sstream>

#include "replicate_statistics.hpp"

namespace rupture::server {
namespace {

/// The job's rows as JSON objects (summary rows, or aggregated points).
Json rowsOf(const ComparedJob& j, bool aggregate, const UnitLookup& units, Json& columns) {
  const Json doc = aggregate ? aggregateJson(j.table, aggregateReplicates(j.table), units) : summaryJson(j.table, units);
  columns = doc["columns"];
  return doc["rows"];
}

void addColumn(Json& columns, const Json& column) {
  for (const auto& c : columns) {
    if (c["name"] == column["name"]) return;
  }
  columns.push_back(column);
}

/// {"a": {"mean": 1}} -> {"a.mean": 1}; arrays (run lists) are left out of CSV cells.
void flattenCells(const Json& value, const std::string& prefix, Json& out) {
  if (value.is_object()) {
    for (const auto& [k, v] : value.items()) flattenCells(v, prefix.empty() ? k : prefix + "." + k, out);
  } else if (!value.is_array()) {
    out[prefix] = value;
  }
}

std::string cell(const Json& v) {
  if (v.is_null()) return "";
  if (v.is_string()) return csvTextCell(v.get<std::string>());
  if (v.is_number_float()) return formatNumber(v.get<double>());
  return csvTextCell(v.dump());
}

}  // namespace

std::string jobLabel(const JobRecord& job) {
  return job.name.empty() ? "job " + std::to_string(job.id) : std::to_string(job.id) + ": " + job.name;
}

Json comparisonJson(const std::vector<ComparedJob>& jobs, bool aggregate,
                    const std::function<UnitLookup(const std::string& scenario)>& unitsOf) {
  Json doc = Json::object();
  Json list = Json::array();
  Json columns = Json::array({Json{{"name", "job"}, {"kind", "job"}, {"unit", ""}}});
  Json rows = Json::array();
  for (const ComparedJob& j : jobs) {
    list.push_back({{"jobID", std::to_string(j.job.id)},
                    {"name", j.job.name},
                    {"label", jobLabel(j.job)},
                    {"processID", j.job.processId},
                    {"status", toString(j.job.status)},
                    {"runs_total", j.job.runsTotal},
                    {"runs_successful", j.job.runsSuccessful}});
    Json jobColumns;
    const Json jobRows = rowsOf(j, aggregate, unitsOf ? unitsOf(j.job.processId) : UnitLookup(), jobColumns);
    for (const auto& c : jobColumns) addColumn(columns, c);
    for (const auto& r : jobRows) {
      Json row = Json::object();
      row["job"] = std::to_string(j.job.id);
      for (const auto& [k, v] : r.items()) row[k] = v;
      rows.push_back(std::move(row));
    }
  }
  doc["jobs"] = list;
  doc["aggregate"] = aggregate ? "replicates" : "none";
  if (aggregate) doc["confidence_level"] = kConfidenceLevel;
  doc["columns"] = columns;
  doc["rows"] = rows;
  return doc;
}

std::string comparisonCsv(const std::vector<ComparedJob>& jobs, bool aggregate) {
  std::vector<std::string> header = {"job", "job_name"};
  std::vector<Json> flat;
  for (const ComparedJob& j : jobs) {
    Json columns;
    for (const auto& r : rowsOf(j, aggregate, UnitLookup(), columns)) {
      Json row = Json::object();
      row["job"] = std::to_string(j.job.id);
      row["job_name"] = j.job.name;
      flattenCells(r, "", row);
      for (const auto& [k, v] : row.items()) {
        if (std::find(header.begin(), header.end(), k) == header.end()) header.push_back(k);
      }
      flat.push_back(std::move(row));
    }
  }
  std::ostringstream out;
  for (std::size_t i = 0; i < header.size(); ++i) out << (i ? "," : "") << csvTextCell(header[i]);
  out << "\r\n";
  for (const Json& row : flat) {
    for (std::size_t i = 0; i < header.size(); ++i) {
      auto it = row.find(header[i]);
      out << (i ? "," : "") << (it == row.end() ? std::string() : cell(*it));
    }
    out << "\r\n";
  }
  return out.str();
}

SummaryTable comparisonPlotTable(const std::vector<ComparedJob>& jobs, const std::string& y,
                                 std::vector<std::pair<double, double>>& yIntervals) {
  SummaryTable out;
  out.sweptPaths.push_back("job");
  for (const ComparedJob& j : jobs) {
    for (const auto& p : j.table.sweptPaths) {
      if (std::find(out.sweptPaths.begin(), out.sweptPaths.end(), p) == out.sweptPaths.end()) out.sweptPaths.push_back(p);
    }
    for (const auto& s : j.table.scalarNames) {
      if (std::find(out.scalarNames.begin(), out.scalarNames.end(), s) == out.scalarNames.end()) out.scalarNames.push_back(s);
    }
  }
  yIntervals.clear();
  for (const ComparedJob& j : jobs) {
    std::vector<std::pair<double, double>> intervals;
    const SummaryTable means = meansTable(j.table, aggregateReplicates(j.table), y, intervals);
    for (std::size_t r = 0; r < means.rows.size(); ++r) {
      SummaryRow row = means.rows[r];
      Json swept = Json::array({jobLabel(j.job)});
      for (std::size_t a = 1; a < out.sweptPaths.size(); ++a) swept.push_back(means.value(row, out.sweptPaths[a]));
      row.swept = swept;
      out.rows.push_back(std::move(row));
      yIntervals.push_back(intervals[r]);
    }
  }
  return out;
}

}  // namespace rupture::server
