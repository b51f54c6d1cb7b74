"""Each claim measured in the world it declares: a paper's measurement groups the claims it is asked for by their
configuration projected onto their ``DEPENDS`` (:func:`tvtrack.register.project`).

A measurement that computes several claims from one shared simulation (one scene, one batch of runs) would
otherwise apply every register entry of the configuration to every claim, whether the claim declares it or not:
a track geometry declared by two claims would reach every two-object scene. :func:`claim_groups` splits the
claims asked into groups whose projected configurations agree; the measurement runs once per group, so a claim
never sees an entry it does not declare (its value is the one it has when measured alone), and at the default,
where every projection is the default, it runs once, as before.

Example
-------
>>> depends = {"A": ["x"], "B": ["x", "y"]}
>>> [(cfg, sorted(c)) for cfg, c in claim_groups({"x": 1, "y": 2}, None, depends, {"x": 0, "y": 0})]
[({'x': 1, 'y': 0}, ['A']), ({'x': 1, 'y': 2}, ['B'])]
>>> claim_groups({"x": 0, "y": 0}, None, depends, {"x": 0, "y": 0})
[({'x': 0, 'y': 0}, None)]
"""

from __future__ import annotations

import functools
from typing import Any, Callable, Iterable, Mapping, Sequence

from .register import project

__all__ = ["claim_groups", "as_declared"]


def claim_groups(
    config: Mapping[str, Any],
    claims: Iterable[str] | None,
    depends: Mapping[str, Sequence[str]],
    default: Mapping[str, Any],
) -> list[tuple[dict, frozenset | None]]:
    """The claims asked, grouped by their configuration projected onto their ``DEPENDS``.

    Parameters
    ----------
    config : mapping entry name -> value
        The configuration the measurement received (entries it lacks are at ``default``; entries a claim does
        not declare are never used, so a guarded configuration's sentinels are never touched).
    claims : iterable of claim ids, or None
        The claims asked (None: every claim of ``depends``).
    depends : mapping claim id -> entry names
        The claims' declared entries (the paper's ``DEPENDS``); a claim asked that it lacks declares nothing.
    default : mapping entry name -> value
        The register's default configuration.

    Returns
    -------
    list of (dict, frozenset or None)
        ``(projected configuration, claims)`` in the order the claims were asked; a single group keeps
        ``claims`` as it came (None stays None: the measurement computes everything it computes for all claims,
        its figures' data included).
    """
    asked = list(depends) if claims is None else list(claims)
    groups: dict[tuple, tuple[dict, list]] = {}
    for cid in asked:
        cfg = project(config, depends.get(cid, ()), default)
        key = tuple((k, repr(v)) for k, v in cfg.items())
        groups.setdefault(key, (cfg, []))[1].append(cid)
    if len(groups) <= 1:
        cfg = next(iter(groups.values()))[0] if groups else project(config, (), default)
        return [(cfg, None if claims is None else frozenset(asked))]
    return [(cfg, frozenset(cs)) for cfg, cs in groups.values()]


def as_declared(claims_of: Sequence[str], load: Callable[..., tuple[Mapping, Mapping]]) -> Callable:
    """A decorator for a measurement ``fn(config, seed, *args, claims=None, **kwargs) -> {claim id: measured}``:
    it runs ``fn`` once per group of :func:`claim_groups` and merges what each returns.

    Parameters
    ----------
    claims_of : sequence of claim ids
        The claims ``fn`` measures (``claims=None`` asks for these).
    load : callable
        ``load(args, kwargs) -> (DEPENDS, default)``, called at each measurement with the arguments after
        ``seed`` (a paper imports its register there, after its modules are loaded; a notebook that moves a
        default passes it in its sizes).
    """

    def wrap(fn: Callable) -> Callable:
        @functools.wraps(fn)
        def measure(config, seed, *args, claims=None, **kwargs):
            depends, default = load(args, kwargs)
            mine = {cid: depends.get(cid, ()) for cid in claims_of}
            out: dict = {}
            for cfg, asked in claim_groups(config, claims, mine, default):
                out.update(fn(cfg, seed, *args, claims=asked, **kwargs))
            return out

        return measure

    return wrap
