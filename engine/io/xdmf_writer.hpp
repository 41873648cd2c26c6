#pragma once
// ParaView sidecar for a run file. XDMF keeps the small metadata in XML and points at the arrays in
// the HDF5 file, so ParaView can show snapshots without a converter (dependencies notes §5.3).
#include <string>
#include <vector>

namespace rupture::io {

/// Writes an Xdmf2 sidecar (ParaView's "XDMF Reader") describing every snapshot of a run file as a
/// temporal collection of point clouds (Polyvertex topology).
///
/// Snapshots are the groups /snapshots/<k>, taken in sorted name order (zero-padded, "000000"),
/// each holding position {n,3} (m) and velocity {n,3} (m/s), and any of stress {n,3,3} (Pa),
/// damage {n} (1), radius {n} (m) (bonded runs), density {n} (kg/m³), pressure {n} (Pa) and body {n}
/// (SPH runs), with attribute time (s); n may differ per snapshot.
/// Snapshots with n = 0 are left out (a grid without points is not useful to the reader).
/// The HDF5 file is referenced by its path relative to the sidecar's directory, so the two can be
/// moved together. Name the sidecar `*.xdmf2`: ParaView 5.11 opens `.xmf`/`.xdmf` with its broken
/// Xdmf3 readers. The sidecar is written to a temporary file and renamed into place. If this
/// process still has the run file open for writing, flush it first.
///
/// Bonded runs also get a second temporal collection, "bonds": per snapshot, the bond pairs of
/// /sample/bonds {b,2} as line cells (Polyline, 2 nodes) over that snapshot's positions, with cell
/// data bond_intact (1 intact, 0 broken), bond_load (criterion measure / threshold, 1) and, for
/// beams, bond_equivalent_stress (Pa), whichever the snapshot holds.
///
/// `root` is the group that holds the run ("" for a run file, "/run-<k>" inside a job's merged
/// file).
///
/// Throws Hdf5Error if the run file cannot be read or does not have this layout, and
/// std::runtime_error if the sidecar cannot be written.
void writeXdmfSidecar(const std::string& hdf5Path, const std::string& xdmfPath,
                      const std::string& root = "");

/// The sidecar's text, naming the HDF5 file as `fileRef` (the server names it by its download
/// name, so the sidecar and the file work side by side in the user's directory).
std::string xdmfDocument(const std::string& hdf5Path, const std::string& fileRef,
                         const std::string& root = "");

/// The runs of a file that XDMF can describe: {""} for a run file with /snapshots, else the
/// "/run-<k>" groups of a merged job file that hold snapshots, in run order.
std::vector<std::string> runGroupsWithSnapshots(const std::string& hdf5Path);

}  // namespace rupture::io
