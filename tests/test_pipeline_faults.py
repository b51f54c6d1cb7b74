"""A sweep under faults loses nothing: interrupted (Ctrl-C) and resumed, kernels killed at random
(SIGKILL), one run's record that cannot be written (ENOSPC); at every stop each run is either complete and
valid (``ok`` with its results, or ``failed`` with its error) or absent, and summary.csv says which."""

import csv
import errno
import json
import os
import re
import signal
import socket
import subprocess
import sys
import threading
import time
from pathlib import Path

import numpy as np
import psutil
import pytest

from conftest import minimal_claim, FIXTURE_NOTEBOOK
from load import wall_budget
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
    assert proc.returncode == 130 and stderr.strip().startswith("interrupted: "), stdout + stderr
    assert stdout.startswith("faults: 6 runs, 0 finished before, 6 to run (2 at once)"), stdout
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


# --- nothing of the user's is deleted, every stop stops, damaged files are one line -------------


def tvtrack(*args, timeout=60, **kwargs):
    return subprocess.run(
        [sys.executable, "-m", "tvtrack", *map(str, args)], capture_output=True, text=True, timeout=timeout, **kwargs
    )


def one_line(proc, code, *fragments) -> str:
    assert proc.returncode == code, (proc.returncode, proc.stdout, proc.stderr)
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in proc.stderr + proc.stdout, proc.stderr
    for fragment in fragments:
        assert fragment in lines[0], (fragment, lines[0])
    return lines[0]


def _claim(cid: str, verdict: str) -> dict:
    return minimal_claim(cid, verdict)


def _paper_run(root: Path, name: str, claims: list, **record) -> Path:
    """A finished run directory as the runner leaves it, with a hand-made results.json."""
    run = root / name
    run.mkdir(parents=True)
    base = {"notebook": name, "profile": "paper", "status": "ok", "runtime_s": 12.0, "finished_utc": "2026-12-01"}
    (run / "run.json").write_text(json.dumps({**base, **record}))
    results = {"notebook": name, "citation": f"A: {name}", "seed": 1, "runtime_s": 10.0, "git_commit": "abc"}
    (run / "results.json").write_text(json.dumps({**results, "metrics": {}, "figures": [], "claims": claims}))
    notebook = {"nbformat": 4, "nbformat_minor": 5, "metadata": {}, "cells": []}
    (run / "notebook.ipynb").write_text(json.dumps(notebook))
    return run


def test_site_onto_a_folder_of_the_users_files_is_refused_and_a_site_is_replaced_without_losing_theirs(tmp_path):
    runs = tmp_path / "runs"
    (runs / "reproduce").mkdir(parents=True)
    mine = tmp_path / "mine"
    mine.mkdir()
    (mine / "index.html").write_text("my homepage")
    (mine / "notes.txt").write_text("my notes")
    one_line(tvtrack("site", "--runs", runs, "-o", mine), 2, f"-o {mine}", "not a site built here")
    assert {p.name: p.read_text() for p in mine.iterdir()} == {"index.html": "my homepage", "notes.txt": "my notes"}

    site = tmp_path / "site"
    assert tvtrack("site", "--runs", runs, "-o", site).returncode == 0
    (site / "notebooks" / "draft.html").write_text("my draft")  # a file of the user's inside a site built here
    one_line(tvtrack("site", "--runs", runs, "-o", site), 2, f"-o {site}", "notebooks/draft.html")
    assert (site / "notebooks" / "draft.html").read_text() == "my draft"
    (site / "notebooks" / "draft.html").unlink()
    first = (site / "index.html").stat().st_ino
    assert tvtrack("site", "--runs", runs, "-o", site).returncode == 0
    assert (site / "index.html").stat().st_ino != first  # rebuilt, through a temporary folder and a rename
    assert [p.name for p in tmp_path.iterdir() if p.name.startswith(".")] == []


