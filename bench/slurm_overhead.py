#!/usr/bin/env python3
"""Overhead of the Slurm executor against the local one, for a tiny run (submission to result).

Starts rupture-server once with --executor local and once with --executor slurm (needs a Slurm
cluster: SLURM_CONF, e.g. from deploy/slurm/test-cluster.sh), submits the same one-run job N times
in turn to each, and prints the median seconds from POST to `successful`, with the run's own wall
time, as one JSON line.

usage: bench/slurm_overhead.py BUILD_DIR [--repeats N]
"""
import json
import statistics
import subprocess
import sys
import tempfile
import time
import urllib.request
from pathlib import Path

build = Path(sys.argv[1])
repeats = int(sys.argv[sys.argv.index("--repeats") + 1]) if "--repeats" in sys.argv else 5
root = Path(__file__).resolve().parent.parent
spec = json.loads((root / "examples" / "dynamic-tension-small.json").read_text())
spec.pop("scenario")
spec["loading"] = {"strain_rate": 1e7, "initial_velocity": "VL"}


def call(port, path, body=None, method=None):
    data = json.dumps(body).encode() if body is not None else None
    req = urllib.request.Request(f"http://127.0.0.1:{port}{path}", data=data, method=method,
                                 headers={"Content-Type": "application/json"} if data else {})
    return json.load(urllib.request.urlopen(req))


def measure(executor):
    with tempfile.TemporaryDirectory() as tmp:
        args = [str(build / "server" / "rupture-server"), "--port", "0", "--data-dir", f"{tmp}/data",
                "--executor", executor, "--workers", "1"]
        if executor == "slurm":
            args += ["--shared-dir", f"{tmp}/shared"]
        server = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
        port = int(server.stdout.readline().strip().rsplit(":", 1)[1])
        totals, walls = [], []
        try:
            for _ in range(repeats):
                start = time.monotonic()
                job = call(port, "/processes/dynamic-tension/execution", {"inputs": spec})["jobID"]
                while (doc := call(port, f"/jobs/{job}"))["status"] not in ("successful", "failed"):
                    time.sleep(0.02)
                totals.append(time.monotonic() - start)
                walls.append(doc["runs"][0]["summary"]["wall_time_s"])
        finally:
            server.terminate()
            server.wait()
        return statistics.median(totals), statistics.median(walls)


local_total, local_wall = measure("local")
slurm_total, slurm_wall = measure("slurm")
print(json.dumps({"workload": "slurm-overhead", "repeats": repeats,
                  "local_submission_to_result_s": round(local_total, 3), "local_run_wall_s": round(local_wall, 3),
                  "slurm_submission_to_result_s": round(slurm_total, 3), "slurm_run_wall_s": round(slurm_wall, 3),
                  "slurm_overhead_s": round((slurm_total - slurm_wall) - (local_total - local_wall), 3)}))
