"""The paper contract: every paper package (``tvtrack.papers.pNNN_name``) declares one
:class:`tvtrack.paper.Paper`, ``PAPER``, in its ``paper.py``; :func:`check` reads it and :func:`check_paper` runs it.

A notebook, the report, the site and the tests read a paper through its ``PAPER`` (and the names below, each read
from it, for callers that name one thing), so that five papers (and the sixth one ``python -m tvtrack new``
writes) have one shape:

==============  ==============================================================================================
name            what it is (the ``Paper`` attribute)
==============  ==============================================================================================
``CITATION``    str: the paper's full citation (authors, title, venue, year), as the report prints it
                (``citation``; the package's ``__init__`` holds it, ``paper.py`` reads it from there)
``REGISTER``    :class:`tvtrack.register.Register`: every choice the paper left unstated, with its default
``DEPENDS``     ``{claim id: [register entry names]}``: the entries that can change what the claim measures
``RULES``       ``{claim id: Rule}``: the :mod:`tvtrack.verdicts` rule that decides each claim (claim rules
                only), built at the notebook's default parameters (``claim_rules``)
``PARAMETERS``  ``{notebook parameter: ParamRule}``: the rules :meth:`tvtrack.paper.Paper.validate` applies to
                the notebook's parameters cell (ranges written once; ``rules``); a notebook that spreads work
                over processes names their number ``n_workers`` (``make reproduce`` sets it to the usable cores)
``CLAIMS``      ``{claim id: {"statement": str, "paper_value": str}}``: what the paper says, in its words
``Sizes``       the class that holds one full-size run's Monte Carlo sizes and grids (``Paper.sizes`` fills it
                from the parameters)
``recording``   the module with the Rerun layout of one trial and ``VIEWER_EXPECTATIONS``: a dict of the
                viewer check's deviations from its default expectation (``tests/viewer``), each with a reason
                in a comment
==============  ==============================================================================================

A package exports them lazily (:func:`lazy_exports`): importing it imports none of its modules, and the first
name read imports ``paper.py`` (``CITATION`` lives in the ``__init__``). The core never imports a paper:
:func:`paper_packages` only lists the folders, and :func:`check` takes a package the caller imported.
"""

from __future__ import annotations

import dataclasses
import importlib
import re
import sys
from collections.abc import Callable, Mapping
from pathlib import Path
from types import ModuleType
from typing import Any

__all__ = ["EXPORTS", "PAPERS_DIR", "VIEWER_KEYS", "check", "check_paper", "lazy_exports", "paper_packages"]

#: The names a paper package exports, what each means (for messages) and the :class:`tvtrack.paper.Paper` attribute
#: it is read from.
EXPORTS = {
    "CITATION": ("the paper's full citation (str)", "citation"),
    "REGISTER": ("the register of unstated choices (tvtrack.register.Register)", "register"),
    "DEPENDS": ("{claim id: [register entry names]}", "depends"),
    "RULES": ("{claim id: tvtrack.verdicts.Rule} (claim rules only)", "claim_rules"),
    "PARAMETERS": ("{notebook parameter: tvtrack.parameters.ParamRule}", "rules"),
    "CLAIMS": ('{claim id: {"statement": str, "paper_value": str}}', "claims"),
    "Sizes": ("the run-size class (a dataclass, or a TypedDict where the notebook passes a dict)", "Sizes"),
    "recording": ("the module with the Rerun layout and VIEWER_EXPECTATIONS", "recording"),
}

#: The keys ``recording.VIEWER_EXPECTATIONS`` may set: the fields of the viewer check's expectation
#: (``tvtrack.pipeline.viewer.Expectation``; ``tests/test_contract.py`` keeps the two lists equal).
VIEWER_KEYS = (
    "image",
    "overlays",
    "series_root",
    "timeline",
    "min_overlay_px",
    "min_line_px",
    "min_image_fraction",
    "labels_when_overlapping",
    "other_timelines",
)

#: Where the paper packages live.
PAPERS_DIR = Path(__file__).resolve().parent / "papers"

_PACKAGE = re.compile(r"^p(\d{3})_[a-z0-9_]+$")


def paper_packages(root: Path = PAPERS_DIR) -> list[str]:
    """Folder names of the paper packages under ``root`` (``p000_dissector_ekf`` ...), in name order; read from
    the file system, nothing imported."""
    return sorted(p.name for p in Path(root).iterdir() if _PACKAGE.match(p.name) and (p / "__init__.py").is_file())


def lazy_exports(package: str) -> tuple[Callable[[str], Any], Callable[[], list[str]]]:
    """``__getattr__`` and ``__dir__`` for a paper package's ``__init__``: ``PAPER`` is imported from the package's
    ``paper`` module on first use, and each name of :data:`EXPORTS` is read from it.

    Parameters
    ----------
    package : str
        The package's ``__name__``.
    """

    def __getattr__(name: str) -> Any:
        if name != "PAPER" and name not in EXPORTS:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        paper = importlib.import_module(f"{package}.paper").PAPER
        return paper if name == "PAPER" else getattr(paper, EXPORTS[name][1])

    def __dir__() -> list[str]:
        return sorted(set(vars(sys.modules[package])) | set(EXPORTS) | {"PAPER"})

    return __getattr__, __dir__


