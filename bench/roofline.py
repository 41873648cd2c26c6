#!/usr/bin/env python3
"""The roofline of the W1, W2 and W3 loops on this host (bench/README.md, "Roofline").

Runs `rupture bench STREAM` (bandwidth and arithmetic ceilings) and the three workloads at each
thread count, and prints the table of bytes and flops per bond or pair, the bounds they give and
where each workload stands. Every measured figure comes from this run; the per-bond and per-pair
counts are constants read off the loop code (the comments say where).

    python3 bench/roofline.py                      # 1 and 2 threads, the workloads' 1000 steps
    python3 bench/roofline.py --threads 1 --steps 200 --rupture build/engine/rupture
"""
import argparse
import datetime
import json
import os
import statistics
import subprocess
import sys

# Bytes and flops per bond (W1, W2) or computed pair (W3) and step, counted from the loops' code.
# "read"/"write": streamed from and to memory, counted as STREAM counts them (no write-allocate);
# "allocate": the write-allocate reads of write-only lines, listed apart (STREAM's triad hides
# its own the same way); "gathered": particle data read at random, from cache at these sizes
# (bench/README.md, "Roofline"); "particle": bytes streamed per particle by the loop, shared by
# its bonds. Flops count additions and multiplications (GCC contracts some into FMAs: 2 each);
# divisions and square roots are apart (they go to the divider, not the FMA pipes). W1's and W2's
# counts match the vector loops' instructions in `objdump -d` of the build (bench/README.md).
LOOPS = {
    "W1": {
        # engine/core/bond_loop.hpp evaluateBonds<BeamLaw, Rankine> then gatherBondLoads<true, false>.
        # evaluate reads i, j (int32) and L0, n0x, n0y, n0z, stiffness, failureThreshold, intact
        # (8 + 7 * 8 = 64 B); the gather reads 2 incidence entries (8 B) and the 9 loads back (72 B:
        # 9 arrays of 4.7 MB, 42 MB in all, more than the L3, so from memory).
        "read": 64 + 8 + 72,
        # evaluate writes intact, failureMeasure, fjx..fjz, tix..tiz, tjx..tjz: 11 doubles.
        "write": 88,
        "allocate": 80,  # the 10 write-only arrays
        # x, y, z, radius, qw, qx, qy, qz of both ends (engine/core/bond_loop.hpp, the loop's loads).
        "gathered": 128,
        # gather: incidenceStart (4 B), f and t written (48 B; + 48 B write-allocate not counted).
        "particle": 4 + 48,
        # engine/dem/beam_bond.hpp beamResponse (its energy and twist are dead in the loop), then
        # BeamLaw's scaling by the bond's factor and the loop's integrity products:
        #   section and stiffnesses 13 mul 1 add; chord (d, |d|, n) 6 mul 5 add;
        #   two end tangents (rotateByQuaternion) 36 mul 24 add;
        #   two bending rotations (bendingRotation, atan2Branchless 11 mul 15 add each) 52 mul 44 add;
        #   twist (q_j q_i*, atan2Branchless) 33 mul 29 add; loads F_j, T_i, T_j 31 mul 22 add;
        #   moments, σ_N, τ, Rankine 16 mul 15 add; BeamLaw's factor 10 mul; integrity 10 mul 1 add:
        #   207 mul + 141 add.
        "flops": 348,
        # 1/L0, 1/L, 3 per atan2 (3 of them), angle/s at both ends, σ_N's 2 and τ's 1; roots:
        # |d|, |n × a| at both ends, the bending moment and Rankine's.
        "divisions": 16,
        "roots": 5,
        "per": "bond",
    },
    "W2": {
        # engine/core/central_bond_loop.hpp, the compact form (W2's 153 kinds): each bond is two
        # slots, each a partner (int32) and a kind (uint16).
        "read": 2 * (4 + 2),
        "write": 0,
        "allocate": 0,
        # 2 partners' packed 32-byte records (x, y, z, s_min); the kinds' 32-byte records (4.9 KB
        # table, L1) not counted.
        "gathered": 2 * 32,
        # the packing pass reads x, y, z, s_min and writes the record (32 + 32 B), the loop reads
        # x, y, z, s_min, incidenceStart (36 B) and writes fx, fy, fz, s_min' (32 B); the torques
        # zeroed (24 B).
        "particle": 64 + 36 + 32 + 24,
        # per slot (engine/core/central_spring_law.hpp, energy dead): dx 3 add, |d| 3 mul 2 add,
        # extension 1 add, force 1 mul, F 6 mul, the stretch extension × (1/L0) 1 mul (1/L0 from
        # the kind table since 50af05c; a division before), α max(s_min) 1 mul 1 add,
        # the sum 3 add: 12 mul + 10 add, twice per bond.
        "flops": 2 * 22,
        "divisions": 2 * 1,  # 1/|d| (the stretch's extension / L0 was the second until 50af05c)
        "roots": 2 * 1,
        "per": "bond",
    },
    "W3": {
        # engine/sph/fluid_rates.cpp pairsOfLanes<L, false, true> (uniform mass, no diffusion):
        # one int32 list entry per pair, each pair once (half lists).
        "read": 4,
        "write": 0,
        "allocate": 0,
        # the neighbour's 64-byte Packed record, its accumulator read and written (32 + 32 B).
        "gathered": 64 + 64,
        # own record (64 B), the chunk's accumulator zeroed and read back by the reduction (32 + 32 B).
        "particle": 64 + 64,
        # dx 3, r² 5, 1/r and r from rsqrt14 13, F 6, dv 3, v·r 5, μ (with 1/(r² + η²) from
        # rcp14) 10, Π 5, c 3, f 3, continuity 1, own sums 8, the neighbour's 4.
        "flops": 69,
        "divisions": 0,  # rcp14 and rsqrt14 estimates and their corrections instead
        "roots": 0,
        "per": "pair",
    },
}


