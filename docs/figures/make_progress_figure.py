#!/usr/bin/env python3
"""The progress a run reports against the progress it actually made: docs/figures/progress-seed-sample.*

Starts a server from a built tree, submits the seed's own sample (examples/dynamic-tension-seed.json)
at 1e6 /s with the VL initial field (the run that separates early and then runs on to its stop, the
case where progress used to lie), polls GET /jobs/{id} every 0.25 s, and once the run is over compares
what it said with what happened: the actual fraction done at wall time t is t / T (T its whole running
time) and the actual time left T - t. Writes the samples (CSV), a plot (SVG) and, with Debian's
chromium, the PNG of the plot.

    python3 docs/figures/make_progress_figure.py [BUILD_DIR]

Only the standard library: the plot is written as SVG by hand.
"""
import csv
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
import urllib.request

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
OUT = os.path.join(ROOT, "docs", "figures")
NAME = "progress-seed-sample"


def get(url):
    with urllib.request.urlopen(url, timeout=30) as r:
        return json.load(r)


def post(url, body):
    req = urllib.request.Request(url, data=json.dumps(body).encode(), headers={"Content-Type": "application/json"})
    with urllib.request.urlopen(req, timeout=30) as r:
        return json.load(r)


def start_server(build, work):
    log = open(os.path.join(work, "server.out"), "w")
    proc = subprocess.Popen([os.path.join(build, "server", "rupture-server"), "--port", "0", "--data-dir",
                             os.path.join(work, "data"), "--workers", "1", "--threads-per-run", "1"],
                            stdout=log, stderr=subprocess.STDOUT)
    for _ in range(200):
        text = open(os.path.join(work, "server.out")).read()
        m = re.search(r"listening on (http\S+)", text)
        if m:
            return proc, m.group(1).rstrip("/")
        time.sleep(0.1)
    proc.kill()
    raise SystemExit("the server did not start: " + open(os.path.join(work, "server.out")).read())


def follow(base, job):
    """(t, progress %, eta s or None, status) every 0.25 s from the moment the run runs."""
    samples, start = [], None
    while True:
        doc = get(f"{base}/jobs/{job}")
        run = doc["runs"][0]
        now = time.monotonic()
        if run["status"] == "running" and start is None:
            start = now
        if start is not None:
            samples.append((now - start, run.get("progress"), run.get("eta_s"), run["status"]))
        if doc["status"] in ("successful", "failed", "dismissed"):
            return samples, doc
        time.sleep(0.25)


def polyline(points, sx, sy, colour, dash=""):
    path = " ".join(f"{sx(x):.1f},{sy(y):.1f}" for x, y in points)
    extra = f' stroke-dasharray="{dash}"' if dash else ""
    return f'<polyline fill="none" stroke="{colour}" stroke-width="2"{extra} points="{path}"/>'


def panel(x0, title, ylabel, ymax, series, total):
    """One plot 480 x 300 at x0: series = [(label, colour, dash, [(t, y)])]."""
    w, h, left, top = 480, 300, 60, 40
    sx = lambda t: x0 + left + t / total * (w - left - 20)
    sy = lambda y: top + (1 - y / ymax) * (h - top - 50)
    out = [f'<text x="{x0 + w / 2}" y="20" text-anchor="middle" font-size="15">{title}</text>']
    for t in ticks(total):  # the time axis: tick marks below it
        out.append(f'<line x1="{sx(t):.1f}" y1="{sy(0):.1f}" x2="{sx(t):.1f}" y2="{sy(0) + 5:.1f}" stroke="#000"/>')
        out.append(f'<text x="{sx(t):.1f}" y="{sy(0) + 20:.1f}" text-anchor="middle" font-size="12">{t:g}</text>')
    for y in ticks(ymax):  # the value axis: grid lines across
        out.append(f'<line x1="{sx(0) - 5:.1f}" y1="{sy(y):.1f}" x2="{sx(total):.1f}" y2="{sy(y):.1f}" stroke="#ddd"/>')
        out.append(f'<text x="{sx(0) - 8:.1f}" y="{sy(y) + 4:.1f}" text-anchor="end" font-size="12">{y:g}</text>')
    out.append(f'<line x1="{sx(0)}" y1="{sy(0)}" x2="{sx(total)}" y2="{sy(0)}" stroke="#000"/>')
    out.append(f'<line x1="{sx(0)}" y1="{sy(0)}" x2="{sx(0)}" y2="{sy(ymax)}" stroke="#000"/>')
    out.append(f'<text x="{x0 + left + (w - left) / 2}" y="{h - 8}" text-anchor="middle" font-size="13">wall time since the run started (s)</text>')
    out.append(f'<text transform="translate({x0 + 16},{top + (h - top - 50) / 2}) rotate(-90)" text-anchor="middle" font-size="13">{ylabel}</text>')
    for k, (label, colour, dash, points) in enumerate(series):
        out.append(polyline(points, sx, sy, colour, dash))
        ly = top + 8 + 18 * k
        out.append(f'<line x1="{x0 + w - 190}" y1="{ly}" x2="{x0 + w - 160}" y2="{ly}" stroke="{colour}" stroke-width="2"'
                   + (f' stroke-dasharray="{dash}"' if dash else "") + "/>")
        out.append(f'<text x="{x0 + w - 155}" y="{ly + 4}" font-size="12">{label}</text>')
    return out


