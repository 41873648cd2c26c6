#include "scenarios/bonded/bond_snapshot.hpp"

#include <cmath>
#include <cstdint>
#include <variant>
#include <vector>

namespace rupture {

void writeBondPairs(io::Hdf5File& file, const BondStore& bonds) {
  std::vector<std::int32_t> pairs(2 * bonds.size());
  for (std::size_t b = 0; b < bonds.size(); ++b) {
    pairs[2 * b] = bonds.i[b];
    pairs[2 * b + 1] = bonds.j[b];
  }
  file.writeDataset("/sample/bonds", pairs, {bonds.size(), 2}, "1");
}

void writeBondState(io::Hdf5File& file, const std::string& snapshot, const BondedSystem& system) {
  const BondStore& bonds = system.bondLoads();
  const std::size_t nb = bonds.size();
  std::vector<std::uint8_t> intact(nb);
  for (std::size_t b = 0; b < nb; ++b) intact[b] = bonds.intact[b] > 0.0 ? 1 : 0;
  file.writeDataset(snapshot + "/bond_intact", intact, {nb}, "1");

  // Measure and threshold exist once the loop has run (initialize() evaluates every bond).
  const bool measured = bonds.failureMeasure.size() == nb && bonds.failureThreshold.size() == nb;
  std::vector<double> load(nb, 0.0);
  if (measured) {
    for (std::size_t b = 0; b < nb; ++b) {
      const double limit = bonds.failureThreshold[b];
      // An unbreakable bond (+inf threshold) carries no load fraction; 0 keeps the colour map honest.
      load[b] = std::isfinite(limit) && limit > 0 ? bonds.failureMeasure[b] / limit : 0.0;
    }
  }
  file.writeDataset(snapshot + "/bond_load", load, {nb}, "1");
  if (measured && std::holds_alternative<BeamModel>(system.model)) {
    file.writeDataset(snapshot + "/bond_equivalent_stress", bonds.failureMeasure, {nb}, "Pa");
  }
}

}  // namespace rupture
