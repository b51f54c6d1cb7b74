"""The claims of paper 001 (Fisenko et al. 2008) and the rules that decide them.

``CLAIMS`` holds what the paper says (statement and the paper's value), ``RULES`` the rule of each claim (the
notebook's, written once here).
"""

from __future__ import annotations

from ...verdicts import AllOf, InBand, Monotone, NotCheckable, Ordering, WithinFactor
from .study import COMPARATORS

__all__ = ["CLAIMS", "RULES"]


def _claim(statement: str, paper_value: str) -> dict[str, str]:
    return {"statement": statement, "paper_value": paper_value}


CLAIMS = {
    "C001-1": _claim("A manoeuvre at 5 s is detected at 5.5 s.", "5.5 s (one run)"),
    "C001-2": _claim(
        "Rule (14) is invariant, uniformly most powerful and unbiased among invariant rules.", "invariant, optimal"
    ),
    "C001-3": _claim(
        "Neighbouring velocity samples correlate by <= 0.5, negligibly; the pair distributions may be multiplied.",
        "rho <= 0.5",
    ),
    "C001-4": _claim(
        "Switching to 3rd order with raised gains speeds up compensation of the dynamic error; the gain law "
        "minimizes the RMS error.",
        "qualitative (Fig. 3)",
    ),
    "C001-5": _claim(
        "The gains decrease smoothly with frame number and stay constant at the lower bound.", "qualitative (Fig. 3)"
    ),
    "C001-6": _claim(
        "With zero gains the filter reproduces the trajectory; the prediction error is F^m times the errors at the "
        "last observed frame.",
        "(E1), (E2)",
    ),
    "C001-7": _claim(
        "Manoeuvre-induced dynamic errors substantially affect the prediction if the object is lost before the "
        "dynamic error is worked off.",
        "qualitative",
    ),
    "C001-8": _claim(
        "Fig. 4: prediction errors depend on the frame at which the gain bound is set; an optimal bound is implied.",
        "curves 1-3 (values not in the text)",
    ),
    "C001-9": _claim(
        "Within ±20° the trajectory stays linear in spherical coordinates with accuracy acceptable for prediction.",
        "±20°",
    ),
    "C001-10": _claim("0.008° = 1 raster element and 0.02° = 10 elements/frame.", "1 element; 10 elements/frame"),
}

RULES = {
    "C001-1": AllOf(
        {
            "median": InBand("median detection time", 5.25, 5.75, "s"),
            "early": InBand("fraction of runs x channels alarming before the onset", None, 0.05),
            "missed": InBand("fraction of runs x channels missing the manoeuvre before the loss", None, 0.01),
        }
    ),
    "C001-2": AllOf(
        {
            "size": WithinFactor("per-test false-alarm rate / alpha (exact sigma_S)", 1.0, 1.5),
            "invariance": NotCheckable("S is a difference of two window sums: a common shift cancels by construction"),
            "unbiased": InBand("alarm rate after the onset / alpha", 1.0, None),
            "UMP": Ordering("P(detect within the delay) of |S|", "that of Q at the same per-test rate", ">"),
        }
    ),
    "C001-3": InBand("per-test false-alarm rate / alpha with the paper's independence threshold", 0.5, 2.0),
    "C001-4": AllOf(
        {
            "faster compensation": Ordering(
                "MS error of the 2nd-order filter without the switch", "the scheme's", ">", "ratio"
            ),
            **{
                f"min RMS vs {c}": Ordering(f"MS error of the tuned {c}", "the scheme's", ">", "ratio")
                for c in COMPARATORS
            },
        }
    ),
    "C001-5": NotCheckable(
        "true by construction: the growing-memory least-squares schedule frozen at its bound (the paper prints "
        "none); checks: increases of kappa1 outside the switches, runs at the bound before the loss"
    ),
    "C001-6": NotCheckable("an identity of the zero-gain recursion for a polynomial truth of degree <= 2"),
    "C001-7": AllOf(
        {
            "decreasing": Monotone("|dynamic error| after a 10 s loss", "loss time", "decreasing"),
            "dominates early": Ordering("|dynamic error|", "RMS error for the earliest loss", ">", "ratio"),
        }
    ),
    "C001-8": AllOf(
        {
            "RMS decreasing": Monotone("RMS prediction error", "k_b3", "decreasing"),
            "interior minimum": Ordering(
                "smallest |dynamic|+RMS at the ends of the grid", "the smallest inside it", ">"
            ),
            "dynamic grows beyond the optimum": Monotone("|dynamic error| from the optimum on", "k_b3", "increasing"),
        }
    ),
    "C001-9": InBand(
        "fraction of geometries within ±20° whose 10 s extrapolation stays within the tolerance", 0.9, 1.0
    ),
    "C001-10": AllOf(
        {
            "0.008°": WithinFactor("0.008° in raster elements", 1.0, 1.1),
            "0.02°": WithinFactor("0.02° in raster elements", 10.0, 1.1),
        }
    ),
}
