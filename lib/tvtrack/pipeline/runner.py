"""Running notebooks through papermill, one run per output directory.

A run executes a notebook with some parameters into its own directory. The directory appears
only when the run has ended: the notebook runs in ``<parent>/.tmp-<name>-<random>`` with the
kernel's working directory there and ``output_dir = "."``, and the directory is renamed into
place at the end. A run interrupted (Ctrl-C, or SIGTERM in a pool worker: :mod:`.interrupt`) ends
its kernel and removes its temporary folder; one left by a killed process (its owner, written in
``.tmp-*/.owner``, is gone) is removed by the next run or sweep in the same folder
(:func:`remove_stale_temporaries`). Every run directory holds:

- ``run.json``: notebook, profile, parameters as injected, status (``"ok"`` or ``"failed"``),
  error and traceback for a failure, runtime;
- ``notebook.ipynb``: the executed copy;
- what the notebook wrote: ``results.json``, figures, ``recording.rrd``.
"""

from __future__ import annotations

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
from .paths import NOTEBOOK_DIR, PROFILE_DIR
from .preflight import UsageError

__all__ = [
    "find_notebook",
    "list_notebooks",
    "load_profile",
    "read_toml",
    "RunOutcome",
    "run_notebook",
    "read_run",
    "remove_stale_temporaries",
]

KERNEL_NAME = os.environ.get("TVTRACK_KERNEL", "python3")
OWNER_FILE = ".owner"  # "<host> <pid>" of the process running a temporary run folder
# papermill's 60 s default is too short for a kernel to start while a sweep loads every core
KERNEL_START_TIMEOUT_S = 300


def list_notebooks() -> list[Path]:
    """The paper notebooks, in name order."""
    return sorted(NOTEBOOK_DIR.glob("*.ipynb"))


def find_notebook(name: str | Path) -> Path:
    """Resolve a notebook given as a path, a file name or a name without ``.ipynb``
    (looked up in ``notebooks/``)."""
    p = Path(name)
    candidates = [p, p.with_suffix(".ipynb"), NOTEBOOK_DIR / p.name, NOTEBOOK_DIR / f"{p.name}.ipynb"]
    for c in candidates:
        if c.is_file() and c.suffix == ".ipynb":
            return c.resolve()
    known = ", ".join(n.stem for n in list_notebooks()) or "none"
    raise UsageError(f"no notebook {str(name)!r}; notebooks here: {known}")


def load_profile(notebook: Path, profile: str | None) -> dict[str, Any]:
    """Parameters of a named profile, from ``papermill_runs/profiles/<stem>.<profile>.toml``
    (or, for notebooks outside ``notebooks/``, ``<stem>.<profile>.toml`` beside the notebook).
    ``None`` or ``"paper"`` is the notebook's own defaults: no overrides."""
    if profile in (None, "paper"):
        return {}
    for folder in (PROFILE_DIR, notebook.parent):
        path = folder / f"{notebook.stem}.{profile}.toml"
        if path.is_file():
            return read_toml(path)
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
    """A TOML file as a dict; a syntax error is a :class:`UsageError` naming the file and line."""
    try:
        with path.open("rb") as fh:
            return dict(tomllib.load(fh))
    except tomllib.TOMLDecodeError as exc:
        raise UsageError(f"{path}: invalid TOML: {exc}") from exc


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
        ``status`` is ``"failed"`` (with the error) if the notebook raised; this function
        itself raises only if the run directory cannot be written.
    """
    import papermill as pm  # heavy import, only when running

    nb = find_notebook(notebook)
    run_dir = Path(run_dir).resolve()
    if run_dir.exists():
        raise FileExistsError(f"run directory {run_dir} exists already")
    params = {**load_profile(nb, profile), **(parameters or {}), "output_dir": "."}
    run_dir.parent.mkdir(parents=True, exist_ok=True)
    tmp = run_dir.parent / f".tmp-{run_dir.name}-{uuid.uuid4().hex[:8]}"
    tmp.mkdir()
    (tmp / OWNER_FILE).write_text(f"{socket.gethostname()} {os.getpid()}")
    record = {
        "notebook": nb.stem,
        "notebook_path": str(nb),
        "profile": profile or "paper",
        "parameters": params,
        **(extra_record or {}),
    }
    t0 = time.perf_counter()
    error = tb = None
    spare = child_pids()  # the caller's own processes: an interrupt ends only this run's kernel
    try:
        with kernels_end_on_ctrl_c():
            pm.execute_notebook(
                str(nb),
                str(tmp / "notebook.ipynb"),
                parameters=params,
                cwd=str(tmp),
                kernel_name=kernel_name or KERNEL_NAME,
                progress_bar=progress,
                execution_timeout=timeout_s,
                log_output=False,
                start_timeout=KERNEL_START_TIMEOUT_S,
                extra_arguments=KERNEL_ARGUMENTS,
                shutdown_kernel=KERNEL_SHUTDOWN,
            )
        status = "ok"
        if not (tmp / "results.json").is_file():
            status, error = "failed", "the notebook finished without writing results.json"
    except Exception as exc:  # noqa: BLE001 - a failed run is recorded, never raised
        status = "failed"
        error = _short_error(exc)
        tb = traceback.format_exc()
    except BaseException:  # Ctrl-C (KeyboardInterrupt) or a pool worker told to stop: no run, no leftovers
        end_children(spare=spare)
        shutil.rmtree(tmp, ignore_errors=True)
        raise
    runtime = time.perf_counter() - t0
    record.update(
        status=status, error=error, runtime_s=runtime, finished_utc=time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime())
    )
    (tmp / "run.json").write_text(json.dumps(record, indent=2, default=str))
    if tb:
        (tmp / "error.txt").write_text(tb)
    (tmp / OWNER_FILE).unlink(missing_ok=True)
    os.replace(tmp, run_dir)
    return RunOutcome(run_dir=run_dir, status=status, runtime_s=runtime, error=error, record=record)


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


def remove_stale_temporaries(parent: Path) -> int:
    """Delete the ``.tmp-*`` folders under ``parent`` left by runs whose process is gone; returns how many.

    Folders of runs still in progress (another ``tvtrack run`` writing to the same folder) are kept."""
    n = 0
    if not Path(parent).is_dir():
        return 0
    for tmp in Path(parent).glob(".tmp-*"):
        if tmp.is_dir() and not _owner_alive(tmp):
            shutil.rmtree(tmp, ignore_errors=True)
            n += 1
    return n
