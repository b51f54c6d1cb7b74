"""Runs and sweeps interrupted (Ctrl-C, SIGTERM, SIGKILL) and resumed, and the temporaries a dead process leaves,
all on the fixture notebook (tests/fixtures/fixture_centroid.ipynb). Kept apart from test_runner.py so that the
two files' minutes of kernels are spread over two test workers."""

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from load import wall_budget

from conftest import FIXTURE_NOTEBOOK
from tvtrack.pipeline.runner import read_run
from tvtrack.pipeline.sweep import run_sweep


def write_spec(path: Path, body: str) -> Path:
    path.write_text(f'notebook = "{FIXTURE_NOTEBOOK}"\n' + body)
    return path


@pytest.mark.determinism
def test_sigkill_midway_then_resume_finishes_only_missing_runs(tmp_path):
    spec = write_spec(
        tmp_path / "killed.toml",
        'repeats = 2\n[fixed]\nn_trials = 20\nn_frames = 5\nrerun_mode = "off"\n[grid]\nspot_sigma_px = [1.0, 2.0, 3.0]\n',
    )
    out = tmp_path / "killed"
    proc = subprocess.Popen(
        [sys.executable, "-m", "tvtrack", "sweep", str(spec), "--jobs", "2", "-o", str(out)],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
        start_new_session=True,
    )
    runs = out / "runs"
    deadline = time.time() + 240
    while time.time() < deadline:
        done = [p for p in runs.glob("[0-9a-f]*")] if runs.exists() else []
        if len(done) >= 2:
            break
        time.sleep(0.2)
    os.killpg(proc.pid, signal.SIGKILL)
    proc.wait()
    finished = {p.name for p in runs.iterdir() if not p.name.startswith(".")}  # not .tmp-* nor a lock file
    assert 2 <= len(finished) < 6
    for name in finished:  # no half-written run directory
        assert read_run(runs / name)["status"] == "ok"
        assert (runs / name / "results.json").is_file()
    resumed = run_sweep(spec, jobs=2, output=out, progress=False)
    assert resumed.n_skipped == len(finished)
    assert resumed.n_ok == 6 and not list(runs.glob(".tmp-*")) and not list(runs.glob(".*.lock"))


def _wait_for(predicate, timeout_s=240):
    deadline = time.time() + timeout_s
    while time.time() < deadline:
        if predicate():
            return True
        time.sleep(0.1)
    return False


def _tvtrack_in_own_group(*args):
    """``python -m tvtrack ARGS`` as a terminal starts it: its own process group, Ctrl-C not ignored."""
    return subprocess.Popen(
        [sys.executable, "-m", "tvtrack", *map(str, args)],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        start_new_session=True,
    )


def _kernels_of_tree(tmp_path) -> list[str]:
    """Command lines of live ipykernel processes whose working directory is under ``tmp_path``."""
    import psutil

    found = []
    for proc in psutil.process_iter(["cmdline", "cwd"]):
        cwd = proc.info.get("cwd") or ""
        if "ipykernel" in " ".join(proc.info.get("cmdline") or []) and cwd.startswith(str(tmp_path)):
            found.append(cwd)
    return found


def test_ctrl_c_during_a_sweep_stops_it_cleanly_and_the_sweep_resumes(tmp_path):
    spec = write_spec(
        tmp_path / "int.toml",
        'repeats = 2\n[fixed]\nn_trials = 200\nn_frames = 10\nrerun_mode = "off"\n[grid]\nspot_sigma_px = [1.0, 2.0]\n',
    )
    out = tmp_path / "int"
    runs = out / "runs"
    proc = _tvtrack_in_own_group("sweep", spec, "--jobs", "2", "-o", out)
    finished = lambda: [p for p in runs.iterdir() if not p.name.startswith(".")] if runs.exists() else []  # noqa: E731
    assert _wait_for(lambda: finished() and list(runs.glob(".tmp-*"))), "no run finished and none running"
    t0 = time.time()
    os.killpg(proc.pid, signal.SIGINT)  # what Ctrl-C in a terminal does
    stdout, stderr = proc.communicate(timeout=30)
    assert time.time() - t0 < wall_budget(10)
    assert proc.returncode == 130, stderr
    lines = stderr.strip().splitlines()  # stdout: the sweep's count, stated before it started
    assert len(lines) == 1 and lines[0].startswith("interrupted: ") and "resumes" in lines[0], stdout + stderr
    assert stdout.splitlines() == [f"int: 4 runs, 0 finished before, 4 to run (2 at once) -> {out}"], stdout
    assert not list(runs.glob(".tmp-*"))
    assert _wait_for(lambda: not _kernels_of_tree(tmp_path), 5), "a kernel outlived the sweep"
    done = {p.name for p in finished()}
    assert 1 <= len(done) < 4
    for name in done:
        assert read_run(runs / name)["status"] == "ok"
    resumed = run_sweep(spec, jobs=2, output=out, progress=False)
    assert (resumed.n_skipped, resumed.n_ok) == (len(done), 4)


