"""Reading a run's files (``run.json``, ``results.json``) with every reader's checks in one place.

Every reader of run files (``report``, ``site``, the sweep's resume and summary, ``reproduce``'s resume) reads them
through :func:`load_run` and :func:`load_results`: a file that is not valid JSON, not an object, lacks what the
readers use, or holds a verdict this library does not know is a :class:`DamagedRun`, one line naming the file and
what is wrong and how to get a sound one (exit status 2). Nothing is dropped silently: a claim whose verdict is
unknown would leave the counts short of the claims, so it stops the reader instead.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from .preflight import UsageError

__all__ = ["DamagedRun", "load_run", "load_results", "known_verdicts", "RUN_STATUSES"]

RUN_STATUSES = ("ok", "failed")
_REPORT_KEYS = ("citation", "seed", "runtime_s")
_CLAIM_KEYS = ("id", "statement", "paper_value", "verdict", "measured")


class DamagedRun(UsageError):
    """A run file that cannot be read as the run left it (truncated, edited, of another program)."""


def _damaged(path: Path, what: str) -> DamagedRun:
    return DamagedRun(
        f"{path}: {what}; the run folder is damaged: remove {path.parent} and run it again "
        "(the same command re-runs a missing run)"
    )


def known_verdicts() -> tuple[str, ...]:
    """Every verdict a claim may carry (:data:`tvtrack.verdicts.VERDICTS`, imported at first use: it is heavy)."""
    from ..verdicts import VERDICTS

    return tuple(VERDICTS) + tuple(v for v in ("undecided",) if v not in VERDICTS)


def _read_object(path: Path) -> dict[str, Any]:
    try:
        text = path.read_text()
    except UnicodeDecodeError:
        raise _damaged(path, "not text (binary content)") from None
    except OSError as exc:
        raise _damaged(path, f"cannot be read: {exc.strerror or exc}") from None
    try:
        data = json.loads(text)
    except json.JSONDecodeError as exc:
        where = "empty" if not text.strip() else f"line {exc.lineno} column {exc.colno}: {exc.msg}"
        raise _damaged(path, f"not valid JSON ({where})") from None
    if not isinstance(data, dict):
        raise _damaged(path, f"holds a JSON {type(data).__name__}, not an object")
    return data


def load_run(run_dir: str | Path) -> dict[str, Any] | None:
    """``run.json`` of ``run_dir``, checked; ``None`` when the folder has none (not run).

    Raises
    ------
    DamagedRun
        Not valid JSON, not an object, a ``status`` other than ``ok``/``failed``, no numeric ``runtime_s``, a
        ``profile`` that is not a string.
    """
    path = Path(run_dir) / "run.json"
    if not path.is_file():
        return None
    record = _read_object(path)
    if record.get("status") not in RUN_STATUSES:
        raise _damaged(path, f"status {record.get('status')!r}; a run's status is one of {', '.join(RUN_STATUSES)}")
    runtime = record.get("runtime_s")
    if not _is_number(runtime):
        raise _damaged(path, f"runtime_s {runtime!r} is not a number of seconds")
    if record.get("profile") is not None and not isinstance(record["profile"], str):
        raise _damaged(path, f"profile {record['profile']!r} is not a profile name (a string)")
    return record


def _is_number(value: Any) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def _check_named_files(path: Path, data: dict[str, Any]) -> None:
    """``figures`` (a list of ``{file, caption}``) and ``recording`` (a file name or null) of a ``results.json``:
    every file name a relative path inside the run folder (:func:`.outputs.listed_inside`)."""
    from .outputs import listed_inside

    figures = data.get("figures") or []
    if not isinstance(figures, list):
        raise _damaged(path, f"'figures' is a JSON {type(figures).__name__}, not a list of {{file, caption}}")
    for k, fig in enumerate(figures, start=1):
        if not isinstance(fig, dict) or not isinstance(fig.get("caption"), str):
            raise _damaged(path, f"figure {k} is not an object with a file name and a caption (a string)")
        if not listed_inside(path.parent, fig.get("file")):
            raise _damaged(
                path, f"figure {k} names the file {fig.get('file')!r}: allowed is a file in the run folder (no '..')"
            )
    recording = data.get("recording")
    if recording is not None and not listed_inside(path.parent, recording):
        raise _damaged(path, f"'recording' {recording!r}: allowed is null or a file in the run folder (no '..')")


def _check_claim(path: Path, k: int, claim: Any, keys: tuple[str, ...]) -> None:
    """One claim of a ``results.json``: an object with ``keys``, a string id, a known verdict, and a ``rule`` and
    ``robustness`` record that are objects where present."""
    if not isinstance(claim, dict):
        raise _damaged(path, f"claim {k} is not an object")
    lacks = [key for key in keys if key not in claim]
    if lacks:
        raise _damaged(path, f"claim {claim.get('id', k)} lacks {', '.join(repr(key) for key in lacks)}")
    cid = claim["id"]
    if not isinstance(cid, str) or not cid.strip() or cid in (".", "..") or any(ch in cid for ch in "/\\\0"):
        raise _damaged(path, f"claim {k} has the id {cid!r}; a claim id is a string without '/' (it names a page)")
    if claim["verdict"] not in known_verdicts():
        raise _damaged(
            path,
            f"claim {claim['id']} has the verdict {claim['verdict']!r}, which this library does not know "
            f"(known: {', '.join(known_verdicts())})",
        )
    for key in ("rule", "robustness"):
        if claim.get(key) is not None and not isinstance(claim[key], dict):
            raise _damaged(path, f"claim {claim['id']}: {key!r} is a JSON {type(claim[key]).__name__}, not an object")


def load_results(run_dir: str | Path, for_report: bool = True) -> dict[str, Any]:
    """``results.json`` of a finished (``ok``) run, checked: an object whose ``claims`` is a list of claims, each
    with its id, statement, the paper's value, a measured value and a verdict this library knows; with
    ``for_report`` also the citation, seed and runtime the report shows.

    Raises
    ------
    DamagedRun
        The file is missing, not valid JSON or an object, lacks a key, a claim's verdict is unknown, a value has
        the wrong type, or (with ``for_report``) a figure or the recording names a file outside the run folder.
    """
    path = Path(run_dir) / "results.json"
    if not path.is_file():
        raise _damaged(path, "missing, though run.json says the run finished (status ok)")
    data = _read_object(path)
    missing = [k for k in ("claims", *(_REPORT_KEYS if for_report else ())) if k not in data]
    if missing:
        raise _damaged(path, f"lacks {', '.join(repr(k) for k in missing)}")
    if not isinstance(data["claims"], list):
        raise _damaged(path, f"'claims' is a JSON {type(data['claims']).__name__}, not a list")
    if not isinstance(data.get("metrics", {}), dict):
        raise _damaged(path, "'metrics' is not an object")
    if for_report:
        if not _is_number(data["runtime_s"]):
            raise _damaged(path, f"runtime_s {data['runtime_s']!r} is not a number of seconds")
        _check_named_files(path, data)
    for k, claim in enumerate(data["claims"], start=1):
        _check_claim(path, k, claim, _CLAIM_KEYS if for_report else ("id", "verdict"))
    return data
