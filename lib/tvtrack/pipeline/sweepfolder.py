"""The folder a sweep writes: which folders it may write into, and what it may delete when it tries a run again.

A sweep writes only into a folder that is new, empty or a sweep's (:func:`check_sweep_folder`: its marker,
:data:`.outputs.MARKER` of kind ``sweep``, lists the files the sweep wrote there), and never deletes a file it did
not write: a failed run tried again loses the files its ``run.json`` lists (:func:`files_to_clear`,
:func:`clear_run`), and a run folder holding anything else is refused in one line. The folder is checked once
before the sweep's own checks (a refusal then writes nothing) and again under the folder's lock
(:func:`held_sweep_folder`), since another process may have written into it meanwhile.
"""

from __future__ import annotations

import contextlib
import json
import os
from pathlib import Path
from typing import Iterator

from .lock import LOCK_NAME, output_lock, written_by_tvtrack
from .outputs import MARKER, replace_text
from .paths import writable_directory
from .preflight import UsageError

__all__ = ["SWEEP_FILES", "mark_sweep", "check_sweep_folder", "held_sweep_folder", "files_to_clear", "clear_run"]

#: The files a sweep writes in its folder, beside ``runs/`` (and its marker, :data:`.outputs.MARKER`).
SWEEP_FILES = ("spec.toml", "summary.csv", "summary.png")


def _sweep_marker(sweep_dir: Path) -> dict | None:
    """The sweep folder's marker (:data:`.outputs.MARKER`, JSON), or ``None`` when it has none it can read."""
    try:
        data = json.loads((sweep_dir / MARKER).read_text())
    except (OSError, ValueError):
        return None
    return data if isinstance(data, dict) and isinstance(data.get("files"), list) else None


def mark_sweep(sweep_dir: Path, names: set[str]) -> None:
    """List ``names`` in the sweep folder's marker, before they are written: the files the sweep writes there
    (and writes again when it resumes)."""
    marker = _sweep_marker(sweep_dir) or {}
    files = sorted({str(f) for f in marker.get("files", [])} | names)
    replace_text(sweep_dir / MARKER, json.dumps({"kind": "sweep", "written_by": "tvtrack", "files": files}, indent=0))


def check_sweep_folder(sweep_dir: Path, parameter: str = "-o") -> None:
    """Refuse to write a sweep into ``sweep_dir`` unless it is new, empty, or a sweep's folder.

    A sweep's folder holds the marker :data:`.outputs.MARKER` of kind ``sweep`` (listing the files the sweep
    wrote beside ``runs/``), or, from before sweeps were marked, nothing but ``runs/`` (run folders, each with its
    ``run.json``, and tvtrack's temporary folders and locks), ``spec.toml``, ``summary.csv``, ``summary.png`` and
    tvtrack's lock.

    Raises
    ------
    UsageError
        One line naming ``parameter`` and the folder: a file; a folder of something else; a file of the sweep's
        (``spec.toml``, ``summary.csv``, ``summary.png``) that the sweep did not write or that is no plain file.
    """
    if not sweep_dir.exists() and not sweep_dir.is_symlink():
        return
    if not sweep_dir.is_dir():
        raise UsageError(f"{parameter} {sweep_dir}: cannot write a sweep there: it is a file; give a new folder")
    present = {p.name for p in sweep_dir.iterdir()}
    if LOCK_NAME in present and written_by_tvtrack(sweep_dir / LOCK_NAME):
        present.discard(LOCK_NAME)
    if not present:
        return
    marker = _sweep_marker(sweep_dir)
    how = "move it out, or give another folder (tvtrack never overwrites a file it did not write)"
    if marker is not None and marker.get("kind") != "sweep":
        raise UsageError(
            f"{parameter} {sweep_dir}: a {marker.get('kind')} tvtrack built, not a sweep: give another folder"
        )
    ours = set(marker["files"]) if marker else _legacy_sweep_files(sweep_dir, present)
    if ours is None:
        raise UsageError(
            f"{parameter} {sweep_dir}: not a sweep's folder (no {MARKER}) and not empty; a sweep writes "
            "spec.toml, summary.csv and summary.png there: give an empty or new folder"
        )
    for name in sorted(present & set(SWEEP_FILES)):
        if name not in ours:
            raise UsageError(f"{parameter} {sweep_dir}: holds {name}, which no sweep wrote there; {how}")
        if (sweep_dir / name).is_symlink() or not (sweep_dir / name).is_file():
            raise UsageError(f"{parameter} {sweep_dir}: {name} is not a plain file, so no sweep wrote it; {how}")