def test_stale_cleanup_leaves_a_users_tmp_folder_and_lock_file_alone(tmp_path):
    from tvtrack.pipeline.runner import OWNER_FILE, remove_stale_temporaries

    ours = tmp_path / ".tmp-run-1"  # a run's temporary folder whose process is gone
    ours.mkdir()
    dead = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"], capture_output=True, text=True)
    (ours / OWNER_FILE).write_text(f"{__import__('socket').gethostname()} {int(dead.stdout)}")
    theirs = tmp_path / ".tmp-thesis"
    theirs.mkdir()
    (theirs / "chapter1.tex").write_text("keep me")
    os.utime(theirs, (time.time() - 3600, time.time() - 3600))
    (tmp_path / ".editor.lock").write_text("opened by my editor\n")
    (tmp_path / ".dead.lock").write_text("99999999 host\n")  # a tvtrack lock whose writer was killed
    assert remove_stale_temporaries(tmp_path) == 1
    assert sorted(p.name for p in tmp_path.iterdir()) == [".editor.lock", ".tmp-thesis"]
    assert (theirs / "chapter1.tex").read_text() == "keep me"


def test_a_sweep_states_its_count_and_a_large_one_needs_yes(tmp_path):
    spec = tmp_path / "large.toml"
    spec.write_text(f'notebook = "{FIXTURE_NOTEBOOK}"\nrepeats = 1001\n[fixed]\nn_trials = 20\n')
    proc = tvtrack("sweep", spec, "-o", tmp_path / "large", timeout=30, start_new_session=True)
    one_line(proc, 2, "1,001 runs", "--yes")
    assert not (tmp_path / "large").exists()
    assert "1,000 runs starts only with --yes" in " ".join(tvtrack("sweep", "--help").stdout.split())


def test_a_ctrl_c_while_the_pool_starts_its_workers_is_held_and_raised_after_never_lost():
    # the shield ignores SIGINT so that spawned workers inherit it ignored; a Ctrl-C in that window used to be
    # dropped (a sweep then ran on through its 20,000 runs)
    code = (
        "import os, signal, time\n"
        "from tvtrack.pipeline.interrupt import shielded_spawn\n"
        "try:\n"
        "    with shielded_spawn():\n"
        "        os.kill(os.getpid(), signal.SIGINT)\n"
        "        time.sleep(0.3)\n"
        "        print('inside', flush=True)\n"
        "    print('lost')\n"
        "except KeyboardInterrupt:\n"
        "    print('raised', signal.getsignal(signal.SIGINT) is signal.default_int_handler)\n"
    )
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert proc.stdout.split() == ["inside", "raised", "True"], proc.stdout + proc.stderr


@pytest.mark.parametrize("where", ["pool worker", "single run"])
def test_a_stop_that_cuts_a_kernel_launch_short_prints_no_warning(where):
    # a stop that lands while jupyter_client has made its launch coroutine but not yet awaited it left Python's
    # "coroutine ... was never awaited" warning on the user's terminal before the one "interrupted:" line
    stop = (
        "interrupt.worker_init()\nctx = interrupt.running_a_task()\nsig = signal.SIGTERM\n"
        if where == "pool worker"
        else "ctx = interrupt.kernels_end_on_ctrl_c()\nsig = signal.SIGINT\n"
    )
    code = (
        "import gc, os, signal, time\n"
        "from tvtrack.pipeline import interrupt\n"
        "async def launch_kernel():\n"
        "    pass\n"
        "async def earlier():\n"
        "    pass\n"
        "earlier()\n"  # until a stop, an unawaited coroutine still warns: nothing is silenced at import
        f"{stop}"
        "try:\n"
        "    with ctx:\n"
        "        cut = launch_kernel()\n"
        "        os.kill(os.getpid(), sig)\n"
        "        time.sleep(5)\n"
        "except KeyboardInterrupt:\n"
        "    print('stopped', flush=True)\n"
        "del cut\n"
        "gc.collect()\n"
    )
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert proc.stdout.split() == ["stopped"], proc.stdout + proc.stderr
    assert "launch_kernel" not in proc.stderr and "'earlier' was never awaited" in proc.stderr, proc.stderr


