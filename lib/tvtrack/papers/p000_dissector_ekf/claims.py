"""The claims of paper 000 (Martyshevsky 1995) and the rules that decide them.

``CLAIMS`` holds what the paper says (statement and the paper's value); :func:`claim_rules` builds the rule of
each claim from the run's sizes (the grids and the acquisition time the notebook's parameters set), and
``RULES`` is that at the default sizes. The notebook passes its own :class:`~.study.Sizes`.
"""

from __future__ import annotations

from ... import verdicts as vd
from .study import Sizes

__all__ = ["CLAIMS", "RULES", "claim_rules"]


def _claim(statement: str, paper_value: str) -> dict[str, str]:
    return {"statement": statement, "paper_value": paper_value}


CLAIMS = {
    "C000-1": _claim("Both algorithms converge fairly quickly.", "fairly quickly (no number)"),
    "C000-2": _claim("At psi_A = 20 the coordinate error is 2 % of the micro-raster size.", "2 %"),
    "C000-3": _claim(
        "The two algorithms give approximately the same estimate of potential accuracy.", "approximately equal"
    ),
    "C000-4": _claim("Variant 1 is two-dimensional and needs more computation.", "qualitative"),
    "C000-5": _claim(
        "For P < 0.5 the non-stationary noise does not substantially affect accuracy; for P > 0.5 it "
        "substantially determines it.",
        "threshold near P = 0.5",
    ),
    "C000-6": _claim(
        "At P = 0.9 the estimate variance exceeds the potentially achievable one by more than 20 times.", "> 20"
    ),
    "C000-7": _claim(
        "sigma_x^2 grows with P relative to sigma_x^2*; the measurement variance grows faster than the "
        "estimate variance.",
        "monotone growth",
    ),
    "C000-8": _claim("dt = 0.05 keeps discretisation errors within 3 %.", "<= 3 %"),
    "C000-9": _claim("sigma_x^2 decreases with psi_A (Fig. 2).", "qualitative"),
    "C000-10": _claim(
        "Experiment (Fig. 3, triangles) agrees with the model; a practical test confirmed the algorithms.",
        "qualitative",
    ),
}


def claim_rules(sizes: Sizes | None = None) -> dict[str, vd.Rule]:
    """``{claim id: rule}`` for a run of ``sizes`` (:class:`~.study.Sizes`): its grids ``psi_grid``,
    ``contrast_grid``, ``dt_points``, ``dt_factor`` and its ``acquire_by_T`` name the rules' parts
    (the defaults if None)."""
    sizes = Sizes() if sizes is None else sizes
    acquire_by_T, contrast_grid, psi_grid = sizes.acquire_by_T, sizes.contrast_grid, sizes.psi_grid
    band = vd.InBand
    identity = vd.NotCheckable("at P = 0 both variants are the same filter: the ratio is 1 by construction")
    ratio_parts = [f"P={p:g}" for p in contrast_grid] + [f"psi_A={p:g}" for p in psi_grid]
    return {
        "C000-1": vd.AllOf(
            {
                f"variant {v}": band(
                    f"fraction of runs (variant {v}) not in lock for good by {acquire_by_T:g} T", None, 0.1
                )
                for v in (1, 2)
            }
        ),
        "C000-2": vd.AllOf(
            {
                k: band(f"steady RMS error / micro-raster size at psi_A = 20, {k}", 0.01, 0.03)
                for k in ("P=0", "P=0.5 variant 1", "P=0.5 variant 2")
            }
        ),
        "C000-3": vd.AllOf(
            {
                k: identity if k == "P=0" else band(f"sigma_x^2(v1) / sigma_x^2(v2) at {k}", 0.8, 1.25)
                for k in ratio_parts
            }
        ),
        "C000-4": vd.Ordering("variant 1 CPU time per step", "variant 2 CPU time per step", ">", "ratio"),
        "C000-5": vd.AllOf(
            {
                **{
                    f"P={p:g}": band(f"sigma_x^2 / sigma_x^2* at P={p:g}", None, 1.3)
                    for p in contrast_grid
                    if 0 < p <= 0.5
                },
                "P=0.9": band("sigma_x^2 / sigma_x^2* at P=0.9", 2.0, None),
            }
        ),
        "C000-6": band("variance ratio at P = 0.9 (the reading's filter over the potentially achievable)", 20.0, None),
        "C000-7": vd.AllOf(
            {
                "trend": vd.Monotone("sigma_x^2 / sigma_x^2*", "contrast P", "increasing"),
                "measurement vs estimate": vd.Ordering(
                    "single-scan measurement CRLB ratio at P = 0.9", "estimate variance ratio", ">", "difference"
                ),
            }
        ),
        "C000-8": vd.AllOf(
            {
                f"variant {v} at psi_A={psi:g}, P={p:g}": band(
                    f"sigma_x^2(dt) / sigma_x^2(dt/{sizes.dt_factor}) - 1, variant {v}, psi_A={psi:g}, P={p:g}",
                    -0.03,
                    0.03,
                )
                for psi, p in sizes.dt_points
                for v in (1, 2)
            }
        ),
        "C000-9": vd.AllOf(
            {f"variant {v}": vd.Monotone(f"steady sigma_x^2 of variant {v}", "psi_A", "decreasing") for v in (1, 2)}
        ),
        "C000-10": vd.NotCheckable("no experimental data or conditions are given in the paper"),
    }


RULES = claim_rules()
