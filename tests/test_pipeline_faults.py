"""A sweep under faults loses nothing (issue 42): interrupted (Ctrl-C) and resumed, kernels killed at random
(SIGKILL), one run's record that cannot be written (ENOSPC); at every stop each run is either complete and
valid (``ok`` with its results, or ``failed`` with its error) or absent, and summary.csv says which."""

import csv
import errno
import json
import os
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import numpy as np
import psutil

from conftest import FIXTURE_NOTEBOOK
from tvtrack.pipeline.lock import LOCK_NAME
from tvtrack.pipeline.sweep import expand, load_spec, run_sweep


def _kernels_under(folder: Path) -> list[psutil.Process]:
    found = []
    for proc in psutil.process_iter(["cmdline", "cwd"]):
        with_kernel = "ipykernel" in " ".join(proc.info.get("cmdline") or [])
        if with_kernel and (proc.info.get("cwd") or "").startswith(str(folder)):
            found.append(proc)
    return found


def _check_every_run(out: Path, runs) -> dict[str, str]:
    """Each run complete and valid or absent, no temporary folder or lock left, and summary.csv saying which;
    returns ``{run id: status}``."""
    runs_dir = out / "runs"
    assert not list(runs_dir.glob(".tmp-*")) and not list(runs_dir.glob(".*.lock")) and not (out / LOCK_NAME).exists()
    assert {p.name for p in runs_dir.iterdir()} <= {r.run_id for r in runs}
    on_disk = {}
    for run in runs:
        folder = runs_dir / run.run_id
        if not folder.exists():
            on_disk[run.run_id] = "absent"
            continue
        record = json.loads((folder / "run.json").read_text())
        assert record["parameters"]["seed"] == run.parameters["seed"]
        if record["status"] == "ok":
            rms = json.loads((folder / "results.json").read_text())["metrics"]["centroid_rms_px"]
            assert 0 < rms["ci_low"] <= rms["value"] <= rms["ci_high"] < 1.0
        else:
            assert record["status"] == "failed" and record["error"] and (folder / "error.txt").is_file()
        on_disk[run.run_id] = record["status"]
    with (out / "summary.csv").open() as fh:
        summary = {row["run_id"]: row["status"] for row in csv.DictReader(fh)}
    assert summary == on_disk
    return on_disk


def _kill_kernels(folder: Path, rng: np.random.Generator, stop: threading.Event, killed: list) -> None:
    """SIGKILL a kernel under ``folder`` after a random wait, twice at most."""
    while not stop.is_set() and len(killed) < 2:
        stop.wait(rng.uniform(1.0, 3.0))
        kernels = _kernels_under(folder)
        if kernels and not stop.is_set():
            victim = kernels[int(rng.integers(len(kernels)))]
            try:
                victim.send_signal(signal.SIGKILL)
                killed.append(victim.pid)
            except psutil.NoSuchProcess:
                pass


def test_a_sweep_under_kills_a_failed_write_and_an_interrupt_loses_nothing(tmp_path, monkeypatch):
    spec = tmp_path / "faults.toml"
    spec.write_text(
        f'notebook = "{FIXTURE_NOTEBOOK}"\nrepeats = 2\n[fixed]\nn_trials = 200\nn_frames = 4\nrerun_mode = "off"\n'
        '[grid]\nspot_sigma_px = [1.0, 2.0, 3.0]\n[summary]\nx = "spot_sigma_px"\ny = "centroid_rms_px.value"\n'
    )
    runs = expand(load_spec(spec))
    out = tmp_path / "faults"
    # 1. Ctrl-C once a run has finished
    proc = subprocess.Popen(
        [sys.executable, "-m", "tvtrack", "sweep", str(spec), "--jobs", "2", "-o", str(out)],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        start_new_session=True,
    )
    deadline = time.time() + 120
    while time.time() < deadline and not [p for p in (out / "runs").glob("[0-9a-f]*")]:
        time.sleep(0.1)
    os.killpg(proc.pid, signal.SIGINT)
    stdout, stderr = proc.communicate(timeout=60)
    assert proc.returncode == 130 and (stdout + stderr).strip().startswith("interrupted: "), stdout + stderr
    (out / "summary.csv").write_text("run_id,status\n")  # an interrupted sweep writes none: check the disk alone
    done = [r.run_id for r in runs if (out / "runs" / r.run_id).exists()]
    assert 1 <= len(done) < len(runs)

    # 2. resumed with kernels killed at random and the first record written out of space
    write_text, failures = Path.write_text, []

    def write(self, *args, **kwargs):
        if self.name == "run.json" and not failures:
            failures.append(self.parent.name)
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC), str(self))
        return write_text(self, *args, **kwargs)

    monkeypatch.setattr(Path, "write_text", write)
    stop, killed = threading.Event(), []
    killer = threading.Thread(target=_kill_kernels, args=(out, np.random.default_rng(42), stop, killed))
    killer.start()
    try:
        faulty = run_sweep(spec, jobs=1, output=out, progress=False)
    finally:
        stop.set()
        killer.join()
    monkeypatch.undo()
    status = _check_every_run(out, runs)
    print(f"killed kernels {killed}; statuses after the faults {sorted(status.values())}")
    assert killed, "no kernel was killed"
    assert faulty.n_skipped == len(done) and faulty.n_absent == 1 and len(failures) == 1
    assert list(status.values()).count("absent") == 1
    assert faulty.n_ok == list(status.values()).count("ok") and faulty.n_failed == len(runs) - faulty.n_ok

    # 3. resumed once more without faults: every run complete and valid
    final = run_sweep(spec, jobs=2, output=out, progress=False)
    assert _check_every_run(out, runs) == {r.run_id: "ok" for r in runs}
    assert final.n_skipped == faulty.n_ok and final.n_ok == len(runs) and final.plot is not None
