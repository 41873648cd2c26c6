#!/usr/bin/python3
"""Reproduces the README's peak-stress figure through the Python client: the example sweep
(examples/sweep-small.json: strain rate x initial velocity field), then peak stress against
strain rate, one line per field, on log-log axes with matplotlib.

    python3 clients/python/example_peak_stress.py [--server http://127.0.0.1:8080] [--out peak_stress.png]
"""
import argparse
import json
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from rupture_client import Client  # noqa: E402

root = pathlib.Path(__file__).resolve().parents[2]
parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--server", default="http://127.0.0.1:8080")
parser.add_argument("--token", default=None)
parser.add_argument("--out", default="peak_stress.png")
args = parser.parse_args()

request = json.loads((root / "examples" / "sweep-small.json").read_text())
client = Client(args.server, token=args.token)
job = client.submit("dynamic-tension", request["inputs"], request["sweep"], name=request["name"])
client.wait(job, progress=True)
rows = client.summary(job, as_dataframe=False)

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

fig, ax = plt.subplots(figsize=(5.5, 4))
for field in request["sweep"]["loading.initial_velocity"]:
    points = sorted((r["loading.strain_rate"], r["peak_stress"]) for r in rows
                    if r["loading.initial_velocity"] == field and r.get("peak_stress") is not None)
    ax.plot([p[0] for p in points], [p[1] / 1e9 for p in points], marker="o", label=field)
ax.set_xscale("log")
ax.set_xlabel("strain rate (1/s)")
ax.set_ylabel("peak stress (GPa)")
ax.set_title(f"Peak stress vs strain rate (job {job})")
ax.legend(title="initial velocity field")
fig.tight_layout()
fig.savefig(args.out, dpi=150)
print(args.out)
