#!/usr/bin/env python3
"""bench/README.md's roofline table against bench/roofline.py re-run on the recorded reports.

The README's bounds are what the script computes from bench/roofline_2026-12-06.json with its
byte and flop constants; a change of either (a recount, a new formula) that leaves the README's
figures behind fails here. Usage: check_roofline_tables.py SOURCE_DIR
"""
import re
import subprocess
import sys

source = sys.argv[1]
printed = subprocess.run([sys.executable, f"{source}/bench/roofline.py", "--from-json",
                          f"{source}/bench/roofline_2026-12-06.json"], capture_output=True, text=True, check=True).stdout
readme = open(f"{source}/bench/README.md").read()
section = readme[readme.index("## Roofline"):readme.index("## S1")]


def cells(line):
    return [c.strip().strip("*") for c in line.strip().strip("|").split("|")]


failures = []
rows = 0
for line in printed.splitlines():
    c = cells(line)
    if len(c) == 11 and c[0] in ("W1", "W2", "W3"):  # loop, threads, memory, L3, arithmetic, divider, wall, cpu, …
        rows += 1
        loop, threads = c[0], c[1]
        # The README's row: loop (or blank under it), intensity (first row only), threads, then the bounds.
        pattern = re.compile(r"^\|\s*(?:" + loop + r")?\s*\|\s*[0-9.]*\s*\|\s*" + threads + r"\s*\| (.*)$", re.M)
        found = [cells("| " + m.group(1)) for m in pattern.finditer(section)]
        want = [c[2], c[3], c[4], c[5], c[6]]  # memory, L3, arithmetic, divider bounds and the wall figure

        def close(a, b):
            # The README rounds the L3 column to whole M; the rest are as printed.
            na, nb = a.rstrip(" M"), b.rstrip(" M")
            try:
                return abs(float(na) - float(nb)) <= 0.5 + 1e-9 * abs(float(nb))
            except ValueError:
                return na == nb

        if not any(len(f) >= 5 and all(close(f[k], want[k]) if k == 1 else f[k] == want[k] for k in range(5))
                   for f in found):
            failures.append(f"{loop} at {threads} threads: the script gives {want}, the README {[f[:5] for f in found]}")
if rows != 6:
    failures.append(f"the script printed {rows} rows of bounds, not 6")
if failures:
    sys.exit("\n".join(failures))
print("bench/README.md's roofline bounds are the script's")