def run_json(command):
    """Runs a `rupture bench` command under /usr/bin/time; its JSON line and its user CPU seconds."""
    # Passive waits: on a shared host libgomp's spinning threads would count as processor time.
    env = dict(os.environ, OMP_WAIT_POLICY=os.environ.get("OMP_WAIT_POLICY", "passive"))
    proc = subprocess.run(["/usr/bin/time", "-f", "%U"] + command, capture_output=True, text=True, env=env)
    if proc.returncode != 0:
        sys.exit(f"{' '.join(command)} failed ({proc.returncode}):\n{proc.stderr}")
    report = json.loads(proc.stdout.strip().splitlines()[-1])
    report["time_user_s"] = float(proc.stderr.strip().splitlines()[-1])
    return report


def git_commit():
    here = os.path.dirname(os.path.abspath(__file__))
    try:
        commit = subprocess.run(["git", "-C", here, "rev-parse", "--short", "HEAD"], capture_output=True,
                                text=True, check=True).stdout.strip()
        dirty = subprocess.run(["git", "-C", here, "status", "--porcelain", "--untracked-files=no"],
                               capture_output=True, text=True).stdout.strip()
        return commit + ("+changes" if dirty else "")
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def items_per_particle(name, report):
    """Bonds (W1, W2: every bond is evaluated, broken or not) or computed pairs (W3: each listed
    pair once; listed_pairs_per_particle counts them directed) per particle."""
    if name == "W3":
        return report["listed_pairs_per_particle"] / 2.0
    return report["bonds"] / report["particles"]


def bounds(name, report, stream):
    """The loop's ceilings in particle-steps/s: memory (STREAM triad), arithmetic (mul-add), divider."""
    c = LOOPS[name]
    n = items_per_particle(name, report)
    dram = (c["read"] + c["write"]) * n + c["particle"]
    flops = c["flops"] * n
    memory = stream["triad_gb_per_s"] * 1e9 / dram
    # The gathered bytes, were they all to come from the L3 (the neighbour's records of W3 do).
    cache = stream["l3_triad_gb_per_s"] * 1e9 / (c["gathered"] * n)
    compute = stream["gflops_mul_add"] * 1e9 / flops
    # Divisions and roots share the divider (one unit on Zen 4); none: no ceiling.
    divider_s = (c["divisions"] / (stream["g_divisions_per_s"] * 1e9) + c["roots"] / (stream["g_square_roots_per_s"] * 1e9)) * n
    divider = 1.0 / divider_s if divider_s > 0 else float("inf")
    return {"items": n, "dram_bytes": dram, "flops": flops, "intensity": flops / dram, "memory": memory, "cache": cache,
            "compute": compute, "divider": divider}


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--rupture", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "build",
                                                         "engine", "rupture"))
    parser.add_argument("--threads", default="1,2", help="thread counts, comma-separated (default 1,2)")
    parser.add_argument("--steps", type=int, default=0, help="steps of each workload (default: theirs, 1000)")
    parser.add_argument("--stream-runs", type=int, default=5, help="STREAM runs per thread count; the best triad is used")
    parser.add_argument("--workloads", default="W1,W2,W3")
    parser.add_argument("--json", help="also write every report to this file")
    parser.add_argument("--from-json", help="print the tables of a run recorded with --json instead of running")
    args = parser.parse_args()
    threads = [int(t) for t in args.threads.split(",")]
    workloads = args.workloads.split(",")
    steps = ["--steps", str(args.steps)] if args.steps > 0 else []

    if args.from_json:
        with open(args.from_json) as f:
            recorded = json.load(f)
        raw = {"stream": {int(k): v for k, v in recorded["stream"].items()},
               "workloads": {(k.split("/")[0], int(k.split("/")[1])): v for k, v in recorded["workloads"].items()}}
        threads = sorted(raw["stream"])
        workloads = sorted({w for w, _ in raw["workloads"]})
        report(raw, threads, workloads, datetime.datetime.fromisoformat(recorded["started"]), recorded["commit"],
               recorded["load"])
        return
    started = datetime.datetime.now(datetime.timezone.utc)
    load_before = os.getloadavg()
    raw = {"stream": {}, "workloads": {}}
    for t in threads:
        runs = [run_json([args.rupture, "bench", "STREAM", "--threads", str(t)]) for _ in range(args.stream_runs)]
        best = max(runs, key=lambda r: r["triad_gb_per_s"])
        best = dict(best)
        best["triad_median_gb_per_s"] = statistics.median(r["triad_gb_per_s"] for r in runs)
        for key in ("gflops_mul_add", "g_divisions_per_s", "g_square_roots_per_s"):
            best[key] = max(r[key] for r in runs)
        # Three arrays of 2 MiB: past the 1 MiB L2, well inside the 32 MiB L3.
        in_l3 = [run_json([args.rupture, "bench", "STREAM", "--threads", str(t), "--megabytes", "2"])
                 for _ in range(args.stream_runs)]
        best["l3_triad_gb_per_s"] = max(r["triad_gb_per_s"] for r in in_l3)
        raw["stream"][t] = best
        for w in workloads:
            raw["workloads"][(w, t)] = run_json([args.rupture, "bench", w, "--threads", str(t)] + steps)
    load = [load_before[0], os.getloadavg()[0]]
    commit = git_commit()
    report(raw, threads, workloads, started, commit, load)
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"started": started.isoformat(), "commit": commit, "load": load,
                       "stream": {str(k): v for k, v in raw["stream"].items()},
                       "workloads": {f"{k[0]}/{k[1]}": v for k, v in raw["workloads"].items()}}, f, indent=1)


