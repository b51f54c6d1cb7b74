"""Where things live in the repository (the package is installed editable from ``lib/``)."""

from pathlib import Path

REPO_ROOT = Path(__file__).resolve().parents[3]
NOTEBOOK_DIR = REPO_ROOT / "notebooks"
RUNS_DIR = REPO_ROOT / "papermill_runs"
PROFILE_DIR = RUNS_DIR / "profiles"
SWEEP_DIR = RUNS_DIR / "sweeps"
