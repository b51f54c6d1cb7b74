"""Running notebooks through papermill, one run per output directory.

A run executes a notebook with some parameters into its own directory. The directory appears
only when the run has ended: the notebook runs in ``<parent>/.tmp-<name>-<random>`` with the
kernel's working directory there and ``output_dir = "."``, and the directory is renamed into
place at the end. A run interrupted (Ctrl-C, or SIGTERM in a pool worker: :mod:`.interrupt`) ends
its kernel and removes its temporary folder; one left by a killed process (its owner, written in
``.tmp-*/.owner``, is gone) is removed by the next run or sweep in the same folder
(:func:`remove_stale_temporaries`). Every run directory holds:

- ``run.json``: notebook, profile, parameters as injected, status (``"ok"`` or ``"failed"``),
  error and traceback for a failure, runtime, and ``files``: every file the run wrote (what replacing it may
  delete, :mod:`.outputs`);
- ``notebook.ipynb``: the executed copy;
- what the notebook wrote: ``results.json``, figures, ``recording.rrd``.
"""

from __future__ import annotations

import contextlib
import errno
import json
import os
import shutil
import socket
import time
import tomllib
import traceback
import uuid
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from .interrupt import child_pids, end_children, kernels_end_on_ctrl_c
from .kernels import KernelSetup as _KernelSetup
from .lock import output_lock, remove_stale_locks
from . import lean_imports
from .paths import NOTEBOOK_DIR, PROFILE_DIR
from .preflight import UsageError, check_names, check_notebook

__all__ = [
    "find_notebook",
    "list_notebooks",
    "load_profile",
    "read_toml",
    "RunOutcome",
    "run_notebook",
    "read_run",
    "remove_stale_temporaries",
    "WriteFailed",
]

KERNEL_NAME = os.environ.get("TVTRACK_KERNEL", "python3")
"""``python3``: the runner starts ``sys.executable -m ipykernel_launcher`` (this environment's Python) whatever
kernel specs are installed (a per-user ``python3`` spec of another environment is never used); the variable
``TVTRACK_KERNEL`` names an installed kernel spec instead."""
KERNEL_LOG = "kernel.log"
#: What ipykernel may print when jupyter_client interrupts it at every shutdown (SIGINT before the shutdown
#: request): chatter of a run that ended well, not worth a log of its own.
SHUTDOWN_CHATTER = "[IPKernelApp] ERROR | KeyboardInterrupt caught in kernel."
KERNEL_START_ATTEMPTS = 3
OWNER_FILE = ".owner"  # "<host> <pid>" of the process running a temporary run folder
# papermill's 60 s default is too short for a kernel to start while a sweep loads every core
KERNEL_START_TIMEOUT_S = 300


def list_notebooks() -> list[Path]:
    """The paper notebooks, in name order."""
    return sorted(NOTEBOOK_DIR.glob("*.ipynb"))


def find_notebook(name: str | Path) -> Path:
    """Resolve a notebook given as a path, a file name or a name without ``.ipynb``
    (looked up in ``notebooks/``).

    Raises
    ------
    UsageError
        No such notebook (an empty name, a folder, a name too long for the file system), or a file that is not a
        notebook papermill can run (not valid JSON, no ``metadata`` naming its language, an ``nbformat`` other than
        4, cells that are not notebook cells: :func:`.preflight.check_notebook`): one line."""
    p = Path(name)
    if p.name:  # "" and "/" name no file (and ``with_suffix`` refuses them)
        candidates = [p, p.with_suffix(".ipynb"), NOTEBOOK_DIR / p.name, NOTEBOOK_DIR / f"{p.name}.ipynb"]
        for c in candidates:
            if _is_file(c) and c.suffix == ".ipynb":
                _check_notebook_file(c)
                return c.resolve()
    known = ", ".join(n.stem for n in list_notebooks()) or "none"
    raise UsageError(f"no notebook {str(name)!r} (a name in notebooks/ or an .ipynb file); notebooks here: {known}")


