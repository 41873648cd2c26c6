#!/usr/bin/python3
"""ctest label "browser": the browser as a workbench, driven like a user through Debian's chromium
(headless, over the DevTools protocol with python3-websocket) against a real rupture-server.

    workbench_test.py RUPTURE_SERVER SOURCE_DIR

1. Submits a 2-run sweep through the scenario's form (named <script>alert(1)</script>), lands on
   the job page, watches it finish; the name shows as text (no script runs, no dialog opens) and
   each run has a loaded thumbnail.
2. Opens a run page: its field picture loads at 900 x 600 and is not one colour.
3. A job whose run fails: its page and its run's page show the reason; Retry runs it again.
4. Submits a slow job through the form and cancels it with the job page's button; resumes it with
   the page's Resume button (it runs again) and cancels it again.
5. Compares two jobs from the job list: the comparison page has both jobs' rows.
6. Opens the sweep's "Submit a variant" form: its preview (a dry run) shows the run count, an
   estimated time and the picture of the first run's sample; submitted unchanged, it makes the sweep's runs again, spec for spec.
7. Opens every scenario's form and submits it unchanged (on a second server whose runs wait for
   disk space, so nothing runs): each lands on its new job's page.
"""
import json
import os
import pathlib
import shutil
import subprocess
import sys
import tempfile
import time
import urllib.request

import websocket

server_binary, source = sys.argv[1], pathlib.Path(sys.argv[2])


def wait_until(what, check, timeout=120, every=0.25):
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        value = check()
        if value:
            return value
        time.sleep(every)
    raise AssertionError(f"timed out waiting for {what}")


