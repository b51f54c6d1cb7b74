"""The claims of paper 002 (Savanevich 1999) and the rules that decide them.

``CLAIMS`` holds what the paper says (statement and the paper's value; the study's table of the claims plus the
summary claim C002-16), ``RULES`` the rule of each claim (the notebook's, written once here).
"""

from __future__ import annotations

from ...verdicts import AllOf, InBand, Monotone, NotCheckable, Ordering
from .study import CLAIMS as _STUDY_CLAIMS

__all__ = ["CLAIMS", "RULES"]

CLAIMS = {cid: {"statement": s, "paper_value": v} for cid, (s, v) in _STUDY_CLAIMS.items()} | {
    "C002-16": {
        "statement": "Where the ULA pays off: poor sensors, or near-potential accuracy for close objects with known Q.",
        "paper_value": "qualitative",
    }
}

_U = dict(measure="ratio", paired=False)  # between independent configurations

RULES = {
    "C002-1": Monotone("ULA Sigma^2 (Fig 1a, m_k = 20)", "separation d/sigma", "decreasing"),
    "C002-2": AllOf(
        {
            "weakens": Ordering("r_m(6 sigma)", "r_m(1 sigma)", ">", **_U),
            "far apart": InBand("r_m = Sigma^2(m_k = 10) / Sigma^2(m_k = 20) at 6 sigma", 1.6, 2.4),
        }
    ),
    "C002-3": Ordering("mean r_m(Delta = sigma)", "mean r_m(Delta = 3 sigma)", ">", **_U),
    "C002-4": Ordering("loss Sigma^2(1 sigma) / Sigma^2(6 sigma) at Delta = 5 sigma", "at Delta = 3 sigma", ">", **_U),
    "C002-5": Monotone("Sigma^2(Delta = 3 sigma) / Sigma^2(Delta = sigma)", "T = 5, 10, 50", "decreasing"),
    "C002-6": Ordering("|ln r_T| at m_k = 20", "|ln r_T| at m_k = 10", ">", "difference", paired=False),
    "C002-7": AllOf(
        {
            "fine pixels": InBand("Var_two-stage / Var_ULA of x_o at Delta = sigma", None, 1.2),
            "coarse pixels": InBand("Var_two-stage / Var_ULA of x_o at coarse Delta", 1.2, None),
        }
    ),
    "C002-8": AllOf(
        {
            "worse than fine pixels": Ordering("Var_ULA(coarse Delta)", "Var_ULA(Delta = sigma)", ">", **_U),
            "better than the marks": Ordering("Var_ULA(coarse Delta)", "Var_two-stage(coarse Delta)", "<", "ratio"),
        }
    ),
    "C002-9": AllOf(
        {
            "centre-of-region >= iterative marks": Ordering("Var_centre", "Var_iterative", ">", "ratio"),
            "iterative marks >= ULA": Ordering("Var_iterative", "Var_ULA", ">", "ratio"),
        }
    ),
    "C002-10": AllOf(
        {
            "closer": Monotone("rho (Fig 4a)", "separation d/sigma", "decreasing"),
            "coarser pixels": Ordering("rho(Delta = 5 sigma)", "rho(Fig 4's Delta)", ">", **_U),
            "more frames": Ordering("rho(T = 50)", "rho(T = 5)", ">", **_U),
        }
    ),
    "C002-11": AllOf(
        {
            p: InBand(f"rho at {p.split(' (')[0]}, T = 50", 3.0, 6.0)
            for p in ("d = 1 sigma (paper x4.5)", "d = 3 sigma (paper x4)")
        }
    ),
    "C002-12": AllOf(
        {f"Delta = {p:g} sigma": InBand(f"rho at d = 8 sigma, Delta = {p:g} sigma", 0.9, 1.1) for p in (0.5, 1.0)}
    ),
    "C002-13": Ordering("mean plain-EM iterations at the smallest d", "at the largest d", ">", **_U),
    "C002-14": Ordering("ULA frame-iterations", "two-stage frame-iterations", ">", "ratio"),
    "C002-15": AllOf(
        {
            p: InBand(f"ULA spread / bound, {p}", 0.8, 1.5)
            for p in ("d = 1 sigma (very close)", "d = 2 sigma", "d = 4 sigma", "velocities, d = 1 sigma")
        }
    ),
    "C002-16": NotCheckable("a summary of C002-7, C002-10, C002-12 and C002-15"),
}
