"""The claim rules of paper 000 (Martyshevsky 1995), one rule per reading where a reading changes the quantity.

A register value that changes *what* a claim measures (not only the conditions it is measured under) brings its
own rule. In paper 000 that is the convergence criterion of C000-1: the default reading measures the share of runs
not in lock for good by ``acquire_by_T`` (at most 0.1), the card's reading measures the ensemble sigma_x^2 over the
scan ending at ``acquire_by_T`` over its steady value, a ratio. The card says "within 10 % of its steady state":
"within" is two-sided, so that reading is judged by ``ratio in [0.9, 1.1]`` (an ensemble variance still 10 % below
its steady value after 5 T has not converged either).

The measurement tags a value measured under a non-default reading (:class:`ReadingEstimate`); :class:`ByReading`
judges it by that reading's rule, an untagged value by the default reading's rule (the replicates, pooled, are
always at the default).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Mapping

from ...montecarlo import Estimate
from ...verdicts import AllOf, InBand, Judgement, Monotone, NotCheckable, Ordering, Rule

__all__ = [
    "ReadingEstimate",
    "ByReading",
    "tagged",
    "claim_rules",
    "cost_rule",
    "CONVERGENCE_READINGS",
    "ENSEMBLE_MEAN",
    "reading_of",
]

#: The two readings of "converge fairly quickly" (register entry "convergence criterion").
LATE_SHARE, ENSEMBLE_MEAN = "90 % of runs acquired", "ensemble mean within 10 %"
CONVERGENCE_READINGS = (LATE_SHARE, ENSEMBLE_MEAN)


@dataclass(frozen=True)
class ReadingEstimate(Estimate):
    """An :class:`~tvtrack.montecarlo.Estimate` measured under a named reading of the paper (``reading``)."""

    reading: str = ""


def tagged(e: Estimate, reading: str) -> ReadingEstimate:
    """``e`` carrying the reading it was measured under."""
    return ReadingEstimate(e.value, e.stderr, e.ci_low, e.ci_high, e.n, e.confidence, e.method, e.extrapolated, reading)


def reading_of(measured: Any, default: str) -> str:
    """The reading a measured value was measured under (``default`` when untagged)."""
    return getattr(measured, "reading", "") or default


@dataclass(frozen=True)
class ByReading(Rule):
    """One rule per reading of the paper: a tagged measured value (:class:`ReadingEstimate`) is judged by its
    reading's rule, an untagged one by ``rules[default]``."""

    rules: Mapping[str, Rule] = field(default_factory=dict)
    default: str = ""
    kind = "by_reading"

    def __post_init__(self):
        if self.default not in self.rules:
            raise ValueError(f"ByReading: default {self.default!r} is not one of {list(self.rules)}")

    def text(self) -> str:
        return "; ".join(
            f"under the reading '{name}'{' (default)' if name == self.default else ''}: {rule.text()}"
            for name, rule in self.rules.items()
        )

    def params(self) -> dict:
        return {"default": self.default, "rules": {k: r.to_dict() for k, r in self.rules.items()}}

    def rule_for(self, reading: str) -> Rule:
        return self.rules[reading]

    def judge(self, measured) -> Judgement:
        reading = reading_of(measured, self.default)
        if reading not in self.rules:
            raise ValueError(f"ByReading: measured under the reading {reading!r}, not one of {list(self.rules)}")
        return self.rules[reading].judge(measured)


def _convergence(variant: int, acquire_by: float) -> ByReading:
    return ByReading(
        {
            LATE_SHARE: InBand(
                f"share of runs (variant {variant}) not yet in lock for good {acquire_by:g} scans after the start",
                high=0.1,
                unit="of the runs",
            ),
            ENSEMBLE_MEAN: InBand(
                f"error variance over the scan ending at {acquire_by:g} T / steady error variance (variant {variant})",
                0.9,
                1.1,
                unit="(ratio)",
            ),
        },
        LATE_SHARE,
    )


def claim_rules(sizes) -> dict:
    """The claim rules of C000-1, -2, -3, -5, -6, -7, -8, -9 for a run of ``sizes`` (:class:`.study.Sizes`: its
    grids name the parts). C000-4 has its own measurement and rule (:func:`cost_rule`); C000-10 is not checkable."""
    band = InBand
    identity = NotCheckable("at P = 0 both variants are the same filter: the ratio is 1 by construction")
    grid_p, grid_psi = sizes.contrast_grid, sizes.psi_grid
    return {
        "C000-1": AllOf({f"variant {v}": _convergence(v, sizes.acquire_by_T) for v in (1, 2)}),
        "C000-2": AllOf(
            {
                k: band(f"steady RMS coordinate error / micro-raster size at psi_A = 20, {k}", 0.01, 0.03, "(ratio)")
                for k in ("P=0", "P=0.5 variant 1", "P=0.5 variant 2")
            }
        ),
        "C000-3": AllOf(
            {
                k: identity
                if k == "P=0"
                else band(f"error variance of variant 1 / of variant 2 at {k}", 0.8, 1.25, "(ratio)")
                for k in [f"P={p:g}" for p in grid_p] + [f"psi_A={p:g}" for p in grid_psi]
            }
        ),
        "C000-5": AllOf(
            {
                **{
                    f"P={p:g}": band(
                        f"error variance / stationary-noise error variance sigma_x^2* at P={p:g}",
                        high=1.3,
                        unit="(ratio)",
                    )
                    for p in grid_p
                    if 0 < p <= 0.5
                },
                "P=0.9": band(
                    "error variance / stationary-noise error variance sigma_x^2* at P=0.9", 2.0, unit="(ratio)"
                ),
            }
        ),
        "C000-6": band(
            "error variance at P = 0.9 of the reading's filter / the reading's potentially achievable variance",
            20.0,
            unit="(ratio)",
        ),
        "C000-7": AllOf(
            {
                "trend": Monotone("error variance / stationary-noise error variance sigma_x^2*", "contrast P"),
                "measurement vs estimate": Ordering(
                    "single-scan measurement CRLB ratio (P = 0.9 over P = 0)",
                    "estimate variance ratio sigma_x^2 / sigma_x^2* at P = 0.9",
                    ">",
                    "difference",
                ),
            }
        ),
        "C000-8": AllOf(
            {
                f"variant {v} at psi_A={psi:g}, P={p:g}": band(
                    f"relative change of the steady error variance from dt to dt/{sizes.dt_factor} (variant {v}, "
                    f"psi_A={psi:g}, P={p:g})",
                    -0.03,
                    0.03,
                    "(fraction)",
                )
                for psi, p in sizes.dt_points
                for v in (1, 2)
            }
        ),
        "C000-9": AllOf(
            {
                f"variant {v}": Monotone(f"steady error variance of variant {v} (T^2)", "psi_A", "decreasing")
                for v in (1, 2)
            }
        ),
    }


def cost_rule() -> Rule:
    """C000-4: variant 1 needs more arithmetic per filter step than variant 2 (the ratio of operation counts, or of
    CPU time under the register's other reading)."""
    return Ordering("variant 1 arithmetic per filter step", "variant 2 arithmetic per filter step", ">", "ratio")
