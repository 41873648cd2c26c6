#pragma once
// The single entry every door uses: the CLI (`rupture run`) and the job server call runSpec with
// a validated spec, a result path, and a RunControl through which they watch and cancel.
#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "rupture/result_fields.hpp"
#include "rupture/spec_error.hpp"

namespace rupture {

/// Shared between a running simulation and its watcher (progress bar, server worker).
struct RunControl {
  /// Set by the watcher; the run checks it at least every 0.2 s of wall time and stops cleanly.
  std::atomic<bool> cancel{false};
  /// Written by the run: fraction done in [0, 1] (estimated from strain / time towards the stop rule).
  std::atomic<double> progress{0.0};
  /// Optional human-readable stage messages ("preliminary VH run", "main run").
  std::function<void(const std::string&)> log;
  /// Where reusable intermediate results (the VH preliminary run) are cached; empty: the
  /// environment's choice ($RUPTURE_CACHE_DIR, $XDG_CACHE_HOME/rupture, ~/.cache/rupture).
  std::string cacheDirectory;
};

/// What a run returns once its HDF5 file is closed.
struct RunOutcome {
  nlohmann::json summary;  ///< scalar results, SI units; the same values as the file's /summary attributes
  bool completed = true;   ///< false when cancelled: the file is kept and marked incomplete
};

struct ScenarioInfo {
  std::string name;         ///< registry key, e.g. "dynamic-tension"
  std::string title;        ///< one line
  std::string description;  ///< a paragraph: what it models, what it outputs
  ResultFields summary;     ///< every scalar a run may write to /summary (and RunOutcome::summary)
  ResultFields series;      ///< every dataset a run may write to /series (one row per output)
};

/// The registered scenario's info, or nullptr for an unknown name.
const ScenarioInfo* findScenario(const std::string& name);

/// The registered scenarios, in registry order.
std::vector<ScenarioInfo> listScenarios();

/// The JSON Schema (draft 2020-12) of a scenario's spec, as kept in api/schemas/<name>.schema.json.
/// Throws SpecError(field "scenario") for an unknown name.
nlohmann::json scenarioSchema(const std::string& name);

/// What a run will need, estimated from its spec before anything is built (for operator limits
/// such as rupture-server's --max-elements, and for the error that names them).
struct RunEstimate {
  double particles = 0;    ///< elements or particles the run will hold (0: the scenario gives no estimate)
  double memoryBytes = 0;  ///< peak resident memory (B), from measured bytes per particle
  std::string field;       ///< the spec field that sets the size, e.g. "sample.element_radius"
  std::string basis;       ///< what the memory estimate counts, for the error that quotes it
};

/// The estimate for a valid spec; throws SpecError like validateSpec for an invalid one.
RunEstimate estimateRun(const nlohmann::json& spec);

/// Checks a whole spec (with its "scenario" key) without running it. Throws SpecError naming the
/// first offending field; unknown fields are errors too.
void validateSpec(const nlohmann::json& spec);

/// Runs the spec and writes one HDF5 file at resultPath (written as resultPath + ".part" and renamed
/// when closed, so a reader never sees a half-written file). A cancelled run (RunControl::cancel)
/// returns completed = false with its file marked incomplete; a run cancelled while its sample was
/// being built holds only /spec and /summary. Throws SpecError for an invalid spec,
/// std::runtime_error for a failure during the run. `threads` = OpenMP threads for this run (>= 1).
RunOutcome runSpec(const nlohmann::json& spec, const std::string& resultPath, RunControl& control,
                   int threads = 1);

}  // namespace rupture