class Browser:
    """One headless chromium page, driven over the DevTools protocol."""

    def __init__(self, profile):
        chromium = shutil.which("chromium") or shutil.which("chromium-browser")
        assert chromium, "chromium is not installed (deploy/test.sh installs it)"
        self.process = subprocess.Popen([chromium, "--headless", "--no-sandbox", "--disable-gpu",
                                         "--remote-debugging-port=0", f"--user-data-dir={profile}",
                                         "--window-size=1280,1000", "about:blank"],
                                        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        port_file = pathlib.Path(profile) / "DevToolsActivePort"
        wait_until("chromium's DevTools port", port_file.exists, 60)
        port = wait_until("the port number", lambda: port_file.read_text().split("\n")[0].strip(), 10)
        targets = json.loads(urllib.request.urlopen(f"http://127.0.0.1:{port}/json/list", timeout=10).read())
        page = next(t for t in targets if t["type"] == "page")
        self.ws = websocket.create_connection(page["webSocketDebuggerUrl"], timeout=60, suppress_origin=True)
        self.next_id = 0
        self.dialogs = []
        self.call("Page.enable")
        self.call("Runtime.enable")

    def call(self, method, **params):
        self.next_id += 1
        self.ws.send(json.dumps({"id": self.next_id, "method": method, "params": params}))
        while True:
            message = json.loads(self.ws.recv())
            if message.get("method") == "Page.javascriptDialogOpening":
                self.dialogs.append(message["params"])
                self.ws.send(json.dumps({"id": 0, "method": "Page.handleJavaScriptDialog",
                                         "params": {"accept": True}}))
            if message.get("id") == self.next_id:
                assert "error" not in message, message
                return message["result"]

    def js(self, expression):
        result = self.call("Runtime.evaluate", expression=expression, awaitPromise=True, returnByValue=True)
        assert "exceptionDetails" not in result, result
        return result["result"].get("value")

    def open(self, url):
        self.call("Page.navigate", url=url)
        self.settle()

    def click_and_reload(self, element_id):
        """Clicks a button whose action reloads the page, and waits for the new page: navigating
        away before the reload would let the old page's reload win the race."""
        self.js(f"window.__old = true; document.getElementById('{element_id}').click(), true")
        wait_until("the page to reload", lambda: self.js("window.__old === undefined"), 60)
        self.settle()

    def settle(self):
        wait_until("the page to load", lambda: self.js("document.readyState") == "complete", 60)
        # every <img> done (loaded or failed)
        wait_until("the images", lambda: self.js("[...document.images].every(i => i.complete)"), 60)

    def close(self):
        try:
            self.ws.close()
        finally:
            self.process.terminate()
            self.process.wait(timeout=30)


def http_json(base, path, body=None):
    data = json.dumps(body).encode() if body is not None else None
    request = urllib.request.Request(base + path, data=data, headers={"Content-Type": "application/json",
                                                                       "Accept": "application/json"})
    return json.loads(urllib.request.urlopen(request, timeout=30).read())


def forms_as_opened(browser, scratch):
    """Every scenario's form, submitted as opened, is a job (issue 55: two of seven were refused
    over defaults the form filled in for a model or shape that was not chosen)."""
    server = subprocess.Popen([server_binary, "--port", "0", "--data-dir", str(scratch / "forms"), "--workers", "1",
                               "--min-free-bytes", str(10 ** 18)], stdout=subprocess.PIPE, stderr=subprocess.DEVNULL,
                              text=True)
    try:
        base = server.stdout.readline().split("listening on ")[1].strip()
        names = [p["id"] for p in http_json(base, "/processes")["processes"]]
        assert len(names) >= 7, names
        for name in names:
            browser.open(base + f"/processes/{name}?f=html")
            browser.js("document.getElementById('submit').click(), true")

            def landed():
                page = browser.js("location.pathname")
                if page.startswith("/jobs/"):
                    return page
                error = browser.js("(document.getElementById('form-error') || {}).textContent || ''")
                assert not error, f"{name}'s form as opened was refused: {error}"
                return None
            path = wait_until(f"{name}'s job page", landed, 30)
            browser.settle()
            assert http_json(base, path)["processID"] == name, path
    finally:
        server.terminate()
        server.wait(timeout=30)
    return len(names)


def main():
    example = json.loads((source / "examples" / "dynamic-tension-small.json").read_text())
    example.pop("scenario")
    with tempfile.TemporaryDirectory() as scratch:
        scratch = pathlib.Path(scratch)
        server = subprocess.Popen([server_binary, "--port", "0", "--data-dir", str(scratch / "data"), "--workers", "2",
                                   "--threads-per-run", "1"], stdout=subprocess.PIPE, stderr=subprocess.DEVNULL,
                                  text=True, env=dict(os.environ, OMP_NUM_THREADS="1"))
        browser = None
        try:
            base = server.stdout.readline().split("listening on ")[1].strip()
            browser = Browser(scratch / "profile")

            # 1. A sweep through the form, with a name that would be a script if it were not escaped.
            browser.open(base + "/processes/dynamic-tension?f=html")
            assert browser.js("document.querySelector('[data-path=\"sample.size\"]').value") == "1e-6, 1e-6"
            browser.js("""(() => {
                document.querySelector('[data-path="loading.initial_velocity"]').value = 'VL';
                const row = document.querySelector('.sweep-row');
                row.querySelector('select').value = 'loading.strain_rate';
                row.querySelector('input').value = '1e6, 1e7';
                document.getElementById('job-name').value = '<script>alert(1)</script>';
                document.getElementById('submit').click(); return true; })()""")
            path = wait_until("the job page", lambda: (lambda p: p if p.startswith("/jobs/") else None)(
                browser.js("location.pathname")), 60)
            job = path.split("/")[2]
            wait_until("the sweep to finish", lambda: http_json(base, "/jobs/" + job)["status"] in
                       ("successful", "failed"), 240, 1)
            assert http_json(base, "/jobs/" + job)["status"] == "successful"
            browser.open(base + f"/jobs/{job}?f=html")
            assert browser.js("document.getElementById('status').textContent") == "successful"
            assert "<script>alert(1)</script>" in browser.js("document.querySelector('h1').textContent")
            assert browser.js("document.scripts.length") == 1, "only the page's own script"
            thumbs = browser.js("[...document.querySelectorAll('img.thumb')].map(i => i.naturalWidth)")
            assert thumbs == [160, 160], thumbs
            # Every column opened ("All N columns"), the wide table scrolls inside the page, which
            # stays as wide as the window (issue 55: it was 4,123 px), its first column held.
            browser.js("document.querySelectorAll('details').forEach(d => d.open = true), true")
            assert browser.js("document.getElementById('summary-all').offsetWidth > window.innerWidth"), \
                "the table is wider than the window, as it should be for this check"
            widths = browser.js("[document.documentElement.scrollWidth, window.innerWidth]")
            assert widths[0] <= widths[1], widths
            assert browser.js("getComputedStyle(document.querySelector('#summary-all td')).position") == "sticky"

            # 2. A run page: the field picture loads and holds a field, not one colour.
            browser.open(base + f"/jobs/{job}/runs/0?f=html")
            size = browser.js("(() => { const i = document.getElementById('field'); "
                              "return [i.naturalWidth, i.naturalHeight]; })()")
            assert size == [900, 600], size
            colours = browser.js("""(() => {
                const i = document.getElementById('field'), c = document.createElement('canvas');
                c.width = i.naturalWidth; c.height = i.naturalHeight;
                const g = c.getContext('2d'); g.drawImage(i, 0, 0);
                const d = g.getImageData(0, 0, c.width, c.height).data, seen = new Set();
                for (let k = 0; k < d.length; k += 4 * 7) seen.add(d[k] << 16 | d[k + 1] << 8 | d[k + 2]);
                return seen.size; })()""")
            assert colours > 50, colours
            # Measurable: the colour range is settable on the page, and the picture follows it.
            browser.js("""(() => { const f = document.getElementById('picture-form');
                f.querySelector('[name=field]').value = 'von_mises';
                f.querySelector('[name=min]').value = '0'; f.querySelector('[name=max]').value = '5e7';
                f.submit(); return true; })()""")
            wait_until("the page with the range", lambda: "max=5e7" in browser.js("location.search"), 30)
            browser.settle()
            assert "max=50000000" in browser.js("document.getElementById('field').src")
            assert browser.js("document.getElementById('field').naturalWidth") == 900

            # 3. A run that fails: the job page and the run page say why; Retry runs it again. (A sample
            # narrower than an element is refused at POST now; pores that two could hold but three
            # cannot are found only by placing them.)
            broken = json.loads(json.dumps(example))
            broken["sample"].update({"size": [1e-6, 1e-6], "porosity": 0.5, "pore_radius": [2.5e-7, 2.5e-7]})
            broken["loading"]["initial_velocity"] = "VL"
            failed = http_json(base, "/processes/dynamic-tension/execution", {"inputs": broken, "name": "fails"})["jobID"]
            wait_until("the failure", lambda: http_json(base, "/jobs/" + failed)["status"] == "failed", 60)
            assert http_json(base, "/jobs/" + failed)["progress"] < 100, "a failed job shows no full bar"
            browser.open(base + f"/jobs/{failed}?f=html")
            assert "could not place the pores" in browser.js("document.getElementById('reason').textContent")
            assert "could not place the pores" in browser.js("document.getElementById('runs').textContent")
            assert browser.js("document.getElementById('bar').value") < 100
            browser.open(base + f"/jobs/{failed}/runs/0?f=html")
            assert "could not place the pores" in browser.js("document.getElementById('reason').textContent")
            browser.open(base + f"/jobs/{failed}?f=html")
            browser.click_and_reload("retry")
            wait_until("the retried run", lambda: http_json(base, f"/jobs/{failed}/runs/0").get("attempts", 1) == 2
                       and http_json(base, "/jobs/" + failed)["status"] == "failed", 60)

            # 4. A slow job through the form, cancelled from its page.
            browser.open(base + "/processes/dynamic-tension?f=html")
            browser.js("""(() => {
                document.querySelector('[data-path="loading.initial_velocity"]').value = 'V0';
                document.querySelector('[data-path="loading.strain_rate"]').value = '1e4';
                document.getElementById('job-name').value = 'slow';
                document.getElementById('submit').click(); return true; })()""")
            path = wait_until("the slow job's page", lambda: (lambda p: p if p.startswith("/jobs/") and
                              p.split("/")[2] not in (job, failed) else None)(browser.js("location.pathname")), 60)
            slow = path.split("/")[2]
            wait_until("the slow job to run", lambda: http_json(base, "/jobs/" + slow)["status"] == "running", 60)
            browser.open(base + f"/jobs/{slow}?f=html")
            browser.click_and_reload("cancel")
            wait_until("the cancel", lambda: http_json(base, "/jobs/" + slow)["status"] == "dismissed", 30)
            # Resumed from its page, it runs again; cancelled again, so that it does not hold the worker.
            wait_until("the cancelled run to stop", lambda: http_json(base, "/jobs/" + slow)["runs"][0]["status"] ==
                       "dismissed", 30)
            browser.open(base + f"/jobs/{slow}?f=html")
            browser.click_and_reload("resume")
            assert http_json(base, "/jobs/" + slow)["status"] in ("accepted", "running")
            assert browser.js("document.getElementById('status').textContent") in ("accepted", "running")
            browser.click_and_reload("cancel")
            wait_until("the second cancel", lambda: http_json(base, "/jobs/" + slow)["status"] == "dismissed", 30)

            # 5. Two jobs compared from the list.
            browser.open(base + "/jobs?f=html")
            browser.js(f"""(() => {{
                for (const id of ['{job}', '{failed}'])
                  document.querySelector('input[name="jobs"][value="' + id + '"]').checked = true;
                document.getElementById('compare').click(); return true; }})()""")
            wait_until("the comparison", lambda: browser.js("location.pathname") == "/summary", 30)
            browser.settle()
            rows = browser.js("document.querySelectorAll('#compare tr').length")
            assert rows == 1 + 3, rows  # header, two runs of the sweep, the failed run

            # 6. A variant of the sweep keeps what was asked: its preview counts its runs, and submitted
            # unchanged it makes the same runs, spec for spec, under the same name.
            browser.open(base + f"/processes/dynamic-tension?f=html&from={job}")
            browser.js("document.getElementById('preview-button').click(), true")
            preview = wait_until("the preview", lambda: browser.js(
                "(document.getElementById('preview-table') || {}).textContent || ''"), 30)
            assert "Runs2" in preview and "Estimated time" in preview and "not estimated" not in preview, preview
            # ... and draws the first run's sample, built as the run builds it: a 900 x 600 picture
            # from the server (the page's policy admits no other) whose caption counts its elements.
            height = wait_until("the preview picture", lambda: browser.js(
                "(p => p.complete && !p.hidden && p.naturalWidth === 900 ? p.naturalHeight : 0)"
                "(document.getElementById('preview-picture'))"), 60)
            assert height == 600, height
            caption = browser.js("document.getElementById('preview-caption').textContent")
            assert " elements, " in caption and "first of the job's 2 runs" in caption, caption
            browser.js("document.getElementById('submit').click(), true")
            path = wait_until("the variant's page", lambda: (lambda p: p if p.startswith("/jobs/") else None)(
                browser.js("location.pathname")), 60)
            variant = path.split("/")[2]
            assert variant not in (job, failed, slow), variant
            old, new = http_json(base, "/jobs/" + job), http_json(base, "/jobs/" + variant)
            for key in ("name", "swept", "sweep_mode", "runs_total"):
                assert new.get(key) == old.get(key), (key, old.get(key), new.get(key))
            for k in range(old["runs_total"]):
                assert http_json(base, f"/jobs/{variant}/runs/{k}")["spec"] == http_json(base, f"/jobs/{job}/runs/{k}")["spec"], k

            forms = forms_as_opened(browser, scratch)

            assert not browser.dialogs, f"a page opened a dialog (script injection?): {browser.dialogs}"
            print(f"ok: sweep job {job}, failed job {failed}, cancelled job {slow}, variant {variant}, "
                  f"{forms} forms submitted as opened")
        finally:
            if browser:
                browser.close()
            server.terminate()
            server.wait(timeout=30)


if __name__ == "__main__":
    main()
