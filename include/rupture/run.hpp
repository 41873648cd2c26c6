#pragma once
// The single entry every door uses: the CLI (`rupture run`) and the job server parse a spec once
// (parseSpec) and call runSpec with it, a result path, and a RunControl through which they watch
// and cancel.
#include <atomic>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "rupture/result_fields.hpp"
#include "rupture/run_status.hpp"
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

  // Checkpoints (docs/checkpoints.md). Set by the door before the run:
  /// Continue from the result's checkpoint (RESULT.checkpoint); runSpec throws CheckpointError
  /// (include/rupture/state_archive.hpp) when it is missing or belongs to another spec or version.
  bool resume = false;
  /// With cancel: write a checkpoint before stopping (SIGTERM, a server shutting down, a Slurm
  /// time limit's warning), so a resume loses nothing. Without it a cancel writes none.
  std::atomic<bool> checkpointOnCancel{false};
  /// Wall time between checkpoints (s): < 0 takes the spec's run.checkpoint_interval_s, 0 writes none.
  double checkpointInterval = -1;
  /// For tests and tools: write a checkpoint and stop, as cancelled, once this many steps are done
  /// (< 0: never).
  std::int64_t stopAtStep = -1;
  /// Written by the run: the step it continued from (−1: it started at step 0), the step of its
  /// last checkpoint (−1: none), and that checkpoint's size (B) and write time (s).
  std::atomic<std::int64_t> resumedFromStep{-1};
  std::atomic<std::int64_t> checkpointStep{-1};
  std::atomic<double> checkpointBytes{0}, checkpointSeconds{0};
  /// Written by the run: checkpoints it could not write (a full disk) and went on without.
  std::atomic<int> checkpointsSkipped{0};
  int threads = 1;  ///< set by runSpec: the OpenMP threads of the run (a checkpoint records them)
  /// Written by the run: where it is now (step, time, strain, headline quantity, broken bonds),
  /// for the watcher's periodic status line.
  RunStatusBoard status;
  /// Written by the run: its wall time by phase, for the timing breakdown at its end.
  RunPhases phases;
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
  int ranks = 1;           ///< MPI ranks the spec asks for (run.ranks); memoryBytes is their sum

  // Length (for --max-run-steps): the run's end (end strain over strain rate, or end time) over
  // its stable time step, both estimated from the spec by the scenario's own step rule, capped by
  // the spec's run.max_steps. An estimate, not a count: within a few times of the steps taken.
  double steps = 0;          ///< time steps the run will take at most (0: the scenario gives no estimate)
  double timeStep = 0;       ///< the estimated stable step (s) the count divides by
  std::string stepsField;    ///< the spec field that sets the run's length, e.g. "loading.strain_rate"
  std::string timeStepField; ///< the spec field that sets the time step, e.g. "material.density"
  std::string stepsBasis;    ///< how the count was reached (end, step rule), for the error that quotes it
};

/// The default of --max-run-steps (rupture-server, rupture validate and rupture run): well above
/// every example and validation case (docs/server.md lists their estimates), well below a run that
/// would hold a worker for days.
inline constexpr double kDefaultMaxRunSteps = 1e8;

/// The most MPI ranks a spec may ask for (run.ranks): a bound on input, not on a machine; servers
/// refuse what their own site allows less of (docs/distributed.md).
inline constexpr int kMaxRanks = 4096;

/// `rupture run`'s exit code when a run stopped before its end (Ctrl-C, SIGTERM, --stop-at-step),
/// after writing its checkpoint: 128 + SIGINT, the shell's convention. The executors read it.
inline constexpr int kExitInterrupted = 130;

struct Scenario;

/// A spec parsed and validated once: its scenario, unknown keys rejected, every value checked and
/// held as the scenario's typed value, which the estimate and the run then read. Cheap to copy.
class ParsedSpec {
public:
  const nlohmann::json& json() const { return *m_json; }
  const std::string& scenarioName() const;
  /// What the run will need; 0 particles for a scenario that gives no estimate.
  RunEstimate estimate() const;

private:
  friend ParsedSpec parseSpec(const nlohmann::json& spec);
  friend RunOutcome runSpec(const ParsedSpec& spec, const std::string& resultPath, RunControl& control, int threads);
  friend struct SpecInternals;  // the sample preview's door to the scenario (rupture/sample_preview.hpp)
  const Scenario* m_scenario = nullptr;
  std::shared_ptr<const nlohmann::json> m_json;
  std::shared_ptr<const void> m_value;  ///< the scenario's typed spec (DynamicTensionSpec, ...)
};

/// Parses a whole spec (with its "scenario" key). Throws SpecError naming the first offending
/// field; unknown fields are reported first, with the nearest allowed key.
ParsedSpec parseSpec(const nlohmann::json& spec);

/// Runs the parsed spec and writes one HDF5 file at resultPath (written as resultPath + ".part"
/// and renamed when closed, so a reader never sees a half-written file). A cancelled run
/// (RunControl::cancel) returns completed = false with its file marked incomplete; a run cancelled
/// while its sample was being built holds only /spec and /summary. Throws std::runtime_error for a
/// failure during the run. `threads` = OpenMP threads for this run (>= 1).
RunOutcome runSpec(const ParsedSpec& spec, const std::string& resultPath, RunControl& control, int threads = 1);

/// parseSpec(spec).estimate(): throws SpecError for an invalid spec.
RunEstimate estimateRun(const nlohmann::json& spec);

/// Throws SpecError naming estimate.stepsField (the value as `spec` holds it, the estimate and
/// its basis in what is allowed) when the run would take more than maxSteps time steps.
void checkRunSteps(const nlohmann::json& spec, const RunEstimate& estimate, double maxSteps);

/// parseSpec without keeping the result: throws SpecError naming the first offending field.
void validateSpec(const nlohmann::json& spec);

/// runSpec(parseSpec(spec), ...): throws SpecError for an invalid spec.
RunOutcome runSpec(const nlohmann::json& spec, const std::string& resultPath, RunControl& control,
                   int threads = 1);

}  // namespace rupture
