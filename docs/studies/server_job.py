"""Submitting a study's request to a running rupture-server and reading its job back, for the
study scripts of docs/studies/. Standard library only."""
import argparse
import json
import math
import os
import time
import urllib.request

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def get(url):
    with urllib.request.urlopen(url) as r:
        return json.load(r)


def submit(server, request, scenario="tank-impact"):
    """POSTs the request file (a path under the repository) and returns the new job's id."""
    with open(os.path.join(ROOT, request), "rb") as f:
        body = f.read()
    req = urllib.request.Request(f"{server}/processes/{scenario}/execution", data=body,
                                 headers={"Content-Type": "application/json"}, method="POST")
    with urllib.request.urlopen(req) as r:
        return json.load(r)["jobID"]


def wait(server, job):
    """The job's status once it has ended (successful, failed or dismissed)."""
    while True:
        status = get(f"{server}/jobs/{job}")
        if status["status"] in ("successful", "failed", "dismissed"):
            return status
        time.sleep(5)


def study_job(doc, request, table):
    """The study's command line (--server, --job, --request, --out) and its job: submits the
    request (a path under the repository; --request another of the same shape) unless --job names
    a finished one, and waits for it to end. Returns (server, job, status, out), out the Markdown
    table's path (default docs/studies/table)."""
    ap = argparse.ArgumentParser(description=doc, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--server", default="http://127.0.0.1:8080")
    ap.add_argument("--job")
    ap.add_argument("--request", default=request)
    ap.add_argument("--out", default=os.path.join(ROOT, "docs", "studies", table))
    a = ap.parse_args()
    job = a.job or submit(a.server, a.request)
    return a.server, job, wait(a.server, job), a.out


def write_table(out, lines):
    """Writes the generated table and prints its path."""
    with open(out, "w") as f:
        f.write("\n".join(lines) + "\n")
    print(out)


def job_line(job, status):
    """One sentence on the job: its runs, the commit and host it ran on, its wall time."""
    prov = status.get("provenance", {})
    commit = prov.get("git_commit", "?")
    # The short hash, and whether the build had uncommitted changes.
    commit = commit[:7] + (" (a build with uncommitted changes on top of it)" if commit.endswith("-dirty") else "")
    return (f"Job {job} ({status['status']}, {status['runs_by_status']['successful']} of {status['runs_total']} runs), "
            f"commit {commit}, host processor {prov.get('host_processor', '?')}, "
            f"{prov.get('threads_per_run', '?')} thread per run, wall time of the job {status.get('elapsed_s', 0):.0f} s "
            f"(started {status.get('started', '?')}).")


def fmt(v, scale=1.0, digits=0, unit=""):
    """v × scale with the given decimals; "–" for a missing value."""
    if v is None or (isinstance(v, float) and math.isnan(v)):
        return "–"
    return f"{v * scale:.{digits}f}{unit}"
