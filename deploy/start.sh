#!/usr/bin/env bash
# The README's first command: install the dependencies, build, start rupture-server on an embedded
# SQLite database in ./data (port $RUPTURE_PORT, default 8080), and submit the example sweep
# (examples/sweep-small.json: strain rate × initial velocity field of the small dynamic-tension
# sample). The server stays in the foreground; Ctrl-C stops it gracefully, and the next start on
# the same data directory resumes any unfinished runs.
set -euo pipefail
cd "$(dirname "$0")/.."
bash deploy/setup.sh
bash deploy/build.sh
PORT="${RUPTURE_PORT:-8080}"
DATA="${RUPTURE_DATA_DIR:-data}"
# Its first stdout line says it listens; a busy port or a data directory another server holds
# ends it at once with the reason on stderr (and then nothing is submitted to that other server).
coproc SERVER { exec ./build/server/rupture-server --data-dir "$DATA" --port "$PORT"; }
server=$SERVER_PID
trap 'kill -TERM "$server" 2>/dev/null; wait "$server"' INT TERM
if ! read -r listening <&"${SERVER[0]}"; then
  echo "== rupture-server did not start (the reason is above)" >&2
  exit 1
fi
echo "== $listening"
echo "== submitting the example sweep (examples/sweep-small.json)"
response=$(curl -sS -D - --json @examples/sweep-small.json "http://127.0.0.1:$PORT/processes/dynamic-tension/execution")
echo "$response"
job=$(printf '%s\n' "$response" | tr -d '\r' | sed -n 's|^[Ll]ocation: */jobs/\([0-9]*\).*|\1|p')
job=${job:-1}
cat <<MSG
== rupture-server is running on http://127.0.0.1:$PORT (data in $DATA/); the sweep runs in the background.
   curl -s http://127.0.0.1:$PORT/jobs/$job                           # status and per-run progress
   curl -s "http://127.0.0.1:$PORT/jobs/$job/summary?format=csv"      # peak stress versus strain rate
   curl -s -o plot.svg "http://127.0.0.1:$PORT/jobs/$job/summary.svg?x=loading.strain_rate&y=peak_stress"
   curl -s -o results.h5 http://127.0.0.1:$PORT/jobs/$job/results     # every run's HDF5 groups, once finished
Ctrl-C stops the server.
MSG
wait "$server"
