#include "scenarios/dynamic_tension/tension_recorder.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <system_error>

#include "io/interleave.hpp"
#include "scenarios/bonded/intact_network.hpp"
#include "scenarios/bonded/bond_snapshot.hpp"
#include "scenarios/dynamic_tension/dynamic_tension_results.hpp"
#include "scenarios/dynamic_tension/virial_stress.hpp"

namespace rupture {

namespace fs = std::filesystem;

const std::vector<std::pair<std::string, std::string>>& seriesNamesAndUnits() {
  static const std::vector<std::pair<std::string, std::string>> names = [] {
    std::vector<std::pair<std::string, std::string>> out;
    for (const ResultField& f : dynamicTensionSeriesFields()) out.emplace_back(f.name, f.unit);
    return out;
  }();
  return names;
}

TensionRecorder::TensionRecorder(std::string resultPath, const std::string& continueFrom,
                                 io::ResultFile::Destination destination)
    : m_result(std::move(resultPath), "dynamic-tension", destination, continueFrom), m_file(m_result.file()) {
  if (!m_result.continued()) m_file.createGroup("/snapshots");
}

void TensionRecorder::writeSample(const BondedSystem& system, const SampleReport& report,
                                  const TensionGeometry& geometry) {
  const ParticleStore& p = system.particles;
  const std::size_t n = p.size();
  m_file.createGroup("/sample");
  writeAttributes("/sample",
                  {{"elements", static_cast<std::int64_t>(report.elements)},
                   {"bonds", static_cast<std::int64_t>(report.bonds)},
                   {"mean_coordination", report.meanCoordination},
                   {"packing_fraction", report.packingFraction},
                   {"packing_residual_overlap", report.relaxationOverlap},
                   {"porosity", report.porosity},
                   {"thickness", report.thickness},
                   {"element_density", report.elementDensity},
                   {"bulk_density", geometry.bulkDensity},
                   {"gauge_length", geometry.gaugeLength},
                   {"section", geometry.section},
                   {"xmin_elements", static_cast<std::int64_t>(geometry.xmin.size())},
                   {"xmax_elements", static_cast<std::int64_t>(geometry.xmax.size())}},
                  {{"elements", "1"},
                   {"bonds", "1"},
                   {"mean_coordination", "1"},
                   {"packing_fraction", "1"},
                   {"packing_residual_overlap", "1"},
                   {"porosity", "1"},
                   {"xmin_elements", "1"},
                   {"xmax_elements", "1"},
                   {"thickness", "m"},
                   {"element_density", "kg/m^3"},
                   {"bulk_density", "kg/m^3"},
                   {"gauge_length", "m"},
                   {"section", "m^2"}});
  m_file.writeDataset("/sample/radius", p.radius, {n}, "m");
  m_file.writeDataset("/sample/initial_position", io::interleave(p.x, p.y, p.z), {n, 3}, "m");
  writeBondPairs(m_file, system.bonds);
  std::vector<std::int32_t> group(n, 0);
  for (std::int32_t k : geometry.xmin) group[k] = 1;
  for (std::int32_t k : geometry.xmax) group[k] = 2;
  m_file.writeDataset("/sample/face_group", group, {n}, "1");
  std::vector<double> pores;
  for (const Pore& pore : report.pores)
    pores.insert(pores.end(), {pore.centre[0], pore.centre[1], pore.centre[2], pore.radius});
  m_file.writeDataset("/sample/pores", pores, {report.pores.size(), 4}, "m");
}

void TensionRecorder::writeSnapshot(const BondedSystem& system, double packingFraction, double thickness2d,
                                    double strain, const std::string& trigger) {
  const ParticleStore& p = system.particles;
  const std::size_t n = p.size();
  char name[32];
  std::snprintf(name, sizeof name, "/snapshots/%06zu", m_snapshots);
  const std::string base = name;
  m_file.createGroup(base);
  m_file.setAttribute(base, "time", system.time);
  m_file.setAttribute(base, "strain", strain);
  m_file.setAttribute(base, "step", static_cast<std::int64_t>(system.steps));
  m_file.setAttribute(base, "time_unit", std::string("s"));
  m_file.setAttribute(base, "strain_unit", std::string("1"));
  m_file.setAttribute(base, "step_unit", std::string("1"));
  m_file.setAttribute(base, "trigger", trigger);
  m_file.writeDataset(base + "/position", io::interleave(p.x, p.y, p.z), {n, 3}, "m");
  m_file.writeDataset(base + "/velocity", io::interleave(p.vx, p.vy, p.vz), {n, 3}, "m/s");
  m_file.writeDataset(base + "/stress", virialStress(system, packingFraction, thickness2d), {n, 3, 3}, "Pa");
  m_file.writeDataset(base + "/damage", elementDamage(system.bonds, n, &p.volume), {n}, "1");
  m_file.writeDataset(base + "/radius", p.radius, {n}, "m");
  writeBondState(m_file, base, system);
  ++m_snapshots;
}

void TensionRecorder::writeFragments(const FragmentAnalysis& fragments, std::size_t minElements, double minFraction,
                                     std::size_t cracksCrossing) {
  m_file.createGroup("/fragments");
  writeAttributes("/fragments",
                  {{"min_elements", static_cast<std::int64_t>(minElements)},
                   {"min_fraction", minFraction},
                   {"count", static_cast<std::int64_t>(fragments.fragmentSizes.size())},
                   {"debris", static_cast<std::int64_t>(fragments.debris)},
                   {"debris_elements", static_cast<std::int64_t>(fragments.debrisElements)},
                   {"cracks_crossing", static_cast<std::int64_t>(cracksCrossing)}},
                  {{"min_elements", "1"}, {"min_fraction", "1"}, {"count", "1"},
                   {"debris", "1"}, {"debris_elements", "1"}, {"cracks_crossing", "1"}});
  const std::vector<std::int32_t> sizes(fragments.fragmentSizes.begin(), fragments.fragmentSizes.end());
  m_file.writeDataset("/fragments/sizes", sizes, {sizes.size()}, "1");
  m_file.writeDataset("/fragments/element_fragment", fragments.elementFragment, {fragments.elementFragment.size()},
                      "1");
}

void TensionRecorder::finish(bool completed) {
  const auto& names = seriesNamesAndUnits();
  const std::size_t rows = m_rows.size();
  std::vector<std::vector<double>> columns(names.size(), std::vector<double>(rows));
  for (std::size_t r = 0; r < rows; ++r) {
    const SeriesRow& row = m_rows[r];
    const double values[] = {row.time,        row.strain,        row.stressXmin,
                             row.stressXmax,  row.stressMean,    row.brokenBondFraction,
                             row.kineticEnergy, row.elasticEnergy, row.faceVelocity};
    for (std::size_t c = 0; c < names.size(); ++c) columns[c][r] = values[c];
  }
  m_file.createGroup("/series");
  for (std::size_t c = 0; c < names.size(); ++c)
    m_file.writeDataset("/series/" + names[c].first, columns[c], {rows}, names[c].second);
  m_result.finish(completed);
}

}  // namespace rupture
