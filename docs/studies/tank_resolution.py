#!/usr/bin/env python3
"""Convergence of seed 002's tank tests in the fluid's spacing (issue #27, item 4;
docs/tank-impact.md#resolution): E14A5, E14A2, E20A5, E20A2, FUA5 and TF14A5 from their coarse example
files (tank-impact-*-coarse.json: the plate as measured, uniform 2 mm with pinballs) at fluid dx = 4, 3 and 2 mm (the seed's about 2 mm), the plate at its 2 mm spacing, and the
table of what the seed measured: the first pressure peak, the jet (front, outflow at the end, the
largest mean), the tongue, the time to fracture and the deflection, each with its change from the
finest fluid.

    python3 docs/studies/tank_resolution.py build/engine/rupture [--threads 2] [--work DIR]
        [--only TEST ...] [--set JSON] [--out docs/studies/tank-resolution.md]

--set merges a JSON object into every spec, to run the same study on a variant: the tied carriage
of docs/tank-impact.md#impactor is
    --set '{"impactor": {"contact": "tied"}}' --out docs/studies/tank-resolution-tied.md

Each run is `rupture run SPEC -o RUN.h5 --json --threads N`, one after the other (about 70 minutes
on two cores in all). The steady outflow is the summary's mean_outflow_speed (for runs of a build
before it, the same mean read from the run file with h5py: /usr/bin/python3 with python3-h5py). A finished run in --work whose spec has not changed is reused (the run file
is named by the hash of the spec and of the binary), so an interrupted study continues where it stopped.
"""
import argparse
import hashlib
import json
import os
import subprocess
import sys
import time

from host import host_processor
from tank_first_peak import SEED, angle, fracture, merge

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
TESTS = ["E14A5", "E14A2", "E20A5", "E20A2", "FUA5", "TF14A5"]
FLUID = [0.004, 0.003, 0.002]
SEED = dict(SEED, E20A2="jet about 45 m/s (film); 44 m/s simulated")


def finished(rupture, test, dx, work, variant):
    """The summary of a finished run in work for this spec and binary, or None."""
    return run(rupture, test, dx, 0, work, variant, start=False)


def run(rupture, test, dx, threads, work, variant, start=True):
    with open(os.path.join(ROOT, "examples", f"tank-impact-{test}-coarse.json")) as f:
        spec = merge(merge(json.load(f), variant), {"resolution": {"spacing": dx}})
    text = json.dumps(spec, sort_keys=True)
    with open(rupture, "rb") as f:  # a rebuilt binary reruns
        binary = hashlib.sha256(f.read()).hexdigest()
    key = hashlib.sha256((text + binary).encode()).hexdigest()[:12]
    stem = os.path.join(work, f"{test}-{dx * 1e3:g}mm-{key}")
    if os.path.exists(stem + ".summary.json"):
        with open(stem + ".summary.json") as f:
            summary = json.load(f)
        summary["mean_outflow_speed"] = steady_outflow(summary, stem + ".h5")
        return summary
    if not start:
        return None
    with open(stem + ".json", "w") as f:
        f.write(text)
    start = time.time()
    out = subprocess.run([rupture, "run", stem + ".json", "-o", stem + ".h5", "--json", "--force",
                          "--threads", str(threads)], capture_output=True, text=True)
    if out.returncode != 0:
        raise RuntimeError(f"{test} at dx {dx}: rupture run exited {out.returncode}: {out.stderr.strip()}")
    summary = json.loads(out.stdout)
    summary["_wall"] = time.time() - start
    summary["mean_outflow_speed"] = steady_outflow(summary, stem + ".h5")
    with open(stem + ".summary.json", "w") as f:
        json.dump(summary, f)
    return summary


def steady_outflow(s, run_file):
    """The summary's mean_outflow_speed; for a run file from a build before it, the same mean read
    from the file's outflow_speed series (rows of the run's second half with water leaving), if
    h5py is at hand."""
    if s.get("mean_outflow_speed") is not None or "final_outflow_speed" not in s:
        return s.get("mean_outflow_speed")
    try:
        import h5py
    except ImportError:
        return None
    with h5py.File(run_file, "r") as f:
        t, v = f["series/time"][:], f["series/outflow_speed"][:]
    rows = [x for x, ti in zip(v, t) if ti >= 0.5 * s["final_time"] * (1 - 1e-12) and x != 0]
    return sum(rows) / len(rows) if rows else None


