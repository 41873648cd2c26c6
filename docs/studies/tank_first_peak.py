#!/usr/bin/env python3
"""The study of docs/tank-impact.md#what-sets-the-first-peak: seed 002's tests E14A5, E14A2 and
E20A5 (and, for the plate's spacing, FUA5, TF14A5 and FXA5) run from their coarse example files (tank-impact-*-coarse.json, fluid 4 mm) with one
thing changed at a time (impactor model, piston length, contact stiffness, the plate's clamp, fluid
and plate resolution, gauge position, contact method), and the table of the first pressure peak, the largest
jet speed, the piston face's largest speed, the tongue, the fracture and the deflection.

    python3 docs/studies/tank_first_peak.py build/engine/rupture [--jobs 2] [--only NAME ...]
        [--out docs/studies/tank-first-peak.md]

Each run is `rupture run EXAMPLE -o RUN.h5 --json --threads 1` on a modified copy of the example;
the table is written as Markdown with the commit and the host processor. Runs in parallel on
--jobs processes (one thread each). The 2 mm rows take about 15 minutes of one core each.
"""
import argparse
import concurrent.futures
import copy
import json
import os
import subprocess
import sys
import tempfile
import time

from host import host_processor

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SEED = {  # the seed's measurements (Caleyron et al. 2013, §3.1.1, §5.1-5.3)
    "E14A5": "first peak 210-277 bar",
    "E14A2": "first peak 58-83 bar",
    "E20A5": "jet about 92 m/s (film); 97 m/s simulated",
    "FUA5": "tongue about 50°",
    "TF14A5": "fracture at about 1.5 ms, along the rim",
    "FXA5": "cracks from the notches, not through",
}


def variants():
    """(name, test, description, change) in the order of the table."""
    out = []
    def add(name, tests, text, change):
        for t in tests:
            out.append((name, t, text, change))
    tests = ["E14A5", "E14A2", "E20A5"]
    add("rigid", tests, "carriage and piston one rigid body (before issue #27)", {"impactor": {"model": "rigid"}})
    add("two_body", tests, "carriage and a rigid 100 mm steel piston, contact", {"impactor": {"model": "two_body"}})
    add("elastic", tests + ["FUA5", "TF14A5", "FXA5"], "carriage and an elastic 100 mm steel piston, contact (default)", {})
    add("rim clamp", tests + ["FUA5", "TF14A5", "FXA5"], "spot face clamped at its rim (Calculation 1) instead of its thick bottom held at 140 mm",
        {"plate": {"clamp": "rim"}})
    add("piston 50 mm", ["E14A5", "E14A2"], "elastic piston 50 mm long", {"impactor": {"piston": {"length": 0.05}}})
    add("piston 200 mm", ["E14A5", "E14A2"], "elastic piston 200 mm long", {"impactor": {"piston": {"length": 0.2}}})
    add("soft contact", ["E14A5"], "contact stiffness / 10 (E A / 50 mm)",
        {"impactor": {"contact_stiffness": 211e9 * 3.14159265358979 * 0.04 ** 2 / 0.05}})
    add("gauge 5 mm", ["E14A5"], "gauge 5 mm above the plate (instead of 10)", {"gauge": [0.035, 0.0, 0.0125 + 0.005]})
    add("gauge on axis", ["E14A5"], "gauge on the axis, 20 mm above the plate", {"gauge": [0.0, 0.0, 0.0125 + 0.02]})
    add("master_slave", ["E14A5"], "master-slave contact (instead of pinball)", {"contact": {"method": "master_slave"}})
    add("dx 3 mm", ["E14A5", "E14A2", "E20A5"], "fluid spacing 3 mm (instead of 4)", {"resolution": {"spacing": 0.003}})
    add("dx 2 mm", ["E14A5"], "fluid spacing 2 mm, the seed's", {"resolution": {"spacing": 0.002}})
    # (not E14A5: a shell node stands for the whole thickness, so its spacing is at least e_p/20 = 1.25 mm)
    add("plate 1 mm", ["FUA5", "TF14A5", "FXA5"], "plate spacing 1 mm (instead of 2)", {"plate": {"spacing": 0.001}})
    return out