def test_a_ctrl_c_with_nothing_to_say_still_prints_a_whole_line(monkeypatch, capsys):
    # a KeyboardInterrupt without a message used to print "interrupted: " and nothing after it
    from tvtrack.pipeline import cli

    def stopped(args):
        raise KeyboardInterrupt()

    monkeypatch.setattr(cli, "_cmd_report", stopped)
    assert cli.main(["report"]) == 130
    assert capsys.readouterr().err == "interrupted: report stopped\n"


@pytest.mark.parametrize("phase", ["preflight", "_finish"])
def test_a_ctrl_c_before_the_runs_or_while_summing_up_names_the_sweep(tmp_path, monkeypatch, phase):
    # a Ctrl-C outside the runs themselves (the values' checks, the summary) reached the command line bare
    from tvtrack.pipeline import sweep

    spec = tmp_path / "edges.toml"
    spec.write_text(f'notebook = "{FIXTURE_NOTEBOOK}"\n[fixed]\nn_trials = 20\nn_frames = 2\nrerun_mode = "off"\n')

    def stopped(*args, **kwargs):
        raise KeyboardInterrupt()

    monkeypatch.setattr(sweep, phase, stopped)
    with pytest.raises(KeyboardInterrupt) as caught:
        sweep.run_sweep(spec, output=tmp_path / "out", progress=False)
    assert str(caught.value) == "edges: sweep stopped; the runs finished so far are kept and the same command resumes"
    assert not list((tmp_path / "out").glob("runs/.tmp*"))


