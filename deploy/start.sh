#!/usr/bin/env bash
# The README's first command: install the dependencies, build the CLI and the server (not the
# tests), start rupture-server on an embedded SQLite database in ./data (port $RUPTURE_PORT,
# default 8080), and submit the example sweep (examples/sweep-small.json: strain rate × initial
# velocity field of the small dynamic-tension sample) unless a job of that name is already in the
# data directory. The server stays in the foreground with its log in $DATA/server.log; Ctrl-C stops
# it gracefully, and the next start on the same data directory resumes any unfinished runs.
set -euo pipefail
cd "$(dirname "$0")/.."
RUPTURE_TARGETS="rupture rupture-server" bash deploy/build.sh
PORT="${RUPTURE_PORT:-8080}"
DATA="${RUPTURE_DATA_DIR:-data}"
mkdir -p "$DATA"
LOG="$DATA/server.log"
BASE="http://127.0.0.1:$PORT"
# Its first stdout line says it listens; a busy port or a data directory another server holds
# ends it at once with the reason in the log (and then nothing is submitted to that other server).
coproc SERVER { exec ./build/server/rupture-server --data-dir "$DATA" --port "$PORT" 2>>"$LOG"; }
server=$SERVER_PID
trap 'kill -TERM "$server" 2>/dev/null; wait "$server"' INT TERM
if ! read -r listening <&"${SERVER[0]}"; then
  tail -n 5 "$LOG" >&2
  echo "== rupture-server did not start (the reason is above; log: $LOG)" >&2
  exit 1
fi
echo "== $listening (log: $LOG)"

# The example sweep, once per data directory: a job with its name is reused.
name=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["name"])' examples/sweep-small.json)
job=$(curl -sS --fail "$BASE/jobs?limit=1000" | python3 -c '
import json, sys
name = sys.argv[1]
jobs = [j for j in json.load(sys.stdin)["jobs"] if j.get("name") == name and j["status"] != "dismissed"]
print(jobs[0]["jobID"] if jobs else "")' "$name")
if [ -n "$job" ]; then
  echo "== the example sweep is already job $job in $DATA/ (not submitted again)"
else
  job=$(curl -sS --fail --json @examples/sweep-small.json "$BASE/processes/dynamic-tension/execution" |
        python3 -c 'import json,sys; print(json.load(sys.stdin)["jobID"])')
  echo "== submitted the example sweep (examples/sweep-small.json) as job $job: 9 runs, a few minutes"
fi
cat <<MSG

== rupture-server is running on $BASE (data in $DATA/, log in $LOG). Try:
   curl -s $BASE/jobs/$job | head -30                              # status, progress, stage, ETA
   curl -s "$BASE/jobs/$job/summary?format=csv"                    # peak stress versus strain rate
   curl --fail -o plot.svg "$BASE/jobs/$job/summary.svg?x=loading.strain_rate&y=peak_stress"
   curl --fail -o results.h5 $BASE/jobs/$job/results              # every run in one HDF5 file, once finished
   open $BASE/jobs/$job?f=html in a browser                        # the same as a page, live
   tail -f $LOG                                                    # what the server does
Ctrl-C stops the server.
MSG
wait "$server"
