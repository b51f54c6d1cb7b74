"""The ``results.json`` every notebook run writes.

A notebook builds one :class:`Results`, adds metrics, figures and claim verdicts while it runs,
and calls :meth:`Results.write` at the end. Notebooks never write JSON by hand.

A claim's verdict is decided by a rule object (:mod:`tvtrack.verdicts`) from the measured value,
never typed; every claim that is not ``not checkable`` carries a robustness record.

Schema (``schema_version`` 2)::

    notebook, citation, parameters, seed, versions {python, packages...}, git_commit,
    runtime_s, cpu_s (the kernel's CPU seconds, all threads and waited-for children), started_utc, metrics {name: number | Estimate-dict | list | dict},
    figures [{file, caption}], recording (file name or null),
    claims [{id, statement, paper_value, rule {kind, text, ...}, acceptance (= rule text), measured,
             verdict, decision (the rule's sentence with the numbers), note,
             robustness {label, where, coverage, parts {name: {verdict, label, where, replicate_verdicts}},
                         replicates, conditions, register, design, deterministic} or null}],
    register [{name, kind, default, values, why, origin}] or null (the notebook's register)
"""

from __future__ import annotations

import datetime as _dt
import importlib.metadata
import json
import math
import os
import platform
import re
import subprocess
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from .estimate import Estimate
from .labels import NO_PART_LABEL, Robustness
from .lost_labels import mark_lost_runs
from .markdown import md_escape
from .measured import record_end
from .verdicts import LABELS, VERDICTS, Rule
from .flip_words import flip_with_kind, label_basis, mixed_kinds
from .paragraphs import label_verdict, label_words, paper_paragraph, results_summary
from .numbers import format_measured
from .figure_checks import figure_problems
from .run_words import share_counts
from .part_lines import coverage_words, exploration_lines, hold_note, parts_held
from .parameters import cell_literals  # re-exported: the pipeline reads a notebook's parameters cell with it
from .wording import (
    FLIP_SHORT,
    FLIP_WORDS,
    GLOSSARY,
    LABEL_WORDS,
    VERDICT_WORDS,
    at_profile,
    claim_flips,
    claim_summary,
    main_part,
    shown_label,
    side_words,
)

__all__ = [
    "VERDICTS",
    "share_counts",
    "Claim",
    "Results",
    "load_results",
    "to_jsonable",
    "SCHEMA_VERSION",
    "format_measured",
    "md_escape",
    "claims_table",
    "claim_summary",
    "claim_flips",
    "flip_with_kind",
    "mixed_kinds",
    "label_basis",
    "label_words",
    "label_verdict",
    "record_end",
    "coverage_words",
    "exploration_lines",
    "hold_note",
    "parts_held",
    "results_summary",
    "paper_paragraph",
    "at_profile",
    "main_part",
    "side_words",
    "shown_label",
    "GLOSSARY",
    "VERDICT_WORDS",
    "LABEL_WORDS",
    "FLIP_WORDS",
    "FLIP_SHORT",
    "FINDINGS_ID",
    "cell_literals",
]

#: The display id of a notebook's findings cell, filled in when the run finishes.
FINDINGS_ID = "tvtrack-findings"

SCHEMA_VERSION = 2

_CLAIM_ID = re.compile(r"^C\d{3}-[0-9A-Za-z.]+$")

_VERSIONED_PACKAGES = ("numpy", "scipy", "matplotlib", "rerun-sdk", "papermill", "scikit-learn")


#: an estimate's numbers that may be infinite (a bound's open end): JSON has no infinity
_INFINITE_FIELDS = ("value", "stderr", "ci_low", "ci_high", "sampling_low", "sampling_high")


