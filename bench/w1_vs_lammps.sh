#!/usr/bin/env bash
# W1 side by side: Rupture (`rupture bench W1`) and LAMMPS's BPM package (bench/w1_lammps.in) on
# the same machine, in the same run, one thread each; prints each figure and the ratio.
#   bench/w1_vs_lammps.sh [BUILD_DIR] [STEPS]     (defaults: build, 1000)
# Debian 12's `lammps` has no BPM package: LMP names a LAMMPS built with it
# (../shared/peers/lammps/build.sh, or bench/README.md's W1 section).
set -euo pipefail
build=${1:-build}
steps=${2:-1000}
lmp=${LMP:-lmp}
deck="$(dirname "$0")/w1_lammps.in"
rupture="$build/engine/rupture"
[ -x "$rupture" ] || { echo "$rupture not built: cmake --build $build --target rupture" >&2; exit 1; }
# (The help text is read whole: grep -q would stop reading, and pipefail count lmp's SIGPIPE.)
if ! grep -q "bpm/rotational" <<< "$("$lmp" -h 2>/dev/null || true)"; then
  echo "$lmp has no bond style bpm/rotational: set LMP to a LAMMPS built with -DPKG_BPM=on" >&2
  exit 1
fi

# LAMMPS prints "Loop time of T on P procs for N steps with A atoms": particle-steps/s = A N / T.
lammps_rate() {
  awk '/^Loop time of/ { for (i = 1; i <= NF; i++) { if ($i == "of") t = $(i + 1); if ($i == "for") n = $(i + 1); if ($i == "with") a = $(i + 1) } }
       END { if (t > 0) printf "%.6g\n", a * n / t; else exit 1 }'
}

ours=$(OMP_WAIT_POLICY=passive "$rupture" bench W1 --threads 1 --steps "$steps" |
       python3 -c 'import json, sys; print(json.load(sys.stdin)["particle_steps_per_s"])')
theirs=$(OMP_NUM_THREADS=1 "$lmp" -in "$deck" -var nsteps "$steps" -log none | lammps_rate)
python3 - "$ours" "$theirs" <<'PY'
import sys
ours, theirs = float(sys.argv[1]), float(sys.argv[2])
print(f"W1 1 thread: rupture {ours / 1e6:.3f} M particle-steps/s, LAMMPS bpm/rotational {theirs / 1e6:.3f} M, ratio {ours / theirs:.2f}x")
PY
