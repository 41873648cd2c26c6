#include "jobs/sweep.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <charconv>
#include <limits>

#include "common/files.hpp"
#include "jobs/job_store.hpp"
#include "rupture/run.hpp"

namespace rupture::server {
namespace {

ApiError sweepError(const std::string& path, const std::string& detail) {
  return ApiError(400, problem::kInvalidSweep, "Invalid sweep", detail, path,
                  Json{{"in", "sweep"}});
}

bool arrayIndex(const std::string& segment, std::size_t& index) {
  if (segment.empty()) return false;
  auto [ptr, ec] = std::from_chars(segment.data(), segment.data() + segment.size(), index);
  return ec == std::errc() && ptr == segment.data() + segment.size();
}

/// The child of `node` named by `segment`, or nullptr.
Json* child(Json& node, const std::string& segment) {
  if (node.is_object()) {
    auto it = node.find(segment);
    return it == node.end() ? nullptr : &*it;
  }
  std::size_t index = 0;
  if (node.is_array() && arrayIndex(segment, index) && index < node.size()) return &node[index];
  return nullptr;
}

/// Sets the value at `path`; its parent must exist. Returns "" or what is wrong.
std::string setAtPath(Json& root, const std::vector<std::string>& segments, const Json& value) {
  Json* node = &root;
  std::string walked;
  for (std::size_t i = 0; i + 1 < segments.size(); ++i) {
    walked += (i ? "." : "") + segments[i];
    node = child(*node, segments[i]);
    if (!node) return "'" + walked + "' does not exist in the inputs";
  }
  const std::string& leaf = segments.back();
  if (node->is_object()) {
    (*node)[leaf] = value;
    return "";
  }
  std::size_t index = 0;
  if (node->is_array() && arrayIndex(leaf, index) && index < node->size()) {
    (*node)[index] = value;
    return "";
  }
  return walked.empty() ? "the inputs are not an object"
                        : "'" + walked + "' is not an object (nor an array with index '" + leaf + "')";
}

}  // namespace

const char* toString(SweepMode mode) { return mode == SweepMode::Zip ? "zip" : "grid"; }

std::vector<std::string> splitPath(const std::string& path) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (true) {
    std::size_t dot = path.find('.', start);
    std::string segment = path.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
    if (segment.empty()) return {};
    out.push_back(segment);
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  return out;
}

const Json* findAtPath(const Json& root, const std::string& path) {
  auto segments = splitPath(path);
  if (segments.empty()) return nullptr;
  Json* node = const_cast<Json*>(&root);
  for (const auto& s : segments) {
    node = child(*node, s);
    if (!node) return nullptr;
  }
  return node;
}

SweepPlan parseSweepPlan(const Json* sweep, const Json* mode) {
  SweepPlan plan;
  if (mode && !mode->is_null()) {
    if (!mode->is_string() || (*mode != "grid" && *mode != "zip")) {
      throw ApiError(400, problem::kInvalidRequest, "Invalid request",
                     "sweep_mode must be \"grid\" or \"zip\", got " + mode->dump(), "sweep_mode",
                     Json{{"in", "body"}, {"value", *mode}, {"allowed", Json::array({"grid", "zip"})}});
    }
    plan.mode = *mode == "zip" ? SweepMode::Zip : SweepMode::Grid;
  }
  if (!sweep || sweep->is_null()) return plan;
  if (!sweep->is_object()) {
    throw ApiError(400, problem::kInvalidSweep, "Invalid sweep",
                   "sweep must be an object mapping dotted spec paths to lists of values, e.g. "
                   "{\"loading.strain_rate\": [1e5, 1e6]}",
                   "sweep", Json{{"in", "body"}});
  }
  for (const auto& [path, values] : sweep->items()) {
    if (splitPath(path).empty()) {
      throw sweepError(path, "sweep path '" + path + "' is not a dotted path such as loading.strain_rate");
    }
    if (path == "scenario" || path.rfind("scenario.", 0) == 0) {
      throw sweepError(path, "the scenario comes from the URL and cannot be swept");
    }
    if (!values.is_array() || values.empty()) {
      throw sweepError(path, "sweep path '" + path + "' needs a non-empty list of values");
    }
    for (const SweepAxis& other : plan.axes) {
      const std::string& a = other.path.size() < path.size() ? other.path : path;
      const std::string& b = other.path.size() < path.size() ? path : other.path;
      if (b.rfind(a + ".", 0) == 0) {
        throw sweepError(path, "sweep paths '" + a + "' and '" + b + "' overlap");
      }
    }
    plan.axes.push_back({path, values});
  }
  if (plan.mode == SweepMode::Zip && !plan.axes.empty()) {
    const std::size_t n = plan.axes.front().values.size();
    for (const SweepAxis& axis : plan.axes) {
      if (axis.values.size() != n) {
        throw sweepError(axis.path, "zip sweeps need lists of equal length: '" + plan.axes.front().path +
                                        "' has " + std::to_string(n) + " values, '" + axis.path +
                                        "' has " + std::to_string(axis.values.size()));
      }
    }
  }
  return plan;
}

std::size_t runCount(const SweepPlan& plan) {
  if (plan.axes.empty()) return 1;
  if (plan.mode == SweepMode::Zip) return plan.axes.front().values.size();
  std::size_t n = 1;
  for (const SweepAxis& axis : plan.axes) {
    const std::size_t k = axis.values.size();
    if (n > std::numeric_limits<std::size_t>::max() / k) return std::numeric_limits<std::size_t>::max();
    n *= k;
  }
  return n;
}

void forEachSweepPoint(const std::string& scenario, const Json& inputs, const SweepPlan& plan, std::size_t maxRuns,
                       const std::function<void(SweepPoint&&)>& visit) {
  const std::size_t total = runCount(plan);
  if (total > maxRuns) {
    throw ApiError(400, problem::kTooManyRuns, "Too many runs",
                   "the sweep expands to " +
                       (total == std::numeric_limits<std::size_t>::max() ? std::string("too many")
                                                                         : std::to_string(total)) +
                       " runs; this server accepts at most " + std::to_string(maxRuns) +
                       " per job (--max-runs)",
                   "sweep", Json{{"in", "body"}, {"runs", total}, {"max_runs", maxRuns}});
  }
  const Json base = jobBaseSpec(scenario, inputs);
  // Check every path against the base once, so the error names the path, not a point.
  std::vector<std::vector<std::string>> segments;
  for (const SweepAxis& axis : plan.axes) {
    segments.push_back(splitPath(axis.path));
    Json probe = base;
    std::string err = setAtPath(probe, segments.back(), axis.values.front());
    if (!err.empty()) throw sweepError(axis.path, "sweep path '" + axis.path + "': " + err);
  }

  std::vector<std::size_t> odometer(plan.axes.size(), 0);
  for (std::size_t n = 0; n < total; ++n) {
    SweepPoint point{base, Json::array()};
    for (std::size_t a = 0; a < plan.axes.size(); ++a) {
      const std::size_t i = plan.mode == SweepMode::Zip ? n : odometer[a];
      const Json& value = plan.axes[a].values[i];
      setAtPath(point.spec, segments[a], value);
      point.swept.push_back(value);
    }
    visit(std::move(point));
    // Advance the odometer: the last axis varies fastest.
    for (std::size_t a = plan.axes.size(); a-- > 0;) {
      if (++odometer[a] < plan.axes[a].values.size()) break;
      odometer[a] = 0;
    }
  }
}

std::vector<SweepPoint> expandSweep(const std::string& scenario, const Json& inputs,
                                    const SweepPlan& plan, std::size_t maxRuns) {
  std::vector<SweepPoint> points;
  forEachSweepPoint(scenario, inputs, plan, maxRuns, [&](SweepPoint&& point) { points.push_back(std::move(point)); });
  return points;
}

void validateSweepPoints(const std::vector<SweepPoint>& points, const SweepPlan& plan, double maxElements,
                         double maxMemoryBytes, double maxSteps, int maxRanks, const std::string& ranksWhy) {
  for (std::size_t k = 0; k < points.size(); ++k)
    validateSweepPoint(points[k], k, plan, maxElements, maxMemoryBytes, maxSteps, maxRanks, ranksWhy);
}

rupture::RunEstimate validateSweepPoint(const SweepPoint& point, std::size_t k, const SweepPlan& plan,
                                        double maxElements, double maxMemoryBytes, double maxSteps, int maxRanks,
                                        const std::string& ranksWhy) {
  double memoryEstimate = -1;  // set when the point is refused for memory
  int memoryRanks = 1;         // the ranks that memory is spread over
  double stepsEstimate = -1;   // set when the point is refused for its length
  try {
    const nlohmann::json spec(point.spec);  // one copy at a time
    const rupture::RunEstimate estimate = rupture::estimateRun(spec);  // validates first
    auto valueAt = [&](const std::string& field) {
      std::string pointer = "/" + field;
      std::replace(pointer.begin(), pointer.end(), '.', '/');
      const nlohmann::json::json_pointer at(pointer);
      return spec.contains(at) ? spec.at(at).dump() : std::string("(default)");
    };
    if (estimate.particles > maxElements) {
      std::ostringstream allowed;
      allowed << "a run of at most " << maxElements << " elements (this server's --max-elements); this spec needs about "
              << std::llround(estimate.particles) << " elements and " << std::llround(estimate.memoryBytes / 1048576.0)
              << " MiB of memory";
      throw rupture::SpecError(estimate.field, valueAt(estimate.field), allowed.str());
    }
    if (estimate.ranks > maxRanks)
      throw rupture::SpecError("run.ranks", valueAt("run.ranks"),
                               "at most " + std::to_string(maxRanks) + " on this server (" + ranksWhy + ")");
    // A run of N ranks takes N workers' places, so N workers' memory (the estimate is their sum).
    if (estimate.memoryBytes > maxMemoryBytes * estimate.ranks) {
      std::ostringstream allowed;
      allowed << "a run needing at most " << formatBytes(maxMemoryBytes * estimate.ranks)
              << " of memory (this server's --max-run-memory" << (estimate.ranks > 1 ? " per rank" : "") << "); this spec needs about " << formatBytes(estimate.memoryBytes)
              << " for about " << std::llround(estimate.particles) << " elements (" << estimate.basis
              << "): make " << estimate.field << " larger or the sample smaller";
      memoryEstimate = estimate.memoryBytes;
      memoryRanks = estimate.ranks;
      throw rupture::SpecError(estimate.field, valueAt(estimate.field), allowed.str());
    }
    stepsEstimate = estimate.steps;  // quoted in the problem when checkRunSteps refuses it
    rupture::checkRunSteps(spec, estimate, maxSteps);
    return estimate;
  } catch (const rupture::SpecError& e) {
    Json extra = Json::object();
    extra["in"] = "inputs";
    extra["value"] = e.value();
    extra["allowed"] = e.allowed();
    if (memoryEstimate >= 0) {
      extra["estimated_memory_bytes"] = std::llround(memoryEstimate);
      extra["max_run_memory_bytes"] = std::llround(maxMemoryBytes * std::max(1, memoryRanks));
    }
    if (stepsEstimate != -1) {  // NaN too: a step count that is not a number
      extra["estimated_steps"] = std::isfinite(stepsEstimate) ? Json(stepsEstimate) : Json(nullptr);
      extra["max_run_steps"] = maxSteps;
    }
    std::string where;
    if (!plan.axes.empty()) {
      Json swept = Json::object();
      for (std::size_t a = 0; a < plan.axes.size(); ++a) {
        swept[plan.axes[a].path] = point.swept[a];
        const std::string& path = plan.axes[a].path;
        if (e.field() == path || e.field().rfind(path + ".", 0) == 0 ||
            e.field().rfind(path + "[", 0) == 0) {
          extra["in"] = "sweep";
        }
      }
      extra["sweep_point"] = k;
      extra["swept"] = swept;
      where = " (sweep point " + std::to_string(k) + ": " + swept.dump() + ")";
    }
    throw ApiError(400, problem::kInvalidSpec, "Invalid spec", std::string(e.what()) + where,
                   e.field(), extra);
  } catch (const std::exception& e) {
    // The validator choked on an input it did not expect: still the client's input, still a 400.
    Json extra = Json::object();
    extra["in"] = "inputs";
    if (!plan.axes.empty()) extra["sweep_point"] = k;
    throw ApiError(400, problem::kInvalidSpec, "Invalid spec",
                   std::string("the spec could not be validated: ") + e.what(), "", extra);
  }
}

}  // namespace rupture::server
