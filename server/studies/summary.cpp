#include "studies/summary.hpp"

#include "jobs/replicates.hpp"
#include "jobs/sweep.hpp"
#include "rupture/run.hpp"

#include <algorithm>
#include <charconv>
#include <string_view>
#include <cmath>
#include <map>
#include <sstream>

namespace rupture::server {

void flattenInto(const Json& value, const std::string& prefix, Json& out, bool arrays) {
  if (value.is_object()) {
    for (const auto& [k, v] : value.items()) flattenInto(v, prefix.empty() ? k : prefix + "." + k, out, arrays);
  } else if (!prefix.empty() && (arrays || !value.is_array())) {
    out[prefix] = value;
  }
}

std::string csvTextCell(const std::string& text) {
  // No raw control bytes: a NUL ends the text in C tools, others garble a terminal or a
  // spreadsheet. Each becomes U+FFFD (as bytes that are not UTF-8 do); tab, CR and LF stay, quoted.
  std::string cell;
  cell.reserve(text.size());
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if ((byte < 0x20 && c != '\t' && c != '\r' && c != '\n') || byte == 0x7f) cell += "\xEF\xBF\xBD";
    else cell += c;
  }
  // Spreadsheets evaluate a cell starting with = + - @ (or a tab or CR) as a formula, also after
  // leading spaces or line feeds, which they skip; a leading apostrophe makes it text. A cell that
  // is a plain number ("-1.5") stays a number.
  const std::size_t first = cell.find_first_not_of(" \t\r\n\v\f");
  const bool trigger = (!cell.empty() && (cell.front() == '\t' || cell.front() == '\r')) ||
                       (first != std::string::npos && std::string_view("=+-@").find(cell[first]) != std::string_view::npos);
  if (trigger) {
    double number = 0;
    const bool plus = cell.front() == '+';  // from_chars takes '-' but not '+'
    const char* begin = cell.data() + (plus ? 1 : 0);
    const char* last = cell.data() + cell.size();
    auto [ptr, ec] = std::from_chars(begin, last, number);
    const bool plainNumber =
        begin != last && !(plus && (*begin == '-' || *begin == '+')) && ec == std::errc() && ptr == last;
    if (!plainNumber) cell.insert(0, 1, '\'');
  }
  if (cell.find_first_of(",\"\r\n") == std::string::npos) return cell;
  std::string out = "\"";
  for (char c : cell) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

std::string csvCell(const Json& v) {
  if (v.is_null()) return "";
  if (v.is_string()) return csvTextCell(v.get<std::string>());
  if (v.is_number_float()) return formatNumber(v.get<double>());
  if (v.is_number()) return v.dump();
  return csvTextCell(v.dump(-1, ' ', false, Json::error_handler_t::replace));
}

std::string formatNumber(double value) {
  if (!std::isfinite(value)) return "";  // NaN/inf: an empty CSV cell
  return nlohmann::json(value).dump();
}

Json SummaryTable::value(const SummaryRow& row, const std::string& column) const {
  for (std::size_t i = 0; i < sweptPaths.size(); ++i) {
    if (sweptPaths[i] == column) return i < row.swept.size() ? row.swept[i] : Json();
  }
  for (std::size_t i = 0; i < inputPaths.size(); ++i) {
    if (inputPaths[i] == column) return i < row.inputs.size() ? row.inputs[i] : Json();
  }
  auto it = row.scalars.find(column);
  return it == row.scalars.end() ? Json() : *it;
}

bool SummaryTable::hasColumn(const std::string& column) const {
  return std::find(sweptPaths.begin(), sweptPaths.end(), column) != sweptPaths.end() ||
         std::find(inputPaths.begin(), inputPaths.end(), column) != inputPaths.end() ||
         std::find(scalarNames.begin(), scalarNames.end(), column) != scalarNames.end();
}

ColumnInfo SummaryTable::columnInfo(const std::string& column) const {
  auto it = info.find(column);
  return it != info.end() ? it->second : ColumnInfo{"", column, ""};
}

std::string SummaryTable::headlineQuantity() const {
  auto numeric = [&](const std::string& name) {
    for (const SummaryRow& row : rows)
      if (value(row, name).is_number()) return true;
    return false;
  };
  if (std::find(scalarNames.begin(), scalarNames.end(), "peak_stress") != scalarNames.end() && numeric("peak_stress"))
    return "peak_stress";
  for (const std::string& name : scalarNames)
    if (numeric(name)) return name;
  // No run has reported yet: the declared headline, so that the plot fills in as runs finish.
  if (std::find(declaredScalars.begin(), declaredScalars.end(), "peak_stress") != declaredScalars.end())
    return "peak_stress";
  for (const std::string& name : declaredScalars)
    if (!columnInfo(name).unit.empty()) return name;  // numbers have a unit ("1" at least); text has none
  return "";
}

namespace {

/// True when scalar `name` repeats swept column `path` (same last segment, same value in every row
/// that has both).
bool repeatsSweptValue(const SummaryTable& table, const std::string& path, const std::string& name) {
  const std::size_t dot = path.rfind('.');
  if ((dot == std::string::npos ? path : path.substr(dot + 1)) != name) return false;
  for (const SummaryRow& row : table.rows) {
    const Json a = table.value(row, path), b = table.value(row, name);
    if (a.is_null() || b.is_null()) continue;
    if (a.is_number() && b.is_number()) {
      const double x = a.get<double>(), y = b.get<double>();
      if (std::abs(x - y) > 1e-12 * std::max(std::abs(x), std::abs(y))) return false;
    } else if (a != b) {
      return false;
    }
  }
  return true;
}

/// True when a JSON Patch operation may change the value at `pointer` (it writes there, above or below).
bool touches(const Json& op, const std::string& pointer) {
  const std::string opName = op.value("op", "");
  if (opName != "add" && opName != "remove" && opName != "replace" && opName != "test") return true;  // move, copy
  const std::string path = op.value("path", "");
  return path == pointer || pointer.rfind(path + "/", 0) == 0 || path.rfind(pointer + "/", 0) == 0;
}

/// The value `run` used at the dotted `path`: its spec's, else the schema's `fallback` (null: none).
/// Runs are stored as patches against the job's `base` spec: one that leaves the path alone reads
/// it from the base, without building its spec.
Json resolvedInput(const JobRecord& job, const RunRecord& run, const Json& base, const std::string& path,
                   const Json& fallback) {
  auto at = [&](const Json& spec) {
    const Json* v = findAtPath(spec, path);
    return v ? *v : fallback;
  };
  if (!run.spec.is_null() || !run.specPatch.is_array()) return at(run.spec);
  std::string pointer = '/' + path;  // "sample.seed" -> "/sample/seed" (spec keys hold no '.', '/' or '~')
  std::replace(pointer.begin(), pointer.end(), '.', '/');
  for (const Json& op : run.specPatch)
    if (touches(op, pointer)) return at(runSpec(job, run));
  return at(base);
}

/// The seed column's path ("sample.seed") in a scenario's `schema`; "" when it has none or the sweep names it.
std::string seedColumn(const nlohmann::json& schema, const std::vector<std::string>& sweptPaths) {
  static const std::string kSeed = "sample.seed";
  if (!schemaNodeAt(schema, kSeed)) return "";
  return std::find(sweptPaths.begin(), sweptPaths.end(), kSeed) == sweptPaths.end() ? kSeed : "";
}

}  // namespace

SummaryTable buildSummary(const JobRecord& job, const std::vector<RunRecord>& runs) {
  SummaryTable table;
  table.jobId = job.id;
  for (const auto& p : job.sweptPaths) table.sweptPaths.push_back(p.get<std::string>());
  table.replicated = job.study.is_object() && job.study.contains("replicates");
  const rupture::ScenarioInfo* scenario = rupture::findScenario(job.processId);
  const nlohmann::json schema = scenario ? rupture::scenarioSchema(job.processId) : nlohmann::json::object();
  if (const std::string seed = seedColumn(schema, table.sweptPaths); !seed.empty()) table.inputPaths.push_back(seed);
  std::vector<Json> fallbacks;
  for (const std::string& p : table.inputPaths) {
    const nlohmann::json* node = schemaNodeAt(schema, p);
    fallbacks.push_back(node && node->contains("default") ? Json((*node)["default"]) : Json());
  }
  const Json base = table.inputPaths.empty() ? Json() : jobBaseSpec(job.processId, job.inputs);
  std::vector<std::string> seen;
  for (const RunRecord& run : runs) {
    SummaryRow row;
    row.run = run.key.index;
    row.status = run.status;
    row.swept = run.swept.is_array() ? run.swept : Json::array();
    row.inputs = Json::array();
    for (std::size_t i = 0; i < table.inputPaths.size(); ++i)
      row.inputs.push_back(resolvedInput(job, run, base, table.inputPaths[i], fallbacks[i]));
    row.scalars = Json::object();
    if (run.summary.is_object()) flattenInto(run.summary, "", row.scalars);
    row.error = run.error;
    row.replicate = run.replicate;
    for (const auto& [k, v] : row.scalars.items()) {
      if (std::find(seen.begin(), seen.end(), k) == seen.end()) seen.push_back(k);
    }
    table.rows.push_back(std::move(row));
  }
  // Column metadata from the scenario's declarations and its schema.
  const int dimension = rupture::specDimension(schema, runs.empty() ? Json::object() : runSpec(job, runs.front()));
  for (const std::string& p : table.sweptPaths) {
    table.info[p] = {rupture::specFieldUnit(schema, p), rupture::specFieldLabel(schema, p), ""};
  }
  for (const std::string& p : table.inputPaths) {
    table.info[p] = {rupture::specFieldUnit(schema, p), rupture::specFieldLabel(schema, p),
                     "The value this run used (its spec's, else the schema's default)"};
  }
  auto keep = [&](const std::string& name) {
    for (const std::string& p : table.sweptPaths)
      if (repeatsSweptValue(table, p, name)) return false;
    return std::find(table.sweptPaths.begin(), table.sweptPaths.end(), name) == table.sweptPaths.end() &&
           std::find(table.inputPaths.begin(), table.inputPaths.end(), name) == table.inputPaths.end();
  };
  if (scenario) {
    for (const rupture::ResultField& f : scenario->summary) {
      if (std::find(seen.begin(), seen.end(), f.name) == seen.end() || !keep(f.name)) continue;
      table.scalarNames.push_back(f.name);
    }
  }
  for (const std::string& name : seen) {
    if (std::find(table.scalarNames.begin(), table.scalarNames.end(), name) == table.scalarNames.end() && keep(name)) {
      table.scalarNames.push_back(name);
    }
  }
  if (scenario) {
    for (const rupture::ResultField& f : scenario->summary) {
      table.declaredScalars.push_back(f.name);
      table.info[f.name] = {f.unitFor(dimension), f.label, f.description};
    }
  }
  for (const std::string& name : table.scalarNames) {
    const rupture::ResultField* f = scenario ? rupture::findResultField(scenario->summary, name) : nullptr;
    table.info[name] = f ? ColumnInfo{f->unitFor(dimension), f->label, f->description} : ColumnInfo{"", name, ""};
  }
  return table;
}

Json summaryJson(const SummaryTable& table) {
  Json doc = Json::object();
  doc["jobID"] = std::to_string(table.jobId);
  Json columns = Json::array(), units = Json::object();
  auto column = [&](const std::string& name, const char* kind) {
    const ColumnInfo info = table.columnInfo(name);
    columns.push_back({{"name", name}, {"kind", kind}, {"unit", info.unit}, {"label", info.label},
                       {"description", info.description}});
    units[name] = info.unit;
  };
  for (const auto& p : table.sweptPaths) column(p, "swept");
  for (const auto& p : table.inputPaths) column(p, "input");
  for (const auto& s : table.scalarNames) column(s, "result");
  doc["columns"] = columns;
  doc["units"] = units;
  Json rows = Json::array();
  for (const SummaryRow& row : table.rows) {
    Json r = Json::object();
    r["run"] = row.run;
    r["status"] = toString(row.status);
    if (table.replicated) r["replicate"] = row.replicate;
    for (std::size_t i = 0; i < table.sweptPaths.size(); ++i) {
      r[table.sweptPaths[i]] = i < row.swept.size() ? row.swept[i] : Json();
    }
    for (const auto& p : table.inputPaths) r[p] = table.value(row, p);
    for (const auto& s : table.scalarNames) r[s] = table.value(row, s);
    if (!row.error.empty()) r["error"] = row.error;
    rows.push_back(std::move(r));
  }
  doc["rows"] = rows;
  return doc;
}

std::string summaryCsv(const SummaryTable& table) {
  std::ostringstream out;
  out << "run,status" << (table.replicated ? ",replicate" : "");
  for (const auto& p : table.sweptPaths) out << ',' << csvTextCell(rupture::nameWithUnit(p, table.columnInfo(p).unit));
  for (const auto& p : table.inputPaths) out << ',' << csvTextCell(rupture::nameWithUnit(p, table.columnInfo(p).unit));
  for (const auto& s : table.scalarNames) out << ',' << csvTextCell(rupture::nameWithUnit(s, table.columnInfo(s).unit));
  out << ",error\r\n";
  for (const SummaryRow& row : table.rows) {
    out << row.run << ',' << toString(row.status);
    if (table.replicated) out << ',' << row.replicate;
    for (const auto& p : table.sweptPaths) out << ',' << csvCell(table.value(row, p));
    for (const auto& p : table.inputPaths) out << ',' << csvCell(table.value(row, p));
    for (const auto& s : table.scalarNames) out << ',' << csvCell(table.value(row, s));
    out << ',' << csvTextCell(row.error) << "\r\n";
  }
  return out.str();
}

}  // namespace rupture::server
