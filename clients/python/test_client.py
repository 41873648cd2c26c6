#!/usr/bin/python3
"""ctest label "python": the client package installed as a user installs it, then used against a
real rupture-server (started here on a free port with its own data directory).

    test_client.py RUPTURE_SERVER SOURCE_DIR

1. Installs clients/python with pip into a fresh venv made with --system-site-packages, offline
   (--no-build-isolation --no-index: Debian's setuptools, wheel and pandas, no package index), from a
   copy of the sources so that nothing is written into the source tree.
2. Runs the checks below with the venv's python, which must import the installed package:
   preview a 2-rate sweep with 2 replicates (a dry run: 4 runs, nothing queued; a bad rate raises
   the 400), submit it (and the same request again with reuse=True: the same
   job), wait with progress, summary per run and aggregated (DataFrames with units), a run's series,
   the files, a comparison of two jobs, a download of a valid HDF5 file, the job's RO-Crate (read with
   zipfile and checked against RO-Crate's and the Workflow Run Crate's required entities), a plot, and the errors: a
   misspelled key raises RuptureError with the server's message and status 400, an unknown job 404.
3. Runs the README's walk-through (its ```python blocks) as written, against the same server: the
   runs' table has each replicate's sample.seed, the files it names are written.
"""
import ast
import json
import os
import pathlib
import re
import shutil
import subprocess
import sys
import tempfile


def check_crate(path, job, runs):
    """The RO-Crate of a job, read with the standard library's zipfile (an independent reader):
    RO-Crate 1.1's required entities (metadata descriptor, root data entity with name, description,
    datePublished, license), the Workflow Run Crate's (conformsTo, a ComputationalWorkflow mainEntity,
    a CreateAction with it as instrument), every listed file in the ZIP with its stated size, and
    each run's spec and HDF5 file (their /provenance is checked by the server tests)."""
    import zipfile

    with zipfile.ZipFile(path) as crate:
        assert crate.testzip() is None, "a member's CRC does not match"
        names = set(crate.namelist())
        metadata = json.loads(crate.read("ro-crate-metadata.json"))
        assert metadata["@context"] == "https://w3id.org/ro/crate/1.1/context", metadata["@context"]
        graph = {e["@id"]: e for e in metadata["@graph"]}
        descriptor = graph["ro-crate-metadata.json"]
        assert descriptor["@type"] == "CreativeWork" and descriptor["about"] == {"@id": "./"}, descriptor
        assert {"@id": "https://w3id.org/ro/crate/1.1"} in descriptor["conformsTo"], descriptor
        root = graph["./"]
        assert root["@type"] == "Dataset", root
        for key in ("name", "description", "datePublished", "license", "hasPart", "mainEntity"):
            assert key in root, key
        assert graph[root["license"]["@id"]]["name"], root["license"]
        profiles = {p["@id"] for p in root["conformsTo"]}
        assert "https://w3id.org/ro/wfrun/workflow/0.5" in profiles and "https://w3id.org/ro/wfrun/process/0.5" in profiles
        workflow = graph[root["mainEntity"]["@id"]]
        assert {"File", "SoftwareSourceCode", "ComputationalWorkflow"} <= set(workflow["@type"]), workflow
        request = json.loads(crate.read(workflow["@id"]))
        assert request["sweep"] == {"loading.strain_rate": [1e6, 1e7]}, request
        actions = [graph[m["@id"]] for m in root["mentions"]]
        assert all(a["@type"] == "CreateAction" for a in actions), actions
        assert [a for a in actions if a["instrument"] == root["mainEntity"]], "no action runs the workflow"
        # Every data entity the root lists is in the ZIP with the stated size, and nothing else is.
        parts = [p["@id"] for p in root["hasPart"]]
        assert set(parts) | {"ro-crate-metadata.json"} == names, (sorted(parts), sorted(names))
        for part in parts:
            assert int(graph[part]["contentSize"]) == crate.getinfo(part).file_size, part
        run_actions = [a for a in actions if a["instrument"] == {"@id": "#rupture"}]
        assert len(run_actions) == runs, run_actions
        for action in run_actions:
            spec = json.loads(crate.read(action["object"][0]["@id"]))
            result = action["result"][0]["@id"]
            assert crate.read(result)[:8] == b"\x89HDF\r\n\x1a\n", result
            assert graph[result]["encodingFormat"] == "application/x-hdf5", graph[result]
            assert spec["loading"]["strain_rate"] in (1e6, 1e7) and spec["scenario"] == "dynamic-tension", spec
            assert action["actionStatus"]["@id"] == "http://schema.org/CompletedActionStatus", action
    return path


