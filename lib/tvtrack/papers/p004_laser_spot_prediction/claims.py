"""The claims of paper 004 (Kokryatska and Hrynchyshyn 2005) and the rules that decide them.

``CLAIMS`` holds what the paper says (statement and the paper's value), ``RULES`` the rule of each claim (the
notebook's, written once here).
"""

from __future__ import annotations

from ...verdicts import AllOf, InBand, NotCheckable, Ordering, Rule
from .prediction_study import CLASSICAL
from .study import NETWORKS

__all__ = ["CLAIMS", "RULES", "claim_rules"]


def _claim(statement: str, paper_value: str) -> dict[str, str]:
    return {"statement": statement, "paper_value": paper_value}


CLAIMS = {
    "C004-1": _claim("The prediction error does not exceed 2 pixels (Fig. 4 text).", "<= 2 px"),
    "C004-2": _claim("Prediction accuracy improved to 1...2 pixels (abstract, conclusions).", "1-2 px"),
    "C004-3": _claim(
        "The filter is more accurate than finite differences and splines (2-10 px) and linear regression "
        "(3-10 px), compared on one and the same data base.",
        "filter 1-2 px; others 2-10 px",
    ),
    "C004-3b": _claim(
        "The filter is more accurate than back-propagation networks (2-3 px) and RBF networks (2-4 px).",
        "filter 1-2 px; MLP 2-3 px; RBF 2-4 px",
    ),
    "C004-4": _claim("The recursion (5)-(6) reproduces the growing-memory least-squares estimate (4).", "exact"),
    "C004-5": _claim("The correction is large for small n, tends to 0, and smoothing improves with n.", "qualitative"),
    "C004-6": _claim(
        "Without a floor the accuracy degrades on signals that follow the model only locally; the floor prevents it.",
        "qualitative",
    ),
    "C004-7": _claim(
        "Estimates exist once the number of observations equals the number of state components (3).", "n = 3"
    ),
    "C004-8": _claim("The algorithm works in real time.", "real time"),
}


def _better(baseline: str) -> Ordering:
    """The baseline's MSE above the filter's: a paired per-path ratio above 1."""
    return Ordering(f"mean squared error of {baseline}", "that of the paper's filter", ">", measure="ratio")


def claim_rules() -> dict[str, Rule]:
    """``{claim id: rule}``: the rule that decides each claim (built in a function, so that every part of it is
    open to mutation testing)."""
    return {
        "C004-1": InBand(
            'mean per-path 95th percentile of the per-axis |prediction error| (the paper\'s "does not exceed" read as '
            "a 95th percentile)",
            high=2.0,
            unit="px",
        ),
        "C004-2": NotCheckable(
            "the simulated world is calibrated so that the paper's filter errs 1.5 px (the wander's bandwidth is the root "
            "of that equation, calibration.calibrate_bandwidth): the paper's 1-2 px is the calibration's input, so at the "
            "default it holds by construction, and without the paper's recordings nothing else can check it; the "
            "measured RMS is still shown (per axis, and radial as a reading)"
        ),
        "C004-3": AllOf({b: _better(b) for b in CLASSICAL}),
        "C004-3b": AllOf({b: _better(b) for b in NETWORKS}),
        "C004-4": InBand(
            "largest relative deviation of the recursion (5)-(6) from least squares on eq. (4)",
            high=1e-9,
            unit="relative",
        ),
        "C004-5": NotCheckable(
            "a statement about the derivation, true by construction: the paper reads it off eq. (6) ('from formula "
            "(6) it is obvious'); the gain g_N1 = 3(3N^2 - 3N + 2) / (N(N+1)(N+2)) falls as 9/N in closed form, and "
            "the filtered position's variance sigma^2 g_N1 is an identity of least squares under the uncorrelated "
            "noise of eq. (1), whatever its law (Student t3 included); the Monte Carlo checks the code, not the paper; "
            "the gains and variances are still shown"
        ),
        "C004-6": InBand("RMS error over the second half of the frames, no floor / floor", low=2.0, unit="ratio"),
        "C004-7": NotCheckable(
            "true by construction: eq. (4) on the first three samples is the exact interpolating quadratic"
        ),
        "C004-8": InBand(
            "time per frame (energy centre + filter + prediction) / frame interval", high=1.0, unit="ratio"
        ),
    }


RULES = claim_rules()
