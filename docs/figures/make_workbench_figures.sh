#!/usr/bin/env bash
# Regenerates the browser figures of docs/server.md from a built tree (bash deploy/build.sh) with
# Debian's chromium: the job page, run pages with their field pictures (dynamic tension, impact,
# tank impact), the submission form, a variant's form with its preview and the compare view.
#   bash docs/figures/make_workbench_figures.sh [BUILD_DIR]
# Short runs stand in for the examples (each spec below says what it shortens): the pages, not the
# physics, are what these figures show.
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
build="${1:-$root/build}"
out="$root/docs/figures"
work="$(mktemp -d)"
trap 'kill "$server_pid" 2>/dev/null || true; rm -rf "$work"' EXIT
"$build/server/rupture-server" --port 0 --data-dir "$work/data" --workers 2 --threads-per-run 1 > "$work/server.out" 2>&1 &
server_pid=$!
for _ in $(seq 100); do grep -q "listening on" "$work/server.out" && break; sleep 0.1; done
base="$(sed -n 's/.*listening on \(http[^ ]*\).*/\1/p' "$work/server.out" | head -1)"

submit() {  # submit SCENARIO BODY.json -> job id
  curl -sS --fail -H 'Content-Type: application/json' --data-binary "@$2" "$base/processes/$1/execution" |
    python3 -c 'import json,sys; print(json.load(sys.stdin)["jobID"])'
}
wait_job() {
  for _ in $(seq 1800); do
    status="$(curl -sS "$base/jobs/$1" | python3 -c 'import json,sys; print(json.load(sys.stdin)["status"])')"
    case "$status" in successful|failed|dismissed) return 0 ;; esac
    sleep 1
  done
  echo "job $1 did not finish" >&2
  return 1
}
shot() {  # shot URL-PATH OUT.png WIDTH HEIGHT
  chromium --headless --no-sandbox --disable-gpu --hide-scrollbars --user-data-dir="$work/profile" \
    --virtual-time-budget=8000 --window-size="$3,$4" --screenshot="$out/$2" "$base$1" > /dev/null 2>&1
  echo "== $out/$2"
}

# Dynamic tension: the small example at two strain rates, VL (no preliminary run), and a variant.
python3 - "$root" "$work" <<'PY'
import json, sys
root, work = sys.argv[1], sys.argv[2]
spec = json.load(open(f"{root}/examples/dynamic-tension-small.json")); spec.pop("scenario"); spec.pop("description", None)
spec["loading"]["initial_velocity"] = "VL"
json.dump({"name": "small sample, VL", "inputs": spec, "sweep": {"loading.strain_rate": [1e6, 1e7]}}, open(f"{work}/dt.json", "w"))
spec["loading"]["initial_velocity"] = "V0"
json.dump({"name": "small sample, V0", "inputs": spec, "sweep": {"loading.strain_rate": [1e6, 1e7]}}, open(f"{work}/dt0.json", "w"))
# Impact: the PMB branching plate to 15 µs, as it branches (the example runs to 46 µs).
imp = json.load(open(f"{root}/examples/impact-branching-pmb.json")); imp.pop("scenario"); imp.pop("description", None)
imp["run"]["end_time"] = 1.5e-5; imp["run"]["snapshot_times"] = [5e-6, 1e-5]
json.dump({"name": "PMB branching plate to 15 us", "inputs": imp}, open(f"{work}/impact.json", "w"))
# Tank impact: TF14A5 to 0.5 ms (the example runs to 3 ms).
tank = json.load(open(f"{root}/examples/tank-impact-TF14A5.json")); tank.pop("scenario"); tank.pop("description", None)
tank["run"]["end_time"] = 5e-4
json.dump({"name": "TF14A5 to 0.5 ms", "inputs": tank}, open(f"{work}/tank.json", "w"))
PY
dt="$(submit dynamic-tension "$work/dt.json")"; dt0="$(submit dynamic-tension "$work/dt0.json")"
wait_job "$dt"; wait_job "$dt0"
impact="$(submit impact "$work/impact.json")"; wait_job "$impact"
tank="$(submit tank-impact "$work/tank.json")"; wait_job "$tank"

shot "/jobs/$dt?f=html" html-job-page.png 1280 1400
shot "/jobs/$dt/runs/1?f=html" html-run-page-dynamic-tension.png 1280 1500
shot "/jobs/$impact/runs/0?f=html&snapshot=1" html-run-page-impact.png 1280 1500
shot "/jobs/$tank/runs/0?f=html&field=pressure" html-run-page-tank-impact.png 1280 1500
shot "/processes/dynamic-tension?f=html" html-submission-form.png 1280 1400
# The variant of the sweep: the form filled from its request, its preview (runs, elements, memory, time) at the foot.
shot "/processes/dynamic-tension?f=html&from=$dt" html-submission-variant-preview.png 1280 3000
shot "/summary?jobs=$dt,$dt0&f=html" html-compare-view.png 1280 1100
