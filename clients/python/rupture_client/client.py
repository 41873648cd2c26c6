"""A small client for rupture-server, on Python's standard library (pandas and h5py are used when
they are installed, never required).

    from rupture_client import Client
    c = Client("http://127.0.0.1:8080")            # token="..." when the server has one
    job = c.submit("dynamic-tension", inputs, {"loading.strain_rate": [1e5, 1e6]}, name="rates")
    c.wait(job, progress=True)                        # prints progress, stage and ETA on stderr
    table = c.summary(job)                            # a pandas DataFrame, or a list of dicts
    c.download(job, "job.h5")                         # every run in one HDF5 file

Every error the server answers with raises RuptureError carrying its status, its problem document
and the server's message (detail).
"""
import json
import sys
import time
import urllib.error
import urllib.parse
import urllib.request

__all__ = ["Client", "RuptureError"]

FINAL = ("successful", "failed", "dismissed")


class RuptureError(Exception):
    """The server answered with an error: status (HTTP), problem (the RFC 7807 document, or {}),
    field (the offending field when the server named one) and the server's message as str(e)."""

    def __init__(self, status, problem, message):
        super().__init__(message)
        self.status = status
        self.problem = problem
        self.field = problem.get("field") if isinstance(problem, dict) else None


class Client:
    def __init__(self, base_url="http://127.0.0.1:8080", token=None, timeout=60.0):
        self.base = base_url.rstrip("/")
        self.token = token
        self.timeout = timeout

    # -- HTTP ------------------------------------------------------------------------------------

    def _request(self, method, path, body=None, accept="application/json"):
        headers = {"Accept": accept}
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

    def _json(self, method, path, body=None):
        with self._request(method, path, body) as response:
            return json.loads(response.read().decode("utf-8"))

    @staticmethod
    def _id(job):
        return str(job["jobID"] if isinstance(job, dict) else job)

    # -- the API -----------------------------------------------------------------------------------

    def processes(self):
        """The scenario names."""
        return [p["id"] for p in self._json("GET", "/processes")["processes"]]

    def submit(self, scenario, inputs, sweep=None, name=None, sweep_mode="grid"):
        """Submits a sweep (dotted path -> list of values) and returns the job id (a string)."""
        body = {"inputs": inputs, "sweep_mode": sweep_mode}
        if sweep:
            body["sweep"] = sweep
        if name:
            body["name"] = name
        path = "/processes/" + urllib.parse.quote(scenario, safe="") + "/execution"
        return self._json("POST", path, body)["jobID"]

    def status(self, job):
        """The job's status document (status, progress, stage, elapsed_s, eta_s, runs, ...)."""
        return self._json("GET", "/jobs/" + self._id(job))

    def wait(self, job, progress=False, poll=1.0, timeout=None):
        """Polls until the job is successful, failed or dismissed; returns its last status document.
        With progress=True prints one line per change on stderr. Raises RuptureError when the job
        failed or was dismissed (the message says which runs and why), TimeoutError after timeout s."""
        start, last = time.monotonic(), None
        while True:
            doc = self.status(job)
            if progress:
                eta = doc.get("eta_s")
                line = (f"job {doc['jobID']}: {doc['status']} {doc['progress']:3d} %  {doc.get('stage', '')}"
                        + (f"  ETA {eta:.0f} s" if isinstance(eta, (int, float)) else ""))
                if line != last:
                    print(line, file=sys.stderr, flush=True)
                    last = line
            if doc["status"] in FINAL:
                break
            if timeout is not None and time.monotonic() - start > timeout:
                raise TimeoutError(f"job {doc['jobID']} still {doc['status']} after {timeout} s")
            time.sleep(poll)
        if doc["status"] != "successful":
            errors = [f"run {r['index']}: {r.get('error', r['status'])}" for r in doc.get("runs", [])
                      if r["status"] != "successful"]
            raise RuptureError(200, doc, f"job {doc['jobID']} {doc['status']}: {doc.get('message', '')}; "
                               + "; ".join(errors))
        return doc

    def summary(self, job, as_dataframe=None):
        """One row per run: the swept values and the summary scalars. A pandas DataFrame when pandas
        is installed (as_dataframe=False forces a list of dicts), with the units in .attrs["units"]."""
        doc = self._json("GET", "/jobs/" + self._id(job) + "/summary")
        rows = doc.get("rows", [])
        columns = ["run", "status"] + [c["name"] if isinstance(c, dict) else c for c in doc.get("columns", [])]
        units = {c["name"]: c.get("unit", "") for c in doc.get("columns", []) if isinstance(c, dict)}
        units.update(doc.get("units") or {})
        if as_dataframe is not False:
            try:
                import pandas
            except ImportError:
                if as_dataframe:
                    raise
            else:
                extra = [k for row in rows for k in row if k not in columns]
                frame = pandas.DataFrame(rows, columns=columns + sorted(set(extra)))
                frame.attrs["units"] = units
                return frame
        return rows

    def summary_document(self, job):
        """The summary as the server sends it (columns, units, rows, ...)."""
        return self._json("GET", "/jobs/" + self._id(job) + "/summary")

    def download(self, job, path, run=None):
        """Saves the job's merged HDF5 file (or one run's file with run=k) at path; returns path.
        Written to path + ".part" and renamed, so a failed download leaves no file behind."""
        where = "/jobs/" + self._id(job) + ("/results" if run is None else f"/runs/{int(run)}/results")
        part = str(path) + ".part"
        with self._request("GET", where, accept="application/x-hdf5") as response, open(part, "wb") as out:
            while True:
                chunk = response.read(1 << 16)
                if not chunk:
                    break
                out.write(chunk)
        import os
        os.replace(part, path)
        return path

    def dismiss(self, job):
        return self._json("DELETE", "/jobs/" + self._id(job))

    def open_results(self, job, path):
        """Downloads the merged file and opens it with h5py (which must be installed)."""
        import h5py
        return h5py.File(self.download(job, path), "r")
