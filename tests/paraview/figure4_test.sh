#!/bin/bash
# ctest label "paraview": a small run, its sidecar from `rupture xdmf`, opened in ParaView's XDMF
# reader (tests/paraview/check_sidecar.py checks points, bond cells and broken bonds against the
# HDF5 file) and rendered by examples/paraview_figure4.py on a virtual X server. Exit 77 (skipped)
# when pvbatch, its Python module or Xvfb is not installed: ParaView is too heavy for CI (docs/paraview.md).
set -euo pipefail
rupture=$1 source_dir=$2
for tool in pvbatch pvpython Xvfb h5dump /usr/bin/python3; do
  command -v "$tool" > /dev/null || { echo "skipped: $tool is not installed"; exit 77; }
done
work=$(mktemp -d)
# Our own virtual X server on a free display (Xvfb picks it: -displayfd), 24-bit for OpenGL;
# xvfb-run (the documented recipe) intermittently lost its display on this busy test machine.
Xvfb -displayfd 3 -screen 0 1280x1024x24 -nolisten tcp 3> "$work/display" 2> /dev/null &
xvfb=$!
trap 'kill "$xvfb" 2> /dev/null; rm -rf "$work"' EXIT
for _ in $(seq 100); do [ -s "$work/display" ] && break; sleep 0.1; done
export DISPLAY=":$(head -n 1 "$work/display")"
if ! pvpython -c "import paraview.simple" > /dev/null 2>&1; then
  echo "skipped: ParaView's Python module is missing (apt-get install python3-paraview)"; exit 77
fi
/usr/bin/python3 - "$source_dir/examples/dynamic-tension-small.json" "$work/spec.json" <<'PY'
import json, sys
spec = json.load(open(sys.argv[1]))
spec["loading"]["initial_velocity"] = "VL"   # no preliminary run: a few seconds
json.dump(spec, open(sys.argv[2], "w"))
PY
OMP_NUM_THREADS=1 "$rupture" run "$work/spec.json" -o "$work/run.h5" > /dev/null 2>&1
"$rupture" xdmf "$work/run.h5" -o "$work/fig.xdmf2"
elements=$(h5ls "$work/run.h5/sample/radius" | sed -E 's/.*\{([0-9]+)\}.*/\1/')
bonds=$(h5ls "$work/run.h5/sample/bonds" | sed -E 's/.*\{([0-9]+), 2\}.*/\1/')
last=$(h5ls "$work/run.h5/snapshots" | awk '{print $1}' | sort | tail -1)
broken=$(h5dump -d "/snapshots/$last/bond_intact" -y -w 0 "$work/run.h5" | sed -n '/DATA {/,/}/p' | tr -c '0-9\n' ' ' | tr ' ' '\n' | grep -cx '0' || true)
pvpython "$source_dir/tests/paraview/check_sidecar.py" "$work/fig.xdmf2" "$elements" "$bonds" "$broken"
# pvbatch on a virtual X server sometimes loses its display when the machine is loaded ("bad X server
# connection"): three tries.
for try in 1 2 3; do
  pvbatch "$source_dir/examples/paraview_figure4.py" "$work/fig.xdmf2" "$work/figure4.png" -1 600 500 > "$work/pvbatch.log" 2>&1 && break
  echo "pvbatch try $try failed: $(grep -m1 -o 'bad X server connection' "$work/pvbatch.log" || tail -n 1 "$work/pvbatch.log")"
done
# A PNG of the asked size (IHDR width and height, big-endian at bytes 16..23).
/usr/bin/python3 - "$work/figure4.png" <<'PY'
import struct, sys
data = open(sys.argv[1], "rb").read()
assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
assert struct.unpack(">II", data[16:24]) == (600, 500), struct.unpack(">II", data[16:24])
print("figure4.png ok")
PY
