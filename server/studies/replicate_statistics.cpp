#include "studies/replicate_statistics.hpp"

#include <cmath>
#include <limits>
#include <map>
#include <sstream>

#include "rupture/result_fields.hpp"
#include "studies/student_t.hpp"

namespace rupture::server {
namespace {

Json numberOrNull(const std::optional<double>& v) { return v && std::isfinite(*v) ? Json(*v) : Json(); }

Json statisticsJson(const ScalarStatistics& s) {
  Json doc = Json::object();
  doc["mean"] = s.n > 0 && std::isfinite(s.mean) ? Json(s.mean) : Json();
  doc["sd"] = numberOrNull(s.sd);
  doc["ci95_low"] = s.ciHalfWidth ? numberOrNull(s.mean - *s.ciHalfWidth) : Json();
  doc["ci95_high"] = s.ciHalfWidth ? numberOrNull(s.mean + *s.ciHalfWidth) : Json();
  doc["ci95_half_width"] = numberOrNull(s.ciHalfWidth);
  doc["n"] = s.n;
  return doc;
}

std::string csvNumber(const std::optional<double>& v) { return v ? formatNumber(*v) : std::string(); }

/// The scalars that are columns of an aggregate table: those some point has statistics for.
std::vector<std::string> scalarsWithStatistics(const SummaryTable& table, const std::vector<PointAggregate>& points) {
  std::vector<std::string> numeric;
  for (const auto& s : table.scalarNames) {
    for (const PointAggregate& p : points) {
      if (p.find(s)) {
        numeric.push_back(s);
        break;
      }
    }
  }
  return numeric;
}

}  // namespace

ScalarStatistics describeSample(const std::vector<double>& values) {
  ScalarStatistics s;
  s.n = static_cast<int>(values.size());
  if (s.n == 0) return s;
  double sum = 0;
  for (double v : values) sum += v;
  s.mean = sum / s.n;
  if (s.n < 2) return s;
  double squares = 0;
  for (double v : values) squares += (v - s.mean) * (v - s.mean);
  s.sd = std::sqrt(squares / (s.n - 1));
  s.ciHalfWidth = studentTQuantile(0.5 + kConfidenceLevel / 2, s.n - 1) * *s.sd / std::sqrt(double(s.n));
  return s;
}

const ScalarStatistics* PointAggregate::find(const std::string& name) const {
  for (const auto& [n, s] : scalars) {
    if (n == name) return &s;
  }
  return nullptr;
}

const std::vector<double>* PointAggregate::valuesOf(const std::string& name) const {
  for (std::size_t i = 0; i < scalars.size(); ++i) {
    if (scalars[i].first == name) return &values[i];
  }
  return nullptr;
}

std::vector<PointAggregate> aggregateReplicates(const SummaryTable& table) {
  std::vector<PointAggregate> points;
  std::map<std::string, std::size_t> byKey;
  std::vector<std::vector<std::vector<double>>> samples;  // point -> scalar -> values
  std::vector<std::vector<bool>> nonNumeric;              // point -> scalar -> reported, not as a number
  for (const SummaryRow& row : table.rows) {
    const std::string key = row.swept.dump();
    auto [it, inserted] = byKey.emplace(key, points.size());
    if (inserted) {
      PointAggregate p;
      p.swept = row.swept;
      points.push_back(std::move(p));
      samples.emplace_back(table.scalarNames.size());
      nonNumeric.emplace_back(table.scalarNames.size(), false);
    }
    PointAggregate& p = points[it->second];
    p.runs.push_back(row.run);
    if (row.status != Status::Successful) {
      p.excluded.push_back({{"run", row.run}, {"status", toString(row.status)}});
      continue;
    }
    p.successfulRuns.push_back(row.run);
    for (std::size_t s = 0; s < table.scalarNames.size(); ++s) {
      const Json v = table.value(row, table.scalarNames[s]);
      if (v.is_number() && !v.is_boolean() && std::isfinite(v.get<double>())) {
        samples[it->second][s].push_back(v.get<double>());
      } else if (!v.is_null() && !v.is_number()) {
        nonNumeric[it->second][s] = true;
      }
    }
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    for (std::size_t s = 0; s < table.scalarNames.size(); ++s) {
      // Scalars that are never numbers at this point (text, lists) have no statistics.
      if (samples[i][s].empty() && nonNumeric[i][s]) continue;
      points[i].scalars.emplace_back(table.scalarNames[s], describeSample(samples[i][s]));
      points[i].values.push_back(samples[i][s]);
    }
  }
  return points;
}

Json aggregateJson(const SummaryTable& table, const std::vector<PointAggregate>& points) {
  Json doc = Json::object();
  doc["jobID"] = std::to_string(table.jobId);
  doc["aggregate"] = "replicates";
  doc["confidence_level"] = kConfidenceLevel;
  Json columns = Json::array();
  Json units = Json::object();
  auto column = [&](const std::string& name, const char* kind) {
    const ColumnInfo info = table.columnInfo(name);
    units[name] = info.unit;
    return Json{{"name", name}, {"kind", kind}, {"unit", info.unit}, {"label", info.label}, {"description", info.description}};
  };
  for (const auto& p : table.sweptPaths) columns.push_back(column(p, "swept"));
  columns.push_back({{"name", "n_runs"}, {"kind", "count"}, {"unit", "1"}, {"label", "Runs"}, {"description", "Runs of the point"}});
  columns.push_back({{"name", "n_successful"}, {"kind", "count"}, {"unit", "1"}, {"label", "Successful runs"},
                     {"description", "Successful runs of the point (the statistics use only these)"}});
  units["n_runs"] = "1";
  units["n_successful"] = "1";
  const std::vector<std::string> numeric = scalarsWithStatistics(table, points);
  for (const auto& s : numeric) {
    Json c = column(s, "statistics");
    c["members"] = Json::array({"mean", "sd", "ci95_low", "ci95_high", "ci95_half_width", "n"});
    columns.push_back(std::move(c));
  }
  doc["columns"] = columns;
  doc["units"] = units;
  Json rows = Json::array();
  for (const PointAggregate& p : points) {
    Json r = Json::object();
    for (std::size_t i = 0; i < table.sweptPaths.size(); ++i) r[table.sweptPaths[i]] = i < p.swept.size() ? p.swept[i] : Json();
    r["n_runs"] = p.runs.size();
    r["n_successful"] = p.successfulRuns.size();
    r["runs"] = p.runs;
    r["excluded"] = p.excluded;
    for (const auto& s : numeric) {
      const ScalarStatistics* stats = p.find(s);
      r[s] = statisticsJson(stats ? *stats : ScalarStatistics{});
    }
    rows.push_back(std::move(r));
  }
  doc["rows"] = rows;
  return doc;
}

std::string aggregateCsv(const SummaryTable& table, const std::vector<PointAggregate>& points) {
  const std::vector<std::string> numeric = scalarsWithStatistics(table, points);
  std::ostringstream out;
  bool first = true;
  auto sep = [&] { if (!first) out << ','; first = false; };
  for (const auto& p : table.sweptPaths) { sep(); out << csvTextCell(rupture::nameWithUnit(p, table.columnInfo(p).unit)); }
  sep(); out << "n_runs [1],n_successful [1]";
  for (const auto& s : numeric) {
    const std::string unit = table.columnInfo(s).unit;
    for (const char* member : {".mean", ".sd", ".ci95_low", ".ci95_high", ".ci95_half_width"})
      out << ',' << csvTextCell(rupture::nameWithUnit(s + member, unit));
    out << ',' << csvTextCell(rupture::nameWithUnit(s + ".n", "1"));
  }
  out << "\r\n";
  for (const PointAggregate& p : points) {
    first = true;
    for (std::size_t i = 0; i < table.sweptPaths.size(); ++i) { sep(); out << csvCell(i < p.swept.size() ? p.swept[i] : Json()); }
    sep(); out << p.runs.size() << ',' << p.successfulRuns.size();
    for (const auto& s : numeric) {
      const ScalarStatistics* st = p.find(s);
      const ScalarStatistics none;
      const ScalarStatistics& v = st ? *st : none;
      out << ',' << (v.n > 0 ? formatNumber(v.mean) : std::string()) << ',' << csvNumber(v.sd) << ','
          << (v.ciHalfWidth ? formatNumber(v.mean - *v.ciHalfWidth) : std::string()) << ','
          << (v.ciHalfWidth ? formatNumber(v.mean + *v.ciHalfWidth) : std::string()) << ',' << csvNumber(v.ciHalfWidth)
          << ',' << v.n;
    }
    out << "\r\n";
  }
  return out.str();
}

std::string ciHalfWidthColumn(const std::string& scalar) { return scalar + ".ci95_half_width"; }

SummaryTable meansTable(const SummaryTable& table, const std::vector<PointAggregate>& points) {
  SummaryTable means;
  means.jobId = table.jobId;
  means.sweptPaths = table.sweptPaths;
  means.info = table.info;
  means.declaredScalars = table.declaredScalars;
  // Every scalar keeps its column (now the mean); numeric ones get their derived columns.
  std::vector<std::string> numeric;
  for (const auto& s : table.scalarNames) {
    means.scalarNames.push_back(s);
    for (const PointAggregate& p : points) {
      if (p.find(s)) {
        numeric.push_back(s);
        break;
      }
    }
  }
  for (const auto& s : numeric) {
    const ColumnInfo base = table.columnInfo(s);
    means.info[s] = {base.unit, base.label, "Mean over the successful replicates of: " + base.description};
    means.scalarNames.push_back(s + ".sd");
    means.info[s + ".sd"] = {base.unit, base.label + " (sd)", "Sample standard deviation (n - 1) of " + s + " over the replicates"};
    means.scalarNames.push_back(ciHalfWidthColumn(s));
    means.info[ciHalfWidthColumn(s)] = {base.unit, base.label + " (95 % CI half-width)",
                                        "Half-width of the 95 % confidence interval of the mean of " + s + " (Student t)"};
    means.scalarNames.push_back(s + ".n");
    means.info[s + ".n"] = {"1", base.label + " (n)", "Successful replicates that reported " + s};
  }
  for (const PointAggregate& p : points) {
    SummaryRow row;
    row.run = p.runs.empty() ? 0 : p.runs.front();
    row.status = p.successfulRuns.empty() ? Status::Failed : Status::Successful;
    row.swept = p.swept;
    row.scalars = Json::object();
    for (const auto& [name, stats] : p.scalars) {
      if (stats.n == 0) continue;
      row.scalars[name] = stats.mean;
      row.scalars[name + ".n"] = stats.n;
      if (stats.sd) row.scalars[name + ".sd"] = *stats.sd;
      if (stats.ciHalfWidth) row.scalars[ciHalfWidthColumn(name)] = *stats.ciHalfWidth;
    }
    means.rows.push_back(std::move(row));
  }
  return means;
}

}  // namespace rupture::server
