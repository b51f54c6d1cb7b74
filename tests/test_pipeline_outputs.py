"""Outputs nobody else can clobber: one writer per output folder (a second gets one line naming
the holder's process id, exit 2), and a write that fails (full disk, read-only) gives one line and leaves
no temporary folder."""

import errno
import os
import subprocess
import sys
import time

import pytest

from conftest import one_line_error, FIXTURE_NOTEBOOK
from tvtrack.pipeline import runner
from tvtrack.pipeline.lock import LOCK_NAME, FolderBusy, output_lock

TINY = ["-p", "n_trials", "3", "-p", "n_frames", "2", "-p", "rerun_mode", "'off'"]


def tvtrack(*args, timeout=120):
    return subprocess.run(
        [sys.executable, "-m", "tvtrack", *map(str, args)], capture_output=True, text=True, timeout=timeout
    )


def hold_lock(lock_file, target):
    """Another process that holds the lock of ``target`` until its stdin closes; returns it once it holds it."""
    code = (
        "import sys; from pathlib import Path; from tvtrack.pipeline.lock import output_lock\n"
        f"with output_lock(Path({str(lock_file)!r}), Path({str(target)!r})):\n"
        "    print('held', flush=True); sys.stdin.read()\n"
    )
    proc = subprocess.Popen([sys.executable, "-c", code], stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
    assert proc.stdout.readline().strip() == "held"
    return proc


def one_line(proc, code, *fragments):
    return one_line_error(proc, *fragments, status=(code,))


def test_a_second_writer_of_a_run_directory_is_refused_naming_the_holder(tmp_path):
    """Two ``tvtrack run -o OUT`` at once: the second is refused at once, naming the first's process id."""
    import signal

    out = tmp_path / "run"
    first = subprocess.Popen(
        [sys.executable, "-m", "tvtrack", "run", FIXTURE_NOTEBOOK, "-q", "-p", "n_trials", "20000", "-o", out],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        start_new_session=True,
    )
    try:
        deadline = time.time() + 120
        while not list(tmp_path.glob(".tmp-run-*")) and time.time() < deadline:
            time.sleep(0.1)
        assert list(tmp_path.glob(".tmp-run-*")), "the first run did not start"
        proc = tvtrack("run", FIXTURE_NOTEBOOK, "-q", *TINY, "-o", out)
        one_line(proc, 2, str(out), f"pid {first.pid}", "another tvtrack")
        assert first.poll() is None  # the first writer goes on
    finally:
        os.killpg(first.pid, signal.SIGINT)
        first.communicate(timeout=60)
    assert first.returncode == 130
    assert sorted(p.name for p in tmp_path.iterdir()) == []  # no run, no temporary folder, lock file removed


def test_a_second_sweep_into_the_same_folder_is_refused_naming_the_holder(tmp_path):
    spec = tmp_path / "one.toml"
    spec.write_text(f'notebook = "{FIXTURE_NOTEBOOK}"\n[fixed]\nn_trials = 3\nn_frames = 2\nrerun_mode = "off"\n')
    out = tmp_path / "sweep"
    out.mkdir()
    holder = hold_lock(out / LOCK_NAME, out)
    try:
        one_line(tvtrack("sweep", spec, "-o", out), 2, str(out), f"pid {holder.pid}")
    finally:
        holder.communicate("")
    assert not list((out / "runs").glob("*")) and not (out / LOCK_NAME).exists()


def test_the_lock_is_released_when_its_holder_is_killed(tmp_path):
    holder = hold_lock(tmp_path / "x.lock", tmp_path)
    with pytest.raises(FolderBusy, match=f"pid {holder.pid}"):
        with output_lock(tmp_path / "x.lock", tmp_path):
            pass
    holder.kill()
    holder.wait()
    with output_lock(tmp_path / "x.lock", tmp_path):
        assert (tmp_path / "x.lock").read_text().split()[0] == str(os.getpid())
    assert not (tmp_path / "x.lock").exists()


def _no_space_for_the_record(monkeypatch):
    """ENOSPC from the writer of a run's record (``run.json``), as a full disk gives it."""
    from pathlib import Path

    write_text = Path.write_text

    def write(self, *args, **kwargs):
        if self.name == "run.json":
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC), str(self))
        return write_text(self, *args, **kwargs)

    monkeypatch.setattr(Path, "write_text", write)


def test_a_full_disk_gives_one_line_and_leaves_no_temporary_folder(tmp_path, monkeypatch, capsys):
    from tvtrack.pipeline.cli import main

    _no_space_for_the_record(monkeypatch)
    out = tmp_path / "runs" / "r"
    code = main(["run", str(FIXTURE_NOTEBOOK), "-q", *TINY, "-o", str(out)])
    captured = capsys.readouterr()
    lines = captured.err.strip().splitlines()
    assert code == 1 and len(lines) == 1, captured.err
    assert lines[0].startswith("error: cannot write the run ") and "No space left on device" in lines[0]
    assert "Traceback" not in captured.err + captured.out
    assert list((tmp_path / "runs").iterdir()) == []  # no run, no .tmp-*, no lock file


def test_what_counts_as_a_failure_to_write():
    """A full disk or a read-only folder, in this process or in the kernel's own writes (the notebook's OSError
    reaches the runner as papermill's error with ``ename``/``evalue``); a missing file is no such failure."""
    err = type("PapermillExecutionError", (Exception,), {"ename": "OSError", "evalue": "[Errno 30] Read-only"})()
    assert runner._is_write_error(err) and runner._is_write_error(OSError(errno.EROFS, "x"))
    assert runner._is_write_error(OSError(errno.ENOSPC, "x"))
    assert not runner._is_write_error(OSError(errno.ENOENT, "x"))


def test_lock_files_nobody_holds_are_removed_held_ones_kept(tmp_path):
    from tvtrack.pipeline.lock import remove_stale_locks

    (tmp_path / ".dead.lock").write_text("99999999 host\n")  # its writer was killed: nobody holds it
    holder = hold_lock(tmp_path / ".live.lock", tmp_path / "live")
    try:
        assert remove_stale_locks(tmp_path) == 1
        assert [p.name for p in tmp_path.iterdir()] == [".live.lock"]
    finally:
        holder.communicate("")
