"""Reading a run's files (``run.json``, ``results.json``) with every reader's checks in one place.

Every reader of run files (``report``, ``site``, the sweep's resume and summary, ``reproduce``'s resume) reads them
through :func:`load_run` and :func:`load_results`: a file that is not a regular file (a folder of that name), not
valid JSON, not an object, lacks what the readers use, holds a value of the wrong kind (a runtime that is NaN or
negative, a file list that is not a list), two claims of one id, or a verdict this library does not know is a
:class:`DamagedRun`, one line naming the file and what is wrong and how to get a sound one (exit status 2). Nothing
is dropped silently: a claim whose verdict is unknown would leave the counts short of the claims, so it stops the
reader instead.
"""

from __future__ import annotations

import json
import math
import os
import stat
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


def _check_regular(path: Path) -> None:
    """A run file that exists (its name is taken) but is not a regular file: a folder, a device, a pipe, a symbolic
    link that leads nowhere or to itself. Such a file is never read (a device could be endless)."""
    try:
        mode = os.stat(path).st_mode
    except OSError as exc:
        raise _damaged(path, f"cannot be read: {exc.strerror or exc}") from None
    if stat.S_ISDIR(mode):
        raise _damaged(path, "is a folder, not a file")
    if not stat.S_ISREG(mode):
        raise _damaged(path, "is not a regular file (a device, a pipe or a socket)")


def _read_object(path: Path) -> dict[str, Any]:
    _check_regular(path)
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
    except (ValueError, RecursionError) as exc:  # a number of more digits than Python converts, nesting too deep
        raise _damaged(path, f"not JSON a record can hold ({type(exc).__name__}: {str(exc)[:80]})") from None
    if not isinstance(data, dict):
        raise _damaged(path, f"holds a JSON {type(data).__name__}, not an object")
    return data


def load_run(run_dir: str | Path) -> dict[str, Any] | None:
    """``run.json`` of ``run_dir``, checked; ``None`` when the folder has none (not run).

    Raises
    ------
    DamagedRun
        A folder or anything else but a regular file by that name, not valid JSON, not an object, a ``status``
        other than ``ok``/``failed``, a ``runtime_s`` that is not a finite number of seconds at least 0, a
        ``profile``, ``error`` or ``finished_utc`` that is not a string, a ``files`` that is not a list of
        relative paths inside the run folder.
    """
    path = Path(run_dir) / "run.json"
    if not os.path.lexists(path):
        return None
    record = _read_object(path)
    if record.get("status") not in RUN_STATUSES:
        raise _damaged(path, f"status {record.get('status')!r}; a run's status is one of {', '.join(RUN_STATUSES)}")
    _check_seconds(path, record.get("runtime_s"))
    if record.get("profile") is not None and not isinstance(record["profile"], str):
        raise _damaged(path, f"profile {record['profile']!r} is not a profile name (a string)")
    for key, what in (("error", "the run's error"), ("finished_utc", "the time it finished")):
        if record.get(key) is not None and not isinstance(record[key], str):
            raise _damaged(path, f"{key!r} is {_json_kind(record[key])}, not {what} (a string or null)")
    _check_files(path, record)
    return record


def _is_number(value: Any) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def _json_kind(value: Any) -> str:
    """What a JSON value is, as the messages name it ("null", "a JSON list", "a JSON str")."""
    return "null" if value is None else f"a JSON {type(value).__name__}"


def _check_seconds(path: Path, runtime: Any) -> None:
    """``runtime_s`` of a record: a number of seconds, finite and not negative (JSON lets NaN, Infinity and integers
    of any size in)."""
    try:
        seconds = float(runtime) if _is_number(runtime) else math.nan
    except OverflowError:  # an integer beyond any float
        seconds = math.inf
    if not math.isfinite(seconds) or seconds < 0:
        shown = repr(runtime) if len(repr(runtime)) <= 40 else f"{repr(runtime)[:20]}... ({len(repr(runtime))} digits)"
        raise _damaged(path, f"runtime_s {shown} is not a number of seconds (finite, at least 0)")


def _check_files(path: Path, record: dict[str, Any]) -> None:
    """``files`` of a ``run.json`` (absent in runs from before runs listed them): a list of the files the run
    wrote, each a relative path inside the run folder (:func:`.outputs.listed_inside`)."""
    from .outputs import listed_inside

    if "files" not in record:
        return
    files = record["files"]
    if not isinstance(files, list):
        raise _damaged(path, f"'files' is {_json_kind(files)}, not a list of the files the run wrote")
    outside = [f for f in files if not listed_inside(path.parent, f)]
    if outside:
        raise _damaged(
            path,
            f"'files' lists {outside[0]!r}: allowed are files in the run folder (no '..', no link leading out of it)",
        )


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
        The file is missing, not a regular file, not valid JSON or an object, lacks a key, a claim's verdict is
        unknown, two claims share an id, a value has the wrong type, or (with ``for_report``) a runtime that is not
        a finite number of seconds at least 0, or a figure or the recording naming a file outside the run folder.
    """
    path = Path(run_dir) / "results.json"
    if not os.path.lexists(path):
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
        _check_seconds(path, data["runtime_s"])
        if not isinstance(data["citation"], str):
            raise _damaged(path, f"'citation' is {_json_kind(data['citation'])}, not the paper's citation (a string)")
        _check_named_files(path, data)
    first = {}  # claim id -> its place
    for k, claim in enumerate(data["claims"], start=1):
        _check_claim(path, k, claim, _CLAIM_KEYS if for_report else ("id", "verdict"))
        if claim["id"] in first:
            raise _damaged(
                path,
                f"claim {claim['id']} appears twice (claims {first[claim['id']]} and {k}); each claim has its own id",
            )
        first[claim["id"]] = k
    return data
