"""The deterministic curves of C001-7 and C001-8 (Fisenko et al. 2008, Fig. 4 and the text before Fig. 1) as
measured values: each point carries the register's ``curve_tolerance`` as its resolution, and Fig. 4's optimum is
reported with what it rests on (where the signed dynamic error crosses zero).
"""

from __future__ import annotations

import numpy as np

from ...montecarlo import Estimate

__all__ = ["resolved", "optimum_location"]


def resolved(values, tolerance: float) -> list[Estimate]:
    """Deterministic curve values (elements) as estimates whose interval is ``value ± tolerance / 2``.

    A neighbouring step then counts as a change (its intervals separate) only when it exceeds ``tolerance``:
    the curves are noise-free runs and covariance recursions, exact up to float rounding, and where the gains
    never reach the bound before the loss they are flat by construction; a step below the tolerance is flat.
    """
    t = float(tolerance)
    if not t > 0:
        raise ValueError(f"curve tolerance = {tolerance!r}; it must be > 0 (elements)")
    return [
        Estimate(float(v), 0.0, float(v) - t / 2, float(v) + t / 2, 1, 0.95, f"deterministic; resolution ±{t / 2:g} el")
        for v in np.asarray(values, float)
    ]


def optimum_location(cur: dict) -> dict:
    """Where curve 3 (|dynamic| + RMS) is smallest and what puts it there.

    Returns
    -------
    dict
        ``kb3`` (the grid point of the minimum), ``sum``, ``dyn``, ``rms`` there; ``crossings``: the k_b3 values
        (linear interpolation between grid points) where the signed dynamic error changes sign; ``nearest_crossing``
        (None without a crossing); ``at_crossing``: whether the minimum is the grid point next to a crossing on
        either side (the optimum then sits where the dynamic error passes through zero, not where a trade-off
        of two monotone errors balances); ``rms_share``: RMS / sum at the minimum.
    """
    kb = np.asarray(cur["kb3"], float)
    dyn, rms, s = (np.asarray(cur[k], float) for k in ("dyn", "rms", "sum"))
    i = int(np.argmin(s))
    a, b = dyn[:-1], dyn[1:]
    j = np.nonzero(a * b < 0)[0]  # strict sign changes (exact zeros of a rounded curve are not crossings)
    cross = [float(kb[k] + (kb[k + 1] - kb[k]) * a[k] / (a[k] - b[k])) for k in j]
    near = min(cross, key=lambda c: abs(c - kb[i])) if cross else None
    adjacent = near is not None and (
        (i > 0 and kb[i - 1] <= near <= kb[i]) or (i < len(kb) - 1 and kb[i] <= near <= kb[i + 1])
    )
    return {
        "kb3": int(kb[i]),
        "sum": float(s[i]),
        "dyn": float(dyn[i]),
        "rms": float(rms[i]),
        "crossings": cross,
        "nearest_crossing": near,
        "at_crossing": bool(adjacent),
        "rms_share": float(rms[i] / s[i]),
    }
