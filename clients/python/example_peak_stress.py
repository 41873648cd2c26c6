#!/usr/bin/python3
"""Reproduces the README's peak-stress figure through the Python client: the example sweep
(examples/sweep-small.json: strain rate x initial velocity field), then peak stress against
strain rate, one line per field, on log-log axes.

    python3 clients/python/example_peak_stress.py [--server http://127.0.0.1:8080] [--out peak_stress.png]

The sweep is submitted with reuse=True: a second call finds the job the first one made (the one
deploy/start.sh submits is another request: it has no Idempotency-Key) and only waits for it. The
figure is drawn with matplotlib when it is installed, otherwise the server renders it (PNG or SVG
after --out's extension).
"""
import argparse
import json
import pathlib
import sys

try:
    from rupture_client import Client
except ImportError:  # not installed: the package beside this file (pandas is still needed)
    sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
    from rupture_client import Client

root = pathlib.Path(__file__).resolve().parents[2]
parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--server", default="http://127.0.0.1:8080")
parser.add_argument("--token", default=None)
parser.add_argument("--out", default="peak_stress.png")
args = parser.parse_args()

try:  # decided before the sweep runs, not after
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    plt = None

request = json.loads((root / "examples" / "sweep-small.json").read_text())
client = Client(args.server, token=args.token)
job = client.submit("dynamic-tension", request["inputs"], request["sweep"], name=request["name"], reuse=True)
client.wait(job, progress=True)
table = client.summary(job)

if plt is None:
    client.plot(job, args.out, x="loading.strain_rate", y="peak_stress",
                title=f"Peak stress vs strain rate (job {job})")
    print(f"{args.out} (rendered by the server: matplotlib is not installed)")
else:
    fig, ax = plt.subplots(figsize=(5.5, 4))
    for field, rows in table.groupby("loading.initial_velocity"):
        rows = rows.dropna(subset=["peak_stress"]).sort_values("loading.strain_rate")
        ax.plot(rows["loading.strain_rate"], rows["peak_stress"] / 1e6, marker="o", label=field)
    ax.set_xscale("log")
    ax.set_xlabel("strain rate (1/s)")
    ax.set_ylabel("peak stress (MPa)")
    ax.set_title(f"Peak stress vs strain rate (job {job})")
    ax.legend(title="initial velocity field")
    fig.tight_layout()
    fig.savefig(args.out, dpi=150)
    print(args.out)
