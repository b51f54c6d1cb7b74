"""The ``results.json`` every notebook run writes.

A notebook builds one :class:`Results`, adds metrics, figures and claim verdicts while it runs,
and calls :meth:`Results.write` at the end. Notebooks never write JSON by hand.

Schema (``schema_version`` 1)::

    notebook, citation, parameters, seed, versions {python, packages...}, git_commit,
    runtime_s, started_utc, metrics {name: number | Estimate-dict | list | dict},
    figures [{file, caption}], recording (file name or null),
    claims [{id, statement, paper_value, acceptance, measured, verdict, note}]
"""

from __future__ import annotations

import datetime as _dt
import importlib.metadata
import json
import math
import platform
import re
import subprocess
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from .montecarlo import Estimate

__all__ = ["VERDICTS", "Claim", "Results", "judge_interval", "load_results", "to_jsonable"]

#: The only verdicts a claim may carry.
VERDICTS = ("reproduced", "partly", "not reproduced", "not checkable")

_CLAIM_ID = re.compile(r"^C\d{3}-[0-9A-Za-z.]+$")

_VERSIONED_PACKAGES = ("numpy", "scipy", "matplotlib", "rerun-sdk", "papermill", "scikit-learn")


def to_jsonable(value: Any) -> Any:
    """Convert numpy scalars/arrays, Estimates, Paths and non-finite floats to JSON values
    (NaN and infinities become ``null``)."""
    if isinstance(value, Estimate):
        return to_jsonable(value.to_dict())
    if isinstance(value, dict):
        return {str(k): to_jsonable(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [to_jsonable(v) for v in value]
    if isinstance(value, np.ndarray):
        return to_jsonable(value.tolist())
    if isinstance(value, (np.bool_, bool)):
        return bool(value)
    if isinstance(value, (np.integer, int)):
        return int(value)
    if isinstance(value, (np.floating, float)):
        v = float(value)
        return v if math.isfinite(v) else None
    if isinstance(value, Path):
        return str(value)
    return value


def judge_interval(estimate: Estimate, low: float | None = None, high: float | None = None) -> str:
    """Verdict for a claim of the form "the quantity lies in [low, high]".

    ``reproduced`` when the whole confidence interval lies inside, ``not reproduced`` when
    the whole interval lies outside, ``partly`` when the interval straddles a bound (the
    Monte Carlo cannot decide at this sample size; the note should say so).
    """
    lo = -math.inf if low is None else low
    hi = math.inf if high is None else high
    a, b = estimate.ci_low, estimate.ci_high
    if not (math.isfinite(a) and math.isfinite(b)):
        a = b = estimate.value
    if lo <= a and b <= hi:
        return "reproduced"
    if b < lo or a > hi:
        return "not reproduced"
    return "partly"


@dataclass
class Claim:
    """One claim of the paper, checked.

    Attributes
    ----------
    id : str
        As in the paper card, e.g. ``"C001-3"``.
    statement : str
        What the paper claims, in words.
    paper_value : str
        The paper's number(s), as printed.
    acceptance : str
        The rule applied, fixed before the run (the card's, or tightened).
    measured : Any
        What was measured, with Monte Carlo uncertainty where it applies
        (an :class:`Estimate`, a dict of them, or plain numbers).
    verdict : str
        One of :data:`VERDICTS`.
    note : str
        Why, in one or two sentences; for a claim that did not reproduce, the likely reason.
    """

    id: str
    statement: str
    paper_value: str
    acceptance: str
    measured: Any
    verdict: str
    note: str = ""

    def __post_init__(self):
        if not _CLAIM_ID.match(self.id):
            raise ValueError(f"claim id {self.id!r} must look like 'C004-1'")
        if self.verdict not in VERDICTS:
            raise ValueError(f"claim {self.id}: verdict {self.verdict!r} must be one of {VERDICTS}")


@dataclass
class Results:
    """Everything one run reports; written as ``output_dir/results.json``.

    Parameters
    ----------
    notebook : str
        Notebook name without extension, e.g. ``"004_laser_spot_prediction"``.
    citation : str
        The paper, as it should be cited.
    parameters : dict
        The validated parameters (from :func:`tvtrack.parameters.validate_parameters`);
        must include ``seed`` and ``output_dir``.
    """

    notebook: str
    citation: str
    parameters: dict
    metrics: dict = field(default_factory=dict)
    claims: list = field(default_factory=list)
    figures: list = field(default_factory=list)
    recording: str | None = None
    _t0: float = field(default_factory=time.perf_counter, repr=False)
    _started: str = field(
        default_factory=lambda: _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"),
        repr=False,
    )

    def __post_init__(self):
        for key in ("seed", "output_dir"):
            if key not in self.parameters:
                raise ValueError(f"Results needs the parameter {key!r}")

    @property
    def output_dir(self) -> Path:
        return Path(self.parameters["output_dir"])

    def metric(self, name: str, value: Any) -> Any:
        """Record a metric (number, :class:`Estimate`, list or dict) and return it."""
        self.metrics[name] = value
        return value

    def claim(self, **fields) -> Claim:
        """Record a claim's verdict; see :class:`Claim` for the fields. Ids must be unique."""
        c = Claim(**fields)
        if any(existing.id == c.id for existing in self.claims):
            raise ValueError(f"claim {c.id} recorded twice")
        self.claims.append(c)
        return c

    def save_figure(self, fig, name: str, caption: str, dpi: int = 110) -> Path:
        """Save a matplotlib figure as ``output_dir/<name>.png`` and list it with its caption."""
        if not re.fullmatch(r"[A-Za-z0-9_.-]+", name):
            raise ValueError(f"figure name {name!r} may hold only letters, digits, '_', '.', '-'")
        path = self.output_dir / f"{name}.png"
        fig.savefig(path, dpi=dpi, bbox_inches="tight")
        self.figures.append({"file": path.name, "caption": caption})
        return path

    def to_dict(self) -> dict:
        return to_jsonable({
            "schema_version": 1,
            "notebook": self.notebook,
            "citation": self.citation,
            "parameters": self.parameters,
            "seed": self.parameters["seed"],
            "versions": _versions(),
            "git_commit": _git_commit(),
            "started_utc": self._started,
            "runtime_s": time.perf_counter() - self._t0,
            "metrics": self.metrics,
            "figures": self.figures,
            "recording": self.recording,
            "claims": [c.__dict__ for c in self.claims],
        })

    def write(self) -> Path:
        """Write ``results.json`` (atomically) and return its path."""
        path = self.output_dir / "results.json"
        tmp = path.with_suffix(".json.tmp")
        tmp.write_text(json.dumps(self.to_dict(), indent=2, allow_nan=False))
        tmp.replace(path)
        return path


def load_results(path: str | Path) -> dict:
    """Read a ``results.json`` and check it against the schema; raise ``ValueError`` if not."""
    data = json.loads(Path(path).read_text())
    required = ("notebook", "citation", "parameters", "seed", "versions", "git_commit",
                "runtime_s", "metrics", "claims")
    missing = [k for k in required if k not in data]
    if missing:
        raise ValueError(f"{path}: results.json lacks {missing}")
    for c in data["claims"]:
        Claim(**c)  # re-validates id and verdict
    return data


def _versions() -> dict:
    out = {"python": platform.python_version()}
    for pkg in _VERSIONED_PACKAGES:
        try:
            out[pkg] = importlib.metadata.version(pkg)
        except importlib.metadata.PackageNotFoundError:
            pass
    return out


def _git_commit() -> str | None:
    try:
        here = Path(__file__).resolve().parent
        out = subprocess.run(["git", "rev-parse", "HEAD"], cwd=here, capture_output=True,
                             text=True, timeout=10)
        if out.returncode != 0:
            return None
        dirty = subprocess.run(["git", "status", "--porcelain", "--untracked-files=no"], cwd=here,
                               capture_output=True, text=True, timeout=10).stdout.strip()
        return out.stdout.strip() + ("-dirty" if dirty else "")
    except (OSError, subprocess.SubprocessError):
        return None