def to_jsonable(value: Any) -> Any:
    """Convert numpy scalars/arrays, Estimates, Paths and non-finite floats to JSON values
    (NaN and infinities become ``null``; an estimate's infinite numbers are named beside them, ``"infinite":
    {"ci_high": "+inf"}``, so that :func:`tvtrack.measured.as_estimate` reads an open end back as one)."""
    if isinstance(value, Estimate):
        return to_jsonable(value.to_dict())
    if isinstance(value, dict):
        out = {str(k): to_jsonable(v) for k, v in value.items()}
        if "value" in value and "ci_low" in value and "ci_high" in value:
            inf = {k: "+inf" if value[k] > 0 else "-inf" for k in _INFINITE_FIELDS if _is_infinite(value.get(k))}
            out.update({"infinite": inf} if inf else {})
        return out
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


def _is_infinite(x: Any) -> bool:
    return isinstance(x, (float, np.floating)) and bool(np.isinf(x))


def claims_table(claims: list) -> str:
    """The one claims-at-a-glance table (Markdown): per claim what the paper said, the verdict, the robustness
    label (``provisional`` for a design too small to label) and one sentence (:func:`claim_summary`): the
    measured value in its unit against the rule's band, the share of explored configurations that agree, the
    readings that flip it and, where undecided, the runs that would decide it. ``claims`` are :class:`Claim`
    objects or their dicts (``results.json``)."""
    rows = [
        "| claim | the paper says | verdict | label | measured against the paper, and on what it turns |",
        "| --- | --- | --- | --- | --- |",
    ]
    for c in claims:
        c = to_jsonable(c if isinstance(c, dict) else c.__dict__)
        st = " ".join(str(c["statement"]).split())  # whole: a cut statement misleads
        rows.append(
            f"| {c['id']} | {md_escape(st)} | **{c['verdict']}** | {md_escape(label_words(label_verdict(c), shown_label(c)))} | "
            f"{md_escape(claim_summary(c))} |"
        )
    return "\n".join(rows)


def _cpu_seconds() -> float:
    """CPU seconds of this process (all threads) and its waited-for children (process-pool workers)."""
    t = os.times()
    return t.user + t.system + t.children_user + t.children_system


