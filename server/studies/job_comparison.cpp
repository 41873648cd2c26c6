#include "studies/job_comparison.hpp"

#include <algorithm>
#include <map>
#include <set>
#include <sstream>

#include "rupture/result_fields.hpp"
#include "studies/replicate_statistics.hpp"

namespace rupture::server {
namespace {

/// The job's rows as JSON objects (summary rows, or aggregated points).
Json rowsOf(const ComparedJob& j, bool aggregate, Json& columns) {
  const Json doc = aggregate ? aggregateJson(j.table, aggregateReplicates(j.table)) : summaryJson(j.table);
  columns = doc["columns"];
  return doc["rows"];
}

void addColumn(Json& columns, const Json& column) {
  for (const auto& c : columns) {
    if (c["name"] == column["name"]) return;
  }
  columns.push_back(column);
}

}  // namespace

std::string jobLabel(const JobRecord& job) {
  return job.name.empty() ? "job " + std::to_string(job.id) : std::to_string(job.id) + ": " + job.name;
}

namespace {

/// Every leaf of `node` by dotted path (arrays are leaves: a size or a list of radii is one input).
void flattenInputs(const Json& node, const std::string& prefix, std::map<std::string, Json>& out) {
  if (node.is_object() && !node.empty()) {
    for (const auto& [key, value] : node.items()) flattenInputs(value, prefix.empty() ? key : prefix + "." + key, out);
    return;
  }
  if (!prefix.empty()) out[prefix] = node;
}

}  // namespace

Json differingInputs(const std::vector<ComparedJob>& jobs) {
  Json list = Json::array();
  if (jobs.size() < 2) return list;
  std::vector<std::map<std::string, Json>> flat(jobs.size());
  std::set<std::string> paths;
  for (std::size_t k = 0; k < jobs.size(); ++k) {
    flattenInputs(jobs[k].job.inputs, "", flat[k]);
    // A swept path shows as its list of values: the job's rows vary it.
    if (jobs[k].job.sweep.is_object())
      for (const auto& [path, values] : jobs[k].job.sweep.items()) flat[k][path] = Json{{"swept", values}};
    if (jobs[k].job.study.is_object() && jobs[k].job.study.contains("replicates"))
      flat[k]["replicates"] = jobs[k].job.study["replicates"];
    for (const auto& [path, value] : flat[k]) paths.insert(path);
  }
  if (std::any_of(jobs.begin(), jobs.end(), [&](const ComparedJob& j) { return j.job.processId != jobs[0].job.processId; })) {
    Json values = Json::object();
    for (const ComparedJob& j : jobs) values[std::to_string(j.job.id)] = j.job.processId;
    list.push_back({{"path", "scenario"}, {"values", values}});
  }
  for (const std::string& path : paths) {
    Json values = Json::object();
    bool differs = false;
    for (std::size_t k = 0; k < jobs.size(); ++k) {
      const auto it = flat[k].find(path);
      const Json value = it == flat[k].end() ? Json() : it->second;  // null: left to the default
      const auto first = flat[0].find(path);
      differs = differs || value != (first == flat[0].end() ? Json() : first->second);
      values[std::to_string(jobs[k].job.id)] = value;
    }
    if (differs) list.push_back({{"path", path}, {"values", values}});
  }
  return list;
}

Json comparisonJson(const std::vector<ComparedJob>& jobs, bool aggregate) {
  Json doc = Json::object();
  Json list = Json::array();
  Json columns = Json::array({Json{{"name", "job"}, {"kind", "job"}, {"unit", ""}, {"label", "Job"}, {"description", "The job id"}}});
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
    const Json jobRows = rowsOf(j, aggregate, jobColumns);
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
  Json units = Json::object();
  for (const auto& c : columns) units[c.value("name", "")] = c.value("unit", "");
  doc["units"] = units;
  doc["rows"] = rows;
  doc["differing_inputs"] = differingInputs(jobs);
  return doc;
}

std::string comparisonCsv(const std::vector<ComparedJob>& jobs, bool aggregate) {
  std::vector<std::string> header = {"job", "job_name"};
  std::vector<Json> flat;
  Json unitOf = Json::object();  // column -> unit, from the first job that declares it
  for (const ComparedJob& j : jobs) {
    Json columns;
    const Json jobRows = rowsOf(j, aggregate, columns);
    for (const auto& c : columns)
      if (!unitOf.contains(c.value("name", ""))) unitOf[c.value("name", "")] = c.value("unit", "");
    for (const auto& r : jobRows) {
      Json row = Json::object();
      row["job"] = std::to_string(j.job.id);
      row["job_name"] = j.job.name;
      flattenInto(r, "", row, /*arrays=*/false);
      for (const auto& [k, v] : row.items()) {
        if (std::find(header.begin(), header.end(), k) == header.end()) header.push_back(k);
      }
      flat.push_back(std::move(row));
    }
  }
  std::ostringstream out;
  // Headers carry their units as the per-job CSV's do ("peak_stress [Pa]"); a statistic's member
  // ("peak_stress.mean") has its column's unit, its count ".n" is "1".
  auto unitFor = [&](const std::string& name) -> std::string {
    if (unitOf.contains(name)) return unitOf[name].get<std::string>();
    const std::size_t dot = name.rfind('.');
    if (dot == std::string::npos || !unitOf.contains(name.substr(0, dot))) return "";
    return name.substr(dot + 1) == "n" ? "1" : unitOf[name.substr(0, dot)].get<std::string>();
  };
  for (std::size_t i = 0; i < header.size(); ++i)
    out << (i ? "," : "") << csvTextCell(i < 2 ? header[i] : rupture::nameWithUnit(header[i], unitFor(header[i])));
  out << "\r\n";
  for (const Json& row : flat) {
    for (std::size_t i = 0; i < header.size(); ++i) {
      auto it = row.find(header[i]);
      out << (i ? "," : "") << (it == row.end() ? std::string() : csvCell(*it));
    }
    out << "\r\n";
  }
  return out.str();
}

SummaryTable comparisonPlotTable(const std::vector<ComparedJob>& jobs) {
  SummaryTable out;
  out.sweptPaths.push_back("job");
  out.info["job"] = {"", "Job", "The job (id: name)"};
  std::vector<SummaryTable> means;
  for (const ComparedJob& j : jobs) means.push_back(meansTable(j.table, aggregateReplicates(j.table)));
  auto addColumns = [](const std::vector<std::string>& from, std::vector<std::string>& to) {
    for (const auto& c : from) {
      if (std::find(to.begin(), to.end(), c) == to.end()) to.push_back(c);
    }
  };
  for (const SummaryTable& m : means) {
    addColumns(m.sweptPaths, out.sweptPaths);
    addColumns(m.scalarNames, out.scalarNames);
    addColumns(m.declaredScalars, out.declaredScalars);
    out.info.insert(m.info.begin(), m.info.end());  // the first job that names a column gives its unit
  }
  for (std::size_t k = 0; k < jobs.size(); ++k) {
    for (SummaryRow row : means[k].rows) {
      Json swept = Json::array({jobLabel(jobs[k].job)});
      for (std::size_t a = 1; a < out.sweptPaths.size(); ++a) swept.push_back(means[k].value(row, out.sweptPaths[a]));
      row.swept = swept;
      out.rows.push_back(std::move(row));
    }
  }
  return out;
}

}  // namespace rupture::server
