#pragma once
// The result file of one dynamic-tension run (layout in docs/dynamic-tension.md):
//   /            attributes scenario, rupture_version, completed (1/0)
//   /spec        attributes json (the resolved spec, defaults filled in) and input (as submitted)
//   /sample      attributes (elements, bonds, ...); datasets radius {n}, initial_position {n,3},
//                bonds {m,2} (int32 element indices), face_group {n} (int32: 0, 1 X_min, 2 X_max),
//                pores {p,4} (centre x, y, z, radius; m)
//   /preliminary attributes of the VH preliminary run (or used = 0)
//   /series/<name>     1-D float64 datasets with a "unit" attribute, one row per output interval
//   /snapshots/<k>     position {n,3}, velocity {n,3}, stress {n,3,3}, damage {n}, radius {n},
//                      bond_intact {m} (uint8; rows of /sample/bonds); attributes time, strain, step, trigger
//   /fragments   attributes min_elements, min_fraction, count, debris, debris_elements,
//                cracks_crossing; datasets sizes {k} (int32, elements per macroscopic fragment, largest
//                first), element_fragment {n} (int32: index in sizes, −1 for debris); at the end
//   /summary     attributes (SI), each with a companion "<name>_unit"
// The file's life cycle (RESULT.part renamed by finish(), deleted if unfinished), /, /spec and the
// scalar groups are io::ResultFile's.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bonded/bonded_system.hpp"
#include "samples/sample_builder.hpp"
#include "io/result_file.hpp"
#include "scenarios/bonded/intact_network.hpp"
#include "scenarios/dynamic_tension/tension_loading.hpp"

namespace rupture {

/// One row of /series.
struct SeriesRow {
  double time, strain, stressXmin, stressXmax, stressMean, brokenBondFraction, kineticEnergy, elasticEnergy,
      faceVelocity;
};

class TensionRecorder {
public:
  /// continueFrom: a checkpoint whose partial result this run continues (io::ResultFile).
  /// kDiscarded: an empty file in memory, dropped (the ranks of a decomposed run after the first,
  /// which record nothing: the first writes the outputs).
  explicit TensionRecorder(std::string resultPath, const std::string& continueFrom = "",
                           io::ResultFile::Destination destination = io::ResultFile::Destination::kDisk);
  io::ResultFile& result() { return m_result; }
  /// The rows so far and the snapshot count (docs/checkpoints.md).
  void exchangeState(StateArchive& archive) {
    StateGroup group(archive, "recorder");
    archive.records("rows", m_rows);
    archive.value("snapshots", m_snapshots);
  }

  void writeSpec(const nlohmann::json& resolved, const nlohmann::json& input) { m_result.writeSpec(resolved, input); }
  void writeSample(const BondedSystem& system, const SampleReport& report, const TensionGeometry& geometry);
  /// Writes each member of `values` as an attribute of `group` (numbers, strings, booleans as 1/0,
  /// null as NaN), plus "<name>_unit" for the names found in `units`.
  void writeAttributes(const std::string& group, const nlohmann::json& values,
                       const std::map<std::string, std::string>& units) {
    m_result.writeAttributes(group, values, units);
  }

  void appendRow(const SeriesRow& row) { m_rows.push_back(row); }
  std::size_t rowCount() const { return m_rows.size(); }

  /// Writes /snapshots/<k> (k = 0, 1, ... zero-padded) from the current state of the system.
  void writeSnapshot(const BondedSystem& system, double packingFraction, double thickness2d, double strain,
                     const std::string& trigger);
  std::size_t snapshotCount() const { return m_snapshots; }

  /// Writes /fragments: the pieces of the final state (minElements = the size threshold used).
  void writeFragments(const FragmentAnalysis& fragments, std::size_t minElements, double minFraction,
                      std::size_t cracksCrossing);

  /// Writes /series, marks "/" completed, closes and renames the partial file onto the result.
  void finish(bool completed);

private:
  io::ResultFile m_result;
  io::Hdf5File& m_file;  ///< m_result's open file
  std::vector<SeriesRow> m_rows;
  std::size_t m_snapshots = 0;
};

/// Names and units of the /series datasets, in file order.
const std::vector<std::pair<std::string, std::string>>& seriesNamesAndUnits();

}  // namespace rupture
