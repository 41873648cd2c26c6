#!/usr/bin/env bash
# `mpiexec -np N rupture run SPEC` against `rupture run SPEC` (docs/distributed.md): the impact
# and dynamic-tension scenarios on N ranks write the one-process file bit for bit (series,
# snapshots, sample; h5diff)
# and prints the same summary (all but the wall time); a run stopped with a checkpoint on N ranks
# and resumed on N ranks writes the uninterrupted file, and its resume on another rank count is
# refused; what is not decomposed yet is refused with exit 2, naming the field or the scenario.
# Both specs have contact between fragments on (the impact scenario's default).
#   cli_ranks_test.sh RUPTURE MPIEXEC RANKS [MPIEXEC FLAGS...]
set -euo pipefail
rupture=$1 mpiexec=$2 ranks=$3
shift 3
here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

# The seed's beams in dynamic tension (the small example: VH field, its preliminary run, contact),
# without the caches, so that each run builds its sample and preliminary run itself.
python3 - "$here/../../examples/dynamic-tension-small.json" "$work/tension_small.json" <<'PY'
import json, sys
spec = json.load(open(sys.argv[1]))
spec.setdefault("output", {}).update({"cache_sample": False, "cache_preliminary": False})
json.dump(spec, open(sys.argv[2], "w"))
PY

for path in "$here/impact_pmb_projectile.json" "$here/impact_springs_precrack.json" "$work/tension_small.json"; do
  spec=$(basename "$path" .json)
  "$rupture" run "$path" -o "$work/one.h5" --json > "$work/one.json" 2> "$work/one.err" \
    || { cat "$work/one.err" >&2; fail "$spec on one process"; }
  "$mpiexec" -np "$ranks" "$@" "$rupture" run "$path" -o "$work/many.h5" --json \
    > "$work/many.json" 2> "$work/many.err" || { cat "$work/many.err" >&2; fail "$spec on $ranks ranks"; }
  for group in /series /snapshots /sample; do
    h5diff -r "$work/one.h5" "$work/many.h5" "$group" > "$work/diff.txt" \
      || { tail -n 20 "$work/diff.txt" >&2; fail "$spec: $group differs between one process and $ranks ranks"; }
  done
  python3 - "$work/one.json" "$work/many.json" "$spec" "$ranks" <<'PY' || fail "$spec: the summaries differ"
import json, sys
one, many = (json.load(open(p)) for p in sys.argv[1:3])
assert one.get("broken_bonds", 0) > 0, f"{sys.argv[3]}: nothing broke, the test would prove little"
for key in sorted(set(one) | set(many)):
    if key == "wall_time_s":
        continue
    if one.get(key) != many.get(key):
        sys.exit(f"{sys.argv[3]}: summary {key}: one process {one.get(key)}, {sys.argv[4]} ranks {many.get(key)}")
PY
  rm -f "$work"/one.* "$work"/many.*
  echo "$spec: the same file and summary on 1 and $ranks ranks"
done

# Refused on several ranks, with exit 2 and the reason.
expect_refusal() {  # SPEC PATTERN [run options...]
  local spec=$1 pattern=$2
  shift 2
  set +e
  "$mpiexec" -np "$ranks" "${mpi_flags[@]}" "$rupture" run "$spec" -o "$work/refused.h5" "$@" > /dev/null 2> "$work/refused.err"
  local code=$?
  set -e
  [ "$code" -eq 2 ] || { cat "$work/refused.err" >&2; fail "$spec on $ranks ranks: exit $code, expected 2"; }
  grep -q -- "$pattern" "$work/refused.err" || { cat "$work/refused.err" >&2; fail "$spec: no '$pattern' in the message"; }
  [ ! -e "$work/refused.h5" ] && [ ! -e "$work/refused.h5.part" ] || fail "$spec: a refused run left a file"
  echo "refused as expected: $pattern"
}
mpi_flags=("$@")
expect_refusal "$here/../../examples/dam-break-2d.json" "scenario runs on one rank"

# Checkpoint on N ranks, stop, resume on N ranks: the uninterrupted file bit for bit. Each rank keeps
# its own checkpoint; a resume on another rank count is refused, naming the count to use. The
# dynamic-tension spec on two ranks only: on three, oversubscribed, it would add a minute to CI.
resumed=("$here/impact_pmb_projectile.json")
[ "$ranks" -eq 2 ] && resumed+=("$work/tension_small.json")
for spec in "${resumed[@]}"; do
  "$rupture" run "$spec" -o "$work/whole.h5" --json > "$work/whole.json" 2> "$work/whole.err" \
    || { cat "$work/whole.err" >&2; fail "uninterrupted run on one process"; }
  set +e
  "$mpiexec" -np "$ranks" "${mpi_flags[@]}" "$rupture" run "$spec" -o "$work/split.h5" --stop-at-step 100 \
    > /dev/null 2> "$work/stop.err"
  code=$?
  set -e
  [ "$code" -eq 130 ] || { cat "$work/stop.err" >&2; fail "--stop-at-step on $ranks ranks: exit $code, expected 130"; }
  [ -f "$work/split.h5.checkpoint" ] || fail "no checkpoint of the first rank"
  for ((r = 1; r < ranks; ++r)); do
    [ -f "$work/split.h5.checkpoint.rank-$r" ] || fail "no checkpoint of rank $r"
  done
  set +e
  "$rupture" run "$spec" -o "$work/split.h5" --resume > /dev/null 2> "$work/wrong.err"
  code=$?
  set -e
  [ "$code" -eq 2 ] || { cat "$work/wrong.err" >&2; fail "resume on one process of a $ranks-rank checkpoint: exit $code, expected 2"; }
  grep -q "resume it with mpirun -np $ranks" "$work/wrong.err" || { cat "$work/wrong.err" >&2; fail "the refusal does not name the rank count"; }
  "$mpiexec" -np "$ranks" "${mpi_flags[@]}" "$rupture" run "$spec" -o "$work/split.h5" --resume --json \
    > "$work/split.json" 2> "$work/resume.err" || { cat "$work/resume.err" >&2; fail "resume on $ranks ranks"; }
  grep -q "resumed from the checkpoint at step 100" "$work/resume.err" || { cat "$work/resume.err" >&2; fail "the run did not resume at step 100"; }
  for group in /series /snapshots /sample; do
    h5diff -r "$work/whole.h5" "$work/split.h5" "$group" > "$work/diff.txt" \
      || { tail -n 20 "$work/diff.txt" >&2; fail "$group differs between the uninterrupted run and the one resumed on $ranks ranks"; }
  done
  ls "$work"/split.h5.checkpoint* > /dev/null 2>&1 && fail "checkpoints left after the resumed run completed: $(ls "$work"/split.h5.checkpoint*)"
  echo "$(basename "$spec" .json): stopped at step 100 and resumed on $ranks ranks: the uninterrupted file; another rank count refused"
  rm -f "$work"/whole.* "$work"/split.*
done
