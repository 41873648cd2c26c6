#pragma once
// The result file of an SPH scenario, through io::ResultFile:
//   /spec, /summary (attributes with <name>_unit), /geometry (attributes)
//   /series/<column> {rows} (unit attribute) and /series/probe_pressure_<k> {rows} (Pa) for probe k,
//     its point in the string attribute "position" (JSON array, m)
//   /snapshots/<k> attributes time (s), step, trigger; datasets position {n,3} (m), velocity {n,3}
//     (m/s), density {n} (kg/m³), pressure {n} (Pa), body {n} (int32: −1 fluid, else body index),
//     every particle (fluid and boundary) in creation order, so row k is the same particle in
//     every snapshot.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "io/result_file.hpp"
#include "sph/sph_system.hpp"

namespace rupture::io {

/// Points of a structure written in the same snapshot after the particles (the tank's plate
/// nodes), so that one point cloud shows both: interleaved position and velocity {m,3}, and per
/// point density (kg/m³), body index, damage (1) and fractured (0/1).
struct StructurePoints {
  std::vector<double> position, velocity;
  std::vector<double> density, damage;
  std::vector<std::int32_t> body, fractured;
  std::size_t size() const { return body.size(); }
};

class FluidRecorder {
public:
  /// columns: series names and units, in the order of appendRow's values; probePositions: each
  /// probe's point as JSON text.
  /// continueFrom: a checkpoint whose partial result this run continues (ResultFile).
  FluidRecorder(std::string resultPath, const std::string& scenario,
                std::vector<std::pair<std::string, std::string>> columns, std::vector<std::string> probePositions,
                const std::string& continueFrom = "");
  ResultFile& result() { return m_result; }
  /// The rows so far and the snapshot count (docs/checkpoints.md).
  void exchangeState(StateArchive& archive);

  void writeSpec(const nlohmann::json& resolved, const nlohmann::json& input) { m_result.writeSpec(resolved, input); }
  void writeAttributes(const std::string& group, const nlohmann::json& values,
                       const std::map<std::string, std::string>& units) {
    m_result.writeAttributes(group, values, units);
  }
  void appendRow(const std::vector<double>& values, const std::vector<double>& probePressures);
  void writeSnapshot(const sph::SphSystem& system, const std::string& trigger);
  /// The same with a structure's points appended (rows n .. n + m − 1), and damage {n + m} and
  /// fractured {n + m} (0 for the particles) besides the fluid fields (pressure 0 on the structure).
  void writeSnapshot(const sph::SphSystem& system, const std::string& trigger, const StructurePoints& structure);
  /// The file, for datasets a scenario adds (crack paths).
  Hdf5File& file() { return m_result.file(); }
  std::size_t rows() const { return m_rows.size(); }
  /// Writes /series and renames the file into place.
  void finish(bool completed);

private:
  ResultFile m_result;
  std::vector<std::pair<std::string, std::string>> m_columns;
  std::size_t m_probes;
  std::vector<std::string> m_probePositions;
  std::vector<std::vector<double>> m_rows;
  std::vector<double> m_probeRows;
  std::size_t m_snapshots = 0;
};

}  // namespace rupture::io
