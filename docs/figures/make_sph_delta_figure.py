#!/usr/bin/env python3
"""Regenerates docs/figures/sph-density-diffusion.svg: the pressure at a gauge with and without
delta-SPH density diffusion, in a water column at rest (hydrostatic) and in the piston column.

Usage: python3 docs/figures/make_sph_delta_figure.py build/engine/rupture
(needs the Debian packages python3-matplotlib and python3-h5py; about a minute on one core)."""
import json
import os
import subprocess
import sys
import tempfile

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

rupture = sys.argv[1] if len(sys.argv) > 1 else "build/engine/rupture"
here = os.path.dirname(os.path.abspath(__file__))

COLUMN = {"scenario": "dam-break", "dimension": 2,
          "geometry": {"column_width": 0.1, "column_height": 0.2, "tank_length": 0.1, "tank_height": 0.25},
          "resolution": {"spacing": 0.005}, "probes": [[0.05, 0.1]],
          "run": {"end_time": 0.5, "output_interval": 0.0005}}
PISTON = {"scenario": "piston-column", "dimension": 2,
          "geometry": {"diameter": 0.08, "column_height": 0.203}, "resolution": {"spacing": 0.002},
          "piston": {"motion": "free", "mass": 245, "speed": 5}, "probes": [[0, 0.1015]],
          "run": {"end_time": 0.0002, "output_interval": 0.0000005}}


def run(spec, model, work):
    spec = json.loads(json.dumps(spec))
    spec.setdefault("fluid", {})["density_diffusion"] = {"model": model}
    path = os.path.join(work, f"{spec['scenario']}-{model}")
    with open(path + ".json", "w") as f:
        json.dump(spec, f)
    subprocess.run([rupture, "run", path + ".json", "-o", path + ".h5"], check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    with h5py.File(path + ".h5") as f:
        last = sorted(f["/snapshots"].keys())[-1]
        snap = f["/snapshots/" + last]
        fluid = snap["body"][:] == -1
        particles = (snap["position"][:][fluid, 1], snap["pressure"][:][fluid])
        return (f["/series/time"][:], f["/series/probe_pressure_0"][:], json.loads(f["/spec"].attrs["json"]),
                particles)


with tempfile.TemporaryDirectory() as work:
    fig, (a, c, b) = plt.subplots(1, 3, figsize=(14, 3.9))
    for model, style in (("off", "C3"), ("molteni_colagrossi", "C0"), ("fourtakas", "C2")):
        t, p, _, (y, pp) = run(COLUMN, model, work)
        a.plot(t, p / 1e3, style, lw=0.8, label=f"density diffusion {model}")
        c.plot((pp - 1000 * 9.81 * (0.2 - y)) / 1e3, y, ".", color=style, ms=2.5,
               label=f"density diffusion {model}")
        t, p, spec, _ = run(PISTON, model, work)
        b.plot(t * 1e3, p / 1e6, style, lw=0.8, label=f"density diffusion {model}")
    a.axhline(1000 * 9.81 * 0.1 / 1e3, color="k", ls="--", lw=0.8, label="rho0 g H/2")
    a.set(xlabel="t (s)", ylabel="p at the mid-depth gauge (kPa)",
          title="Column at rest (2D, dx = 5 mm): gauge")
    c.axvline(0, color="k", ls="--", lw=0.8)
    c.set(xlabel="p - rho0 g (H - y) of each particle at t = 0.5 s (kPa)", ylabel="y (m)",
          title="Column at rest: particles about the hydrostatic line")
    c0 = spec["fluid"]["sound_speed"]
    b.axhline(1000 * c0 * 5 / 1e6, color="k", ls="--", lw=0.8, label="rho0 c0 V")
    b.set(xlabel="t (ms)", ylabel="p at the mid-height gauge (MPa)",
          title="Piston column (M = 245 kg, V = 5 m/s, 2D, dx = 2 mm)")
    for ax in (a, c, b):
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(here, "sph-density-diffusion.svg"))
    if len(sys.argv) > 2:  # an extra raster copy, e.g. to look at it
        fig.savefig(sys.argv[2], dpi=90)