def _is_file(path: Path) -> bool:
    """``path.is_file()``, false also for a path the file system refuses (a name too long, a symbolic link loop)."""
    try:
        return path.is_file()
    except (OSError, RuntimeError):
        return False


def _check_notebook_file(path: Path) -> None:
    """Refuse a file that is not a Jupyter notebook papermill can run (:func:`.preflight.check_notebook`), in one
    line naming it."""
    try:  # UTF-8 text, as Jupyter and papermill read it (a byte-order mark is not valid JSON to them)
        data = json.loads(path.read_text(encoding="utf-8"))
    except json.JSONDecodeError as exc:
        raise UsageError(
            f"{path}: not a notebook: not valid JSON (line {exc.lineno} column {exc.colno}: {exc.msg})"
        ) from None
    except (OSError, UnicodeDecodeError, RecursionError) as exc:
        raise UsageError(f"{path}: not a readable notebook: {getattr(exc, 'strerror', None) or exc}") from None
    except ValueError as exc:  # a number of more digits than Python converts
        raise UsageError(f"{path}: not a notebook: {str(exc)[:100]}") from None
    check_notebook(path, data)


def load_profile(notebook: Path, profile: str | None) -> dict[str, Any]:
    """Parameters of a named profile, from ``papermill_runs/profiles/<stem>.<profile>.toml``
    (or, for notebooks outside ``notebooks/``, ``<stem>.<profile>.toml`` beside the notebook).
    ``None`` or ``"paper"`` is the notebook's own defaults: no overrides.

    Raises
    ------
    UsageError
        No such profile, invalid TOML, or a key that is not a parameter of the notebook (one line naming the
        profile file and the closest parameter names)."""
    if profile in (None, "paper"):
        return {}
    for folder in (PROFILE_DIR, notebook.parent):
        path = folder / f"{notebook.stem}.{profile}.toml"
        if "/" not in profile and _is_file(path):
            values = read_toml(path)
            check_names(notebook, values, where=f"{path}: ")
            return values
    known = sorted(
        {
            p.name.split(".")[1]
            for folder in (PROFILE_DIR, notebook.parent)
            for p in folder.glob(f"{notebook.stem}.*.toml")
        }
        | {"paper"}
    )
    raise UsageError(f"no profile {profile!r} for {notebook.stem}; its profiles: {', '.join(known)}")


def read_toml(path: Path) -> dict[str, Any]:
    """A TOML file as a dict.

    Raises
    ------
    UsageError
        A syntax error (naming the file and line), or a file that is not UTF-8 text (naming the file and the
        byte's offset)."""
    try:
        with path.open("rb") as fh:
            return dict(tomllib.load(fh))
    except tomllib.TOMLDecodeError as exc:
        raise UsageError(f"{path}: invalid TOML: {exc}") from exc
    except UnicodeDecodeError as exc:
        raise UsageError(
            f"{path}: invalid TOML: not UTF-8 text (byte {exc.object[exc.start]:#04x} at offset {exc.start}); "
            "TOML files are UTF-8"
        ) from exc
    except RecursionError as exc:
        raise UsageError(f"{path}: invalid TOML: nested too deeply") from exc


class WriteFailed(RuntimeError):
    """A run's outputs could not be written (full disk, read-only folder): one line, exit status 1."""


@dataclass
class RunOutcome:
    """What became of one run."""

    run_dir: Path
    status: str
    runtime_s: float
    error: str | None = None
    record: dict = field(default_factory=dict)

    @property
    def ok(self) -> bool:
        return self.status == "ok"


# The kernel's own log (e.g. "Kernel is running over TCP without encryption") is not the user's business;
# errors still reach stderr, and the notebook's outputs and exceptions are in the executed copy.
KERNEL_ARGUMENTS = ["--IPKernelApp.log_level=ERROR"]
# Once the last cell has returned, everything the run keeps is on disk (results.json, figures, the recording,
# flushed by Recorder.close): the kernel's process group is killed instead of asked to shut down, which saves
# 2-3 s per run (a kernel that has imported matplotlib and rerun takes that long to exit gracefully;
# benchmarks/bench_runner.py measures it). Worker processes a notebook started are in that group and end too.
KERNEL_SHUTDOWN = "immediate"


