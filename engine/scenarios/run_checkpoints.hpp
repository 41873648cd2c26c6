#pragma once
// A run's checkpoints, as every scenario's loop takes them (docs/checkpoints.md): the loop names its
// state once (a function over a StateArchive), asks poll() at the top of every step, and restores
// from the checkpoint when the door asked to resume. Written every run.checkpoint_interval_s of
// wall time, when the run is stopped to be continued (SIGTERM, a server shutting down, a Slurm
// time limit) and at RunControl::stopAtStep; removed once the run completes, unless the result is
// the caller's own ".part" (io::ResultFile): that caller removes it once it has committed the
// result (renamed it and its summary into place), so a kill between the engine's end and that
// commit still finds the checkpoint and loses at most one interval (docs/checkpoints.md).
//
// On several ranks (docs/distributed.md) each rank keeps its own checkpoint, of its own copy of the
// result and its own state (io::rankCheckpointPath), and every decision is taken by all of them at
// once: poll() is collective every 16th step, and a rank's wish to checkpoint or to stop is every
// rank's.
#include <chrono>
#include <cstdint>
#include <functional>
#include <string>

#include <nlohmann/json.hpp>

#include "distributed/communicator.hpp"
#include "io/result_file.hpp"
#include "rupture/run.hpp"
#include "rupture/state_archive.hpp"

namespace rupture {

class RunCheckpoints {
public:
  using Clock = std::chrono::steady_clock;
  using State = std::function<void(StateArchive&)>;

  /// specInterval: the spec's run.checkpoint_interval_s (RunControl::checkpointInterval, when set,
  /// wins). wallStart: the run's start, moved back on restore by the earlier attempts' wall time.
  RunCheckpoints(RunControl& control, const std::string& resultPath, std::string scenario,
                 const nlohmann::json& inputSpec, double specInterval, Clock::time_point& wallStart);

  bool resuming() const { return m_control.resume; }
  /// The checkpoint the result file continues from (ResultFile's continueFrom), "" for a new run.
  /// On several ranks, the first rank's (only the first writes the result).
  std::string continueFrom() const { return resuming() ? m_firstRankPath : std::string(); }

  /// The result file and the function naming the run's state; call before restore() and poll().
  void attach(io::ResultFile& result, State state);
  /// Loads the state from the checkpoint (the set-up has rebuilt everything it does not hold) and
  /// records the resume on the file and on RunControl::resumedFromStep. With `partsFollow`, a part
  /// of the state is loaded later (restorePart; elastic-properties' test under way, set up once its
  /// fit asks for it) or none (endRestore).
  void restore(bool partsFollow = false);
  /// Loads `part` (named as when saved) from the checkpoint being resumed, and ends the restore.
  void restorePart(const State& part);
  /// Ends a restore begun with partsFollow.
  void endRestore();

  enum class Action { Continue, Stop };
  /// At the top of every step (collective on several ranks at every 16th step, when their wishes are
  /// agreed; a cancel waits for it): Stop when cancelled (after a checkpoint when RunControl asks for
  /// one and the interval is not 0) or at RunControl::stopAtStep (after a checkpoint); a checkpoint
  /// when the interval is up. A checkpoint that cannot be written is logged, not thrown.
  Action poll(std::uint64_t step, double time);
  /// Writes a checkpoint now (throws what the file system throws).
  void write(std::uint64_t step, double time);
  /// The run is over: a completed run's checkpoint is removed (a stopped one is kept to resume),
  /// unless the caller commits the result (a ".part" result path): then the caller removes it.
  void finished(bool completed);

private:
  bool tryWrite(std::uint64_t step, double time);
  /// Free bytes the next checkpoint needs beside the run's files (its copy of the partial result
  /// and its state), or 0 when the partial result's size cannot be told.
  std::uintmax_t bytesForNextCheckpoint() const;

  RunControl& m_control;
  Communicator m_comm = Communicator::world();
  std::string m_path, m_firstRankPath, m_partialPath, m_scenario;
  bool m_callerCommits;
  nlohmann::json m_specIdentity;
  double m_interval;
  Clock::time_point& m_wallStart;
  Clock::time_point m_last;
  io::ResultFile* m_result = nullptr;
  State m_state;
  std::int64_t m_resumes = 0;
  bool m_partsFollow = false;
  std::uintmax_t m_lastBytes = 0;  ///< size of the last checkpoint written or resumed from
  std::int64_t m_lastGoodStep = -1;  ///< its step (−1: none)
};

}  // namespace rupture
