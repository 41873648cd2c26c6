#!/usr/bin/env pvbatch
"""Render the seed's Figure 4 from a run: the virial stress sigma_xx of every element, with the
broken bonds (the cracks) drawn as black lines, at one snapshot.

    rupture xdmf RUN.h5                     # a downloaded RUN.h5 (rupture run writes RUN.xdmf2 itself);
                                            # or download RUN.xdmf2 / the bundle from the server
    xvfb-run -a -s "-screen 0 1600x1200x24" pvbatch examples/paraview_figure4.py RUN.xdmf2 figure4.png [SNAPSHOT] [WIDTH HEIGHT]

SNAPSHOT is the index of the snapshot (default -1, the last). Headless machines need a display:
Debian's pvbatch aborts with --force-offscreen-rendering when no X server runs, so use xvfb-run
(package xvfb) with a 24-bit screen: xvfb-run's default 8-bit screen has no OpenGL visual and
pvbatch aborts with "bad X server connection". Tested with ParaView 5.11 (Debian 12); see docs/paraview.md.
"""
import sys

from paraview.simple import (ColorBy, GetActiveViewOrCreate, GetColorTransferFunction,
                             GetScalarBar, Render, SaveScreenshot, Show, Threshold, XDMFReader)

if len(sys.argv) < 3:
    sys.exit(__doc__)
sidecar, out = sys.argv[1], sys.argv[2]
snapshot = int(sys.argv[3]) if len(sys.argv) > 3 else -1
size = [int(sys.argv[4]), int(sys.argv[5])] if len(sys.argv) > 5 else [1200, 1000]



def reader(name, prefix):
    """The sidecar's grids whose names start with prefix ("snapshot_": the particles, "bonds_": the
    bond lines); ParaView's XDMF reader lists the grids of every temporal collection by name."""
    r = XDMFReader(registrationName=name, FileNames=[sidecar])
    grids = list(r.GetProperty("GridInfo"))[0::2]
    r.GridStatus = [g for g in grids if g.startswith(prefix)]
    return r


# Two readers on the same sidecar: the particles and the bond lines.
particles = reader("particles", "snapshot_")
bonds = reader("bonds", "bonds_")
times = list(particles.TimestepValues) if particles.TimestepValues else [0.0]
if isinstance(particles.TimestepValues, float):
    times = [particles.TimestepValues]
time = times[snapshot]

view = GetActiveViewOrCreate("RenderView")
view.ViewSize = size
view.ViewTime = time
view.OrientationAxesVisibility = 0
view.Background = [1, 1, 1]
try:  # ParaView 5.10+: the background is a palette colour unless told otherwise
    view.UseColorPaletteForBackground = 0
except AttributeError:
    pass

# Elements as discs of their own radius, coloured by sigma_xx (component 0 of the 3x3 tensor).
shown = Show(particles, view)
shown.SetRepresentationType("Point Gaussian")
shown.ScaleByArray = 1
shown.SetScaleArray = ["POINTS", "radius"]
shown.UseScaleFunction = 0  # the radius itself, not mapped through a transfer function
shown.GaussianRadius = 1.0
shown.ShaderPreset = "Plain circle"
ColorBy(shown, ("POINTS", "stress", "0"))
lut = GetColorTransferFunction("stress")
lut.VectorMode = "Component"
lut.VectorComponent = 0
lut.ApplyPreset("Cool to Warm", True)
shown.RescaleTransferFunctionToDataRange(False, True)
bar = GetScalarBar(lut, view)
bar.Title = "virial stress sigma_xx (Pa)"
bar.ComponentTitle = ""
bar.TitleColor = bar.LabelColor = [0, 0, 0]
shown.SetScalarBarVisibility(view, True)

# Broken bonds (bond_intact = 0) as black lines: the crack network.
broken = Threshold(registrationName="broken bonds", Input=bonds)
broken.Scalars = ["CELLS", "bond_intact"]
try:  # ParaView 5.10+
    broken.LowerThreshold, broken.UpperThreshold = 0, 0
    broken.ThresholdMethod = "Between"
except AttributeError:  # older ParaView
    broken.ThresholdRange = [0, 0]
cracks = Show(broken, view)
cracks.ColorArrayName = ["POINTS", ""]  # a solid colour
cracks.AmbientColor = cracks.DiffuseColor = [0, 0, 0]
cracks.LineWidth = 2.0

view.InteractionMode = "2D"
view.ResetCamera()
Render(view)
SaveScreenshot(out, view, ImageResolution=size)
print(f"{out}: snapshot {snapshot} of {len(times)}, t = {time:g} s")
