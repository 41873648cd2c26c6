#pragma once
// The bond network in a result file, so that ParaView can draw it (io/xdmf_writer.hpp exports the
// bonds as line cells): the pairs once under /sample, their state in every snapshot.
#include <string>

#include "bonded/bonded_system.hpp"
#include "io/hdf5_file.hpp"

namespace rupture {

/// /sample/bonds: {bonds, 2} int32 element indices (i, j) of every bond, intact or not.
void writeBondPairs(io::Hdf5File& file, const BondStore& bonds);

/// The state of every bond at this snapshot, under `snapshot` (a group /snapshots/<k>):
///   bond_intact {bonds} uint8 (1 intact, 0 broken),
///   bond_load {bonds} double (1): the failure criterion's measure over its threshold (1 breaks),
///   bond_equivalent_stress {bonds} double (Pa): the Rankine σ_eq, for the beam model only.
/// The measures are those of the last force evaluation (the step that ended at the snapshot).
void writeBondState(io::Hdf5File& file, const std::string& snapshot, const BondedSystem& system);

}  // namespace rupture
