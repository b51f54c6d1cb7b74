"""Runner, sweeps, failure isolation, determinism and the Dask executor, all on the fixture notebook
(tests/fixtures/fixture_centroid.ipynb). Interrupted runs and sweeps: test_runner_interrupts.py."""

import json
import subprocess
import sys
import time
from pathlib import Path

import pytest

from conftest import FIXTURE_NOTEBOOK, FIXTURE_RUNS, FIXTURE_SWEEP
from tvtrack.pipeline.runner import read_run, run_notebook
from tvtrack.pipeline.sweep import expand, load_spec, run_sweep

SWEEP_PARAMS = {"n_trials": 20, "n_frames": 5, "rerun_mode": "off"}


def metrics(run_dir: Path) -> dict:
    return json.loads((run_dir / "results.json").read_text())["metrics"]


def write_spec(path: Path, body: str) -> Path:
    path.write_text(f'notebook = "{FIXTURE_NOTEBOOK}"\n' + body)
    return path


@pytest.fixture(scope="module")
def sweep_two_jobs(tmp_path_factory):
    """The fixture sweep on 2 jobs; ``.workers_up_in_preflight``: the pool processes alive when its preflight
    checked the values (the workers start while it runs)."""
    import multiprocessing

    from tvtrack.pipeline import sweep

    seen, checked = [], sweep.preflight

    def preflight(*args, **kwargs):
        deadline = time.time() + 60
        while len(multiprocessing.active_children()) < 2 and time.time() < deadline:
            time.sleep(0.05)
        seen.append(len(multiprocessing.active_children()))
        return checked(*args, **kwargs)

    out = tmp_path_factory.mktemp("sweep") / "fixture"
    sweep.preflight = preflight
    try:
        summary = run_sweep(FIXTURE_SWEEP, jobs=2, output=out, progress=False)
    finally:
        sweep.preflight = checked
    summary.workers_up_in_preflight = seen
    summary.workers_left = len(multiprocessing.active_children())
    return summary


def test_a_two_job_sweep_starts_its_workers_while_the_preflight_checks(sweep_two_jobs):
    """The workers' start-up (a Python process each, importing the runner and papermill) overlaps the preflight
    instead of following it; the pool ends with the sweep (a refused sweep ends them too, with no traceback:
    tests/test_cli.py)."""
    assert sweep_two_jobs.workers_up_in_preflight == [2] and sweep_two_jobs.workers_left == 0


def test_run_writes_results_figure_recording_and_record(fixture_runs):
    """The session's run of the fixture notebook (``run_notebook`` with ``FIXTURE_RUNS``' overrides, tests/conftest.py,
    which the site and report tests read too): what a run leaves does not depend on its size, so that run is read
    here instead of a kernel started for one of 20 trials."""
    run = fixture_runs / "fixture_centroid"
    names = {p.name for p in run.iterdir()}
    assert {"results.json", "run.json", "notebook.ipynb", "recording.rrd", "centroid_errors.png"} <= names
    record = read_run(run)
    assert record["status"] == "ok" and record["parameters"]["n_trials"] == FIXTURE_RUNS["fixture_centroid"]["n_trials"]
    assert not list(fixture_runs.glob(".tmp-*"))


def test_invalid_parameter_fails_with_the_validation_message(tmp_path):
    outcome = run_notebook(FIXTURE_NOTEBOOK, tmp_path / "bad", {"spot_sigma_px": -1.0})
    assert not outcome.ok
    assert "parameter 'spot_sigma_px' = -1.0 is out of range" in outcome.error
    assert read_run(tmp_path / "bad")["status"] == "failed"
    assert "ValueError" in (tmp_path / "bad" / "error.txt").read_text()
    assert not (tmp_path / "bad" / "results.json").exists()


def test_cli_run_exit_codes(tmp_path):
    cmd = [sys.executable, "-m", "tvtrack", "run", str(FIXTURE_NOTEBOOK), "-q", "-p", "n_trials", "5"]
    ok = subprocess.run(cmd + ["-o", str(tmp_path / "a")], capture_output=True, text=True)
    assert ok.returncode == 0 and "ok: fixture_centroid" in ok.stdout
    # a notebook that raises at run time (not in its validation cell) is a failed run: exit 1, with its record
    broken = subprocess.run(
        cmd + ["-p", "spot_flux_e", "1e-300", "-p", "n_frames", "1", "-o", str(tmp_path / "b")],
        capture_output=True,
        text=True,
    )
    assert broken.returncode in (0, 1)
    assert (tmp_path / "b" / "run.json").is_file()


def test_spec_expansion_and_stable_ids():
    runs = expand(load_spec(FIXTURE_SWEEP))
    assert len(runs) == 8 and len({r.run_id for r in runs}) == 8
    assert sorted({r.parameters["seed"] for r in runs}) == [1, 2]
    assert [r.run_id for r in runs] == [r.run_id for r in expand(load_spec(FIXTURE_SWEEP))]


def test_bad_specs_are_refused(tmp_path):
    with pytest.raises(ValueError, match="unknown key .gird.; did you mean .grid."):
        load_spec(write_spec(tmp_path / "a.toml", "gird = 1\n"))
    with pytest.raises(ValueError, match="same length"):
        load_spec(write_spec(tmp_path / "b.toml", "[zip]\na = [1, 2]\nb = [1]\n"))
    with pytest.raises(ValueError, match="more than one"):
        load_spec(write_spec(tmp_path / "c.toml", "[fixed]\na = 1\n[grid]\na = [1, 2]\n"))


