#!/usr/bin/env python3
"""Seed 000's Table 2 on the seed's own sample, one hypothesis at a time
(docs/dynamic-tension.md, "Reproducing the seed's Table 2"; issue #28 item 1).

Each variant is examples/dynamic-tension-seed.json (or its random-packing twin) changed in one
respect, run as the quasi-static `elastic-properties` scenario (elastic test, then tension to
failure) on sample seeds 1-5 with `rupture run`, two runs at a time, one thread each; the table gives
the mean +- sample standard deviation and the per-seed values.

    python3 docs/studies/seed000_table2.py [--rupture build/engine/rupture] [--work DIR]
        [--out docs/studies/seed000-table2.md] [--jobs 2] [--only NAME[,NAME...]]

Finished runs in --work (default /tmp/seed000-table2) are reused. About 31 minutes on two cores
(1875 s on 2026-11-29; the random packings take 3 minutes a sample, the lattices about one). Standard library only.
"""
import argparse
import concurrent.futures
import copy
import hashlib
import json
import os
import statistics
import subprocess
import time

from host import host_processor

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SEEDS = [1, 2, 3, 4, 5]


def example(name):
    with open(os.path.join(ROOT, "examples", name)) as f:
        spec = json.load(f)
    for key in ("loading", "run", "description"):
        spec.pop(key, None)
    spec["scenario"] = "elastic-properties"
    return spec


def with_changes(base, changes, removals=()):
    spec = copy.deepcopy(base)
    for path, value in changes.items():
        node = spec
        *head, last = path.split(".")
        for key in head:
            node = node.setdefault(key, {})
        node[last] = value
    for path in removals:
        node = spec
        *head, last = path.split(".")
        for key in head:
            node = node[key]
        node.pop(last, None)
    return spec


SEED = example("dynamic-tension-seed.json")
RANDOM = example("dynamic-tension-seed-random.json")
END = {"material.beam.bending_stress": "end_moment"}
ONE_PORE = {"sample.porosity": 0.0314159, "sample.pore_radius": [1e-7, 1e-7]}  # one pore of 100 nm

# name, label, spec, sample seeds
VARIANTS = [
    ("random_end", "random packing (collective rearrangement), end moment, t = R_DE: `dynamic-tension-seed-random.json`",
     RANDOM, SEEDS),
    ("random_relative", "random packing, relative-rotation moment, t = R_DE",
     with_changes(RANDOM, {"material.beam.bending_stress": "relative_rotation"}), SEEDS),
    ("lattice_end", "triangular, end moment, t = 2 R_DE", with_changes(SEED, END), SEEDS),
    ("lattice_relative", "triangular, relative-rotation moment, t = 2 R_DE: **`dynamic-tension-seed.json`**",
     SEED, SEEDS),
    ("lattice_relative_seeds_6_10", "the same, sample seeds 6-10", SEED, [6, 7, 8, 9, 10]),
    ("lattice_relative_6.6nm", "the same at R_DE = 6.6 nm (a coarser stand-in)",
     with_changes(SEED, {"sample.spacing": 13.2e-9, "sample.thickness": 13.2e-9}), SEEDS),
    ("lattice_relative_12nm", "the same at R_DE = 12 nm (the old reduced sample)",
     with_changes(SEED, {"sample.spacing": 24e-9, "sample.thickness": 24e-9}), SEEDS),
    ("lattice_end_6.6nm", "triangular, end moment, R_DE = 6.6 nm",
     with_changes(SEED, {**END, "sample.spacing": 13.2e-9, "sample.thickness": 13.2e-9}), SEEDS),
    ("lattice_end_12nm", "triangular, end moment, R_DE = 12 nm",
     with_changes(SEED, {**END, "sample.spacing": 24e-9, "sample.thickness": 24e-9}), SEEDS),
    ("one_pore_relative", "one pore of 100 nm, relative-rotation moment, R_DE = 3.3 nm",
     with_changes(SEED, ONE_PORE), [1, 2]),
    ("one_pore_end", "one pore of 100 nm, end moment, R_DE = 3.3 nm", with_changes(SEED, {**ONE_PORE, **END}), [1, 2]),
    ("one_pore_end_12nm", "one pore of 100 nm, end moment, R_DE = 12 nm",
     with_changes(SEED, {**ONE_PORE, **END, "sample.spacing": 24e-9, "sample.thickness": 24e-9}), [1, 2]),
    ("dense_relative", "dense matrix (no pores), relative-rotation moment",
     with_changes(SEED, {"sample.porosity": 0}, ["sample.pore_radius"]), [1]),
    ("dense_end", "dense matrix (no pores), end moment",
     with_changes(SEED, {**END, "sample.porosity": 0}, ["sample.pore_radius"]), [1]),
]