def run_notebook(
    notebook: str | Path,
    run_dir: str | Path,
    parameters: dict[str, Any] | None = None,
    profile: str | None = None,
    *,
    kernel_name: str | None = None,
    timeout_s: float | None = None,
    progress: bool = False,
    extra_record: dict | None = None,
) -> RunOutcome:
    """Execute ``notebook`` into ``run_dir`` (which must not exist yet).

    Parameters
    ----------
    notebook : str or Path
        Name in ``notebooks/`` or a path.
    run_dir : str or Path
        Final directory of the run; created by an atomic rename when the run ends.
    parameters : dict, optional
        Overrides on top of the profile; ``output_dir`` is always set to ``"."`` (the run dir).
    profile : str, optional
        Profile name (``"smoke"``); ``None`` runs the notebook's defaults (paper scale).
    timeout_s : float, optional
        Per-cell execution timeout.

    Returns
    -------
    RunOutcome
        ``status`` is ``"failed"`` (with the error) if the notebook raised or its kernel died.

    Raises
    ------
    UsageError
        ``run_dir`` exists already (checked under its lock; nothing in it is touched).
    FolderBusy
        Another process writes ``run_dir`` (:mod:`.lock`).
    WriteFailed
        The run's outputs could not be written (a full disk, a read-only folder); the temporary folder is
        removed and nothing is kept.
    """
    nb = find_notebook(notebook)
    run_dir = _resolved(run_dir)
    params = {**load_profile(nb, profile), **(parameters or {}), "output_dir": "."}
    run_dir.parent.mkdir(parents=True, exist_ok=True)
    with output_lock(run_dir.parent / f".{run_dir.name}.lock", run_dir, "run directory"):
        if os.path.lexists(run_dir):  # made since the caller checked (another run, or the user's folder)
            raise UsageError(f"output directory {run_dir} exists already; choose another -o or remove it")
        tmp = run_dir.parent / f".tmp-{run_dir.name}-{uuid.uuid4().hex[:8]}"
        try:
            tmp.mkdir()
        except OSError as exc:
            raise WriteFailed(f"cannot write the run {run_dir}: {exc.strerror or exc}") from exc
        record = {
            "notebook": nb.stem,
            "notebook_path": str(nb),
            "profile": profile or "paper",
            "parameters": params,
            **(extra_record or {}),
        }
        try:  # from here on, whatever stops the run (Ctrl-C at any moment, a failed write) removes the folder
            try:
                (tmp / OWNER_FILE).write_text(f"{socket.gethostname()} {os.getpid()}")
            except OSError as exc:
                _write_failed(tmp, run_dir, exc)
            t0 = time.perf_counter()
            status, error, tb = _execute_in(tmp, nb, params, kernel_name, timeout_s, progress, run_dir)
            runtime = time.perf_counter() - t0
            record.update(
                status=status,
                error=error,
                runtime_s=runtime,
                finished_utc=time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()),
                files=_files_written(tmp, tb),
            )
            try:
                _write_record(tmp, record, tb)
                (tmp / OWNER_FILE).unlink(missing_ok=True)
                os.replace(tmp, run_dir)
            except OSError as exc:
                _write_failed(tmp, run_dir, exc)
        except BaseException:
            shutil.rmtree(tmp, ignore_errors=True)  # gone already once renamed into run_dir
            raise
    return RunOutcome(run_dir=run_dir, status=status, runtime_s=runtime, error=error, record=record)


def _resolved(run_dir: str | Path) -> Path:
    """``run_dir`` made absolute, its symbolic links followed; a link loop is a :class:`UsageError` naming it."""
    try:
        return Path(run_dir).resolve()
    except (OSError, RuntimeError) as exc:  # a symbolic link loop: RuntimeError before Python 3.13
        raise UsageError(f"cannot use the run directory {run_dir}: {exc}") from None