def value(s, key, scale=1.0, digits=1):
    v = s.get(key)
    return "-" if v is None else f"{v * scale:.{digits}f}"


def change(s, finest, key):
    """Relative change from the finest fluid, or '' when either is missing."""
    a, b = s.get(key), finest.get(key)
    return "" if a is None or b is None or b == 0 else f" ({(a - b) / b * 100:+.1f} %)"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("rupture")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--work", default=os.path.join(ROOT, "build", "tank-resolution"))
    ap.add_argument("--only", nargs="*", help="tests to run (default: all)")
    ap.add_argument("--out", default=os.path.join(ROOT, "docs", "studies", "tank-resolution.md"))
    ap.add_argument("--set", default="{}", help="a JSON object merged into every spec (a variant of the examples)")
    ap.add_argument("--table-only", action="store_true",
                    help="write the table from the runs already finished in --work; the others are marked not run")
    a = ap.parse_args()
    os.makedirs(a.work, exist_ok=True)
    rupture = os.path.abspath(a.rupture)
    tests = [t for t in TESTS if not a.only or t in a.only]
    variant = json.loads(a.set)
    if not isinstance(variant, dict):
        ap.error(f"--set must be a JSON object, not {a.set}")
    results = {}
    for test in tests:
        for dx in FLUID:
            s = (finished(rupture, test, dx, a.work, variant) if a.table_only
                 else run(rupture, test, dx, a.threads, a.work, variant))
            results[(test, dx)] = s
            if s is None:
                continue
            print(f"{test} dx {dx * 1e3:g} mm: first peak {s['first_pressure_peak'] / 1e5:.1f} bar, "
                  f"front {s.get('jet_front_speed')}, {s['_wall']:.0f} s", file=sys.stderr)
    # The binary's own commit (`rupture --version`), "-dirty" when it was built with uncommitted changes.
    version = subprocess.run([rupture, "--version"], capture_output=True, text=True).stdout
    commit = next((l.split()[1] for l in version.splitlines() if l.startswith("commit ")), "?")
    commit = commit[:7] + (" (built with uncommitted changes on top of it)" if commit.endswith("-dirty") else "")
    lines = [
        "<!-- generated by docs/studies/tank_resolution.py; do not edit by hand -->",
        f"Measured at commit {commit} on {time.strftime('%Y-%m-%d')}, host processor: {host_processor()}; "
        f"{a.threads} threads per run, one study run at a time, 3 ms, each example file as given (plate spacing 2 mm) "
        + (f"with {json.dumps(variant)} merged in, " if variant else "")
        + "but for the fluid's spacing dx. In brackets: the change from dx = 2 mm, the seed's. Wall: as measured, "
        "on a host not necessarily quiet (an upper bound).",
        "",
        "| test | fluid dx (mm) | particles | first peak (bar) | jet front at 3 ms (m/s) | steady outflow, 1.5-3 ms (m/s) | "
        "largest mean jet (m/s) | tongue (°) | fracture (ms) | max deflection (mm) | wall (s) | seed |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for test in tests:
        finest = results[(test, FLUID[-1])] or {}
        for dx in FLUID:
            s = results[(test, dx)]
            if s is None:
                lines.append(f"| {test} | {dx * 1e3:g} | not run | | | | | | | | | {SEED[test]} |")
                continue
            lines.append(
                f"| {test} | {dx * 1e3:g} | {s['fluid_particles']} | "
                f"{s['first_pressure_peak'] / 1e5:.0f}{change(s, finest, 'first_pressure_peak')} | "
                f"{value(s, 'jet_front_speed')}{change(s, finest, 'jet_front_speed')} | "
                f"{value(s, 'mean_outflow_speed')}{change(s, finest, 'mean_outflow_speed')} | "
                f"{value(s, 'max_jet_speed')}{change(s, finest, 'max_jet_speed')} | {angle(s)} | {fracture(s)} | "
                f"{s['max_deflection'] * 1e3:.3f}{change(s, finest, 'max_deflection')} | {s['_wall']:.0f} | {SEED[test]} |")
    with open(a.out, "w") as f:
        f.write("\n".join(lines) + "\n")
    print(a.out)


if __name__ == "__main__":
    main()
