"""Where things live in the repository (the package is installed editable from ``lib/``), and output folders
checked before anything is written to them."""

import os
from pathlib import Path

REPO_ROOT = Path(__file__).resolve().parents[3]
NOTEBOOK_DIR = REPO_ROOT / "notebooks"
RUNS_DIR = REPO_ROOT / "papermill_runs"
#: where the notebooks' compiled kernels are kept between runs (:mod:`tvtrack.jit`; ``TVTRACK_JIT_CACHE``)
JIT_CACHE_DIR = REPO_ROOT / ".jit-cache"
PROFILE_DIR = RUNS_DIR / "profiles"
SWEEP_DIR = RUNS_DIR / "sweeps"
INTERACTIVE_DIR = RUNS_DIR / "interactive"
PAPER_PROFILE = "paper"
CONFIRM_ABOVE_RUNS = 1000
"""A sweep of more runs than this starts only with ``--yes`` (:func:`.sweep.run_sweep`): its count is named."""


def profile_name(profile: str | None) -> str:
    """``None`` is the paper profile (the notebooks' own defaults)."""
    return profile or PAPER_PROFILE


def reproduce_dir(profile: str | None = None, runs_dir: Path = RUNS_DIR) -> Path:
    """Where ``make reproduce`` keeps its runs: ``papermill_runs/reproduce/`` at paper scale, and
    ``papermill_runs/reproduce-<profile>/`` for any other profile, so a smoke reproduce never replaces the
    paper runs that the README, REPRODUCTION.md and the site show."""
    name = profile_name(profile)
    return Path(runs_dir) / ("reproduce" if name == PAPER_PROFILE else f"reproduce-{name}")


def resolve_output_dir(output_dir: str | os.PathLike | None, notebook: str) -> Path:
    """The folder a notebook writes to, never outside this clone by accident.

    ``None``, ``""`` or the notebooks' historical default ``"../papermill_runs/interactive/<notebook>"``
    (relative to ``notebooks/``, so plain ``papermill`` started at the repository root wrote beside the clone)
    mean ``papermill_runs/interactive/<notebook>`` inside this clone, whatever the working directory. Any other
    value is used as given (the runner passes ``"."``: the run's own folder).
    """
    if output_dir in (None, "") or str(output_dir).replace("\\", "/") == f"../papermill_runs/interactive/{notebook}":
        return INTERACTIVE_DIR / notebook
    return Path(output_dir)


def writable_directory(path: Path, what: str) -> Path:
    """Create ``path`` (with its parents) and check that a file can be written in it.

    Raises
    ------
    UsageError
        One line naming ``what`` (e.g. "site folder"), the path and the system's reason: a parent that is a
        file, a read-only file system, no permission, a full disk.
    """
    from .preflight import UsageError

    path = Path(path)
    probe = path / f".tvtrack-write-test-{os.getpid()}"
    try:
        path.mkdir(parents=True, exist_ok=True)
        probe.write_bytes(b"")
        probe.unlink()
    except OSError as exc:
        raise UsageError(f"cannot write the {what} {path}: {exc.strerror or exc}") from exc
    return path