def _execute_in(tmp: Path, nb: Path, params: dict, kernel_name, timeout_s, progress, run_dir: Path):
    """Execute the notebook in ``tmp``: ``(status, one-line error or None, traceback or None)``.

    A kernel that dies before it answers (:func:`_died_at_start`) is started again, up to
    :data:`KERNEL_START_ATTEMPTS` times; what kernels print goes to ``kernel.log`` in the run, never to the
    terminal. Ctrl-C (or a pool worker's stop) ends the kernel, removes ``tmp`` and propagates."""
    pm = lean_imports.papermill()  # heavy import, only when running

    spare = child_pids()  # the caller's own processes: an interrupt ends only this run's kernel
    log_path = tmp / KERNEL_LOG
    try:
        with kernels_end_on_ctrl_c(), _KernelSetup(log_path, kernel_name) as setup:
            for attempt in range(1, KERNEL_START_ATTEMPTS + 1):
                try:
                    pm.execute_notebook(
                        str(nb),
                        str(tmp / "notebook.ipynb"),
                        parameters=params,
                        cwd=str(tmp),
                        kernel_name=setup.kernel_name,
                        progress_bar=progress,
                        execution_timeout=timeout_s,
                        log_output=False,
                        start_timeout=KERNEL_START_TIMEOUT_S,
                        extra_arguments=KERNEL_ARGUMENTS,
                        shutdown_kernel=KERNEL_SHUTDOWN,
                        kernel_manager_class=setup.manager_class(),
                    )
                    break
                except RuntimeError as exc:
                    if not _died_at_start(exc) or attempt == KERNEL_START_ATTEMPTS:
                        raise
                    setup.note(f"tvtrack: the kernel died before it answered (attempt {attempt}); starting another")
        if not (tmp / "results.json").is_file():
            return "failed", "the notebook finished without writing results.json", None
        return "ok", None, None
    except Exception as exc:  # noqa: BLE001 - a failed run is recorded, never raised
        if _is_write_error(exc):
            _write_failed(tmp, run_dir, exc)
        error = _short_error(exc)
        if _died_at_start(exc):
            error = f"the kernel died before it answered ({KERNEL_START_ATTEMPTS} attempts); its output: {KERNEL_LOG}"
        return "failed", error, traceback.format_exc()
    except BaseException:  # Ctrl-C (KeyboardInterrupt) or a pool worker told to stop: no run, no leftovers
        end_children(spare=spare)
        shutil.rmtree(tmp, ignore_errors=True)
        raise
    finally:
        drop_quiet_log(log_path)


def drop_quiet_log(log_path: Path) -> bool:
    """Remove a kernel log that holds nothing but :data:`SHUTDOWN_CHATTER` (or nothing); returns whether it did."""
    with contextlib.suppress(OSError):
        if not log_path.read_text(errors="replace").replace(SHUTDOWN_CHATTER, "").strip():
            log_path.unlink()
            return True
    return False


def _files_written(tmp: Path, tb: str | None) -> list[str]:
    """Every file of the run (relative paths), ``run.json`` included: what replacing the run may delete
    (:func:`.outputs.replace_folder`)."""
    written = {str(p.relative_to(tmp)) for p in tmp.rglob("*") if p.is_file()} - {OWNER_FILE}
    return sorted(written | {"run.json"} | ({"error.txt"} if tb else set()))


def _write_record(tmp: Path, record: dict, tb: str | None) -> None:
    """``run.json`` (and ``error.txt`` for a failure) into the temporary folder."""
    (tmp / "run.json").write_text(json.dumps(record, indent=2, default=str))
    if tb:
        (tmp / "error.txt").write_text(tb)


_WRITE_ERRNOS = {errno.ENOSPC, errno.EROFS, errno.EDQUOT, errno.EACCES, errno.EPERM}