@dataclass
class Claim:
    """One claim of the paper, checked (as stored in ``results.json``).

    Attributes
    ----------
    id : str
        This project's claim id: ``"C"``, the paper number, ``"-"``, the claim's number, e.g. ``"C001-3"``.
    statement : str
        What the paper claims, in words.
    paper_value : str
        The paper's number(s), as printed.
    rule : dict
        The acceptance rule (:meth:`tvtrack.verdicts.Rule.to_dict`): its kind, parameters and text.
    acceptance : str
        The rule's text.
    measured : Any
        What was measured, with Monte Carlo uncertainty where it applies.
    verdict : str
        One of :data:`VERDICTS`, decided by the rule.
    decision : str
        The rule's sentence saying why, with the numbers.
    note : str
        What the numbers alone do not say; for a claim that did not reproduce, the likely reason.
    caveat : str
        One sentence the claim's summary must carry, where the verdict shows less than it seems (a default world
        calibrated to the claim's own value: a consistency check); ``""`` where none applies.
    robustness : dict or None
        The robustness record (:meth:`tvtrack.verdicts.Robustness.record`); None only when not checkable.
    """

    id: str
    statement: str
    paper_value: str
    rule: dict
    acceptance: str
    measured: Any
    verdict: str
    decision: str = ""
    note: str = ""
    robustness: dict | None = None
    caveat: str = ""

    def __post_init__(self):
        if not _CLAIM_ID.match(self.id):
            raise ValueError(f"claim id {self.id!r} must look like 'C004-1'")
        if self.verdict not in VERDICTS:
            raise ValueError(f"claim {self.id}: verdict {self.verdict!r} must be one of {VERDICTS}")
        if self.acceptance != self.rule.get("text"):
            raise ValueError(f"claim {self.id}: the acceptance text is not the rule's text")
        if self.verdict != "not checkable":
            if not self.robustness:
                raise ValueError(
                    f"claim {self.id}: a checkable claim needs a robustness record (or a note why "
                    f"no unstated choice matters)"
                )
            undecided = self.verdict == "undecided" and self.robustness.get("label") == NO_PART_LABEL
            if self.robustness.get("label") not in LABELS and not undecided:
                raise ValueError(
                    f"claim {self.id}: robustness label {self.robustness.get('label')!r} must be one of {LABELS}"
                )

    def _repr_markdown_(self) -> str:
        record = to_jsonable(self.__dict__)
        label = label_words(label_verdict(record), shown_label(record))  # "robust in its decided parts only"
        return f"**{self.id}: {self.verdict}, {label}**. {md_escape(claim_summary(record))}"


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
    register: list | None = None
    _t0: float = field(default_factory=time.perf_counter, repr=False)
    _cpu0: float = field(default_factory=lambda: _cpu_seconds(), repr=False)
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

    def claim(
        self,
        id: str,
        statement: str,
        paper_value: str,
        rule: Rule | None = None,
        measured: Any = None,
        note: str = "",
        robustness: Robustness | None = None,
        exploration: Any = None,
        lost_runs: Any = None,
        caveat: str = "",
    ) -> Claim:
        """Record a claim; ``rule`` decides its verdict from ``measured``.

        Parameters
        ----------
        id, statement, paper_value, note
            See :class:`Claim`.
        rule : tvtrack.verdicts.Rule, optional
            The acceptance rule, fixed before the run; with ``exploration`` it defaults to the rule the
            exploration decided the claim with (``exploration.rules[id]``), so it is not passed twice.
        measured : Estimate, number, or what ``rule`` reads (a list for :class:`~tvtrack.verdicts.Monotone`,
            a dict of parts for :class:`~tvtrack.verdicts.AllOf`)
            The claim at the default reading. Omit it with ``exploration`` (the replicates pooled).
        exploration : tvtrack.explore.Exploration
            The claim measured over the register and independent replicates; gives ``measured`` and the
            robustness record (part-level labels, coverage, register entries).
        robustness : tvtrack.verdicts.Robustness
            A hand-built record, where no exploration applies.
        lost_runs : sequence of dict, optional
            The paper's own count of runs that lost lock, at the default (``changed`` {}) and under named flips
            (:func:`tvtrack.lost_labels.mark_lost_runs`): the sentence says where those runs carry the verdict.
        caveat : str, optional
            One sentence the claim's summary must say (:class:`Claim`).

        A checkable claim needs ``exploration`` or ``robustness``.

        Returns
        -------
        Claim
            Shown in a notebook as one line: verdict, robustness label, the rule's reason.
        """
        if rule is None and exploration is not None:
            if id not in exploration.rules:
                raise ValueError(f"claim {id}: the exploration has no rule for it; pass rule=")
            rule = exploration.rules[id]
        if not isinstance(rule, Rule):
            raise TypeError(f"claim {id}: rule must be a tvtrack.verdicts.Rule, got {type(rule).__name__}")
        if exploration is not None:
            if robustness is not None:
                raise ValueError(f"claim {id}: give exploration or robustness, not both")
            if measured is None:
                measured = exploration.measured(id)
            record = exploration.record(id, rule)
            known = {e["name"] for e in self.register or []}  # several explorations: the union of their registers
            self.register = (self.register or []) + [
                e for e in exploration.register.to_dict() if e["name"] not in known
            ]
        else:
            record = robustness.record(rule, measured) if robustness is not None else None
        verdict, decision = rule.explain(measured)
        if lost_runs and record is not None:
            mark_lost_runs(record, lost_runs, verdict)
        c = Claim(
            id=id,
            statement=statement,
            paper_value=paper_value,
            rule=to_jsonable(rule.to_dict()),
            acceptance=rule.text(),
            measured=measured,
            verdict=verdict,
            decision=decision,
            note=note,
            robustness=record,
            caveat=caveat,
        )
        if any(existing.id == c.id for existing in self.claims):
            raise ValueError(f"claim {c.id} recorded twice")
        self.claims.append(c)
        return c

    def findings(self) -> None:
        """Show the findings at the top of a notebook: a placeholder now, replaced by the claims table
        (:func:`claims_table`) when :meth:`finish` runs at the end (the run fills its own first section)."""
        _display_markdown(
            "*Findings appear here when the run finishes (they are computed by the cells below).*",
            display_id=FINDINGS_ID,
        )

    def finish(self) -> Path:
        """Write ``results.json`` and fill the findings section shown by :meth:`findings`."""
        path = self.write()
        counts = {v: sum(c.verdict == v for c in self.claims) for v in VERDICTS}
        head = ", ".join(f"{n} {v}" for v, n in counts.items() if n)
        _display_markdown(
            f"**{len(self.claims)} claims: {head}.**\n\n{claims_table(self.claims)}",
            display_id=FINDINGS_ID,
            update=True,
        )
        return path

    def save_figure(self, fig, name: str, caption: str, dpi: int = 110) -> None:
        """Save a matplotlib figure as ``output_dir/<name>.png``, list it with its caption and,
        inside a notebook, show it inline with the caption under it (then close it, so the
        backend does not show it twice). Returns nothing, so a cell ending with it echoes nothing.
        """
        if not re.fullmatch(r"[A-Za-z0-9_.-]+", name):
            raise ValueError(f"figure name {name!r} may hold only letters, digits, '_', '.', '-'")
        path = self.output_dir / f"{name}.png"
        fig.savefig(path, dpi=dpi, bbox_inches="tight")
        problems = figure_problems(fig)  # drawn: its tick labels are known
        self.figures.append({"file": path.name, "caption": caption, **({"problems": problems} if problems else {})})
        _show_inline(path, f"*Figure {len(self.figures)}.* {caption}", fig)

    def to_dict(self) -> dict:
        return to_jsonable(
            {
                "schema_version": SCHEMA_VERSION,
                "notebook": self.notebook,
                "citation": self.citation,
                "parameters": self.parameters,
                "seed": self.parameters["seed"],
                "versions": _versions(),
                "git_commit": _git_commit(),
                "started_utc": self._started,
                "runtime_s": time.perf_counter() - self._t0,
                "cpu_s": _cpu_seconds() - self._cpu0,
                "metrics": self.metrics,
                "figures": self.figures,
                "recording": self.recording,
                "register": self.register,
                "claims": [c.__dict__ for c in self.claims],
            }
        )

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
    required = (
        "notebook",
        "citation",
        "parameters",
        "seed",
        "versions",
        "git_commit",
        "runtime_s",
        "metrics",
        "claims",
    )
    missing = [k for k in required if k not in data]
    if missing:
        raise ValueError(f"{path}: results.json lacks {missing}")
    if data.get("schema_version") != SCHEMA_VERSION:
        raise ValueError(f"{path}: schema_version {data.get('schema_version')!r}, this library reads {SCHEMA_VERSION}")
    for c in data["claims"]:
        Claim(**c)  # re-validates id, verdict, rule text and robustness label
    return data