def merge(base, change):
    out = copy.deepcopy(base)
    for k, v in change.items():
        if isinstance(v, dict) and isinstance(out.get(k), dict):
            out[k] = merge(out[k], v)
        else:
            out[k] = copy.deepcopy(v)
    return out


def run_one(rupture, test, change, workdir):
    with open(os.path.join(ROOT, "examples", f"tank-impact-{test}-coarse.json")) as f:
        spec = merge(json.load(f), change)
    spec_path = os.path.join(workdir, "spec.json")
    with open(spec_path, "w") as f:
        json.dump(spec, f)
    start = time.time()
    out = subprocess.run([rupture, "run", spec_path, "-o", os.path.join(workdir, "run.h5"), "--json", "--threads", "1"],
                         capture_output=True, text=True)
    if out.returncode != 0:
        raise RuntimeError(f"{test} {change}: rupture run exited {out.returncode}: {out.stderr.strip()}")
    summary = json.loads(out.stdout)
    summary["_wall"] = time.time() - start
    return summary


def angle(s):
    a = s.get("final_tongue_angle")
    return "-" if a is None else f"{a * 180 / 3.141592653589793:.1f}"


def fracture(s):
    t = s.get("time_to_fracture")
    return "none" if t is None else f"{t * 1e3:.2f} ({s['fractured_nodes']} nodes)"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("rupture")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--only", nargs="*", help="variant names to run (default: all)")
    ap.add_argument("--out", default=os.path.join(ROOT, "docs", "studies", "tank-first-peak.md"))
    a = ap.parse_args()
    chosen = [v for v in variants() if not a.only or v[0] in a.only]
    results = {}
    with tempfile.TemporaryDirectory() as tmp, concurrent.futures.ProcessPoolExecutor(a.jobs) as pool:
        futures = {}
        for k, (name, test, _, change) in enumerate(chosen):
            d = os.path.join(tmp, str(k))
            os.makedirs(d)
            futures[pool.submit(run_one, a.rupture, test, change, d)] = (name, test)
        for fut in concurrent.futures.as_completed(futures):
            name, test = futures[fut]
            results[(name, test)] = fut.result()
            print(f"{name} {test}: first peak {results[(name, test)]['first_pressure_peak'] / 1e5:.1f} bar", file=sys.stderr)
    commit = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip()
    lines = [
        "<!-- generated by docs/studies/tank_first_peak.py; do not edit by hand -->",
        f"Measured at commit {commit} on {time.strftime('%Y-%m-%d')}, host processor: {host_processor()}; "
        "one thread per run, 3 ms, each example file as given but for the change named.",
        "",
        "| change | test | first peak (bar) | / ρ0 c0 V | at (ms) | max jet (m/s) | max piston face speed (m/s) | tongue (°) | fracture (ms) | max deflection (mm) | wall (s) | seed |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for name, test, text, _ in chosen:
        s = results[(name, test)]
        jet = s.get("max_jet_speed")
        lines.append(
            f"| {name}: {text} | {test} | {s['first_pressure_peak'] / 1e5:.0f} | "
            f"{s['first_pressure_peak'] / s['acoustic_pressure']:.2f} | {s['time_of_first_peak'] * 1e3:.3f} | "
            f"{'-' if jet is None else f'{jet:.1f}'} | {s['max_piston_face_speed']:.2f} | {angle(s)} | {fracture(s)} | "
            f"{s['max_deflection'] * 1e3:.3f} | {s['_wall']:.0f} | {SEED[test]} |")
    with open(a.out, "w") as f:
        f.write("\n".join(lines) + "\n")
    print(a.out)


if __name__ == "__main__":
    main()
