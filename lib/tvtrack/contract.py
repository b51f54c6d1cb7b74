"""The paper contract: the names every paper package (``tvtrack.papers.pNNN_name``) exports, and a check.

A notebook, the report, the site and the tests read a paper through these names only, so that five papers (and
the sixth one ``python -m tvtrack new`` writes) have one shape:

==============  ==============================================================================================
name            what it is
==============  ==============================================================================================
``CITATION``    str: the paper's full citation (authors, title, venue, year), as the report prints it
``REGISTER``    :class:`tvtrack.register.Register`: every choice the paper left unstated, with its default
``DEPENDS``     ``{claim id: [register entry names]}``: the entries that can change what the claim measures
``RULES``       ``{claim id: Rule}``: the :mod:`tvtrack.verdicts` rule that decides each claim (claim rules
                only), built at the notebook's default parameters
``PARAMETERS``  ``{notebook parameter: ParamRule}``: the rules :func:`tvtrack.parameters.validate_parameters`
                applies to the notebook's parameters cell (ranges written once); a notebook that spreads work
                over processes names their number ``n_workers`` (``make reproduce`` sets it to cores // jobs)
``CLAIMS``      ``{claim id: {"statement": str, "paper_value": str}}``: what the paper says, in its words
``Sizes``       the class that holds one full-size run's Monte Carlo sizes and grids (the notebook fills it
                from its parameters)
``recording``   the module with the Rerun layout of one trial and ``VIEWER_EXPECTATIONS``: a dict of the
                viewer check's deviations from its default expectation (``tests/viewer``), each with a reason
                in a comment
==============  ==============================================================================================

A package exports them lazily (:func:`lazy_exports`), so that importing one of its modules does not import all
the others. The core never imports a paper: :func:`paper_packages` only lists the folders, and :func:`check`
takes a package the caller imported.
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

__all__ = ["EXPORTS", "PAPERS_DIR", "VIEWER_KEYS", "check", "lazy_exports", "paper_packages"]

#: The names a paper package exports, and what each means (the module docstring's table, for messages).
EXPORTS = {
    "CITATION": "the paper's full citation (str)",
    "REGISTER": "the register of unstated choices (tvtrack.register.Register)",
    "DEPENDS": "{claim id: [register entry names]}",
    "RULES": "{claim id: tvtrack.verdicts.Rule} (claim rules only)",
    "PARAMETERS": "{notebook parameter: tvtrack.parameters.ParamRule}",
    "CLAIMS": '{claim id: {"statement": str, "paper_value": str}}',
    "Sizes": "the run-size class (a dataclass, or a TypedDict where the notebook passes a dict)",
    "recording": "the module with the Rerun layout and VIEWER_EXPECTATIONS",
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


#: Where a paper package's exports live unless its ``__init__`` says otherwise (the shape ``tvtrack new`` writes).
SOURCES = {
    "REGISTER": "register:REGISTER",
    "DEPENDS": "register:DEPENDS",
    "RULES": "claims:RULES",
    "CLAIMS": "claims:CLAIMS",
    "PARAMETERS": "params:PARAMETERS",
    "Sizes": "study:Sizes",
    "recording": "recording",
}


def lazy_exports(
    package: str, table: Mapping[str, str] | None = None
) -> tuple[Callable[[str], Any], Callable[[], list[str]]]:
    """``__getattr__`` and ``__dir__`` for a paper package's ``__init__``: each exported name is imported from
    its module on first use.

    Parameters
    ----------
    package : str
        The package's ``__name__``.
    table : mapping, optional
        Where the package departs from :data:`SOURCES`: ``{exported name: "module"}`` (the module itself, e.g.
        ``"recording"``), ``"module:attribute"`` (``"params:RULES"``) or ``"module:function()"`` (called without
        arguments, e.g. ``"register:build_register()"``), modules relative to ``package``.
    """
    table = {**SOURCES, **(table or {})}

    def __getattr__(name: str) -> Any:
        if name not in table:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        module, _, attribute = table[name].partition(":")
        value = importlib.import_module(f"{package}.{module}")
        if not attribute:
            return value
        if attribute.endswith("()"):
            return getattr(value, attribute[:-2])()
        return getattr(value, attribute)

    def __dir__() -> list[str]:
        return sorted(set(vars(sys.modules[package])) | set(table))

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
        f"PARAMETERS[{k!r}]: name the number of worker processes n_workers (make reproduce sets it to cores // jobs)"
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


def check(package: ModuleType) -> list[str]:
    """What is wrong with a paper package against the contract: one line per problem, empty when it conforms.

    Parameters
    ----------
    package : module
        The imported package (``importlib.import_module("tvtrack.papers.p000_dissector_ekf")``); its last name
        ``pNNN_...`` gives the claim-id prefix ``CNNN-``.
    """
    from .register import Register

    short = package.__name__.rsplit(".", 1)[-1]
    m = _PACKAGE.match(short)
    if m is None:
        return [f"{package.__name__}: a paper package is named pNNN_short_name"]
    values, problems = {}, []
    for name in EXPORTS:
        try:
            values[name] = getattr(package, name)
        except Exception as exc:  # noqa: BLE001 - a lazy import that fails is the problem to report
            problems.append(f"{name} ({EXPORTS[name]}) is missing or fails to import: {type(exc).__name__}: {exc}")
    if not (package.__doc__ or "").strip():
        problems.append("the package docstring must cite the paper and say what lives where")
    v = values.get
    if "CITATION" in values and not (isinstance(v("CITATION"), str) and v("CITATION").strip()):
        problems.append("CITATION must be a non-empty string")
    if "REGISTER" in values and not isinstance(v("REGISTER"), Register):
        problems.append("REGISTER must be a tvtrack.register.Register")
    claims = v("CLAIMS") if isinstance(v("CLAIMS"), Mapping) else {}
    checks = {
        "CLAIMS": lambda: _claims_problems(v("CLAIMS"), f"C{m.group(1)}-"),
        "RULES": lambda: _rules_problems(v("RULES"), claims),
        "DEPENDS": lambda: _depends_problems(v("DEPENDS"), v("REGISTER"), claims),
        "PARAMETERS": lambda: _parameters_problems(v("PARAMETERS")),
        "Sizes": lambda: _sizes_problems(v("Sizes")),
        "recording": lambda: _recording_problems(v("recording")),
    }
    for name, run in checks.items():
        if name in values:
            problems += run()
    return [f"{package.__name__}: {p}" for p in problems]