def ticks(span):
    """Round values 0, s, 2s, ... up to span (s a 1-2-5 step)."""
    step = nice_step(span)
    return [k * step for k in range(int(span / step + 1e-9) + 1)]


def nice_step(span):
    """A 1-2-5 tick step giving about 5 ticks over span."""
    raw = span / 5
    mag = 10 ** int(f"{raw:e}".split("e")[1])
    for m in (1, 2, 5, 10):
        if m * mag >= raw:
            return m * mag
    return 10 * mag


def main():
    build = os.path.abspath(sys.argv[1]) if len(sys.argv) > 1 else os.path.join(ROOT, "build")
    work = tempfile.mkdtemp()
    proc, base = start_server(build, work)
    try:
        spec = json.load(open(os.path.join(ROOT, "examples", "dynamic-tension-seed.json")))
        spec.pop("scenario")
        spec.pop("description", None)
        spec["loading"]["initial_velocity"] = "VL"
        job = post(f"{base}/processes/dynamic-tension/execution",
                   {"name": "seed's sample, VL, 1e6 /s", "inputs": spec})["jobID"]
        samples, doc = follow(base, job)
    finally:
        proc.terminate()
        proc.wait()
        shutil.rmtree(work, ignore_errors=True)
    if doc["status"] != "successful":
        raise SystemExit(f"the run ended {doc['status']}: {json.dumps(doc)[:2000]}")
    running = [s for s in samples if s[3] == "running"]
    total = samples[-1][0]  # the first sample that saw the job over
    with open(os.path.join(OUT, NAME + ".csv"), "w", newline="") as f:
        out = csv.writer(f)
        out.writerow(["wall_s", "reported_progress_percent", "actual_progress_percent", "reported_eta_s", "actual_remaining_s"])
        for t, p, eta, _ in running:
            out.writerow([f"{t:.2f}", p, f"{100 * t / total:.1f}", "" if eta is None else f"{eta:.1f}", f"{total - t:.1f}"])
    worst_ahead = max((p - 100 * t / total for t, p, _, _ in running if p is not None), default=0.0)
    zero_eta = sum(1 for _, _, eta, _ in running if eta == 0)
    progress = [("reported", "#1f5fbf", "", [(t, p) for t, p, _, _ in running if p is not None]),
                ("actual (t / T)", "#000", "6,4", [(0, 0), (total, 100)])]
    etas = [(t, eta) for t, _, eta, _ in running if eta is not None]
    eta_max = max([total] + [e for _, e in etas]) * 1.05
    remaining = [("reported ETA", "#bf3f1f", "", etas), ("actual time left (T − t)", "#000", "6,4", [(0, total), (total, 0)])]
    svg = ['<svg xmlns="http://www.w3.org/2000/svg" width="1000" height="340" font-family="sans-serif">',
           '<rect width="1000" height="340" fill="#fff"/>']
    svg += panel(0, "Progress of the seed's sample run", "progress (%)", 100, progress, total)
    svg += panel(500, "Time left", "seconds", eta_max, remaining, total)
    svg.append(f'<text x="500" y="336" text-anchor="middle" font-size="11">T = {total:.1f} s; reported ahead of actual by at most '
               f'{worst_ahead:.1f} points; ETA 0 while running: {zero_eta} of {len(running)} samples</text>')
    svg.append("</svg>")
    svg_path = os.path.join(OUT, NAME + ".svg")
    open(svg_path, "w").write("\n".join(svg) + "\n")
    chromium = shutil.which("chromium")
    if chromium:
        profile = tempfile.mkdtemp()
        subprocess.run([chromium, "--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars",
                        f"--user-data-dir={profile}", "--window-size=1000,340",
                        f"--screenshot={os.path.join(OUT, NAME + '.png')}", "file://" + svg_path],
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=False)
        shutil.rmtree(profile, ignore_errors=True)
    print(json.dumps({"run_seconds": round(total, 2), "samples": len(running), "worst_ahead_points": round(worst_ahead, 1),
                      "eta_zero_while_running": zero_eta}))


if __name__ == "__main__":
    main()
