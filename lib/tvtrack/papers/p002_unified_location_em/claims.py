"""The claims of paper 002 (Savanevich 1999) and the rules that decide them.

``CLAIMS`` holds what the paper says (statement and the paper's value; the study's table of the claims plus the
summary claim C002-16), ``RULES`` the rule of each claim (the notebook's, written once here).
"""

from __future__ import annotations

from ...verdicts import AllOf, InBand, Monotone, NotCheckable, Ordering, Rule
from .study import CLAIMS as _STUDY_CLAIMS

__all__ = ["CLAIMS", "RULES", "claim_rules"]

CLAIMS = {cid: {"statement": s, "paper_value": v} for cid, (s, v) in _STUDY_CLAIMS.items()} | {
    "C002-16": {
        "statement": "Where the ULA pays off: poor sensors, or near-potential accuracy for close objects with known Q.",
        "paper_value": "qualitative",
    }
}

_U = dict(measure="ratio", paired=False)  # between independent configurations
_V, _R = "sigma^2", "variance ratio"  # units: PSF variances; ratios of variance sums
_SAME = 1.1  # C002-12's "practically coincide" band [0.9, 1.1]: a ratio within a tenth of 1 is no dependence


def _one_algorithm_rules() -> dict[str, Rule]:
    """The rules of C002-1 to C002-6: how the unified location algorithm's variance moves with separation, photons,
    pixels and frames."""
    return {
        "C002-1": Monotone(
            "ULA total position variance (Fig 1a, 20 photons)", "separation d / sigma", "decreasing", unit=_V
        ),
        "C002-2": AllOf(
            {
                "weakens": Ordering(
                    "photon gain r_m = variance(10 photons) / variance(20) at d = 6 sigma",
                    "r_m at d = 1 sigma",
                    ">",
                    **_U,
                    unit=_R,
                ),
                "far apart": InBand("photon gain r_m at d = 6 sigma", 1.6, 2.4, unit=_R),
            }
        ),
        "C002-3": Ordering("mean photon gain r_m with 1-sigma pixels", "with 3-sigma pixels", ">", **_U, unit=_R),
        "C002-4": Ordering(
            "loss variance(1 sigma) / variance(6 sigma) with 5-sigma pixels", "with 3-sigma pixels", ">", **_U, unit=_R
        ),
        "C002-5": Monotone(
            "variance with coarser / finer pixels (3 / 1 sigma by default)",
            "frames T = 5, 10, 50",
            "decreasing",
            unit=_R,
        ),
        "C002-6": Ordering(
            "frame dependence |ln r_T| at 20 photons",
            "at 10 photons",
            ">",
            "difference",
            paired=False,
            unit="|ln r_T| difference",
        ),
    }


def _comparison_rules() -> dict[str, Rule]:
    """The rules of C002-7 to C002-16: the unified location algorithm against two-stage tracking, its iterations and
    its efficiency."""
    return {
        "C002-7": AllOf(
            {
                "fine pixels": InBand("two-stage / ULA variance of x_o, 1-sigma pixels", None, 1.2, unit=_R),
                "coarse pixels": InBand("two-stage / ULA variance of x_o, coarse pixels", 1.2, None, unit=_R),
            }
        ),
        "C002-8": AllOf(
            {
                "worse than fine pixels": Ordering(
                    "ULA variance of x_o, coarse pixels", "1-sigma pixels", ">", **_U, unit=_R
                ),
                "better than the marks": Ordering(
                    "ULA variance of x_o, coarse pixels", "two-stage's", "<", "ratio", unit=_R
                ),
            }
        ),
        "C002-9": AllOf(
            {
                "centre-of-region >= iterative marks": Ordering(
                    "centre-of-region variance of x_o", "iterative marks'", ">", "ratio", unit=_R
                ),
                "iterative marks >= ULA": Ordering("iterative marks' variance of x_o", "ULA's", ">", "ratio", unit=_R),
            }
        ),
        "C002-10": AllOf(
            {
                "closer": Monotone(
                    "gain rho = two-stage / ULA variance (Fig 4a)", "separation d / sigma", "decreasing", unit=_R
                ),
                "coarser pixels": Ordering("rho with 5-sigma pixels", "rho with Fig 4's pixels", ">", **_U, unit=_R),
                "more frames": Ordering("rho at T = 50", "rho at T = 5", ">", **_U, unit=_R),
            }
        ),
        "C002-11": AllOf(
            {
                p: InBand(
                    f"gain rho = two-stage / ULA variance at {p.split(' (')[0]}, T = 50",
                    3.0,
                    6.0,
                    unit=_R,
                    better="higher",
                )
                for p in ("d = 1 sigma (paper x4.5)", "d = 3 sigma (paper x4)")
            }
        ),
        "C002-12": AllOf(
            {
                f"Delta = {p:g} sigma": InBand(f"gain rho at d = 8 sigma, {p:g}-sigma pixels", 0.9, 1.1, unit=_R)
                for p in (0.5, 1.0)
            }
        ),
        # "Зависимость числа итераций алгоритма от расстояния между объектами приведена на рис. 7" (l. 131): a
        # dependence, no direction, so two-sided: the fold change either way, a dependence once it exceeds what
        # C002-12's band calls practically the same (a tenth)
        "C002-13": InBand(
            "fold change of mean plain-EM iterations between the smallest and the largest d, either way "
            "(max(q, 1/q), q unpaired)",
            low=_SAME,
            unit="iterations ratio",
        ),
        "C002-14": Ordering(
            "ULA frame-iterations", "two-stage frame-iterations", ">", "ratio", unit="frame-iterations ratio"
        ),
        "C002-15": AllOf(
            {
                p: InBand(f"ULA variance / bound (efficiency), {q}", 0.8, 1.5, unit="variance / bound")
                for p, q in (
                    ("very close", "very close objects (d = 1 sigma by default)"),
                    ("d = 2 sigma", "d = 2 sigma"),
                    ("d = 4 sigma", "d = 4 sigma"),
                    ("velocities, very close", "velocities of very close objects"),
                )
            }
        ),
        "C002-16": NotCheckable("a summary of C002-7, C002-10, C002-12 and C002-15"),
    }


def claim_rules() -> dict[str, Rule]:
    """``{claim id: rule}``: the rule that decides each claim (built in functions, so that every part of it is
    open to mutation testing)."""
    return {**_one_algorithm_rules(), **_comparison_rules()}


RULES = claim_rules()
