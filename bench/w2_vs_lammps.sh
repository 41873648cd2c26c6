#!/usr/bin/env bash
# W2 side by side: Rupture (`rupture bench W2`) and LAMMPS (peri/pmb, Debian's `lammps` package) on
# the same machine, in the same run, at 1 and 2 threads; prints each figure and the ratio.
#   bench/w2_vs_lammps.sh [BUILD_DIR] [STEPS]     (defaults: build, 1000)
# LAMMPS deck: bench/w2_lammps.in (bench/README.md defines W2); $W2_DECK names another.
set -euo pipefail
build=${1:-build}
steps=${2:-1000}
deck=${W2_DECK:-"$(dirname "$0")/w2_lammps.in"}
rupture="$build/engine/rupture"
command -v lmp >/dev/null || { echo "lmp not found: apt-get install -y lammps" >&2; exit 1; }
[ -x "$rupture" ] || { echo "$rupture not built: cmake --build $build --target rupture" >&2; exit 1; }
[ -f "$deck" ] || { echo "LAMMPS deck $deck not found (set W2_DECK)" >&2; exit 1; }

# LAMMPS prints "Loop time of T on P procs for N steps with A atoms": particle-steps/s = A N / T.
lammps_rate() {
  awk '/^Loop time of/ { for (i = 1; i <= NF; i++) { if ($i == "of") t = $(i + 1); if ($i == "for") n = $(i + 1); if ($i == "with") a = $(i + 1) } }
       END { if (t > 0) printf "%.6g\n", a * n / t; else exit 1 }'
}

for threads in 1 2; do
  ours=$("$rupture" bench W2 --threads "$threads" --steps "$steps" |
         python3 -c 'import json, sys; print(json.load(sys.stdin)["particle_steps_per_s"])')
  if [ "$threads" = 1 ]; then
    theirs=$(OMP_NUM_THREADS=1 lmp -in "$deck" -var nsteps "$steps" -log none | lammps_rate)
  else
    theirs=$(mpirun --allow-run-as-root -np 2 lmp -in "$deck" -var nsteps "$steps" -log none | lammps_rate)
  fi
  python3 - "$threads" "$ours" "$theirs" <<'PY'
import sys
threads, ours, theirs = int(sys.argv[1]), float(sys.argv[2]), float(sys.argv[3])
print(f"W2 {threads} thread(s): rupture {ours / 1e6:.3f} M particle-steps/s, LAMMPS peri/pmb {theirs / 1e6:.3f} M, ratio {ours / theirs:.2f}x")
PY
done
