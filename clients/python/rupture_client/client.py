"""The client: one method per thing a user does with rupture-server (submit, wait, read tables,
series and files, compare jobs), on the standard library's HTTP and pandas for every table."""
import hashlib
import json
import os
import sys
import time
import urllib.error
import urllib.parse
import urllib.request

import pandas

FINAL = ("successful", "failed", "dismissed")


class RuptureError(Exception):
    """The server answered with an error: status (HTTP), problem (the RFC 7807 document, or {}),
    field (the offending field when the server named one) and the server's message as str(e)."""

    def __init__(self, status, problem, message):
        super().__init__(message)
        self.status = status
        self.problem = problem
        self.field = problem.get("field") if isinstance(problem, dict) else None


def _frame(rows, columns, units, labels=None):
    """A DataFrame with the given leading columns (then any others, sorted), units and labels in attrs."""
    extra = sorted({k for row in rows for k in row if k not in columns})
    frame = pandas.DataFrame(rows, columns=list(columns) + extra)
    frame.attrs["units"] = dict(units or {})
    frame.attrs["labels"] = dict(labels or {})
    return frame


def _flatten(row):
    """A replicate table's {"peak_stress": {"mean": ..., "sd": ...}} as "peak_stress.mean", ... columns."""
    flat = {}
    for key, value in row.items():
        if isinstance(value, dict):
            for member, inner in value.items():
                flat[f"{key}.{member}"] = inner
        else:
            flat[key] = value
    return flat


class _ProgressLine:
    """Progress on stderr: a redrawn bar on a terminal, one line per change otherwise."""

    def __init__(self):
        self.terminal = sys.stderr.isatty()
        self.last = None

    def show(self, doc):
        eta = doc.get("eta_s")
        eta_text = f"ETA {eta:.0f} s" if isinstance(eta, (int, float)) else "ETA unknown"
        percent = doc.get("progress", 0)
        if self.terminal:
            filled = int(round(percent * 30 / 100))
            line = (f"\r\033[Kjob {doc['jobID']} [{'#' * filled}{'.' * (30 - filled)}] {percent:3d} %  "
                    f"{doc['status']}  {eta_text}  {doc.get('stage', '')}")[:160]
        else:
            line = f"job {doc['jobID']}: {doc['status']} {percent:3d} %  {doc.get('stage', '')}  {eta_text}"
        if line != self.last:
            print(line, file=sys.stderr, end="" if self.terminal else "\n", flush=True)
            self.last = line

    def close(self):
        if self.terminal and self.last is not None:
            print(file=sys.stderr, flush=True)


def _request_body(inputs, sweep, name, sweep_mode, replicates, refine):
    """The body of POST /processes/{scenario}/execution; an int `replicates` n varies sample.seed."""
    body = {"inputs": inputs, "sweep_mode": sweep_mode}
    if isinstance(replicates, int) and not isinstance(replicates, bool):
        replicates = {"count": replicates, "vary": "sample.seed"}
    for key, value in (("sweep", sweep), ("name", name), ("replicates", replicates), ("refine", refine)):
        if value is not None:
            body[key] = value
    return body