def readme_statements(readme):
    """The statements of the README's ```python blocks, in order: their >>> and ... lines without
    the prompts (the lines they print are left out)."""
    lines = []
    for block in re.findall(r"```python\n(.*?)```", readme, re.S):
        for line in block.splitlines():
            if line.startswith((">>> ", "... ")) or line in (">>>", "..."):
                lines.append(line[4:])
    return ast.parse("\n".join(lines)).body


def run_readme(source, base, data):
    """Runs clients/python/README.md's walk-through as written, against the server at `base` (for
    its http://127.0.0.1:8080), from a directory whose examples/ is the repository's; then checks
    what the README says it shows: the runs' table with each replicate's seed, the units."""
    statements = readme_statements((source / "clients" / "python" / "README.md").read_text())
    assert len(statements) > 10, "the README's walk-through is not where the test looks"
    work = pathlib.Path(data) / "readme"
    work.mkdir()
    (work / "examples").symlink_to(source / "examples")
    try:
        import matplotlib  # noqa: F401  (only DataFrame.plot needs it)
        matplotlib.use("Agg")
        plotting = True
    except ImportError:
        plotting = False
    here = os.getcwd()
    os.chdir(work)
    try:
        scope = {}
        for statement in statements:
            text = ast.unparse(statement).replace("http://127.0.0.1:8080", base)
            try:
                exec(compile(text, "README.md", "exec"), scope)
            except ImportError as e:
                if plotting or "matplotlib" not in str(e):
                    raise
                print(f"skipped without matplotlib: {text}")
    finally:
        os.chdir(here)
    runs = scope["runs"]
    shown = runs[["loading.strain_rate", "sample.seed", "peak_stress"]]
    seed = json.loads((source / "examples" / "dynamic-tension-small.json").read_text())["sample"]["seed"]
    for rate in (1e6, 1e7):
        assert sorted(shown.loc[shown["loading.strain_rate"] == rate, "sample.seed"]) == [seed, seed + 1, seed + 2], shown
    assert runs.attrs["units"]["peak_stress"] == "Pa" and runs.attrs["units"]["sample.seed"] == "1", runs.attrs
    assert (work / "rates.h5").read_bytes()[:8] == b"\x89HDF\r\n\x1a\n"
    assert (work / "peak.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert len(scope["points"]) == 2 and (scope["points"]["peak_stress.n"] == 3).all(), scope["points"]
    print(f"ok: the README's {len(statements)} statements ran")


def checks(server_binary, source, data):
    import rupture_client
    from rupture_client import Client, RuptureError
    import pandas

    assert "site-packages" in rupture_client.__file__, f"imported from {rupture_client.__file__}, not the venv"
    server = subprocess.Popen([server_binary, "--port", "0", "--data-dir", data, "--workers", "2",
                               "--threads-per-run", "1"], stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    try:
        base = server.stdout.readline().split("listening on ")[1].strip()
        client = Client(base)
        assert "dynamic-tension" in client.processes()
        spec = json.loads((source / "examples" / "dynamic-tension-small.json").read_text())
        spec.pop("scenario")
        spec["loading"]["initial_velocity"] = "VL"  # no preliminary run: about a second per run
        sweep = {"loading.strain_rate": [1e6, 1e7]}
        before = len(client.jobs())
        plan = client.preview("dynamic-tension", spec, sweep, name="client test", replicates=2)
        assert plan["runs"] == 4 and plan["estimated_wall_s"] > 0 and plan["elements"]["max"] > 0, plan
        assert len(client.jobs()) == before, "a preview queues nothing"
        try:
            client.preview("dynamic-tension", spec, {"loading.strain_rate": [1e6, -1]})
            raise AssertionError("a negative strain rate was previewed")
        except RuptureError as e:
            assert e.status == 400 and e.field == "loading.strain_rate", (e.status, e.field)
        job = client.submit("dynamic-tension", spec, sweep, name="client test", replicates=2, reuse=True)
        assert client.submit("dynamic-tension", spec, sweep, name="client test", replicates=2, reuse=True) == job
        doc = client.wait(job, progress=True, poll=0.5, timeout=300)
        assert doc["status"] == "successful", doc

        runs = client.summary(job)
        assert isinstance(runs, pandas.DataFrame) and len(runs) == 4, runs
        assert sorted(runs["loading.strain_rate"]) == [1e6, 1e6, 1e7, 1e7], runs
        assert (runs["status"] == "successful").all() and (runs["peak_stress"] > 0).all(), runs
        assert runs.attrs["units"]["peak_stress"] == "Pa", runs.attrs

        points = client.summary(job, aggregate="replicates")
        assert isinstance(points, pandas.DataFrame) and len(points) == 2, points
        mean = [c for c in points.columns if c.startswith("peak_stress") and "mean" in c]
        assert mean, list(points.columns)
        for rate in (1e6, 1e7):
            expected = runs.loc[runs["loading.strain_rate"] == rate, "peak_stress"].mean()
            got = points.loc[points["loading.strain_rate"] == rate, mean[0]].iloc[0]
            assert abs(got - expected) <= 1e-9 * abs(expected), (rate, got, expected)

        series = client.series(job, 0)
        assert isinstance(series, pandas.DataFrame) and len(series) > 1 and "time" in series.columns, series
        assert series.attrs["units"]["time"] == "s" and series["time"].is_monotonic_increasing

        files = client.files(job)
        assert list(files["run"]) == [0, 1, 2, 3], files

        other = client.submit("dynamic-tension", spec, {"loading.strain_rate": [1e7]}, name="client test 2")
        client.wait(other, poll=0.5, timeout=300)
        both = client.compare([job, other])
        assert isinstance(both, pandas.DataFrame) and len(both) == 5, both
        assert sorted(set(both["job"].astype(str))) == sorted({str(job), str(other)}), both
        listed = client.jobs()
        assert isinstance(listed, pandas.DataFrame) and set(listed["jobID"].astype(str)) >= {str(job), str(other)}, listed

        path = pathlib.Path(data) / "job.h5"
        client.download(job, path)
        assert path.read_bytes()[:8] == b"\x89HDF\r\n\x1a\n", "not an HDF5 file"
        assert not pathlib.Path(str(path) + ".part").exists()
        check_crate(client.crate(job, pathlib.Path(data) / "crate.zip"), job, 4)
        plot = pathlib.Path(data) / "peak.svg"
        client.plot(job, plot, x="loading.strain_rate", y="peak_stress")
        assert b"<svg" in plot.read_bytes()[:400], plot.read_bytes()[:400]

        # A validation job (one quick case) and its report as a table and as a page.
        check = client.submit("validation", {"level": "quick"}, {"case": ["lattice-elastic-constants"]}, name="client validation")
        client.wait(check, poll=0.5, timeout=300)
        report = client.validation_report(check)
        assert isinstance(report, pandas.DataFrame) and len(report) == 4, report
        assert set(report["verdict"]) <= {"pass", "known failure"}, report[["quantity", "verdict"]]
        assert report.attrs["report"]["passed"] is True
        page = client.validation_report(check, pathlib.Path(data) / "report.html")
        assert b"<svg" in pathlib.Path(page).read_bytes(), "the report page shows its figures inline"

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
        print(f"ok: job {job}, {len(runs)} runs, {path.stat().st_size} bytes downloaded")
        run_readme(source, base, data)
    finally:
        server.terminate()
        server.wait(timeout=30)


def main():
    server_binary, source = str(pathlib.Path(sys.argv[1]).resolve()), pathlib.Path(sys.argv[2]).resolve()
    with tempfile.TemporaryDirectory() as scratch:
        scratch = pathlib.Path(scratch)
        sources = scratch / "rupture-client"
        shutil.copytree(source / "clients" / "python", sources,
                        ignore=shutil.ignore_patterns("build", "*.egg-info", "__pycache__"))
        venv = scratch / "venv"
        subprocess.run([sys.executable, "-m", "venv", "--system-site-packages", str(venv)], check=True)
        install = subprocess.run([str(venv / "bin" / "pip"), "install", "--quiet", "--no-build-isolation", "--no-index",
                                  str(sources)], capture_output=True, text=True)
        assert install.returncode == 0, install.stdout + install.stderr
        data = scratch / "data"
        data.mkdir()
        # The checks run in the venv's interpreter, from a directory without the sources.
        subprocess.run([str(venv / "bin" / "python"), str(pathlib.Path(__file__).resolve()), "--inside",
                        server_binary, str(source), str(data)], check=True, cwd=str(scratch))


if __name__ == "__main__":
    if sys.argv[1] == "--inside":
        sys.path = [p for p in sys.path if pathlib.Path(p or ".").resolve() != pathlib.Path(__file__).resolve().parent]
        checks(sys.argv[2], pathlib.Path(sys.argv[3]), sys.argv[4])
    else:
        main()
