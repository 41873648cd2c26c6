// The embedded validation cases: validation/<case>/case.json read into ValidationCase, the example
// specs they start from resolved, and the specs of a level made from them.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>

#include "validation/validation_case.hpp"

namespace rupture::validation {

namespace {

using Json = nlohmann::json;

/// The embedded files: "validation/<case>/case.json" and "examples/<name>.json" -> text.
const std::map<std::string, std::string>& embeddedFiles() {
  static const std::map<std::string, std::string> files = [] {
    struct Entry { const char* path; const char* text; };
    static const Entry entries[] = {
#include "rupture_validation_files.inc"
        {"", ""}};
    std::map<std::string, std::string> out;
    for (const Entry& e : entries)
      if (*e.path) out.emplace(e.path, e.text);
    return out;
  }();
  return files;
}

Json::json_pointer pointerOf(const std::string& dottedPath) {
  std::string pointer = "/" + dottedPath;
  std::replace(pointer.begin(), pointer.end(), '.', '/');
  return Json::json_pointer(pointer);
}

/// Reads one case file, every error naming the file and the field.
class CaseReader {
public:
  explicit CaseReader(std::string id) : m_file("validation/" + std::move(id) + "/case.json") {}

  [[noreturn]] void fail(const std::string& field, const std::string& what) const {
    throw std::runtime_error(m_file + ": " + field + ": " + what);
  }
  const Json& at(const Json& object, const std::string& key, const std::string& field) const {
    auto it = object.find(key);
    if (it == object.end()) fail(field + key, "missing (required)");
    return *it;
  }
  std::string text(const Json& object, const std::string& key, const std::string& field, bool required = true) const {
    auto it = object.find(key);
    if (it == object.end()) {
      if (required) fail(field + key, "missing (required)");
      return {};
    }
    if (!it->is_string()) fail(field + key, "must be text");
    return it->get<std::string>();
  }
  double number(const Json& value, const std::string& field) const {
    if (!value.is_number() || !std::isfinite(value.get<double>())) fail(field, "must be a finite number");
    return value.get<double>();
  }
  double number(const Json& object, const std::string& key, const std::string& field, double fallback) const {
    auto it = object.find(key);
    return it == object.end() ? fallback : number(*it, field + key);
  }
  bool inQuick(const Json& object, const std::string& field) const {
    auto it = object.find("levels");
    if (it == object.end()) return true;
    if (!it->is_array() || it->empty()) fail(field + "levels", "must be a non-empty list of \"quick\", \"full\"");
    bool quick = false, full = false;
    for (const Json& l : *it) {
      if (!l.is_string() || !isLevel(l.get<std::string>()))
        fail(field + "levels", "must list \"quick\" and/or \"full\"");
      (l == "quick" ? quick : full) = true;
    }
    if (!full) fail(field + "levels", "must include \"full\" (the quick level stands in for the full one, never alone)");
    return quick;
  }
  Json changed(Json spec, const Json& changes, const std::string& field) const {
    if (!changes.is_object()) fail(field, "must be an object of dotted spec paths and values");
    for (const auto& [path, value] : changes.items()) spec[pointerOf(path)] = value;
    return spec;
  }
  ValueSource source(const Json& s, const std::string& field) const {
    if (!s.is_object()) fail(field, "must be an object with \"run\" and \"summary\" or \"series_x\"/\"series_y\"");
    ValueSource out;
    out.run = text(s, "run", field + ".");
    out.summary = text(s, "summary", field + ".", false);
    out.seriesX = text(s, "series_x", field + ".", false);
    out.seriesY = text(s, "series_y", field + ".", false);
    if (out.summary.empty() == (out.seriesX.empty() || out.seriesY.empty()))
      fail(field, "needs either \"summary\" or both \"series_x\" and \"series_y\"");
    out.factor = number(s, "factor", field + ".", 1.0);
    out.xFactor = number(s, "x_factor", field + ".", 1.0);
    if (s.contains("per")) {
      const Json& per = s["per"];
      if (out.summary.empty() || !per.is_object()) fail(field + ".per", "must be {\"run\", \"summary\"} on a summary source");
      out.per = std::pair{text(per, "run", field + ".per."), text(per, "summary", field + ".per.")};
    }
    if (s.contains("max_over")) {
      const Json& w = s["max_over"];
      if (out.seriesX.empty() || !w.is_array() || w.size() != 2)
        fail(field + ".max_over", "must be [x_from, x_to] on a series source");
      out.maxOver = std::pair{number(w[0], field + ".max_over[0]"), number(w[1], field + ".max_over[1]")};
    }
    if (s.contains("first_reaching")) {
      if (out.seriesX.empty() || out.maxOver)
        fail(field + ".first_reaching", "must be a level of y on a series source without max_over");
      out.firstReaching = number(s["first_reaching"], field + ".first_reaching");
    }
    return out;
  }
  const std::string& file() const { return m_file; }

private:
  std::string m_file;
};

std::vector<Json> values(const CaseReader& r, const Json& v, const std::string& field) {
  if (!v.is_array() || v.empty()) r.fail(field, "must be a non-empty list of values");
  return v.get<std::vector<Json>>();
}

CaseRun parseRun(const CaseReader& r, const Json& j, const std::string& field) {
  if (!j.is_object()) r.fail(field, "must be an object");
  CaseRun run;
  run.name = r.text(j, "name", field + ".");
  const std::string example = "examples/" + r.text(j, "example", field + ".");
  auto it = embeddedFiles().find(example);
  if (it == embeddedFiles().end()) r.fail(field + ".example", "no file " + example + " in this build");
  Json spec = Json::parse(it->second);
  spec.erase("description");
  if (j.contains("remove")) {
    const Json& remove = j["remove"];
    if (!remove.is_array()) r.fail(field + ".remove", "must be a list of dotted spec paths");
    for (const Json& path : remove) {
      if (!path.is_string()) r.fail(field + ".remove", "must be a list of dotted spec paths");
      const Json::json_pointer pointer = pointerOf(path.get<std::string>());
      if (!spec.contains(pointer)) r.fail(field + ".remove", "\"" + path.get<std::string>() + "\" is not in " + example);
      spec[pointer.parent_pointer()].erase(pointer.back());
    }
  }
  if (j.contains("changes")) spec = r.changed(std::move(spec), j["changes"], field + ".changes");
  run.spec = std::move(spec);
  run.quickChanges = j.contains("quick_changes") ? j["quick_changes"] : Json::object();
  r.changed(run.spec, run.quickChanges, field + ".quick_changes");  // checked once here
  if (j.contains("vary")) {
    const Json& v = j["vary"];
    run.varyPath = r.text(v, "path", field + ".vary.");
    run.varyValues = values(r, r.at(v, "values", field + ".vary."), field + ".vary.values");
    run.quickVaryValues = v.contains("quick_values") ? values(r, v["quick_values"], field + ".vary.quick_values")
                                                     : run.varyValues;
  }
  run.inQuick = r.inQuick(j, field + ".");
  return run;
}

Reference parseReference(const CaseReader& r, const Json& j, const std::string& field) {
  if (!j.is_object()) r.fail(field, "must be an object with \"value\", \"range\", or \"run\" and \"summary\"");
  Reference ref;
  ref.uncertainty = r.number(j, "uncertainty", field + ".", 0.0);
  int forms = 0;
  if (j.contains("value")) ++forms, ref.value = r.number(j["value"], field + ".value");
  if (j.contains("range")) {
    ++forms;
    const Json& range = j["range"];
    if (!range.is_array() || range.size() != 2 || (range[0].is_null() && range[1].is_null()))
      r.fail(field + ".range", "must be [low, high] (one end may be null: open)");
    if (!range[0].is_null()) ref.low = r.number(range[0], field + ".range[0]");
    if (!range[1].is_null()) ref.high = r.number(range[1], field + ".range[1]");
    if (ref.low && ref.high && *ref.low > *ref.high) r.fail(field + ".range", "low must not exceed high");
  }
  if (j.contains("run")) ++forms, ref.fromRun = r.source(j, field);
  if (forms != 1) r.fail(field, "needs exactly one of \"value\", \"range\", \"run\" (+ \"summary\"), \"points\"");
  return ref;
}

void parseQuantity(const CaseReader& r, const Json& j, const std::string& field, std::vector<Quantity>& out) {
  if (!j.is_object()) r.fail(field, "must be an object");
  Quantity q;
  q.name = r.text(j, "name", field + ".");
  q.label = r.text(j, "label", field + ".");
  q.unit = r.text(j, "unit", field + ".");
  q.ours = r.source(r.at(j, "ours", field + "."), field + ".ours");
  const Json& tol = r.at(j, "tolerance", field + ".");
  q.tolerance.relative = r.number(tol, "relative", field + ".tolerance.", 0.0);
  q.tolerance.absolute = r.number(tol, "absolute", field + ".tolerance.", 0.0);
  if (q.tolerance.relative < 0 || q.tolerance.absolute < 0) r.fail(field + ".tolerance", "must not be negative");
  q.knownFailure = r.text(j, "known_failure", field + ".", false);
  q.inQuick = r.inQuick(j, field + ".");
  const Json& ref = r.at(j, "reference", field + ".");
  if (ref.is_object() && ref.contains("points")) {
    // A published curve: one quantity per point, ours read from the series at the point's x.
    if (q.ours.seriesX.empty() || q.ours.maxOver || q.ours.firstReaching)
      r.fail(field + ".ours",
             "a reference with points needs a series read at each point's x (series_x, series_y, no max_over nor first_reaching)");
    const Json& points = ref["points"];
    if (!points.is_array() || points.empty()) r.fail(field + ".reference.points", "must be a list of [x, y, uncertainty]");
    for (std::size_t k = 0; k < points.size(); ++k) {
      const std::string pf = field + ".reference.points[" + std::to_string(k) + "]";
      if (!points[k].is_array() || points[k].size() != 3) r.fail(pf, "must be [x, y, uncertainty]");
      Quantity p = q;
      p.at = r.number(points[k][0], pf + "[0]");
      p.reference.value = r.number(points[k][1], pf + "[1]");
      p.reference.uncertainty = r.number(points[k][2], pf + "[2]");
      char buffer[32];
      std::snprintf(buffer, sizeof buffer, "%g", *p.at);
      p.name = q.name + "@" + buffer;
      p.label = q.label + " at " + buffer;
      out.push_back(std::move(p));
    }
    return;
  }
  if (!q.ours.seriesX.empty() && !q.ours.maxOver && !q.ours.firstReaching) {
    if (!j.contains("at")) r.fail(field + ".at", "missing: a series quantity is read at an x");
    q.at = r.number(j["at"], field + ".at");
  }
  q.reference = parseReference(r, ref, field + ".reference");
  out.push_back(std::move(q));
}

CaseFigure parseFigure(const CaseReader& r, const Json& j, const std::vector<Quantity>& quantities) {
  if (!j.is_object()) r.fail("figure", "must be an object");
  CaseFigure f;
  f.run = r.text(j, "run", "figure.");
  f.x = r.text(j, "x", "figure.");
  f.y = r.text(j, "y", "figure.");
  f.xFactor = r.number(j, "x_factor", "figure.", 1.0);
  f.yFactor = r.number(j, "y_factor", "figure.", 1.0);
  f.xLabel = r.text(j, "x_label", "figure.");
  f.yLabel = r.text(j, "y_label", "figure.");
  f.pointsLabel = r.text(j, "points_label", "figure.", false);
  if (j.contains("points_from")) {
    const std::string prefix = r.text(j, "points_from", "figure.") + "@";
    for (const Quantity& q : quantities)
      if (q.name.rfind(prefix, 0) == 0) f.points.push_back({*q.at, *q.reference.value, q.reference.uncertainty});
    if (f.points.empty()) r.fail("figure.points_from", "names no quantity with reference points");
  }
  for (const auto& [key, names] : {std::pair{"lines", &f.lineQuantities}, std::pair{"vertical_lines", &f.verticalLineQuantities}}) {
    if (!j.contains(key)) continue;
    for (const Json& l : j[key]) {
      if (!l.is_string() || std::none_of(quantities.begin(), quantities.end(),
                                         [&](const Quantity& q) { return q.name == l.get<std::string>(); }))
        r.fail(std::string("figure.") + key, "must name quantities of this case");
      names->push_back(l.get<std::string>());
    }
  }
  return f;
}

}  // namespace

bool isLevel(const std::string& level) { return level == "quick" || level == "full"; }

ValidationCase parseValidationCase(const std::string& id, const Json& j) {
  const CaseReader r(id);
  if (!j.is_object()) r.fail("(root)", "must be an object");
  ValidationCase c;
  c.id = id;
  c.title = r.text(j, "title", "");
  c.paper = r.text(j, "paper", "");
  c.citation = r.text(j, "citation", "");
  c.howRead = r.text(j, "how_read", "");
  c.comparison = r.text(j, "comparison", "");
  c.inQuick = r.inQuick(j, "");
  c.quickNote = r.text(j, "quick_note", "");
  const Json& runs = r.at(j, "runs", "");
  if (!runs.is_array() || runs.empty()) r.fail("runs", "must be a non-empty list");
  for (std::size_t k = 0; k < runs.size(); ++k) c.runs.push_back(parseRun(r, runs[k], "runs[" + std::to_string(k) + "]"));
  const Json& quantities = r.at(j, "quantities", "");
  if (!quantities.is_array() || quantities.empty()) r.fail("quantities", "must be a non-empty list");
  for (std::size_t k = 0; k < quantities.size(); ++k)
    parseQuantity(r, quantities[k], "quantities[" + std::to_string(k) + "]", c.quantities);
  auto runNamed = [&](const std::string& name) {
    return std::find_if(c.runs.begin(), c.runs.end(), [&](const CaseRun& run) { return run.name == name; });
  };
  for (const Quantity& q : c.quantities) {
    for (const ValueSource* s : {&q.ours, q.reference.fromRun ? &*q.reference.fromRun : nullptr}) {
      if (!s) continue;
      for (const std::string& name : {s->run, s->per ? s->per->first : s->run}) {
        auto run = runNamed(name);
        if (run == c.runs.end()) r.fail("quantities (" + q.name + ")", "reads run \"" + name + "\", which the case does not list");
        if (q.inQuick && !run->inQuick)
          r.fail("quantities (" + q.name + ")", "is in the quick level but reads run \"" + name + "\", which is not");
      }
    }
  }
  if (j.contains("figure")) {
    c.figure = parseFigure(r, j["figure"], c.quantities);
    if (runNamed(c.figure->run) == c.runs.end()) r.fail("figure.run", "names no run of this case");
  }
  return c;
}

const std::vector<ValidationCase>& validationCases() {
  static const std::vector<ValidationCase> cases = [] {
    std::vector<ValidationCase> out;
    const std::string prefix = "validation/", suffix = "/case.json";
    for (const auto& [path, text] : embeddedFiles()) {
      if (path.rfind(prefix, 0) != 0) continue;
      const std::string id = path.substr(prefix.size(), path.size() - prefix.size() - suffix.size());
      out.push_back(parseValidationCase(id, Json::parse(text)));
    }
    return out;
  }();
  return cases;
}

const ValidationCase* findValidationCase(const std::string& id) {
  for (const ValidationCase& c : validationCases())
    if (c.id == id) return &c;
  return nullptr;
}

std::vector<std::pair<std::string, std::vector<Json>>> caseSpecs(const ValidationCase& c, const std::string& level) {
  const bool quick = level == "quick";
  std::vector<std::pair<std::string, std::vector<Json>>> out;
  for (const CaseRun& run : c.runs) {
    if (quick && !run.inQuick) continue;
    Json base = run.spec;
    if (quick)
      for (const auto& [path, value] : run.quickChanges.items()) base[pointerOf(path)] = value;
    std::vector<Json> members;
    if (run.varyPath.empty()) {
      members.push_back(base);
    } else {
      for (const Json& v : quick ? run.quickVaryValues : run.varyValues) {
        Json member = base;
        member[pointerOf(run.varyPath)] = v;
        members.push_back(std::move(member));
      }
    }
    out.emplace_back(run.name, std::move(members));
  }
  return out;
}

}  // namespace rupture::validation
