"""Results of notebook 003's measurement parts, kept by everything they read.

The explorer measures every configuration on the first replicate's seed (common random numbers), so a register
entry that changes one part of a measurement (the static baseline's gate, the decoy's brightness, the Fig. 2 law,
the edge form's normalisation) leaves every other part's inputs, and so its result, as they were at the default.
:func:`memo` returns such a part's result from the run that already computed it. A key holds every input its part
reads (the :class:`.scene.Scenario`, which is frozen and hashable, the sizes, the seed, the loss criterion), so a
result is reused only where recomputing it would give the same numbers bit for bit (tested); values are small
(loss indicators, estimates), kept read-only and handed out as copies.
"""

from __future__ import annotations

import copy
from dataclasses import replace

import numpy as np

__all__ = ["memo", "memo_together", "clear_cache", "scenario_key", "MAX_ENTRIES"]

MAX_ENTRIES = 2048  # oldest forgotten first; one configuration keeps about 10 entries of a few kB
_MEMO: dict = {}


def clear_cache() -> None:
    """Forget every kept result (tests; memory)."""
    _MEMO.clear()


def scenario_key(sc):
    """The part of a :class:`.scene.Scenario` a run reads: ``edge_norm`` only scales the edge form's output
    (:meth:`.scene.Scenario.slope`), so other forms' runs are keyed with the default."""
    return sc if sc.form == "edge" else replace(sc, edge_norm="slope")


def _freeze(value):
    if isinstance(value, np.ndarray):
        value.flags.writeable = False
    elif isinstance(value, dict):
        for v in value.values():
            _freeze(v)
    elif isinstance(value, (list, tuple)):
        for v in value:
            _freeze(v)
    return value


def memo(key: tuple, compute):
    """``compute()``, or the value it returned for ``key`` before (``key``: every input ``compute`` reads), as a copy
    (callers may change what they get).

    Parameters
    ----------
    key : tuple
        Hashable; its first item names the part.
    compute : callable
        No arguments; returns the part's result (arrays in it are made read-only).
    """
    if key not in _MEMO:
        _keep(key, compute())
    return copy.deepcopy(_MEMO[key])


def _keep(key, value) -> None:
    if len(_MEMO) >= MAX_ENTRIES:
        _MEMO.pop(next(iter(_MEMO)))
    _MEMO[key] = _freeze(value)


def memo_together(parts, run) -> list:
    """:func:`memo` of several parts whose computations run together: ``parts`` holds ``(key, prepare, finish)``
    triples; the parts not kept are prepared (``prepare()``), run in one call (``run(list of prepared)``, one result
    each, in order) and finished (``finish(prepared, result)``, the part's value). Returns the parts' values (copies),
    in order."""
    todo = {}
    for key, prepare, finish in parts:
        if key not in _MEMO and key not in todo:
            todo[key] = (prepare, finish)
    if todo:
        ready = [prepare() for prepare, _ in todo.values()]
        got = {key: fin(p, r) for (key, (_, fin)), p, r in zip(todo.items(), ready, run(ready))}
        for key, value in got.items():
            _keep(key, value)
    return [copy.deepcopy(_MEMO[key] if key in _MEMO else _freeze(got[key])) for key, _, _ in parts]
