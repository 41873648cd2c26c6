#!/usr/bin/env bash
# Installs what the build needs (deploy/setup.sh), then configures and builds Rupture (Release)
# into ./build. Arguments go to CMake's configure step (e.g. -DRUPTURE_NATIVE=OFF).
# RUPTURE_TARGETS="rupture rupture-server" builds only those targets (deploy/start.sh does); the
# default builds everything, the tests included. The compiler's output goes to build/build.log and
# is shown only when the build fails.
set -euo pipefail
cd "$(dirname "$0")/.."
bash deploy/setup.sh
mkdir -p build
log=build/build.log
targets=()
for t in ${RUPTURE_TARGETS:-}; do targets+=(--target "$t"); done
echo "== building ${RUPTURE_TARGETS:-everything} (log: $log)"
start=$SECONDS
if ! { cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "$@" &&
       cmake --build build -j"$(nproc)" "${targets[@]}"; } > "$log" 2>&1; then
  grep -E -m 20 "error|Error" "$log" >&2 || tail -n 30 "$log" >&2
  echo "== the build failed; the whole log is in $log" >&2
  exit 1
fi
echo "== built in $((SECONDS - start)) s"