def _is_write_error(exc: BaseException) -> bool:
    """A failure to write (full disk, read-only folder), in this process or in the kernel's own writes."""
    if isinstance(exc, OSError):
        return exc.errno in _WRITE_ERRNOS
    evalue = str(getattr(exc, "evalue", ""))
    return getattr(exc, "ename", None) in ("OSError", "PermissionError") and any(
        f"[Errno {n}]" in evalue for n in _WRITE_ERRNOS
    )


def _write_failed(tmp: Path, run_dir: Path, exc: BaseException) -> None:
    """Remove the temporary folder and raise :class:`WriteFailed` with one line."""
    shutil.rmtree(tmp, ignore_errors=True)
    reason = getattr(exc, "strerror", None) or getattr(exc, "evalue", None) or str(exc)
    raise WriteFailed(f"cannot write the run {run_dir}: {reason}; its temporary folder is removed") from exc


def _died_at_start(exc: BaseException) -> bool:
    """The kernel died (or never answered) before its ``kernel_info`` reply: nothing of the notebook ran."""
    return isinstance(exc, RuntimeError) and (
        "before replying to kernel_info" in str(exc) or "didn't respond in" in str(exc)
    )


def _short_error(exc: Exception) -> str:
    """The notebook's own exception line (papermill wraps it in PapermillExecutionError)."""
    ename = getattr(exc, "ename", None)
    evalue = getattr(exc, "evalue", None)
    if ename:
        return f"{ename}: {evalue}"
    return f"{type(exc).__name__}: {exc}"


def read_run(run_dir: str | Path) -> dict | None:
    """``run.json`` of a finished run directory, or ``None`` if there is none."""
    path = Path(run_dir) / "run.json"
    if not path.is_file():
        return None
    try:
        return json.loads(path.read_text())
    except json.JSONDecodeError:
        return None


def _owner_alive(tmp: Path) -> bool:
    """Whether the process that made the temporary folder ``tmp`` still runs (on this host; a folder of
    another host counts as alive). A folder without an owner file is alive only in its first minute
    (it may have been created a moment ago)."""
    try:
        host, pid = (tmp / OWNER_FILE).read_text().split()
    except (OSError, ValueError):
        try:
            return time.time() - tmp.stat().st_mtime < 60
        except OSError:
            return False
    if host != socket.gethostname():
        return True
    try:
        os.kill(int(pid), 0)
    except ProcessLookupError:
        return False
    except (PermissionError, ValueError):
        return True
    return not _zombie(int(pid))


def _zombie(pid: int) -> bool:
    """A killed process that nobody has reaped yet still answers ``kill(pid, 0)``: its state says it is dead."""
    try:
        state = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
    except (OSError, IndexError):
        return False
    return state in ("Z", "X")


def owner_gone(tmp: Path) -> bool:
    """Whether ``tmp`` is a temporary folder tvtrack made whose process is gone: its owner file names a dead
    process of this host, or it has none and is an empty folder older than a minute (killed between its creation
    and its owner file). A folder with content and no owner file may be the user's: never gone."""
    if (tmp / OWNER_FILE).is_file():
        return not _owner_alive(tmp)
    try:
        return not any(tmp.iterdir()) and not _owner_alive(tmp)
    except OSError:
        return False


def remove_stale_temporaries(parent: Path) -> int:
    """Delete the ``.tmp-*`` folders under ``parent`` left by runs whose process is gone (:func:`owner_gone`);
    returns how many.

    Folders of runs still in progress (another ``tvtrack run`` writing to the same folder) are kept, and so is
    any folder tvtrack did not make; tvtrack's lock files nobody holds are removed too
    (:func:`.lock.remove_stale_locks`)."""
    n = 0
    if not Path(parent).is_dir():
        return 0
    remove_stale_locks(Path(parent))
    for tmp in Path(parent).glob(".tmp-*"):
        if tmp.is_dir() and owner_gone(tmp):
            shutil.rmtree(tmp, ignore_errors=True)
            n += 1
    return n
