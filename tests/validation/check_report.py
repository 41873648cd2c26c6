#!/usr/bin/env python3
"""Checks a validation report directory (docs/validation.md): index.html's table agrees row by row
with report.json and report.csv (case, quantity, our value, verdict), every case the level runs is in
it, and every figure the page shows exists and is not empty. Usage: check_report.py DIR LEVEL"""
import csv
import json
import math
import sys
from html.parser import HTMLParser
from pathlib import Path


class Rows(HTMLParser):
    def __init__(self):
        super().__init__()
        self.rows, self.images = [], []

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if tag == "tr" and "data-quantity" in a:
            self.rows.append(a)
        if tag == "img":
            self.images.append(a.get("src", ""))


def close(a, b):
    if a in ("", None) and b in ("", None):
        return True
    return math.isclose(float(a), float(b), rel_tol=1e-12, abs_tol=0.0)


def main(directory, level):
    d = Path(directory)
    problems = []
    doc = json.loads((d / "report.json").read_text(encoding="utf-8"))
    with open(d / "report.csv", newline="", encoding="utf-8") as f:
        table = list(csv.DictReader(f))
    parser = Rows()
    parser.feed((d / "index.html").read_text(encoding="utf-8"))
    if doc["level"] != level:
        problems.append(f"report.json level {doc['level']!r}, expected {level!r}")
    if not (len(parser.rows) == len(table) == len(doc["table"])):
        problems.append(f"rows: HTML {len(parser.rows)}, CSV {len(table)}, JSON {len(doc['table'])}")
    for h, c, j in zip(parser.rows, table, doc["table"]):
        key = (j["case"], j["quantity"])
        if (h["data-case"], h["data-quantity"]) != key or (c["case"], c["quantity"]) != key:
            problems.append(f"row order differs at {key}")
        if not (h["data-verdict"] == c["verdict"] == j["verdict"]):
            problems.append(f"{key}: verdict HTML {h['data-verdict']}, CSV {c['verdict']}, JSON {j['verdict']}")
        if not (close(h["data-ours"], c["ours"]) and close(c["ours"], j["ours"])):
            problems.append(f"{key}: ours HTML {h['data-ours']}, CSV {c['ours']}, JSON {j['ours']}")
    ran = {case["case"] for case in doc["cases"]}
    for case in doc["cases"]:
        if case.get("level") != level:
            problems.append(f"case {case['case']} ran at level {case.get('level')}")
    for missing in doc["not_run"]:
        if missing["reason"] == "not run":
            problems.append(f"case {missing['case']} of this level did not run")
    for case in ran:
        figure = d / "figures" / f"{case}.svg"
        if not figure.is_file() or figure.stat().st_size == 0 or b"</svg>" not in figure.read_bytes():
            problems.append(f"figure {figure} missing or empty")
        if f"figures/{case}.svg" not in parser.images:
            problems.append(f"index.html does not show figures/{case}.svg")
    if doc["passed"] != all(r["verdict"] in ("pass", "known failure") for r in doc["table"]):
        problems.append("report.json 'passed' disagrees with its rows' verdicts")
    for p in problems:
        print("FAIL:", p)
    print(f"{len(doc['table'])} rows in {len(ran)} cases checked; {len(problems)} problem(s)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2]))
