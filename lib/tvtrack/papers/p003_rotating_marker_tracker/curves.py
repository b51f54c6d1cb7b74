"""The loss curves of notebook 003's interference study (:func:`.study.measure_interference`): a curve's batch of
runs as a part of :func:`.memo.memo_together`, what a batch's runs say (loss indicators, loss criteria), and the
claim parts read from the curves.
"""

from __future__ import annotations

import numpy as np

from tvtrack.measured import fold_about

from .draws import stream_rng
from .estimators import (
    compensation_factor,
    loss_share,
    threshold_bound,
    threshold_ratio,
)
from .lock import CRITERIA, LossCriterion, first_loss, loss_criteria
from .memo import scenario_key
from .scene import Scenario, interference_outcome, prepare_interference

__all__ = ["SIR_GRID", "UNCOMPENSATED_GRID", "curve_part", "curve_outcome", "interference_claims", "loss_mechanisms"]

SIR_GRID = (0.5, 0.75, 1.0, 4 / 3, 2.0, 3.0, 4.5, 6.75)  # post-compensation SIR, steps of 1.33-1.5
UNCOMPENSATED_GRID = (1.0, 2.0, 4.0, 8.0, 16.0)  # SIR_0 without compensation (kappa = 1)


def curve_part(sc: Scenario, sirs, n: int, seed: int, crit: LossCriterion, counts=None, criteria: bool = False):
    """:func:`.study._curve` as a part of :func:`.memo.memo_together`: ``(key, prepare, finish)``."""
    key = ("curve", scenario_key(sc), tuple(float(x) for x in sirs), n, seed, crit, counts and tuple(counts), criteria)
    k = 1 if counts is None else len(counts)
    blocks = (
        None
        if counts is None
        else [
            {"n_interferers": c} if isinstance(c, int) else {"n_interferers": 0, "decoy_offset": c[1]} for c in counts
        ]
    )
    return (
        key,
        lambda: _stopping(prepare_interference([stream_rng(10, seed) for _ in range(k)], n, sc, sirs, blocks), crit),
        lambda p, r: curve_outcome(sc, sirs, n, crit, counts, criteria, interference_outcome(p, r[2])),
    )


def _stopping(p, crit: LossCriterion):
    """A curve's batch, its runs dropped once lost by ``crit`` (all a curve reads of a run ends at its first loss)."""
    p.stop = crit
    return p


def curve_outcome(sc: Scenario, sirs, n: int, crit: LossCriterion, counts, criteria: bool, runs: dict):
    """:func:`.study._curve`'s value from the batch's runs (:func:`.scene.interference_outcome`)."""
    k = 1 if counts is None else len(counts)
    fl = first_loss(runs["miss"], crit, runs["inside"])
    shape = (len(sirs), n) if counts is None else (k, len(sirs), n)
    lost = (fl >= 0).reshape(shape)
    if not criteria:
        return lost, None
    met = loss_criteria(
        fl,
        runs["gate"],
        runs["interferers"],
        runs["miss"],
        runs["omega_error"],
        crit.window,
        sc.diameter / 2 + 0.5,
        crit.fraction,
    )
    return lost, met.reshape(shape + (3,))


def interference_claims(config: dict, base: Scenario, curves: dict, capt, xc: dict, xsirs, bw_ratio, asked) -> dict:
    """The claim parts of :func:`.study.measure_interference` from its loss curves (``curves`` on :data:`SIR_GRID`, ``xc`` on
    the extended grid ``xsirs``), the capture indicators ``capt`` (five interferers, per SIR and run) and C003-11's
    bandwidth ratio; only the ``asked`` claims (their curves present)."""
    sirs, usirs, at = np.asarray(SIR_GRID), np.asarray(UNCOMPENSATED_GRID), {s: i for i, s in enumerate(SIR_GRID)}
    r1, r5 = curves["rotating", 1], curves["rotating", 5]
    parts = {
        "C003-5": lambda: {"no_loss": loss_share(r5[at[3.0]]), "no_capture": loss_share(capt[at[3.0]])},
        "C003-6": lambda: {
            "finite": loss_share(r1[at[0.5]]),
            "loss_free": loss_share(r1[at[2.0]]),
            "not_lower": loss_share(r1[at[4 / 3]]),
        },
        "C003-7": lambda: {
            "loss_free": loss_share(r5[at[3.0]]),
            "not_lower": loss_share(r5[at[2.0]]),
            "rise": threshold_ratio(xc["rotating", 5], xc["rotating", 1], xsirs),
        },
        "C003-10": lambda: {
            # the side a grid-censored threshold certifies decides (threshold_bound), as in the prose's map
            "gate": [
                threshold_bound(curves["gate", 1.5], sirs),
                threshold_bound(r5, sirs),
                threshold_bound(curves["gate", 5.0], sirs),
            ],
            # reported, not judged: at most kappa by construction (claims.py, C003-10's compensation part)
            "compensation": compensation_factor(curves["uncompensated"], usirs, r5, sirs, base.kappa),
        },
        "C003-11": lambda: {
            "dynamics": loss_share(curves["gate", 1.5][-1]),
            "selection": threshold_ratio(curves["gate", 5.0], r5, sirs),
            # l. 192 says the errors depend substantially on the bandwidths, not which way: two-sided (fold distance)
            "bandwidth": fold_about(bw_ratio, 1.0),
        },
        "C003-12": lambda: {
            "one": threshold_ratio(xc["static", 1], xc["rotating", 1], xsirs),
            "five": threshold_ratio(xc["static", 5], xc["rotating", 5], xsirs),
            "imitator": threshold_ratio(xc["decoy"], xc["rotating", 1], xsirs),
        },
    }
    return {c: f() for c, f in parts.items() if c in asked}


def loss_mechanisms(lost, met) -> dict:
    """Counts of the losses (all SIRs) and of those meeting each loss criterion (a loss may meet several)."""
    lost = np.asarray(lost, bool)
    m = np.asarray(met, bool)[lost]
    return {
        "losses": int(lost.sum()),
        **{c: int(m[:, j].sum()) for j, c in enumerate(CRITERIA)},
        "none (drift)": int((~m.any(axis=1)).sum()),
    }