def test_sweep_of_eight_runs_with_two_jobs(sweep_two_jobs):
    s = sweep_two_jobs
    assert (s.n_runs, s.n_ok, s.n_failed) == (8, 8, 0)
    lines = s.summary_csv.read_text().splitlines()
    assert len(lines) == 9 and "centroid_rms_px.value" in lines[0] and "verdict C900-1" in lines[0]
    assert s.plot is not None and s.plot.stat().st_size > 0
    again = run_sweep(FIXTURE_SWEEP, jobs=2, output=s.sweep_dir, progress=False)
    assert again.n_skipped == 8 and again.n_ok == 8


@pytest.mark.determinism
def test_same_seed_gives_identical_metrics_alone_and_in_sweeps(sweep_two_jobs, tmp_path):
    target = next(
        r
        for r in expand(load_spec(FIXTURE_SWEEP))
        if r.parameters["spot_sigma_px"] == 1.5 and r.parameters["seed"] == 2
    )
    in_two_jobs = metrics(sweep_two_jobs.sweep_dir / "runs" / target.run_id)
    alone = run_notebook(FIXTURE_NOTEBOOK, tmp_path / "alone", target.parameters)
    spec = write_spec(
        tmp_path / "one.toml",
        "[fixed]\n"
        + "".join(f"{k} = {json.dumps(v)}\n" for k, v in target.parameters.items() if k != "seed")
        + f"seed = {target.parameters['seed']}\n",
    )
    one_job = run_sweep(spec, jobs=1, output=tmp_path / "one", progress=False)
    assert one_job.n_ok == 1
    (run_dir,) = [p for p in (tmp_path / "one" / "runs").iterdir()]
    assert metrics(tmp_path / "alone") == in_two_jobs == metrics(run_dir)
    assert alone.ok


def test_failed_run_is_isolated_and_recorded(tmp_path):
    # every value passes the preflight; a copy of the fixture fails at run time (after its validation cell) at -2.0
    nb = json.loads(FIXTURE_NOTEBOOK.read_text())
    first_code = next(i for i, c in enumerate(nb["cells"]) if c["cell_type"] == "code")
    nb["cells"].insert(
        first_code + 2,
        {
            "cell_type": "code",
            "id": "planted",
            "metadata": {},
            "execution_count": None,
            "outputs": [],
            "source": "if spot_sigma_px == 2.0:\n    raise RuntimeError('planted failure')\n",
        },
    )
    (tmp_path / "failing.ipynb").write_text(json.dumps(nb))
    spec = tmp_path / "mixed.toml"
    spec.write_text(
        'notebook = "failing.ipynb"\n[fixed]\nn_trials = 10\nn_frames = 3\nrerun_mode = "off"\n'
        "[grid]\nspot_sigma_px = [1.0, 2.0, 3.0]\n"
    )
    s = run_sweep(spec, jobs=2, output=tmp_path / "mixed", progress=False)
    assert (s.n_ok, s.n_failed) == (2, 1)
    rows = s.summary_csv.read_text().splitlines()
    failed = [r for r in rows if ",failed," in r]
    assert len(failed) == 1 and "RuntimeError: planted failure" in failed[0]
    cli = subprocess.run(
        [sys.executable, "-m", "tvtrack", "sweep", str(spec), "-o", str(tmp_path / "mixed")],
        capture_output=True,
        text=True,
    )
    assert cli.returncode == 1  # any failed run makes the sweep exit non-zero
    assert "2 ok, 1 failed, 2 skipped" in cli.stdout


@pytest.mark.determinism
def test_dask_executor_on_a_local_cluster(sweep_two_jobs, tmp_path):
    """Two runs of the fixture sweep (its first seed, two spot widths), one for each of the cluster's two workers,
    give the metrics the module's two-job sweep on this machine gave for the same parameters."""
    distributed = pytest.importorskip("distributed")
    spec = write_spec(
        tmp_path / "dask.toml",
        "repeats = 1\n[fixed]\n"
        + "".join(f"{k} = {json.dumps(v)}\n" for k, v in SWEEP_PARAMS.items())
        + "[grid]\nspot_sigma_px = [1.0, 2.0]\n",
    )
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        s = run_sweep(
            spec, output=tmp_path / "dask", executor="dask", scheduler=cluster.scheduler_address, progress=False
        )
    assert (s.n_runs, s.n_ok) == (2, 2)
    here = {json.dumps(r.parameters, sort_keys=True): r.run_id for r in expand(load_spec(FIXTURE_SWEEP))}
    for run in expand(load_spec(spec)):
        local = sweep_two_jobs.sweep_dir / "runs" / here[json.dumps(run.parameters, sort_keys=True)]
        assert metrics(s.sweep_dir / "runs" / run.run_id) == metrics(local)


def test_the_notebooks_default_output_dir_resolves_inside_the_clone_whatever_the_working_directory(
    tmp_path, monkeypatch
):
    from tvtrack.pipeline.paths import INTERACTIVE_DIR, REPO_ROOT, resolve_output_dir

    for cwd in (REPO_ROOT, REPO_ROOT / "notebooks", tmp_path):  # plain papermill at the root, JupyterLab, elsewhere
        monkeypatch.chdir(cwd)
        for default in ("../papermill_runs/interactive/004_laser_spot_prediction", "", None):
            out = resolve_output_dir(default, "004_laser_spot_prediction")
            assert out.is_absolute() and out == INTERACTIVE_DIR / "004_laser_spot_prediction"
            assert out.is_relative_to(REPO_ROOT)
    assert resolve_output_dir(".", "004_laser_spot_prediction") == Path(".")  # the runner's run directory
    assert resolve_output_dir("/tmp/x", "004_laser_spot_prediction") == Path("/tmp/x")
