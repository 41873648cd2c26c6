#include "sph/fluid_recorder.hpp"

#include <cstdio>
#include <stdexcept>

#include "io/interleave.hpp"

namespace rupture::io {

FluidRecorder::FluidRecorder(std::string resultPath, const std::string& scenario,
                             std::vector<std::pair<std::string, std::string>> columns,
                             std::vector<std::string> probePositions, const std::string& continueFrom)
    : m_result(std::move(resultPath), scenario, continueFrom), m_columns(std::move(columns)),
      m_probes(probePositions.size()), m_probePositions(std::move(probePositions)) {
  if (!m_result.continued()) m_result.file().createGroup("/snapshots");
}

void FluidRecorder::exchangeState(StateArchive& archive) {
  StateGroup group(archive, "recorder");
  // Rows as one table (row-major): every row has one value per column.
  std::vector<double> table;
  for (const auto& row : m_rows) table.insert(table.end(), row.begin(), row.end());
  archive.array("rows", table);
  if (archive.loading()) {
    const std::size_t width = m_columns.size();
    if (width == 0 || table.size() % width != 0)
      throw CheckpointError("the checkpoint's series rows do not have " + std::to_string(width) + " columns");
    m_rows.clear();
    for (std::size_t r = 0; r < table.size(); r += width) m_rows.emplace_back(table.begin() + r, table.begin() + r + width);
  }
  archive.array("probe_rows", m_probeRows);
  archive.value("snapshots", m_snapshots);
}

void FluidRecorder::appendRow(const std::vector<double>& values, const std::vector<double>& probePressures) {
  if (values.size() != m_columns.size() || probePressures.size() != m_probes)
    throw std::logic_error("FluidRecorder: row does not match the series columns");
  m_rows.push_back(values);
  m_probeRows.insert(m_probeRows.end(), probePressures.begin(), probePressures.end());
}

void FluidRecorder::writeSnapshot(const sph::SphSystem& system, const std::string& trigger) {
  writeSnapshot(system, trigger, StructurePoints{});
}

void FluidRecorder::writeSnapshot(const sph::SphSystem& system, const std::string& trigger,
                                  const StructurePoints& structure) {
  const sph::FluidParticles& p = system.particles;
  const std::size_t n = p.size(), m = structure.size(), total = n + m;
  char name[32];
  std::snprintf(name, sizeof name, "/snapshots/%06zu", m_snapshots);
  const std::string base = name;
  Hdf5File& f = m_result.file();
  f.createGroup(base);
  f.setAttribute(base, "time", system.time);
  f.setAttribute(base, "step", static_cast<std::int64_t>(system.steps));
  f.setAttribute(base, "trigger", trigger);
  f.setAttribute(base, "time_unit", std::string("s"));
  f.setAttribute(base, "step_unit", std::string("1"));
  // A snapshot of millions of particles takes seconds to gather and compress: a cancel is honoured
  // between the passes that gather it and between the slabs of its datasets (the file is then
  // marked incomplete, this snapshot partial).
  const Cancellation& cancel = system.cancel;
  std::vector<double> x, y, z, vx, vy, vz, rho, pressure(n);
  p.inCreationOrder(p.x, x); p.inCreationOrder(p.y, y); p.inCreationOrder(p.z, z);
  cancel.throwIfRequested();
  p.inCreationOrder(p.vx, vx); p.inCreationOrder(p.vy, vy); p.inCreationOrder(p.vz, vz);
  cancel.throwIfRequested();
  p.inCreationOrder(p.rho, rho);
  for (std::size_t k = 0; k < n; ++k) pressure[k] = system.model.eos.pressure(rho[k]);
  cancel.throwIfRequested();
  std::vector<std::int32_t> body(n);
  for (std::size_t k = 0; k < n; ++k) body[p.id[k]] = p.body[k];
  std::vector<double> position = interleave(x, y, z);
  cancel.throwIfRequested();
  std::vector<double> velocity = interleave(vx, vy, vz);
  if (m > 0) {
    position.insert(position.end(), structure.position.begin(), structure.position.end());
    velocity.insert(velocity.end(), structure.velocity.begin(), structure.velocity.end());
    rho.insert(rho.end(), structure.density.begin(), structure.density.end());
    pressure.resize(total, 0.0);
    body.insert(body.end(), structure.body.begin(), structure.body.end());
  }
  struct BetweenParts {
    Hdf5File& file;
    BetweenParts(Hdf5File& f, const Cancellation& c) : file(f) { f.setBetweenParts([c] { c.throwIfRequested(); }); }
    ~BetweenParts() { file.setBetweenParts({}); }
  } betweenParts(f, cancel);
  f.writeDataset(base + "/position", position, {total, 3}, "m");
  f.writeDataset(base + "/velocity", velocity, {total, 3}, "m/s");
  f.writeDataset(base + "/density", rho, {total}, "kg/m^3");
  f.writeDataset(base + "/pressure", pressure, {total}, "Pa");
  f.writeDataset(base + "/body", body, {total}, "1");
  if (m > 0) {
    std::vector<double> damage(n, 0.0);
    damage.insert(damage.end(), structure.damage.begin(), structure.damage.end());
    std::vector<std::int32_t> fractured(n, 0);
    fractured.insert(fractured.end(), structure.fractured.begin(), structure.fractured.end());
    f.writeDataset(base + "/damage", damage, {total}, "1");
    f.writeDataset(base + "/fractured", fractured, {total}, "1");
  }
  ++m_snapshots;
}

void FluidRecorder::finish(bool completed) {
  Hdf5File& f = m_result.file();
  const std::size_t rows = m_rows.size();
  f.createGroup("/series");
  for (std::size_t c = 0; c < m_columns.size(); ++c) {
    std::vector<double> column(rows);
    for (std::size_t r = 0; r < rows; ++r) column[r] = m_rows[r][c];
    f.writeDataset("/series/" + m_columns[c].first, column, {rows}, m_columns[c].second);
  }
  // One dataset per probe, so every series is a plain column (the server's series API, CSV).
  for (std::size_t k = 0; k < m_probes; ++k) {
    std::vector<double> column(rows);
    for (std::size_t r = 0; r < rows; ++r) column[r] = m_probeRows[r * m_probes + k];
    const std::string path = "/series/probe_pressure_" + std::to_string(k);
    f.writeDataset(path, column, {rows}, "Pa");
    f.setAttribute(path, "position", m_probePositions[k]);
    f.setAttribute(path, "position_unit", std::string("m"));
  }
  m_result.finish(completed);
}

}  // namespace rupture::io
