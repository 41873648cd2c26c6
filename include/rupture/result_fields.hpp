#pragma once
// What a scenario's results mean: every summary scalar (/summary attributes, the server's summary
// table) and every time series (/series datasets) is declared once, with its SI unit, a human
// label and a description. The HDF5 writers, the server's JSON/CSV/plots and the CLI read these
// declarations; nothing else keeps a table of units.
//
// Unit convention (one for the whole project): SI symbols as plain ASCII text, "1" for a
// dimensionless number (ratios, fractions, counts), products with a space ("N s"), quotients with
// "/" ("m/s", "1/s"), powers with "^" ("m^2"); "" only for text values (e.g. stop_reason).
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace rupture {

struct ResultField {
  std::string name;         ///< key in /summary or dataset name in /series, e.g. "peak_stress"
  std::string unit;         ///< SI unit (see the convention above), "1" dimensionless, "" text
  std::string label;        ///< short human label for axes and tables, e.g. "Peak stress"
  std::string description;  ///< one sentence: what it is and how it is measured
  /// Unit in a 2-D run (spec "dimension": 2), where extensive quantities are per metre of depth
  /// ("J/m"); empty when the same as `unit`. A name ending in '*' declares a family of datasets
  /// ("probe_pressure_*": probe_pressure_0, probe_pressure_1, ...).
  std::string unit2d = {};

  /// The unit in a run of the given dimension (2 or 3).
  const std::string& unitFor(int dimension) const { return dimension == 2 && !unit2d.empty() ? unit2d : unit; }
  /// A yes/no stored as 1/0 (dimensionless, described "1 when ..." or "1 if ..."): people read
  /// it as yes/no (formatFlag), machines as 1/0.
  bool isFlag() const { return describesFlag(unit, description); }
  static bool describesFlag(const std::string& unit, const std::string& description) {
    return unit == "1" && (description.rfind("1 when ", 0) == 0 || description.rfind("1 if ", 0) == 0);
  }
};

using ResultFields = std::vector<ResultField>;

/// The field named `name` (a '*'-ended declaration matches by prefix), or nullptr.
const ResultField* findResultField(const ResultFields& fields, const std::string& name);

/// name -> unit of every non-family field, for a run of the given dimension (the form
/// io::ResultFile::writeAttributes takes).
std::map<std::string, std::string> unitMap(const ResultFields& fields, int dimension = 3);

/// unitMap of the fields a declaration function returns (3-D), built once: a scenario's summary units.
template <const ResultFields& (*declared)()>
const std::map<std::string, std::string>& declaredUnits() {
  static const std::map<std::string, std::string> units = unitMap(declared());
  return units;
}

/// The spatial dimension of a spec: its "dimension" key, else the schema's default for it, else 3.
int specDimension(const nlohmann::json& schema, const nlohmann::json& spec);

/// A spec field's unit from the scenario's JSON Schema keyword "x-unit" at a dotted path
/// ("loading.strain_rate" -> "1/s"); "" when the schema gives none (text, or an unknown path).
std::string specFieldUnit(const nlohmann::json& schema, const std::string& dottedPath);

/// A spec field's human label: the schema's "title" at that path, else the last path segment
/// with underscores as spaces and a capital first letter ("strain_rate" -> "Strain rate").
std::string specFieldLabel(const nlohmann::json& schema, const std::string& dottedPath);

/// "peak_stress [Pa]"; a text column (unit "") keeps its bare name. The CSV header convention.
std::string nameWithUnit(const std::string& name, const std::string& unit);

}  // namespace rupture