class Client:
    def __init__(self, base_url="http://127.0.0.1:8080", token=None, timeout=60.0):
        self.base = base_url.rstrip("/")
        self.token = token
        self.timeout = timeout

    # -- HTTP ------------------------------------------------------------------------------------

    def _request(self, method, path, body=None, accept="application/json", headers=None):
        headers = dict(headers or {}, Accept=accept)
        data = None
        if body is not None:
            data = json.dumps(body).encode("utf-8")
            headers["Content-Type"] = "application/json"
        if self.token:
            headers["Authorization"] = "Bearer " + self.token
        request = urllib.request.Request(self.base + path, data=data, method=method, headers=headers)
        try:
            return urllib.request.urlopen(request, timeout=self.timeout)
        except urllib.error.HTTPError as e:
            text = e.read().decode("utf-8", "replace")
            try:
                problem = json.loads(text)
            except ValueError:
                problem = {}
            detail = problem.get("detail") if isinstance(problem, dict) else None
            raise RuptureError(e.code, problem, f"{method} {path}: {e.code} {detail or text.strip() or e.reason}") from None
        except urllib.error.URLError as e:
            raise RuptureError(0, {}, f"{method} {path}: cannot reach {self.base}: {e.reason}") from None

    def _json(self, method, path, body=None, headers=None):
        with self._request(method, path, body, headers=headers) as response:
            return json.loads(response.read().decode("utf-8"))

    @staticmethod
    def _id(job):
        return str(job["jobID"] if isinstance(job, dict) else job)

    def _save(self, path_on_server, path, accept):
        """Streams a download to path + ".part" and renames it: a failed download leaves no file."""
        part = str(path) + ".part"
        try:
            with self._request("GET", path_on_server, accept=accept) as response, open(part, "wb") as out:
                while True:
                    chunk = response.read(1 << 16)
                    if not chunk:
                        break
                    out.write(chunk)
        except BaseException:
            if os.path.exists(part):
                os.remove(part)
            raise
        os.replace(part, path)
        return path

    # -- jobs --------------------------------------------------------------------------------------

    def processes(self):
        """The scenario names."""
        return [p["id"] for p in self._json("GET", "/processes")["processes"]]

    def submit(self, scenario, inputs, sweep=None, name=None, sweep_mode="grid", replicates=None, refine=None,
               reuse=False):
        """Submits a job and returns its id (a string).

        inputs: the spec without "scenario"; sweep: {dotted path: [values]}; sweep_mode "grid" or
        "zip"; replicates: runs per sweep point (an int n: n runs on sample seeds seed, seed+1, ...; or the server's
        {"count": n, "vary": "sample.seed"}); refine: the server's
        refinement request (docs/server.md, "Studies"). With reuse=True the same request returns the
        job an earlier identical request made (through an Idempotency-Key derived from the request),
        unless that job failed or was dismissed: then a new job is made."""
        body = _request_body(inputs, sweep, name, sweep_mode, replicates, refine)
        path = "/processes/" + urllib.parse.quote(scenario, safe="") + "/execution"
        if not reuse:
            return self._json("POST", path, body)["jobID"]
        digest = hashlib.sha256(json.dumps([scenario, body], sort_keys=True).encode("utf-8")).hexdigest()
        for attempt in range(100):
            key = f"rupture-client-{digest}-{attempt}"
            job = self._json("POST", path, body, headers={"Idempotency-Key": key})["jobID"]
            if self.status(job)["status"] not in ("failed", "dismissed"):
                return job
        raise RuptureError(0, {}, "reuse: 100 earlier identical jobs all failed or were dismissed")

    def preview(self, scenario, inputs, sweep=None, name=None, sweep_mode="grid", replicates=None, refine=None):
        """What submit() with the same arguments would make, checked as a submission is but not
        queued (the server's dry run): runs, elements, memory_bytes, steps, estimated_wall_s,
        run_estimates, ... (docs/server.md, "Preview and cost"). Raises RuptureError where submit()
        would."""
        body = _request_body(inputs, sweep, name, sweep_mode, replicates, refine)
        return self._json("POST", "/processes/" + urllib.parse.quote(scenario, safe="") + "/execution?dry_run=true", body)

    def status(self, job):
        """The job's status document (status, progress, stage, elapsed_s, eta_s, runs, ...)."""
        return self._json("GET", "/jobs/" + self._id(job))

    def jobs(self, status=None, limit=50):
        """The jobs, newest first, as a DataFrame (jobID, name, processID, status, progress, ...)."""
        query = {"limit": limit}
        if status:
            query["status"] = status if isinstance(status, str) else ",".join(status)
        doc = self._json("GET", "/jobs?" + urllib.parse.urlencode(query))
        rows = [{k: v for k, v in j.items() if not isinstance(v, (list, dict))} for j in doc.get("jobs", [])]
        return _frame(rows, ["jobID", "name", "processID", "status", "progress"], {})

    def wait(self, job, progress=False, poll=1.0, timeout=None):
        """Polls until the job is successful, failed or dismissed; returns its last status document.
        With progress=True shows a progress bar (a line per change when stderr is not a terminal).
        Raises RuptureError when the job failed or was dismissed (the message says which runs and
        why), TimeoutError after timeout s."""
        start = time.monotonic()
        line = _ProgressLine() if progress else None
        try:
            while True:
                doc = self.status(job)
                if line:
                    line.show(doc)
                if doc["status"] in FINAL:
                    break
                if timeout is not None and time.monotonic() - start > timeout:
                    raise TimeoutError(f"job {doc['jobID']} still {doc['status']} after {timeout} s")
                time.sleep(poll)
        finally:
            if line:
                line.close()
        if doc["status"] != "successful":
            errors = [f"run {r['index']}: {r.get('error', r['status'])}" for r in doc.get("runs", [])
                      if r["status"] != "successful"]
            raise RuptureError(200, doc, f"job {doc['jobID']} {doc['status']}: {doc.get('message', '')}; "
                               + "; ".join(errors))
        return doc

    def cancel(self, job):
        """Cancels the job: queued runs never start, running runs stop; finished runs stay."""
        return self._json("DELETE", "/jobs/" + self._id(job))

    dismiss = cancel

    def retry(self, job):
        """Puts the job's failed runs back in the queue."""
        return self._json("POST", "/jobs/" + self._id(job) + "/retry", {})

    def resume(self, job):
        """Runs again every run of a cancelled or failed job that did not succeed (cancelled, failed,
        never started); the successful runs stay. Returns the job's status document."""
        return self._json("POST", "/jobs/" + self._id(job) + "/resume", {})

    # -- tables ------------------------------------------------------------------------------------

    def summary(self, job, aggregate=None):
        """The job's summary as a DataFrame: one row per run (swept values and summary scalars), or
        with aggregate="replicates" one row per sweep point (mean, sd, 95 % interval, n of each
        scalar). Units in .attrs["units"], human labels in .attrs["labels"]."""
        return self._table("/jobs/" + self._id(job) + "/summary", aggregate)

    def summary_document(self, job, aggregate=None):
        """The summary as the server sends it (columns, units, rows, rate_dependence, ...)."""
        query = "?aggregate=" + aggregate if aggregate else ""
        return self._json("GET", "/jobs/" + self._id(job) + "/summary" + query)

    def compare(self, jobs, aggregate=None):
        """The rows of several jobs in one DataFrame, with a leading "job" column."""
        ids = ",".join(self._id(j) for j in jobs)
        return self._table("/summary?jobs=" + urllib.parse.quote(ids, safe=","), aggregate)

    def _table(self, path, aggregate):
        if aggregate:
            path += ("&" if "?" in path else "?") + "aggregate=" + urllib.parse.quote(aggregate)
        doc = self._json("GET", path)
        rows = [_flatten(row) for row in doc.get("rows", [])]
        columns = []
        for c in doc.get("columns", []):
            name = c["name"] if isinstance(c, dict) else c
            members = c.get("members") if isinstance(c, dict) else None
            columns += [f"{name}.{m}" for m in members] if members else [name]
        lead = [c for c in ("job", "run", "status") if any(c in row for row in rows) and c not in columns]
        units, labels = {}, {}
        for c in (c for c in doc.get("columns", []) if isinstance(c, dict)):
            for member in c.get("members") or [None]:
                key = f"{c['name']}.{member}" if member else c["name"]
                units[key] = "1" if member == "n" else c.get("unit", "")
                if "label" in c:
                    labels[key] = c["label"] + (f" ({member})" if member else "")
        units.update(doc.get("units") or {})
        labels.update(doc.get("labels") or {})
        return _frame(rows, lead + columns, units, labels)

    def series(self, job, run, names=None):
        """One run's time series as a DataFrame (one column per series, SI units in .attrs["units"])."""
        path = f"/jobs/{self._id(job)}/runs/{int(run)}/series"
        if names:
            path += "?names=" + urllib.parse.quote(",".join(names), safe=",")
        doc = self._json("GET", path)
        frame = pandas.DataFrame({name: doc["series"][name] for name in doc["names"]}, columns=doc["names"])
        frame.attrs["units"] = doc.get("units", {})
        frame.attrs["labels"] = doc.get("labels", {})
        return frame

    # -- files -------------------------------------------------------------------------------------

    def files(self, job):
        """The job's downloadable files as a DataFrame: one row per finished run with the URLs of its
        HDF5 file, ParaView sidecar and bundle (download them with download(job, path, run=k))."""
        doc = self.status(job)
        rows = []
        for r in doc.get("runs", []):
            if r.get("status") != "successful":
                continue
            prefix = f"{self.base}/jobs/{doc['jobID']}/runs/{r['index']}"
            rows.append({"run": r["index"], "results": prefix + "/results", "xdmf": prefix + "/results.xdmf",
                         "bundle": prefix + "/bundle", "series": prefix + "/series"})
        return _frame(rows, ["run", "results", "xdmf", "bundle", "series"], {})

    def download(self, job, path, run=None):
        """Saves the job's merged HDF5 file (or one run's file with run=k) at path; returns path."""
        where = "/jobs/" + self._id(job) + ("/results" if run is None else f"/runs/{int(run)}/results")
        return self._save(where, path, "application/x-hdf5")

    def crate(self, job, path):
        """Saves the job as an RO-Crate ZIP (Workflow Run Crate: request, specs, result files, summary
        and their provenance; docs/provenance.md) at path; returns path."""
        return self._save("/jobs/" + self._id(job) + "/crate", path, "application/zip")

    def validation_report(self, job, path=None):
        """A validation job's report (docs/validation.md): without path, the table as a DataFrame (one
        row per quantity: case, reference, ours, tolerance, deviation, verdict; the whole document in
        .attrs["report"]); with path, saves the HTML page (figures inline) there and returns path."""
        url = "/jobs/" + self._id(job) + "/report"
        if path is not None:
            return self._save(url, path, "text/html")
        import pandas
        doc = self._json("GET", url + "?format=json")
        table = pandas.DataFrame(doc["table"])
        table.attrs["report"] = doc
        return table

    def plot(self, job, path, x=None, y=None, format=None, **options):
        """Saves the server's plot of the job (SVG or PNG, after path's extension or format=),
        e.g. plot(job, "peak.png", x="loading.strain_rate", y="peak_stress", title="...")."""
        fmt = format or os.path.splitext(str(path))[1].lstrip(".").lower() or "svg"
        query = {k: v for k, v in dict(options, x=x, y=y, format=fmt).items() if v is not None}
        types = {"svg": "image/svg+xml", "png": "image/png", "pdf": "application/pdf"}
        return self._save("/jobs/" + self._id(job) + "/summary.svg?" + urllib.parse.urlencode(query), path,
                          types.get(fmt, "*/*"))

    def open_results(self, job, path):
        """Downloads the merged file and opens it with h5py (pip extra "hdf5", Debian python3-h5py)."""
        import h5py
        return h5py.File(self.download(job, path), "r")