def _display_markdown(text: str, display_id: str, update: bool = False) -> None:
    """Show (or update, by display id) Markdown in the running notebook; nothing outside IPython."""
    try:
        from IPython import get_ipython
        from IPython.display import Markdown, display, update_display
    except ImportError:
        return
    if get_ipython() is None:
        return
    (update_display if update else display)(Markdown(text), display_id=display_id)


def _show_inline(path: Path, caption: str, fig) -> None:
    """Display a saved figure and its caption in the running notebook (nothing outside IPython)."""
    try:
        from IPython import get_ipython
        from IPython.display import Image, Markdown, display
    except ImportError:
        return
    if get_ipython() is None:
        return
    import matplotlib.pyplot as plt

    display(Image(filename=str(path)))
    display(Markdown(caption))
    plt.close(fig)


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
        out = subprocess.run(["git", "rev-parse", "HEAD"], cwd=here, capture_output=True, text=True, timeout=10)
        if out.returncode != 0:
            return None
        dirty = subprocess.run(
            ["git", "status", "--porcelain", "--untracked-files=no"],
            cwd=here,
            capture_output=True,
            text=True,
            timeout=10,
        ).stdout.strip()
        return out.stdout.strip() + ("-dirty" if dirty else "")
    except (OSError, subprocess.SubprocessError):
        return None