def _sizes_problems(sizes: Any) -> list[str]:
    if not isinstance(sizes, type):
        return [f"Sizes must be a class, not {type(sizes).__name__}"]
    if dataclasses.is_dataclass(sizes) or getattr(sizes, "__annotations__", None):
        return []
    return ["Sizes must be a dataclass or a TypedDict naming its fields"]


def _claims_problems(claims: Any, prefix: str) -> list[str]:
    if not isinstance(claims, Mapping) or not claims:
        return ["CLAIMS must be a non-empty dict {claim id: {'statement', 'paper_value'}}"]
    out = []
    for cid, c in claims.items():
        if not str(cid).startswith(prefix):
            out.append(f"CLAIMS: claim id {cid!r} does not start with {prefix!r}")
        if not isinstance(c, Mapping) or set(c) != {"statement", "paper_value"}:
            out.append(f"CLAIMS[{cid!r}] must be a dict with exactly 'statement' and 'paper_value'")
        elif not all(isinstance(c[k], str) and c[k].strip() for k in c):
            out.append(f"CLAIMS[{cid!r}]: statement and paper_value must be non-empty strings")
    return out


def _rules_problems(rules: Any, claims: Mapping) -> list[str]:
    from .verdicts import Rule

    if not isinstance(rules, Mapping) or not rules:
        return ["RULES must be a non-empty dict {claim id: Rule}"]
    out = [
        f"RULES[{cid!r}] is a {type(r).__name__}, not a tvtrack.verdicts.Rule"
        for cid, r in rules.items()
        if not isinstance(r, Rule)
    ]
    out += [f"RULES: {cid!r} is not a claim in CLAIMS" for cid in rules if cid not in claims]
    return out


def _depends_problems(depends: Any, register: Any, claims: Mapping) -> list[str]:
    if not isinstance(depends, Mapping):
        return ["DEPENDS must be a dict {claim id: [entry names]}"]
    names = set(getattr(register, "names", ()))
    out = [f"DEPENDS: {cid!r} is not a claim in CLAIMS" for cid in depends if cid not in claims]
    for cid, entries in depends.items():
        if isinstance(entries, str) or not all(isinstance(e, str) for e in entries):
            out.append(f"DEPENDS[{cid!r}] must be a list of entry names")
            continue
        unknown = sorted(set(entries) - names)
        if unknown:
            out.append(f"DEPENDS[{cid!r}] names entries not in REGISTER: {unknown}")
    return out


#: Other names of the worker-process parameter, refused: the pipeline sets ``n_workers`` only (a notebook whose
#: parameter had another name ran its own pool beside another notebook in ``make reproduce``, two processes per core).
WORKER_ALIASES = ("workers", "n_jobs", "jobs", "processes", "n_processes", "n_procs", "n_cores", "cores")


def _parameters_problems(parameters: Any) -> list[str]:
    from .parameters import ParamRule

    if not isinstance(parameters, Mapping) or not parameters:
        return ["PARAMETERS must be a non-empty dict {parameter name: ParamRule}"]
    return [
        f"PARAMETERS[{k!r}] is a {type(v).__name__}, not a tvtrack.parameters.ParamRule"
        for k, v in parameters.items()
        if not isinstance(v, ParamRule)
    ] + [
        f"PARAMETERS[{k!r}]: name the number of worker processes n_workers (make reproduce sets it to the usable cores)"
        for k in parameters
        if k in WORKER_ALIASES
    ]


def _recording_problems(recording: Any) -> list[str]:
    if not isinstance(recording, ModuleType):
        return ["recording must be the package's recording module"]
    expect = getattr(recording, "VIEWER_EXPECTATIONS", None)
    if not isinstance(expect, Mapping):
        return ["recording.VIEWER_EXPECTATIONS must be a dict (empty when the viewer check's defaults hold)"]
    unknown = sorted(set(expect) - set(VIEWER_KEYS))
    if unknown:
        return [f"recording.VIEWER_EXPECTATIONS sets unknown keys {unknown} (known: {', '.join(VIEWER_KEYS)})"]
    return []


