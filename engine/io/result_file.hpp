#pragma once
// The life cycle every scenario's result file shares. Everything is written to RESULT.part, which
// finish() renames onto RESULT, so a reader never sees a half-written file; an unfinished file (an
// exception during the run) is deleted by the destructor. A RESULT that already ends in ".part" is
// the caller's own temporary: the file is written there and finish() leaves it for the caller to
// rename (the job server does, after recording the summary: one rename, not two). Common layout:
//   /        attributes scenario, rupture_version, completed (int64 1/0)
//   /spec    attributes json (the resolved spec, defaults filled in) and input (as submitted)
//   /provenance  what made the file: build, host processor, threads, spec digest, seeds, start and
//            finish times (io/provenance.hpp)
// Scalar groups (/summary, ...) are written by writeAttributes: booleans as int64 0/1, integers as
// int64, numbers as double, null as NaN, strings as strings, anything else as its JSON text, each
// with a "<name>_unit" string attribute when its unit is known.
#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "io/hdf5_file.hpp"

namespace rupture::io {

class ResultFile {
public:
  /// continueFrom: a checkpoint (io/checkpoint_file.hpp) whose copy of the partial result this run
  /// continues: copied onto RESULT.part and opened, nothing written; "" starts a new file.
  ResultFile(std::string resultPath, const std::string& scenario, const std::string& continueFrom = "");
  /// Where the file goes: on disk, or (kDiscarded) in memory only, never written: the ranks of a
  /// decomposed run but the first, which write nothing into it (the first writes the outputs), keep
  /// one for their checkpoints' sake.
  enum class Destination { kDisk, kDiscarded };
  /// continueFrom: as above, for kDisk; a kDiscarded result always starts empty.
  ResultFile(std::string resultPath, const std::string& scenario, Destination destination,
             const std::string& continueFrom = "");
  ~ResultFile();
  ResultFile(const ResultFile&) = delete;
  ResultFile& operator=(const ResultFile&) = delete;

  /// The open partial file, for datasets and groups of the scenario's own layout.
  Hdf5File& file() { return m_file; }

  void writeSpec(const nlohmann::json& resolved, const nlohmann::json& input);
  void writeAttributes(const std::string& group, const nlohmann::json& values,
                       const std::map<std::string, std::string>& units);

  /// Where the partial file is written (RESULT.part, or RESULT itself when it is the caller's ".part").
  const std::string& partPath() const { return m_partPath; }
  /// True when the file continues a checkpoint's partial result.
  bool continued() const { return m_continued; }
  /// True for a result held in memory only and dropped (Destination::kDiscarded).
  bool discarded() const { return m_discarded; }
  /// Records on "/" that the run continued from `step` (checkpoint_resumes, resumed_from_steps: the
  /// steps of every resume so far, a JSON list).
  void recordResume(std::int64_t step);
  /// Makes the partial file whole on disk, copies it to `path` and opens it again (checkpoints).
  void copyTo(const std::string& path);

  /// Marks "/" completed (1/0), closes, and renames the partial file onto the result (unless the
  /// result path is itself a ".part" the caller renames).
  void finish(bool completed);
  /// Closes and deletes the partial file.
  void abandon() noexcept;

private:
  std::string m_resultPath, m_partPath;
  Hdf5File m_file;
  bool m_done = false;
  bool m_continued = false;
  bool m_discarded = false;
};

}  // namespace rupture::io
