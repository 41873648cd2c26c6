#!/usr/bin/env python3
"""Kill trials of the job server's checkpoints (docs/checkpoints.md).

Runs one dynamic-tension run through rupture-server while killing the server with SIGKILL at
random moments (every 1.5 to 4 s) and starting it again on the same data directory, until the run
is successful; then runs the same spec uninterrupted with `rupture run` and compares the two
summaries value by value (all but the wall time and the cache flags). Prints one JSON line: the
kills, the run's attempts and resumes, the step it last continued from, whether the summaries are
identical, and the seconds of each.

usage: bench/checkpoint_kill_trials.py BUILD_DIR [--kills N] [--strain-rate R] [--seed S]
"""
import json
import random
import re
import subprocess
import sys
import tempfile
import time
import urllib.request
from pathlib import Path

build = Path(sys.argv[1])
kills = int(sys.argv[sys.argv.index("--kills") + 1]) if "--kills" in sys.argv else 5
rate = float(sys.argv[sys.argv.index("--strain-rate") + 1]) if "--strain-rate" in sys.argv else 1.5e4
seed = int(sys.argv[sys.argv.index("--seed") + 1]) if "--seed" in sys.argv else int(time.time())
random.seed(seed)
root = Path(__file__).resolve().parent.parent
spec = json.loads((root / "examples" / "dynamic-tension-small.json").read_text())
spec["loading"] = {"strain_rate": rate, "initial_velocity": "VL"}
spec["run"].pop("snapshot_strains", None)
spec["run"]["checkpoint_interval_s"] = 0.5
HOW_IT_RAN = {"wall_time_s", "sample_from_cache"}


def call(port, path, body=None):
    data = json.dumps(body).encode() if body is not None else None
    req = urllib.request.Request(f"http://127.0.0.1:{port}{path}", data=data,
                                 headers={"Content-Type": "application/json"} if data else {})
    return json.load(urllib.request.urlopen(req, timeout=30))


def start(data):
    server = subprocess.Popen([str(build / "server" / "rupture-server"), "--port", "0", "--data-dir", data,
                               "--workers", "1", "--threads-per-run", "1"],
                              stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    port = int(re.search(r":(\d+)$", server.stdout.readline().strip()).group(1))
    return server, port


with tempfile.TemporaryDirectory() as tmp:
    t0 = time.time()
    server, port = start(f"{tmp}/data")
    inputs = {k: v for k, v in spec.items() if k != "scenario"}
    job = call(port, "/processes/dynamic-tension/execution", {"inputs": inputs})["jobID"]
    done = 0
    while True:
        time.sleep(random.uniform(1.5, 4.0))
        run = call(port, f"/jobs/{job}")["runs"][0]
        if run["status"] == "successful" or done == kills:
            break
        server.kill()
        server.wait()
        done += 1
        server, port = start(f"{tmp}/data")
    while (run := call(port, f"/jobs/{job}")["runs"][0])["status"] not in ("successful", "failed"):
        time.sleep(0.5)
    served = time.time() - t0
    server.terminate()
    server.wait()

    (Path(tmp) / "spec.json").write_text(json.dumps(spec))
    t1 = time.time()
    plain = subprocess.run([str(build / "engine" / "rupture"), "run", f"{tmp}/spec.json", "-o", f"{tmp}/whole.h5",
                            "--threads", "1", "--json"], capture_output=True, text=True, check=True)
    uninterrupted = time.time() - t1
    whole = json.loads(plain.stdout)
    differing = sorted(k for k in whole if k not in HOW_IT_RAN and whole[k] != run.get("summary", {}).get(k))
    print(json.dumps({"kills": done, "status": run["status"], "attempts": run.get("attempts", 1),
                      "resumes": run.get("resumes", 0), "resumed_from_step": run.get("resumed_from_step"),
                      "summary_identical": not differing, "differing": differing, "seed": seed,
                      "strain_rate": rate, "served_s": round(served, 1),
                      "uninterrupted_s": round(uninterrupted, 1)}))
