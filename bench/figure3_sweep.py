#!/usr/bin/env python3
"""Wall time of the seed's Figure-3 study through the job server, first run included.

Starts rupture-server on a free port with a fresh data directory (so a fresh sample and
preliminary-run cache: the packing and the VH preliminary run are part of the time), submits
examples/dynamic-tension-seed.json as a grid over strain rates 1e5, 1e6, 4e6, 1e7 /s and initial
fields V0, VL, VH (12 runs), waits for the job, and prints one JSON line: total wall seconds from
POST to the end of the last run, the per-run wall times and peak stresses, and the machine's load
average at start and end (the machine may be shared: say so when quoting the figure).

usage: bench/figure3_sweep.py BUILD_DIR [--workers N] [--threads-per-run N] [--spec FILE] [--element-radius R]
  --spec takes another dynamic-tension spec (default examples/dynamic-tension-seed.json), e.g.
  examples/dynamic-tension-seed-random.json (the figures of bench/README.md up to 2026-11-29
  were measured on it, then the default); --element-radius overrides sample.element_radius
  (m) of a random packing for a quick check on a coarser sample.
Debian's python3 only (no third-party modules).
"""
import json
import os
import subprocess
import sys
import tempfile
import time
import urllib.request
from pathlib import Path


def option(name, default):
    return sys.argv[sys.argv.index(name) + 1] if name in sys.argv else default


build = Path(sys.argv[1])
workers = option("--workers", str(os.cpu_count() or 2))
threads = option("--threads-per-run", "1")
root = Path(__file__).resolve().parent.parent
spec = json.loads(Path(option("--spec", str(root / "examples" / "dynamic-tension-seed.json"))).read_text())
spec.pop("scenario")
spec["run"].pop("snapshot_strains", None)  # the study needs the curves and summaries, not the fields
if "--element-radius" in sys.argv:
    spec["sample"]["element_radius"] = float(option("--element-radius", "0"))
body = {"name": "seed Figure 3: strain rate x initial velocity field",
        "inputs": spec,
        "sweep": {"loading.strain_rate": [1e5, 1e6, 4e6, 1e7], "loading.initial_velocity": ["V0", "VL", "VH"]},
        "sweep_mode": "grid"}


def call(port, path, payload=None):
    data = json.dumps(payload).encode() if payload is not None else None
    req = urllib.request.Request(f"http://127.0.0.1:{port}{path}", data=data,
                                 headers={"Content-Type": "application/json"} if data else {})
    return json.load(urllib.request.urlopen(req))


with tempfile.TemporaryDirectory() as tmp:
    env = dict(os.environ, RUPTURE_CACHE_DIR=f"{tmp}/data/cache")
    server = subprocess.Popen([str(build / "server" / "rupture-server"), "--port", "0", "--data-dir", f"{tmp}/data",
                               "--workers", workers, "--threads-per-run", threads],
                              stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True, env=env)
    try:
        port = int(server.stdout.readline().strip().rsplit(":", 1)[1])
        load_start = os.getloadavg()[0]
        start = time.monotonic()
        job = call(port, "/processes/dynamic-tension/execution", body)["jobID"]
        while (doc := call(port, f"/jobs/{job}"))["status"] not in ("successful", "failed", "dismissed"):
            time.sleep(0.5)
        total = time.monotonic() - start
        runs = []
        for r in doc["runs"]:
            s = r.get("summary") or {}
            runs.append({"swept": r.get("swept"), "status": r.get("status"),
                         "wall_time_s": s.get("wall_time_s"), "peak_stress": s.get("peak_stress"),
                         "crack_onset_strain": s.get("crack_onset_strain"),
                         "sample_from_cache": s.get("sample_from_cache")})
        print(json.dumps({"workload": "figure3-sweep", "status": doc["status"], "runs": len(runs),
                          "workers": int(workers), "threads_per_run": int(threads),
                          "sample": spec["sample"],
                          "wall_s": round(total, 1), "load_average_start": load_start,
                          "load_average_end": os.getloadavg()[0], "per_run": runs}))
    finally:
        server.terminate()
        server.wait()