def report(raw, threads, workloads, started, commit, load):
    """Prints the tables (bench/README.md, "Roofline")."""
    host = raw["stream"][threads[0]]["host"]
    print(f"Measured {started:%Y-%m-%d %H:%M} UTC at {commit} on {host['model_name']} (family {host['family']}, "
          f"model {host['model']}), load average {load[0]:.1f} before and {load[1]:.1f} after "
          f"(a shared host: wall figures count other jobs' turns, CPU figures do not).")
    print()
    print("| threads | STREAM copy | scale | add | triad, best (median) | triad in L3 | mul-add | divisions | square roots |")
    print("|---|---|---|---|---|---|---|---|---|")
    for t in threads:
        s = raw["stream"][t]
        print(f"| {t} | {s['copy_gb_per_s']:.1f} GB/s | {s['scale_gb_per_s']:.1f} | {s['add_gb_per_s']:.1f} | "
              f"{s['triad_gb_per_s']:.1f} ({s['triad_median_gb_per_s']:.1f}) | {s['l3_triad_gb_per_s']:.0f} | "
              f"{s['gflops_mul_add']:.1f} GFLOP/s | "
              f"{s['g_divisions_per_s']:.2f} G/s | {s['g_square_roots_per_s']:.2f} G/s |")
    print()
    print("| loop | per | streamed read + write (+ write-allocate) B | gathered B (cache) | particle B | flops | "
          "div + sqrt | per particle | flops/B (memory) |")
    print("|---|---|---|---|---|---|---|---|---|")
    first = threads[0]
    for w in workloads:
        c = LOOPS[w]
        b = bounds(w, raw["workloads"][(w, first)], raw["stream"][first])
        print(f"| {w} | {c['per']} | {c['read']} + {c['write']} (+{c['allocate']}) | {c['gathered']} | {c['particle']} | "
              f"{c['flops']} | {c['divisions']} + {c['roots']} | {b['items']:.2f} {c['per']}s | {b['intensity']:.2f} |")
    print()
    print("| loop | threads | memory bound | gathers from L3 | arithmetic bound | divider bound | measured (wall) | "
          "measured (CPU) | wall / tightest bound | cpu s (bench) | user s (/usr/bin/time) |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for w in workloads:
        for t in threads:
            r = raw["workloads"][(w, t)]
            b = bounds(w, r, raw["stream"][t])
            tight = min(b["memory"], b["compute"], b["divider"])  # the L3 column is a what-if, not a bound
            particle_steps = r["particles"] * r["steps"]
            per_cpu = particle_steps / r["cpu_seconds"] * t  # as fast as this with a core per thread
            divider = f"{b['divider'] / 1e6:.1f} M" if b["divider"] < float("inf") else "none"
            print(f"| {w} | {t} | {b['memory'] / 1e6:.1f} M | {b['cache'] / 1e6:.1f} M | {b['compute'] / 1e6:.1f} M | "
                  f"{divider} | {r['particle_steps_per_s'] / 1e6:.2f} M | {per_cpu / 1e6:.2f} M | "
                  f"{r['particle_steps_per_s'] / tight:.0%} | {r['cpu_seconds']:.1f} | {r['time_user_s']:.1f} |")


if __name__ == "__main__":
    main()
