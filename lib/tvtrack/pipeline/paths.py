"""Where things live in the repository (the package is installed editable from ``lib/``), and output folders
checked before anything is written to them."""

import os
from pathlib import Path

REPO_ROOT = Path(__file__).resolve().parents[3]
NOTEBOOK_DIR = REPO_ROOT / "notebooks"
RUNS_DIR = REPO_ROOT / "papermill_runs"
PROFILE_DIR = RUNS_DIR / "profiles"
SWEEP_DIR = RUNS_DIR / "sweeps"


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
