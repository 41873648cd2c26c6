#!/usr/bin/python3
"""ctest label "python": the client against a real rupture-server (started here on a free port
with its own data directory) with Debian's /usr/bin/python3 and the standard library only.

    test_client.py RUPTURE_SERVER SOURCE_DIR

Checks: a 2-run sweep end to end (submit, wait with progress, summary as a list of dicts with the
swept values and a positive peak stress per run, download of a valid HDF5 file), and that a
misspelled key raises RuptureError with the server's message and status 400.
"""
import json
import pathlib
import subprocess
import sys
import tempfile

server_binary, source = sys.argv[1], pathlib.Path(sys.argv[2])
sys.path.insert(0, str(source / "clients" / "python"))
from rupture_client import Client, RuptureError  # noqa: E402

with tempfile.TemporaryDirectory() as data:
    server = subprocess.Popen([server_binary, "--port", "0", "--data-dir", data, "--workers", "2",
                               "--threads-per-run", "1"], stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    try:
        base = server.stdout.readline().split("listening on ")[1].strip()
        client = Client(base)
        assert "dynamic-tension" in client.processes()
        spec = json.loads((source / "examples" / "dynamic-tension-small.json").read_text())
        spec.pop("scenario")
        spec["loading"]["initial_velocity"] = "VL"  # no preliminary run: about a second per run
        job = client.submit("dynamic-tension", spec, {"loading.strain_rate": [1e6, 1e7]}, name="client test")
        doc = client.wait(job, progress=True, poll=0.5, timeout=300)
        assert doc["status"] == "successful", doc
        rows = client.summary(job, as_dataframe=False)
        assert [r["loading.strain_rate"] for r in rows] == [1e6, 1e7], rows
        assert all(r["status"] == "successful" and r["peak_stress"] > 0 for r in rows), rows
        path = pathlib.Path(data) / "job.h5"
        client.download(job, path)
        assert path.read_bytes()[:8] == b"\x89HDF\r\n\x1a\n", "not an HDF5 file"
        assert not pathlib.Path(str(path) + ".part").exists()

        spec["loading"]["strain_rte"] = spec["loading"].pop("strain_rate")
        try:
            client.submit("dynamic-tension", spec)
            raise AssertionError("a misspelled key was accepted")
        except RuptureError as e:
            assert e.status == 400 and e.field == "loading.strain_rte", (e.status, e.field)
            assert "did you mean 'strain_rate'?" in str(e), str(e)
        try:
            client.status(999)
            raise AssertionError("an unknown job was found")
        except RuptureError as e:
            assert e.status == 404 and "no job '999'" in str(e), str(e)
        print(f"ok: job {job}, {len(rows)} runs, {path.stat().st_size} bytes downloaded")
    finally:
        server.terminate()
        server.wait(timeout=30)
