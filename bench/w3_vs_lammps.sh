#!/usr/bin/env bash
# W3 side by side: Rupture (`rupture bench W3`) and LAMMPS's SPH package (bench/w3_lammps.in) on
# the same machine, in the same run, one thread each; prints each figure and the ratio.
#   bench/w3_vs_lammps.sh [BUILD_DIR] [STEPS]     (defaults: build, 1000)
# Debian 12's `lammps` has no SPH package: LMP names a LAMMPS built with it (bench/README.md,
# "W3 side by side with LAMMPS", says how to build one from Debian's source package).
set -euo pipefail
build=${1:-build}
steps=${2:-1000}
lmp=${LMP:-lmp}
deck="$(dirname "$0")/w3_lammps.in"
rupture="$build/engine/rupture"
[ -x "$rupture" ] || { echo "$rupture not built: cmake --build $build --target rupture" >&2; exit 1; }
# (The help text is read whole: grep -q would stop reading, and pipefail count lmp's SIGPIPE.)
if ! grep -q "sph/taitwater" <<< "$("$lmp" -h 2>/dev/null || true)"; then
  echo "$lmp has no pair style sph/taitwater: set LMP to a LAMMPS built with -DPKG_SPH=on" >&2
  exit 1
fi

# LAMMPS prints "Loop time of T on P procs for N steps with A atoms": particle-steps/s = A N / T.
lammps_rate() {
  awk '/^Loop time of/ { for (i = 1; i <= NF; i++) { if ($i == "of") t = $(i + 1); if ($i == "for") n = $(i + 1); if ($i == "with") a = $(i + 1) } }
       END { if (t > 0) printf "%.6g\n", a * n / t; else exit 1 }'
}

ours=$(OMP_WAIT_POLICY=passive "$rupture" bench W3 --threads 1 --steps "$steps" |
       python3 -c 'import json, sys; print(json.load(sys.stdin)["particle_steps_per_s"])')
theirs=$("$lmp" -in "$deck" -var nsteps "$steps" -log none | lammps_rate)
python3 - "$ours" "$theirs" <<'PY'
import sys
ours, theirs = float(sys.argv[1]), float(sys.argv[2])
print(f"W3 1 thread: rupture {ours / 1e6:.3f} M particle-steps/s, LAMMPS sph/taitwater {theirs / 1e6:.3f} M, ratio {ours / theirs:.2f}x")
PY