COLUMNS = [("young_modulus", 1e-9, "E (GPa)", "{:.1f}"), ("poisson_ratio", 1, "ν", "{:.3f}"),
           ("tensile_strength", 1e-6, "σ_R (MPa)", "{:.1f}"), ("crack_onset_strain", 1e4, "onset (1e-4)", "{:.2f}"),
           ("mean_coordination", 1, "z", "{:.2f}")]


def run_one(rupture, work, name, spec, seed):
    spec = with_changes(spec, {"sample.seed": seed})
    # The file name carries the spec's hash, so a changed variant or example is run again, not reused.
    digest = hashlib.sha256(json.dumps(spec, sort_keys=True).encode()).hexdigest()[:10]
    stem = os.path.join(work, f"{name}-s{seed}-{digest}")
    if os.path.exists(stem + ".json.out"):
        with open(stem + ".json.out") as f:
            return json.load(f)
    with open(stem + ".json", "w") as f:
        json.dump(spec, f, indent=1)
    out = subprocess.run([rupture, "run", stem + ".json", "-o", stem + ".h5", "--threads", "1", "--json", "--force"],
                         capture_output=True, text=True)
    if out.returncode != 0:
        raise RuntimeError(f"{name}, sample seed {seed}: rupture run exited {out.returncode}: {out.stderr.strip()}")
    summary = json.loads(out.stdout[out.stdout.index("{"):])
    with open(stem + ".json.out", "w") as f:
        json.dump(summary, f)
    return summary


def cell(values, scale, form):
    v = [x * scale for x in values]
    if len(v) == 1:
        return form.format(v[0])
    return f"{form.format(statistics.mean(v))} ± {form.format(statistics.stdev(v))}"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--rupture", default=os.path.join(ROOT, "build", "engine", "rupture"))
    ap.add_argument("--work", default="/tmp/seed000-table2")
    ap.add_argument("--out", default=os.path.join(ROOT, "docs", "studies", "seed000-table2.md"))
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--only", default="")
    a = ap.parse_args()
    os.makedirs(a.work, exist_ok=True)
    only = set(filter(None, a.only.split(",")))
    variants = [v for v in VARIANTS if not only or v[0] in only]
    start = time.time()
    with concurrent.futures.ThreadPoolExecutor(a.jobs) as pool:
        futures = {(name, seed): pool.submit(run_one, a.rupture, a.work, name, spec, seed)
                   for name, _, spec, seeds in variants for seed in seeds}
        results = {key: f.result() for key, f in futures.items()}
    version = subprocess.run([a.rupture, "--version"], capture_output=True, text=True).stdout.split("\n")
    commit = next((line.split()[1] for line in version if line.startswith("commit")), "?")
    lines = ["# Seed 000, Table 2 on the seed's own sample: one hypothesis at a time", "",
             "Generated by `python3 docs/studies/seed000_table2.py` (do not edit): "
             f"{time.strftime('%Y-%m-%d', time.gmtime())}, build {commit}, {host_processor()}, "
             f"{a.jobs} runs at a time, one thread each, {time.time() - start:.0f} s for the runs not reused.", "",
             "The quasi-static `elastic-properties` scenario on the seed's 1 µm sample (Table 1: 11 % porosity, pores "
             "0.05-0.15 µm, R_DE = 3.3 nm unless stated), Table 3's beams; mean ± sample standard deviation over the "
             "sample seeds, then the values per seed. t is the 2D thickness of the stress section S = L × t (eq. 4 "
             "prints t = R_DE). Discussion: docs/dynamic-tension.md, \"Reproducing the seed's Table 2\".", "",
             "| variant | seeds | " + " | ".join(c[2] for c in COLUMNS) + " |",
             "|---|---|" + "---|" * len(COLUMNS),
             "| seed's Table 2, porous (dense) | | 150 (220) | 0.32 (0.30) | 70 (200) | 4.5 | |"]
    for name, label, _, seeds in variants:
        rows = [results[(name, s)] for s in seeds]
        cells = [cell([r[k] for r in rows], scale, form) for k, scale, _, form in COLUMNS]
        lines.append(f"| {label} | {seeds[0]}-{seeds[-1]} | " + " | ".join(cells) + " |")
    lines += ["", "Per seed:", ""]
    for name, label, _, seeds in variants:
        if len(seeds) == 1:
            continue
        rows = [results[(name, s)] for s in seeds]
        per = "; ".join(f"{c[2]} " + " / ".join(c[3].format(r[c[0]] * c[1]) for r in rows) for c in COLUMNS[:4])
        lines.append(f"- {label} (seeds {', '.join(map(str, seeds))}): {per}")
    with open(a.out, "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
