#pragma once
// A run's checkpoint file (docs/checkpoints.md): RESULT.checkpoint beside the result, one HDF5 file
// that is the partial result as it stood (series rows are state, snapshots are in the copy) plus
//   /checkpoint          attributes format, rupture_version, scenario, spec (the input spec's JSON
//                        without run.checkpoint_interval_s), step, time, threads, resumes,
//                        wall_time_s, written (UTC)
//   /checkpoint/state    the run's state, as its parts list it (Hdf5StateArchive)
// It is written beside its final name and renamed onto it, so a kill at any moment leaves the
// previous checkpoint or the new one, never half of one.
#include <cstdint>
#include <functional>
#include <string>

#include <nlohmann/json.hpp>

#include "io/result_file.hpp"
#include "rupture/state_archive.hpp"

namespace rupture::io {

/// RESULT's checkpoint: RESULT (a trailing ".part" dropped) + ".checkpoint".
std::string checkpointPathFor(const std::string& resultPath);

/// The checkpoint format; a file of another format is refused.
inline constexpr std::int64_t kCheckpointFormat = 2;  // 2: bonds carry a fractional integrity

/// What a checkpoint says about the run it belongs to.
struct CheckpointHeader {
  std::string scenario;
  std::string version;       ///< RUPTURE_VERSION of the build that wrote it
  nlohmann::json spec;       ///< the input spec, run.checkpoint_interval_s removed (checkpointSpecIdentity)
  std::int64_t step = 0;     ///< steps done
  double time = 0;           ///< simulated time (s)
  std::int64_t threads = 1;  ///< OpenMP threads of the run that wrote it
  std::int64_t ranks = 1;    ///< MPI ranks of the run that wrote it: each wrote its own (rankCheckpointPath)
  std::int64_t resumes = 0;  ///< how many times the run had been resumed when it wrote it
  double wallTime = 0;       ///< wall time of the run so far, every attempt (s)
  std::string written;       ///< UTC, ISO 8601
};

/// Where rank `rank` of a decomposed run keeps its checkpoint beside the first rank's `checkpoint`
/// (checkpointPathFor): each rank saves its own sub-domain and its own copy of the result.
std::string rankCheckpointPath(const std::string& checkpoint, int rank);

/// The part of a spec that must match for a checkpoint to continue a run: all of it but
/// run.checkpoint_interval_s and run.ranks (how often to checkpoint, and on how many processes the
/// run steps, never change the result).
nlohmann::json checkpointSpecIdentity(const nlohmann::json& spec);

/// Writes the checkpoint at `path`: the partial result made whole on disk and copied, the header
/// and the state that `save` lists added to the copy, the copy renamed onto `path`. Returns the
/// checkpoint's size (B). The partial result stays open for writing.
std::uintmax_t writeCheckpoint(ResultFile& partial, const std::string& path, const CheckpointHeader& header,
                               const std::function<void(StateArchive&)>& save);

/// Reads a checkpoint's header; throws CheckpointError when it is missing, unreadable or of
/// another format.
CheckpointHeader readCheckpointHeader(const std::string& path);

/// Throws CheckpointError naming the first thing that stops `found` from continuing the run of
/// `scenario` and `spec` on this build (another scenario, another spec, another version).
void checkCheckpointFits(const CheckpointHeader& found, const std::string& path, const std::string& scenario,
                         const nlohmann::json& spec);

/// Loads the state that `load` lists from the checkpoint copy the partial result was opened
/// from (ResultFile's continueFrom), then removes /checkpoint from it unless `more` parts of the
/// state are to be loaded later (then endCheckpointLoading removes it).
void loadCheckpointState(ResultFile& partial, const std::function<void(StateArchive&)>& load, bool more = false);
/// Removes /checkpoint from the partial result once its state is loaded.
void endCheckpointLoading(ResultFile& partial);
/// Loads the state of a checkpoint that holds no result (a rank's but the first's, of a decomposed
/// run) from its own file. Throws CheckpointError.
void loadCheckpointState(const std::string& path, const std::function<void(StateArchive&)>& load);

}  // namespace rupture::io