def _paper_problems(paper: Any, prefix: str) -> list[str]:
    """What is wrong with a declared paper's fields, without running anything."""
    from .register import Register

    problems = []
    if not (isinstance(paper.citation, str) and paper.citation.strip()):
        problems.append("CITATION must be a non-empty string")
    if not isinstance(paper.register, Register):
        problems.append("REGISTER must be a tvtrack.register.Register")
    claims = paper.claims if isinstance(paper.claims, Mapping) else {}
    problems += _claims_problems(paper.claims, prefix)
    problems += _rules_problems(paper.claim_rules, claims)
    problems += _depends_problems(paper.depends, paper.register, claims)
    problems += _parameters_problems(paper.rules)
    problems += [f"units: {k!r} is not a parameter" for k in paper.units if k not in paper.rules]
    problems += _sizes_problems(paper.Sizes)
    problems += _recording_problems(paper.recording)
    for name, m in paper.measurements.items():
        problems += [
            f"measurement {name!r} measures {cid!r}, not a claim in CLAIMS" for cid in m.claims if cid not in claims
        ]
        problems += [
            f"measurement {name!r} measures {cid!r}, which has no rule in RULES"
            for cid in m.claims
            if cid in claims and cid not in paper.claim_rules
        ]
    if not paper.measurements:
        problems.append("measurements must name at least one measurement function")
    return problems


def check(package: ModuleType) -> list[str]:
    """What is wrong with a paper package against the contract: one line per problem, empty when it conforms.

    Parameters
    ----------
    package : module
        The imported package (``importlib.import_module("tvtrack.papers.p000_dissector_ekf")``); its last name
        ``pNNN_...`` gives the claim-id prefix ``CNNN-`` and the notebook's name ``NNN_...``.
    """
    from .paper import Paper

    short = package.__name__.rsplit(".", 1)[-1]
    m = _PACKAGE.match(short)
    if m is None:
        return [f"{package.__name__}: a paper package is named pNNN_short_name"]
    problems = []
    if not (package.__doc__ or "").strip():
        problems.append("the package docstring must cite the paper and say what lives where")
    try:
        paper = package.PAPER
    except Exception as exc:  # noqa: BLE001 - a paper module that fails to import is the problem to report
        return [f"{package.__name__}: PAPER (a tvtrack.paper.Paper in paper.py) is missing or fails: {exc!r}"]
    if not isinstance(paper, Paper):
        problems.append(f"PAPER is a {type(paper).__name__}, not a tvtrack.paper.Paper")
    else:
        if paper.name != short[1:]:
            problems.append(f"PAPER.name is {paper.name!r}, not the notebook's name {short[1:]!r}")
        problems += _paper_problems(paper, f"C{m.group(1)}-")
    return [f"{package.__name__}: {p}" for p in problems]


def _estimate_problems(rule: Any, measured: Any) -> str | None:
    """Why a rule cannot decide ``measured`` (None when it can)."""
    if measured is None:
        return "came back empty"
    try:
        rule.explain(measured)
    except Exception as exc:  # noqa: BLE001 - a rule that cannot read the output is the problem to report
        return f"is not what its rule reads ({type(exc).__name__}: {exc})"
    return None


def check_paper(
    paper: Any, overrides: Mapping[str, Any] | None = None, seed: int = 0, only: tuple[str, ...] | None = None
) -> list[str]:
    """Run a declared paper at smoke size, as scikit-learn's ``check_estimator`` runs an estimator: one line per
    problem, empty when it conforms.

    The smoke parameters (with ``overrides``) are validated, the sizes built from them, and each measurement run
    once at the register's default on a seed drawn from ``numpy.random.default_rng(seed)``; every claim it
    declares must come back with a value its rule decides.

    Parameters
    ----------
    paper : tvtrack.paper.Paper
        The declared paper.
    overrides : mapping, optional
        Parameters replacing the smoke profile's (smaller sizes for a quicker check).
    seed : int
        Seed of the generator that draws the measurements' seeds.
    only : tuple of str, optional
        The measurements to run (all by default).
    """
    import numpy as np

    from .paper import Paper

    if not isinstance(paper, Paper):
        return [f"PAPER is a {type(paper).__name__}, not a tvtrack.paper.Paper"]
    problems = _paper_problems(paper, f"C{paper.name[:3]}-")
    try:
        params = paper.validate(paper.smoke_profile() | dict(overrides or {}))
        sizes = paper.sizes(params)
    except ValueError as exc:
        problems.append(f"smoke parameters: {exc}")
        return [f"{paper.name}: {p}" for p in problems]
    if not isinstance(sizes, dict if issubclass(paper.Sizes, dict) else paper.Sizes):
        problems.append(f"sizes(params) gives a {type(sizes).__name__}, not a {paper.Sizes.__name__}")
    rng, default = np.random.default_rng(seed), paper.register.default()
    for name, m in paper.measurements.items():
        if only is not None and name not in only:
            continue
        arg = m.sizes(params, sizes) if m.sizes is not None else sizes
        try:
            out = m.run(default, int(rng.integers(2**31)), arg)
        except Exception as exc:  # noqa: BLE001 - a measurement that fails at smoke size is the problem to report
            problems.append(f"measurement {name!r} fails at smoke size: {type(exc).__name__}: {exc}")
            continue
        for cid in m.claims:
            if cid not in paper.claim_rules:
                continue
            why = "is missing" if cid not in out else _estimate_problems(paper.rule(cid, sizes), out[cid])
            if why:
                problems.append(f"measurement {name!r}: claim {cid} {why}")
    return [f"{paper.name}: {p}" for p in problems]