def test_ctrl_c_during_a_run_ends_the_kernel_and_leaves_nothing(tmp_path):
    proc = _tvtrack_in_own_group("run", FIXTURE_NOTEBOOK, "-p", "n_trials", "20000", "-o", tmp_path / "run")
    assert _wait_for(lambda: _kernels_of_tree(tmp_path), 120)
    time.sleep(1.0)
    os.killpg(proc.pid, signal.SIGINT)
    stdout, stderr = proc.communicate(timeout=30)
    assert proc.returncode == 130
    lines = (stdout + stderr).strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("interrupted: "), stdout + stderr
    assert list(tmp_path.iterdir()) == []
    assert _wait_for(lambda: not _kernels_of_tree(tmp_path), 5)


def test_sigterm_to_a_run_ends_its_kernel_like_ctrl_c(tmp_path):
    """``kill PID`` (SIGTERM: a CI time-out, a process manager) stops a run as Ctrl-C does: the kernel ended (it
    runs in a session of its own, so it never sees the signal), nothing left, one line, exit 128 + 15."""
    proc = _tvtrack_in_own_group("run", FIXTURE_NOTEBOOK, "-p", "n_trials", "20000", "-o", tmp_path / "run")
    assert _wait_for(lambda: _kernels_of_tree(tmp_path), 120)
    time.sleep(1.0)
    proc.send_signal(signal.SIGTERM)  # the process alone, not its group
    stdout, stderr = proc.communicate(timeout=30)
    assert proc.returncode == 128 + signal.SIGTERM, stderr
    lines = (stdout + stderr).strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("interrupted: "), stdout + stderr
    assert list(tmp_path.iterdir()) == []
    assert _wait_for(lambda: not _kernels_of_tree(tmp_path), 5), "a kernel outlived the run"


def test_stale_temporaries_of_a_dead_process_are_removed_live_ones_kept(tmp_path):
    from tvtrack.pipeline.runner import OWNER_FILE, remove_stale_temporaries

    dead = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"], capture_output=True, text=True)
    host = __import__("socket").gethostname()
    for name, pid in ((".tmp-a-1", int(dead.stdout)), (".tmp-b-2", os.getpid())):
        (tmp_path / name).mkdir()
        (tmp_path / name / OWNER_FILE).write_text(f"{host} {pid}")
    assert remove_stale_temporaries(tmp_path) == 1
    assert [p.name for p in tmp_path.iterdir()] == [".tmp-b-2"]


@pytest.mark.parametrize("stage", ["import", "record"])
def test_a_stop_outside_the_kernels_lifetime_leaves_no_temporary_folder(tmp_path, monkeypatch, stage):
    # a Ctrl-C while papermill was still being imported (before the kernel's start), or while the run's record
    # was written, left the run's .tmp-* folder behind under a line saying nothing was written
    from tvtrack.pipeline import lean_imports, runner

    def stopped(*args, **kwargs):
        raise KeyboardInterrupt()

    if stage == "import":
        monkeypatch.setattr(lean_imports, "papermill", stopped)
    else:
        monkeypatch.setattr(runner, "_write_record", stopped)
    with pytest.raises(KeyboardInterrupt):
        runner.run_notebook(FIXTURE_NOTEBOOK, tmp_path / "run", {"n_trials": 20, "n_frames": 2, "rerun_mode": "off"})
    assert sorted(p.name for p in tmp_path.iterdir()) == []
