"""Whether a measurement reads only the register entries its claims declare (``DEPENDS``), checked claim by claim
under :func:`tvtrack.register.guard` (:func:`check_declared`); :func:`tvtrack.explore.explore` applies the same guard
to every condition's run."""

from __future__ import annotations

import inspect
from typing import Any, Callable, Mapping, Sequence

from .register import Register, UndeclaredEntry, guard

__all__ = ["check_declared", "takes_claims"]


def takes_claims(fn: Callable) -> bool:
    """Whether a measurement function takes a ``claims`` keyword (it can skip the work of claims not asked)."""
    try:
        return "claims" in inspect.signature(fn).parameters
    except (TypeError, ValueError):
        return False


def check_declared(
    measure: Callable,
    register: Register,
    depends: Mapping[str, Sequence[str]],
    seed: int,
    claims: Sequence[str] | None = None,
    **measure_kwargs: Any,
) -> dict[str, str]:
    """Each claim measured alone at the default under :func:`tvtrack.register.guard`: the claims whose measurement
    uses a register entry their ``DEPENDS`` does not declare, each with the one-line message naming the entry.

    A measurement taking ``claims`` is asked for the one claim (``claims=frozenset({claim})``) and may read only
    that claim's entries; one that does not take ``claims`` measures every claim at once, so its guard allows the
    union of every claim's entries (it then catches only an entry that no claim declares).

    Parameters
    ----------
    measure : callable
        ``measure(config, seed, **measure_kwargs)`` (unbatched), as :func:`explore` takes it.
    register : Register
    depends : mapping claim id -> entry names
    seed : int
    claims : sequence of claim ids, optional
        The claims to check (default: every claim of ``depends``).
    **measure_kwargs
        Passed on to ``measure`` (e.g. a smaller size for a quick check).

    Returns
    -------
    dict claim id -> str
        Empty when every claim reads only what it declares.
    """
    default = register.default()
    asks = takes_claims(measure)
    everything = {k for names in depends.values() for k in names}
    out = {}
    for cid in claims if claims is not None else list(depends):
        allowed = set(depends[cid]) if asks else everything
        extra = {"claims": frozenset({cid})} if asks else {}
        try:
            measure(guard(default, allowed), seed, **measure_kwargs, **extra)
        except UndeclaredEntry as e:
            out[cid] = str(e)
    return out