def test_a_ctrl_c_after_the_command_finished_leaves_its_exit_status_and_output():
    # a Ctrl-C while Python shut down after a finished sweep ended the process by SIGINT: status -2, no line
    code = (
        "import atexit, os, signal, sys, time\n"
        "def late():\n"
        "    os.kill(os.getpid(), signal.SIGINT)\n"
        "    os.kill(os.getpid(), signal.SIGTERM)\n"
        "    time.sleep(0.3)\n"
        "atexit.register(late)\n"
        "sys.argv = ['tvtrack', 'sweep', 'no-such-spec.toml']\n"
        "import tvtrack.__main__\n"
    )
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert (proc.returncode, proc.stderr) == (-signal.SIGTERM, "error: no sweep spec 'no-such-spec.toml'\n")
    proc = subprocess.run(
        [sys.executable, "-c", code.replace("    os.kill(os.getpid(), signal.SIGTERM)\n", "")],
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert (proc.returncode, proc.stderr) == (2, "error: no sweep spec 'no-such-spec.toml'\n")


def test_a_pool_worker_ignores_ctrl_c_and_does_not_keep_it_blocked():
    from concurrent.futures import ProcessPoolExecutor
    from multiprocessing import get_context

    from tvtrack.pipeline.interrupt import shielded_spawn, worker_init

    pool = ProcessPoolExecutor(1, mp_context=get_context("spawn"), initializer=worker_init, initargs=(1,))
    try:
        with shielded_spawn():
            handler = pool.submit(signal.getsignal, signal.SIGINT)
        blocked = pool.submit(signal.pthread_sigmask, signal.SIG_BLOCK, set())
        assert handler.result(timeout=120) == signal.SIG_IGN
        assert signal.SIGINT not in blocked.result(timeout=120)
    finally:
        pool.shutdown()
    assert signal.SIGINT not in signal.pthread_sigmask(signal.SIG_BLOCK, set())


def test_ctrl_c_stops_a_sweep_of_twenty_thousand_runs_within_10_s_and_no_run_starts_after(tmp_path):
    spec = tmp_path / "huge.toml"
    spec.write_text(
        f'notebook = "{FIXTURE_NOTEBOOK}"\nrepeats = 20000\n[fixed]\nn_trials = 10\nn_frames = 3\nrerun_mode = "off"\n'
    )
    out = tmp_path / "huge"
    runs = out / "runs"
    proc = subprocess.Popen(
        [sys.executable, "-m", "tvtrack", "sweep", str(spec), "--jobs", "2", "--yes", "-o", str(out)],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        start_new_session=True,
    )
    deadline = time.time() + 120
    while time.time() < deadline and not (runs.exists() and list(runs.glob(".tmp-*"))):  # a run under way
        time.sleep(0.05)
    t0 = time.time()
    os.killpg(proc.pid, signal.SIGINT)
    stdout, stderr = proc.communicate(timeout=60)
    assert time.time() - t0 < wall_budget(10), time.time() - t0
    assert proc.returncode == 130, stderr
    assert stdout.splitlines()[0].startswith("huge: 20,000 runs, 0 finished before, 20,000 to run (2 at once)")
    lines = stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("interrupted: huge: ") and "resumes" in lines[0], stderr
    time.sleep(1.0)  # a run started after the signal would show its temporary folder or its run by now
    assert len(list(runs.iterdir())) <= 2  # at most the two runs in flight at the signal, finished meanwhile
    assert not list(runs.glob(".tmp-*")) and not list(runs.glob(".*.lock")) and not (out / LOCK_NAME).exists()


def test_sigkill_leftovers_are_recovered_by_the_next_sweep(tmp_path):
    spec = tmp_path / "killed.toml"
    spec.write_text(f'notebook = "{FIXTURE_NOTEBOOK}"\n[fixed]\nn_trials = 10\nrerun_mode = "off"\n')
    (run,) = expand(load_spec(spec))
    out = tmp_path / "killed"
    done = out / "runs" / run.run_id  # the run had finished when the sweep was killed
    done.mkdir(parents=True)
    (done / "run.json").write_text(json.dumps({"status": "ok", "runtime_s": 1.0, "parameters": run.parameters}))
    (done / "results.json").write_text(json.dumps({"metrics": {"centroid_rms_px": {"value": 0.1}}, "claims": []}))
    killed = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(60)"])
    holder = f"{killed.pid} {socket.gethostname()}\n"
    (out / LOCK_NAME).write_text(holder)  # what SIGKILL leaves: the sweep's lock, a run's lock, a temporary folder
    (out / "runs" / ".0123456789ab.lock").write_text(holder)
    tmp = out / "runs" / ".tmp-0123456789ab-0123abcd"
    tmp.mkdir()
    (tmp / ".owner").write_text(f"{socket.gethostname()} {killed.pid}")
    (tmp / "notebook.ipynb").write_text("{half written")
    killed.kill()
    killed.wait()
    summary = run_sweep(spec, jobs=1, output=out, progress=False)
    assert (summary.n_ok, summary.n_skipped) == (1, 1)
    assert sorted(p.name for p in (out / "runs").iterdir()) == [run.run_id]
    assert not (out / LOCK_NAME).exists()


@pytest.mark.parametrize(
    "damage, fragment",
    [
        (lambda run: (run / "results.json").write_text('{"claims": [{"id": "C1'), "results.json: not valid JSON"),
        (lambda run: (run / "results.json").write_text("{}"), "results.json: lacks 'claims'"),
        (lambda run: (run / "run.json").write_text("\x00garbage"), "run.json: not valid JSON"),
        (lambda run: (run / "run.json").write_text('{"status": "fine"}'), "run.json: status 'fine'"),
        (
            lambda run: (run / "results.json").write_text(
                json.dumps({"citation": "c", "seed": 1, "runtime_s": 1.0, "claims": [_claim("C1-2", "sort of")]})
            ),
            "results.json: claim C1-2 has the verdict 'sort of'",
        ),
    ],
    ids=["truncated", "empty object", "garbage record", "unknown status", "unknown verdict"],
)
def test_a_damaged_run_file_is_one_line_naming_it_for_report_and_site(tmp_path, damage, fragment):
    from tvtrack.pipeline.preflight import UsageError
    from tvtrack.pipeline.report import write_report

    reproduce = tmp_path / "runs" / "reproduce"
    _paper_run(reproduce, "000_sound", [_claim("C0-1", "reproduced")])
    damage(_paper_run(reproduce, "001_damaged", [_claim("C1-1", "partly")]))
    line = one_line(tvtrack("site", "--runs", tmp_path / "runs", "-o", tmp_path / "site"), 2, fragment)
    assert "001_damaged" in line and "remove" in line and not (tmp_path / "site").exists()
    with pytest.raises(UsageError, match=re.escape("001_damaged/" + fragment)):  # the report's reader: the same line
        write_report(reproduce, tmp_path / "R.md", notebooks=["000_sound", "001_damaged"])
    assert not (tmp_path / "R.md").exists()


def test_the_reports_counts_add_up_to_its_claims(tmp_path):
    from tvtrack.pipeline.report import write_report

    verdicts = ["reproduced", "partly", "not reproduced", "undecided", "not checkable", "reproduced", "partly"]
    _paper_run(tmp_path, "000_a", [_claim(f"C0-{k}", v) for k, v in enumerate(verdicts[:4])])
    _paper_run(tmp_path, "001_b", [_claim(f"C1-{k}", v) for k, v in enumerate(verdicts[4:])])
    text = write_report(tmp_path, tmp_path / "R.md", notebooks=["000_a", "001_b"]).read_text()
    head = re.search(r"\*\*Claims: (.*?)\*\* \((\d+) claims", text)
    counts = [int(n) for n in re.findall(r"(\d+) [a-z ]+", head.group(1))]
    assert sum(counts) == int(head.group(2)) == len(verdicts) == 7
    rows = [line for line in text.splitlines() if line.startswith(("| 000_a |", "| 001_b |"))]
    for row in rows:
        cells = [c.strip() for c in row.split("|")[2:-2]]
        assert sum(int(c) for c in cells[1:]) == int(cells[0]), row


def test_a_sweep_refuses_a_damaged_finished_run_in_one_line_before_any_run(tmp_path):
    spec = tmp_path / "one.toml"
    spec.write_text(f'notebook = "{FIXTURE_NOTEBOOK}"\n[fixed]\nn_trials = 10\nrerun_mode = "off"\n')
    (run,) = expand(load_spec(spec))
    folder = tmp_path / "one" / "runs" / run.run_id
    folder.mkdir(parents=True)
    (folder / "run.json").write_text(json.dumps({"status": "ok", "runtime_s": 1.0, "parameters": run.parameters}))
    (folder / "results.json").write_text('{"metrics": {"centroid_rms_px": ')
    line = one_line(tvtrack("sweep", spec, "-o", tmp_path / "one"), 2, f"{run.run_id}/results.json", "not valid JSON")
    assert "remove" in line and (folder / "results.json").read_text().startswith('{"metrics"')


def test_run_on_a_notebook_that_is_not_json_is_one_line(tmp_path):
    bad = tmp_path / "broken.ipynb"
    bad.write_text('{"cells": [')
    one_line(tvtrack("run", bad, "-o", tmp_path / "r"), 2, "broken.ipynb", "not valid JSON")
    assert not (tmp_path / "r").exists()


def test_reproduce_keeps_a_run_finished_at_this_commit_and_force_runs_it_again(tmp_path, monkeypatch, capsys):
    import shutil

    from tvtrack.pipeline import reproduce as rep

    nb = tmp_path / "nbs" / "fixture_centroid.ipynb"
    nb.parent.mkdir()
    shutil.copy(FIXTURE_NOTEBOOK, nb)
    (nb.parent / "fixture_centroid.smoke.toml").write_text('n_trials = 10\nn_frames = 3\nrerun_mode = "off"\n')
    monkeypatch.setattr(rep, "list_notebooks", lambda: [nb])
    run = tmp_path / "runs" / "reproduce-smoke" / "fixture_centroid"
    assert rep.reproduce(profile="smoke", jobs=1, runs_dir=tmp_path / "runs") == 0
    first = (run / "run.json").read_text()
    capsys.readouterr()
    assert rep.reproduce(profile="smoke", jobs=1, runs_dir=tmp_path / "runs") == 0  # resumed: nothing to run
    said = capsys.readouterr().out
    assert "kept 1 run finished at this commit" in said and "fixture_centroid" in said and "--force" in said
    assert (run / "run.json").read_text() == first
    record = json.loads(first)
    assert record["source_digest"] == rep.source_identity()["source_digest"] is not None
    assert record["parameters_digest"] == rep.parameters_digest(nb, "smoke") != rep.parameters_digest(nb, None)
    assert set(record["files"]) == {p.name for p in run.iterdir()} and "run.json" in record["files"]
    (run / "my_notes.txt").write_text("mine")  # a file of the user's in a run tvtrack made
    assert rep.reproduce(profile="smoke", jobs=1, runs_dir=tmp_path / "runs", force=True) == 0
    assert json.loads((run / "run.json").read_text())["finished_utc"] >= record["finished_utc"]
    assert (run / "run.json").read_text() != first and not (run / "my_notes.txt").exists()
    (kept,) = (tmp_path / "runs" / "reproduce-smoke").glob(".old-fixture_centroid-*")
    assert [p.name for p in kept.iterdir()] == ["my_notes.txt"]  # named in one line by the worker that replaced it
    assert "$(if $(FORCE),--force)" in (Path(__file__).parents[1] / "Makefile").read_text()


def test_a_summary_path_typo_is_refused_before_any_run_and_a_dict_key_after_the_first(tmp_path):
    body = f'notebook = "{FIXTURE_NOTEBOOK}"\nrepeats = 3\n[fixed]\nn_trials = 10\nn_frames = 3\nrerun_mode = "off"\n'
    typo = tmp_path / "typo.toml"
    typo.write_text(body + '[summary]\nx = "n_trials"\ny = "centroid_rms_px.valeu"\n')
    one_line(tvtrack("sweep", typo, "-o", tmp_path / "typo"), 2, "'centroid_rms_px.valeu'", "centroid_rms_px.value")
    assert not (tmp_path / "typo").exists()
    deep = tmp_path / "deep.toml"
    deep.write_text(body + '[summary]\nx = "n_trials"\ny = "centroid_rms_px.value.mean"\n')
    line = one_line(tvtrack("sweep", deep, "-o", tmp_path / "deep"), 2, "'centroid_rms_px.value.mean'", "first run")
    assert "resumes" in line
    assert len([p for p in (tmp_path / "deep" / "runs").iterdir() if not p.name.startswith(".")]) == 1


def test_make_edit_as_root_starts_jupyterlab_with_allow_root(tmp_path, monkeypatch):
    from tvtrack.pipeline import cli, edit, kernels

    started = []
    monkeypatch.setattr(edit, "working_copy", lambda *a, **k: (tmp_path / "copy.ipynb", True))
    monkeypatch.setattr(kernels, "install_clone_kernel", lambda: None)
    monkeypatch.setattr(os, "execv", lambda path, argv: started.append(argv))
    for euid, expected in ((0, True), (1000, False)):
        monkeypatch.setattr(os, "geteuid", lambda euid=euid: euid)
        cli.main(["edit", "fixture", "--lab"])
        assert ("--allow-root" in started[-1]) is expected, started[-1]
    assert started[-1][1:] == ["lab", str(tmp_path / "copy.ipynb")]


def test_a_damaged_sweep_summary_is_one_line_for_the_site(tmp_path):
    (tmp_path / "reproduce").mkdir()
    (tmp_path / "my_sweep").mkdir()
    (tmp_path / "my_sweep" / "summary.csv").write_text("run_id,status,x\na1,ok,1.0\nb2,ok\n")  # cut short
    one_line(tvtrack("site", "--runs", tmp_path, "-o", tmp_path / "site"), 2, "my_sweep/summary.csv: line 3 has 2")
    assert not (tmp_path / "site").exists() and not list(tmp_path.glob(".tmp-*"))
