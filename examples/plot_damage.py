#!/usr/bin/python3
"""Plot the damage index of a run's last snapshot (2D runs): plot_damage.py RUN.h5 OUT.png [title]."""
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

path, out = sys.argv[1], sys.argv[2]
title = sys.argv[3] if len(sys.argv) > 3 else path
with h5py.File(path, "r") as f:
    last = sorted(f["snapshots"].keys())[-1]
    snap = f["snapshots"][last]
    pos, damage, time = snap["position"][()], snap["damage"][()], snap.attrs["time"]
    summary = dict(f["summary"].attrs)
fig, ax = plt.subplots(figsize=(8, 3.6))
sc = ax.scatter(pos[:, 0] * 1e3, pos[:, 1] * 1e3, c=damage, s=1.0, cmap="inferno_r", vmin=0, vmax=0.6, linewidths=0)
ax.set_aspect("equal")
ax.set_xlabel("x (mm)")
ax.set_ylabel("y (mm)")
speed = summary.get("crack_speed_max", float("nan"))
branches = summary.get("branches", "?")
ax.set_title(f"{title}: t = {time * 1e6:.1f} us, crack speed max {speed:.0f} m/s, branches {branches}", fontsize=9)
fig.colorbar(sc, ax=ax, label="damage index (1)", shrink=0.8)
fig.tight_layout()
fig.savefig(out, dpi=130)
