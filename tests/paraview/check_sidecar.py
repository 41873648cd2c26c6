"""Run by pvpython: the sidecar opens in ParaView's XDMF reader with what the HDF5 file holds.

    pvpython check_sidecar.py RUN.xdmf2 ELEMENTS BONDS BROKEN_AT_LAST

Asserts the particles grid has ELEMENTS points with the stress tensor (9 components), and the bonds
grid has BONDS line cells of which BROKEN_AT_LAST have bond_intact = 0 at the last snapshot.
"""
import sys

from paraview import servermanager
from paraview.simple import XDMFReader, UpdatePipeline

sidecar, elements, bonds, broken = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4])


def last_block(prefix):
    reader = XDMFReader(FileNames=[sidecar])
    reader.GridStatus = [g for g in list(reader.GetProperty("GridInfo"))[0::2] if g.startswith(prefix)]
    times = reader.TimestepValues
    last = times[-1] if isinstance(times, (list, tuple)) or hasattr(times, "__len__") else times
    UpdatePipeline(time=last, proxy=reader)
    data = servermanager.Fetch(reader)
    # One block per temporal collection; the deselected one is empty.
    blocks = [data.GetBlock(i) for i in range(data.GetNumberOfBlocks())]
    return max((b for b in blocks if b is not None), key=lambda b: b.GetNumberOfPoints())


points = last_block("snapshot_")
assert points.GetNumberOfPoints() == elements, (points.GetNumberOfPoints(), elements)
stress = points.GetPointData().GetArray("stress")
assert stress is not None and stress.GetNumberOfComponents() == 9, "stress tensor missing"

lines = last_block("bonds_")
assert lines.GetNumberOfCells() == bonds, (lines.GetNumberOfCells(), bonds)
assert lines.GetCell(0).GetNumberOfPoints() == 2
intact = lines.GetCellData().GetArray("bond_intact")
zeros = sum(1 for c in range(intact.GetNumberOfTuples()) if intact.GetValue(c) == 0)
assert zeros == broken, (zeros, broken)
assert lines.GetCellData().GetArray("bond_equivalent_stress") is not None
print(f"ok: {elements} points, {bonds} bond cells, {broken} broken")
