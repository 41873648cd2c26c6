#!/usr/bin/env bash
# `mpiexec -np N rupture run SPEC` against `rupture run SPEC` (docs/distributed.md): the impact
# scenario on N ranks writes the one-process file bit for bit (series, snapshots, sample; h5diff)
# and prints the same summary (all but the wall time); what is not decomposed yet is refused with
# exit 2, naming the field or the scenario.
#   cli_ranks_test.sh RUPTURE MPIEXEC RANKS [MPIEXEC FLAGS...]
set -euo pipefail
rupture=$1 mpiexec=$2 ranks=$3
shift 3
here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

for spec in impact_pmb_projectile impact_springs_precrack; do
  "$rupture" run "$here/$spec.json" -o "$work/one.h5" --json > "$work/one.json" 2> "$work/one.err" \
    || { cat "$work/one.err" >&2; fail "$spec on one process"; }
  "$mpiexec" -np "$ranks" "$@" "$rupture" run "$here/$spec.json" -o "$work/many.h5" --json \
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
python3 - "$here/impact_pmb_projectile.json" "$work/with_contact.json" <<'PY'
import json, sys
spec = json.load(open(sys.argv[1]))
spec["material"]["contact"] = {"enabled": True}
json.dump(spec, open(sys.argv[2], "w"))
PY
expect_refusal "$work/with_contact.json" "material.contact.enabled"
expect_refusal "$here/../../examples/dynamic-tension-pmb.json" "scenario runs on one rank"
expect_refusal "$here/impact_pmb_projectile.json" "checkpoints are not carried across ranks" --resume
