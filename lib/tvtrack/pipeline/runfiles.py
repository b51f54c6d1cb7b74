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
        Not valid JSON, not an object, a ``status`` other than ``ok``/``failed``, no numeric ``runtime_s``.
    """
    path = Path(run_dir) / "run.json"
    if not path.is_file():
        return None
    record = _read_object(path)
    if record.get("status") not in RUN_STATUSES:
        raise _damaged(path, f"status {record.get('status')!r}; a run's status is one of {', '.join(RUN_STATUSES)}")
    runtime = record.get("runtime_s")
    if isinstance(runtime, bool) or not isinstance(runtime, (int, float)):
        raise _damaged(path, f"runtime_s {runtime!r} is not a number of seconds")
    return record


def load_results(run_dir: str | Path, for_report: bool = True) -> dict[str, Any]:
    """``results.json`` of a finished (``ok``) run, checked: an object whose ``claims`` is a list of claims, each
    with its id, statement, the paper's value, a measured value and a verdict this library knows; with
    ``for_report`` also the citation, seed and runtime the report shows.

    Raises
    ------
    DamagedRun
        The file is missing, not valid JSON or an object, lacks a key, or a claim's verdict is unknown.
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
    for k, claim in enumerate(data["claims"]):
        if not isinstance(claim, dict):
            raise _damaged(path, f"claim {k + 1} is not an object")
        lacks = [key for key in (_CLAIM_KEYS if for_report else ("id", "verdict")) if key not in claim]
        if lacks:
            raise _damaged(path, f"claim {claim.get('id', k + 1)} lacks {', '.join(repr(key) for key in lacks)}")
        if claim["verdict"] not in known_verdicts():
            raise _damaged(
                path,
                f"claim {claim['id']} has the verdict {claim['verdict']!r}, which this library does not know "
                f"(known: {', '.join(known_verdicts())})",
            )
    return data