@contextlib.contextmanager
def held_sweep_folder(sweep_dir: Path, parameter: str = "-o") -> Iterator[Path]:
    """Create the sweep folder's ``runs/``, hold the folder's lock (:mod:`.lock`) and check the folder again under
    it (:func:`check_sweep_folder`): what was checked before the lock may have changed since (a file of the user's,
    a site built into it). Yields ``runs/``.

    Raises
    ------
    UsageError
        The folder or ``runs/`` cannot be written, another tvtrack holds the lock (:class:`.lock.FolderBusy`), or the
        folder is no longer one a sweep may write into: one line, the same as before the lock; a ``runs/`` made
        here is removed again (when still empty).
    """
    runs_dir = sweep_dir / "runs"
    made = not os.path.lexists(runs_dir)
    try:
        runs_dir.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise UsageError(f"cannot create the sweep directory {sweep_dir}: {exc.strerror}") from exc
    writable_directory(runs_dir, "sweep directory")
    with contextlib.ExitStack() as held:
        try:
            held.enter_context(output_lock(sweep_dir / LOCK_NAME, sweep_dir, "sweep directory"))
            check_sweep_folder(sweep_dir, parameter)
        except UsageError:
            if made:
                with contextlib.suppress(OSError):  # only an empty folder goes
                    runs_dir.rmdir()
            raise
        yield runs_dir


def _legacy_sweep_files(sweep_dir: Path, present: set[str]) -> set[str] | None:
    """The sweep's own files in an unmarked folder an earlier sweep wrote (see :func:`check_sweep_folder`), or
    ``None`` when the folder holds anything else, or the sweep's files with no finished run beside them."""
    runs_dir = sweep_dir / "runs"
    if not present <= {"runs", *SWEEP_FILES} or "runs" not in present or runs_dir.is_symlink() or not runs_dir.is_dir():
        return None
    n_runs = 0
    for entry in runs_dir.iterdir():
        if entry.name.startswith((".tmp-", ".tvtrack-write-test-")) or entry.name.endswith(".lock"):
            continue
        if entry.is_symlink() or not (entry / "run.json").is_file():
            return None
        n_runs += 1
    return set(SWEEP_FILES) if n_runs or present == {"runs"} else None


def files_to_clear(run_dir: Path, record: dict | None) -> tuple[Path, list[str]]:
    """``(run_dir, its files)`` of a failed run to try again: every file in it, each one its ``run.json`` lists.

    Raises
    ------
    UsageError
        One line naming the folder: no ``run.json`` (no run wrote it), a ``run.json`` that lists no files (an
        older tvtrack's), or a file the run did not write (a note of the user's); nothing is removed.
    """
    how = "move it out of the way (tvtrack never deletes a file it did not write), then run the sweep again"
    if run_dir.is_symlink() or not run_dir.is_dir():
        raise UsageError(f"{run_dir}: the place of a run to do, but not a folder a run wrote (a link or a file); {how}")
    if record is None:
        if run_dir.is_dir() and not run_dir.is_symlink() and not any(run_dir.iterdir()):
            return run_dir, []
        raise UsageError(f"{run_dir}: the folder of a run to do, but no run wrote it (it has no run.json); {how}")
    listed = record.get("files")
    if not isinstance(listed, list):
        raise UsageError(
            f"{run_dir}: a failed run to try again, but its run.json lists no files it wrote (an older tvtrack's); "
            "remove the folder yourself to run it again"
        )
    present = _files_in(run_dir)
    foreign = sorted(set(present) - {str(f) for f in listed})
    if foreign:
        more = f" and {len(foreign) - 1} more" if len(foreign) > 1 else ""
        raise UsageError(
            f"{run_dir}: a failed run to try again holds {foreign[0]}{more}, which it did not write; {how}"
        )
    return run_dir, present


def _files_in(folder: Path) -> list[str]:
    """The relative paths of the files (and links) under ``folder``, no link followed."""
    found = []
    for top, dirs, files in os.walk(folder):
        found += [os.path.relpath(os.path.join(top, name), folder) for name in files]
        found += [os.path.relpath(os.path.join(top, d), folder) for d in dirs if os.path.islink(os.path.join(top, d))]
    return sorted(found)


def clear_run(run_dir: Path, files: list[str]) -> None:
    """Delete ``files`` (checked: :func:`files_to_clear`) and the folders they leave empty, ``run_dir`` last."""
    for rel in files:
        (run_dir / rel).unlink(missing_ok=True)
    for top, _, _ in sorted(os.walk(run_dir), key=lambda entry: -len(Path(entry[0]).parts)):
        try:
            os.rmdir(top)
        except OSError as exc:
            raise UsageError(f"{run_dir}: cannot clear the failed run to try it again: {exc.strerror}") from None
