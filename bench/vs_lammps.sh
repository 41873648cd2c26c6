#!/usr/bin/env bash
# W1 or W3 side by side: Rupture (`rupture bench W1|W3`) and LAMMPS (bench/w1_lammps.in: the BPM
# package's bpm/rotational; bench/w3_lammps.in: the SPH package's sph/taitwater) on the same
# machine, in the same run, one thread each; prints each figure and the ratio.
#   bench/vs_lammps.sh W1|W3 [BUILD_DIR] [STEPS]     (defaults: build, 1000)
# Debian 12's `lammps` has neither package: LMP names a LAMMPS built with them
# (../shared/peers/lammps/build.sh; bench/README.md, "W1, W2, W3 side by side with LAMMPS").
# W2 runs on Debian's own `lmp`: bench/w2_vs_lammps.sh.
set -euo pipefail
workload=${1:-}
build=${2:-build}
steps=${3:-1000}
lmp=${LMP:-lmp}
case "$workload" in
  W1) style="bpm/rotational"; what="bond style" ;;
  W3) style="sph/taitwater"; what="pair style" ;;
  *) echo "usage: bench/vs_lammps.sh W1|W3 [BUILD_DIR] [STEPS]" >&2; exit 2 ;;
esac
deck="$(dirname "$0")/$(tr 'W' 'w' <<< "$workload")_lammps.in"
rupture="$build/engine/rupture"
[ -x "$rupture" ] || { echo "$rupture not built: cmake --build $build --target rupture" >&2; exit 1; }
# (The help text is read whole: grep -q would stop reading, and pipefail count lmp's SIGPIPE.)
if ! grep -q "$style" <<< "$("$lmp" -h 2>/dev/null || true)"; then
  echo "$lmp has no $what $style: set LMP to a LAMMPS built with it (../shared/peers/lammps/build.sh)" >&2
  exit 1
fi

# LAMMPS prints "Loop time of T on P procs for N steps with A atoms": particle-steps/s = A N / T.
lammps_rate() {
  awk '/^Loop time of/ { for (i = 1; i <= NF; i++) { if ($i == "of") t = $(i + 1); if ($i == "for") n = $(i + 1); if ($i == "with") a = $(i + 1) } }
       END { if (t > 0) printf "%.6g\n", a * n / t; else exit 1 }'
}

ours=$(OMP_WAIT_POLICY=passive "$rupture" bench "$workload" --threads 1 --steps "$steps" |
       python3 -c 'import json, sys; print(json.load(sys.stdin)["particle_steps_per_s"])')
theirs=$(OMP_NUM_THREADS=1 "$lmp" -in "$deck" -var nsteps "$steps" -log none | lammps_rate)
python3 - "$workload" "$style" "$ours" "$theirs" <<'PY'
import sys
workload, style, ours, theirs = sys.argv[1], sys.argv[2], float(sys.argv[3]), float(sys.argv[4])
print(f"{workload} 1 thread: rupture {ours / 1e6:.3f} M particle-steps/s, LAMMPS {style} {theirs / 1e6:.3f} M, ratio {ours / theirs:.2f}x")
PY
