"""Studies of notebook 002 beyond the paper's claims (paper card 002, section 8): how often the algorithms fail,
swap labels or hit their iteration cap at the configurations of Figs 4-7 (card 8.2), and how often the number of
objects is chosen right by BIC when it is not known (card 8.3).

Both read the simulation points of :func:`.study.figure_data` (``g``: named groups of configurations, ``res``: their
results). Rates are proportions of trials with Clopper-Pearson 95 % intervals.
"""

from __future__ import annotations

import numpy as np

from tvtrack.montecarlo import Estimate, proportion_ci

from .simulation import FLAG_NAMES, gross_errors

__all__ = ["FAILURE_GROUPS", "failure_rates", "bic_correct_q"]

#: The configurations of Figs 4-7 whose failure rates are reported: ``(group of g, key, label)``.
FAILURE_GROUPS = (
    ("4", 20, "Fig 4a (m_k = 20)"),
    ("4", 50, "Fig 4b (m_k = 50)"),
    ("5ab", 5, "Fig 5a (T = 5)"),
    ("5ab", 50, "Fig 5b (T = 50)"),
    ("6", 20, "Fig 6b (Delta = 5 sigma)"),
)
#: The algorithms whose rates are reported: name -> result key of their errors and flags.
_RATES = {"ULA": "ula", "two-stage": "em"}


def _flag(result: dict, alg: str, name: str) -> np.ndarray:
    return result[f"{alg}_flags"][:, FLAG_NAMES[alg].index(name)]


def failure_rates(g: dict, res) -> dict[str, dict[float, dict[str, Estimate]]]:
    """Failure, label-swap and iteration-cap rates of the ULA and the two-stage (iterative marks), per configuration
    of Figs 4-6 and per separation.

    Returns
    -------
    dict
        ``{figure label: {d / sigma: {"<algorithm> <rate>": Estimate}}}`` with, for ``ULA`` and ``two-stage``:
        ``failure`` (some initial-position error beyond 2 sigma), ``label swap`` (the best label order over the
        whole trajectory is not the designation's) and ``cap hit`` (the EM iteration cap reached: per-frame marks,
        in some frame).
    """
    out = {}
    for group, key, label in FAILURE_GROUPS:
        if group not in g or key not in g[group]:
            continue
        rows = {}
        for d, c in g[group][key].items():
            r = res[c]
            row = {}
            for name, alg in _RATES.items():
                n = len(r[alg])
                row[f"{name} failure"] = proportion_ci(int(gross_errors(r, alg).sum()), n)
                row[f"{name} label swap"] = proportion_ci(int(_flag(r, alg, "swap").sum()), n)
                row[f"{name} cap hit"] = proportion_ci(int(_flag(r, alg, "cap_hit").sum()), n)
            rows[d] = row
        out[label] = rows
    return out


def bic_correct_q(g: dict, res) -> dict[float, dict[str, Estimate]]:
    """Share of trials in which BIC over ULA fits with Q' = 1, 2, 3 objects (weights estimated) picks each order,
    per separation; the true order is 2.

    Returns
    -------
    dict
        ``{d / sigma: {"Q' = 1": Estimate, "Q' = 2 (correct)": Estimate, "Q' = 3": Estimate}}``.
    """
    out = {}
    for d, c in g["bic"].items():
        pick = np.argmin(res[c]["bic"], axis=1) + 1
        n = len(pick)
        out[d] = {
            "Q' = 1": proportion_ci(int((pick == 1).sum()), n),
            "Q' = 2 (correct)": proportion_ci(int((pick == 2).sum()), n),
            "Q' = 3": proportion_ci(int((pick == 3).sum()), n),
        }
    return out
