#!/usr/bin/env python3
"""The server's resident memory through the amplification probe of issue 56: one POST under 1 MiB
(a sweep of 1,000 runs of a 900 KB description), then DELETE of the job.

Starts rupture-server (nothing runs: --min-free-bytes is set beyond any disk), reads VmRSS from
/proc/PID/status before the POST, after it, and after the DELETE, and prints one JSON line (MB).

usage: bench/request_memory.py PATH/TO/rupture-server [--jobs N]
"""
import json
import re
import subprocess
import sys
import tempfile
import time
import urllib.request
from pathlib import Path

server = sys.argv[1]
jobs = int(sys.argv[sys.argv.index("--jobs") + 1]) if "--jobs" in sys.argv else 1
root = Path(__file__).resolve().parent.parent
inputs = json.loads((root / "examples" / "dynamic-tension-small.json").read_text())
inputs.pop("scenario")
inputs["description"] = "d" * 900_000
body = {"inputs": inputs, "sweep": {"loading.strain_rate": [1e5 + 100.0 * k for k in range(1000)]}}


def call(port, path, payload=None, method=None):
    data = json.dumps(payload).encode() if payload is not None else None
    req = urllib.request.Request(f"http://127.0.0.1:{port}{path}", data=data, method=method,
                                 headers={"Content-Type": "application/json"} if data else {})
    return json.load(urllib.request.urlopen(req, timeout=600))


def resident_mb(pid):
    status = Path(f"/proc/{pid}/status").read_text()
    return int(re.search(r"VmRSS:\s+(\d+) kB", status).group(1)) / 1024


with tempfile.TemporaryDirectory() as tmp:
    proc = subprocess.Popen([server, "--port", "0", "--data-dir", f"{tmp}/data", "--workers", "1",
                             "--min-free-bytes", str(2**62)], stdout=subprocess.PIPE, text=True)
    try:
        port = int(re.search(r":(\d+)", proc.stdout.readline()).group(1))
        call(port, "/health")
        before = resident_mb(proc.pid)
        posted, deleted = [], []
        start = time.monotonic()
        for _ in range(jobs):
            job = call(port, "/processes/dynamic-tension/execution", body)["jobID"]
            posted.append(resident_mb(proc.pid))
            call(port, f"/jobs/{job}", method="DELETE")
            deleted.append(resident_mb(proc.pid))
        print(json.dumps({"body_bytes": len(json.dumps(body)), "jobs": jobs, "rss_before_mb": round(before, 1),
                          "rss_after_post_mb": [round(x, 1) for x in posted],
                          "rss_after_delete_mb": [round(x, 1) for x in deleted],
                          "seconds": round(time.monotonic() - start, 2)}))
    finally:
        proc.terminate()
        proc.wait(timeout=30)
