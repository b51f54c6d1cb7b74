"""The claims of paper 000 (Martyshevsky 1995) and the rules that decide them, one rule per reading where a reading
changes what a claim measures.

``CLAIMS`` holds what the paper says (statement and the paper's value); :func:`claim_rules` builds the rule of each
claim from the run's sizes (the grids and the acquisition time the notebook's parameters set), and ``RULES`` is that
at the default sizes. The notebook passes its own :class:`~.study.Sizes`.

C000-1's two readings of "converge fairly quickly" (register entry "convergence criterion") measure different
quantities, so each brings its rule (:class:`tvtrack.verdicts.ByReading`): the default reading measures the share of
runs not in lock for good by ``acquire_by_T`` (at most 0.1); the other reading measures the ensemble sigma_x^2 over
the scan ending at ``acquire_by_T`` over its steady value, a ratio. Its acceptance band, set here, is "within 10 %
of its steady state": "within" is two-sided, so that reading is judged by ``ratio in [0.9, 1.1]`` (an ensemble
variance still 10 % below its steady value has not converged either).

C000-5's "does not substantially affect the accuracy" (Conclusions: «не оказывает существенного влияния на
точность») is two-sided too: an effect is substantial either way, so a ratio to sigma_x^2* below ``1 / 1.3`` is as
substantial as one above ``1.3`` (:data:`NOT_SUBSTANTIAL`, symmetric on the ratio's log scale).

C000-3 judges no comparison where it is true by construction: at P = 0 with c_s = N0 P/(1-P) (this project's
reading of eq. (6)) variant 1's signal-noise term vanishes, the variants are one filter and the ratio is 1. There its
P = 0 part is not checkable, and at the register's "contrast" = 0 (Fig. 2 read at P = 0) its Fig. 2 parts are not
measured (:class:`tvtrack.verdicts.ByReading` on "contrast": that value's rule has the Fig. 3 parts only). Under
eq. (6) as printed (register "signal-noise scale" = c_s = A) variant 1 still models a signal noise of intensity A S at
P = 0, which the data do not hold: the variants are two filters, so the P = 0 part and, at "contrast" = 0, the Fig. 2
parts are measured and judged like every other (a second :class:`~tvtrack.verdicts.ByReading`, on "signal-noise
scale", inside each contrast's rule). The Fig. 2 point psi_A = 20 at the default contrast P = 0.5 is Fig. 3's P = 0.5
point at the default psi_A = 20, one measurement: it is the part "P=0.5" only.

C000-5's two halves are strict («при контрастах ТСО P < 0,5 ... Однако при контрасте P > 0,5»): the boundary P = 0.5
is asserted by neither, so no part of its rule is at P = 0.5.

C000-4's "needs more computation" has two readings (register "C000-4 cost measure"). Counted in arithmetic operations
per step, the value is a count of this project's own writing of the paper's equations: the same on every run and
fixed before any run, so that reading is not checkable. The CPU time of the compiled steps is measured, with an
interval, and judged ("variant 1's work per step > variant 2's").
"""

from __future__ import annotations

from ... import verdicts as vd
from ...verdicts import AllOf, InBand, Monotone, NotCheckable, Ordering, Rule
from .readings import AT_09, C2_EVERY, CS_LITERAL, ENSEMBLE_MEAN, EVERY_ABOVE, LATE_SHARE
from .register import REGISTER
from .sizes import Sizes

__all__ = ["CLAIMS", "RULES", "NOT_SUBSTANTIAL", "COST_READINGS", "claim_rules", "cost_rule", "fig2_points"]

#: C000-5's "not substantially" as a band on the ratio to sigma_x^2*: within a factor 1.3 either way.
NOT_SUBSTANTIAL = (1 / 1.3, 1.3)
#: The register defaults of Fig. 2's contrast and Fig. 3's psi_A (register entries "contrast" and "psi_A"): C000-3's
#: Fig. 2 point at psi_A = 20 is its Fig. 3 point at P = 0.5 there, one measurement.
CONTRAST_DEFAULT, PSI_DEFAULT = REGISTER["contrast"].default, REGISTER["psi_A"].default


def _claim(statement: str, paper_value: str) -> dict[str, str]:
    return {"statement": statement, "paper_value": paper_value}


CLAIMS = {
    "C000-1": _claim("Both algorithms converge fairly quickly (Figs. 1-3).", "fairly quickly (no number)"),
    "C000-2": _claim("At psi_A = 20 the coordinate error is 2 % of the micro-raster size.", "2 %"),
    "C000-3": _claim("The two algorithms give approximately the same potential accuracy.", "approximately equal"),
    "C000-4": _claim("Variant 1 is two-dimensional and needs more computation than variant 2.", "qualitative"),
    "C000-5": _claim(
        "Below P = 0.5 accounting for the non-stationary noise barely affects accuracy; above 0.5 the noise "
        "largely determines it.",
        "threshold near P = 0.5",
    ),
    "C000-6": _claim("At P = 0.9 the estimate variance is over 20 times the potentially achievable one.", "> 20"),
    "C000-7": _claim(
        "sigma_x^2 / sigma_x^2* grows with P; the measurement variance grows faster than the estimate variance.",
        "monotone growth",
    ),
    "C000-8": _claim("A sampling step dt = 0.05 T keeps discretisation errors within 3 %.", "<= 3 %"),
    "C000-9": _claim("sigma_x^2 decreases as psi_A grows (Fig. 2).", "qualitative"),
    "C000-10": _claim(
        "Experiment agrees with the model (Fig. 3, triangles); a practical test confirmed the algorithms.",
        "qualitative",
    ),
}


def _convergence(acquire_by: float) -> vd.ByReading:
    """C000-1's rule: per reading of "converge fairly quickly", an AllOf over both variants."""
    share = AllOf(
        {
            f"variant {v}": InBand(
                f"share of runs (variant {v}) not yet in lock for good {acquire_by:g} scans after the start",
                high=0.1,
                unit="of the runs",
            )
            for v in (1, 2)
        }
    )
    ratio = AllOf(
        {
            f"variant {v}": InBand(
                f"error variance over the scan ending at {acquire_by:g} T / steady error variance (variant {v})",
                0.9,
                1.1,
                unit="(ratio)",
            )
            for v in (1, 2)
        }
    )
    return vd.ByReading("convergence criterion", {LATE_SHARE: share, ENSEMBLE_MEAN: ratio}, share)


def _contrast_threshold(grid_p) -> vd.ByReading:
    """C000-5's rule, per reading of "for P > 0.5 it substantially determines": within a factor 1.3 either way
    (:data:`NOT_SUBSTANTIAL`: "does not substantially affect" is two-sided) at every Fig. 3 contrast in (0, 0.5); at
    least 2 at P = 0.9 (the default), or at every Fig. 3 contrast above 0.5 (the adversarial reading "at every
    P > 0.5": the paper's threshold is P = 0.5, not 0.9). Both halves are strict, so P = 0.5 is in neither."""

    def ratio(p):  # the reading "C000-5 comparison" puts the filter ignoring the noise over variant 2 instead
        return f"error variance with the signal noise / with background noise only (sigma_x^2*) at P = {p:g}"

    low, high = NOT_SUBSTANTIAL
    below = {f"P={p:g}": InBand(ratio(p), low, high, unit="(ratio)") for p in grid_p if 0 < p < 0.5}

    def rule(above):
        return AllOf({**below, **{f"P={p:g}": InBand(ratio(p), 2.0, unit="(ratio)") for p in above}})

    default = rule([0.9])
    every = rule([p for p in grid_p if p > 0.5])
    return vd.ByReading("substantially determines", {AT_09: default, EVERY_ABOVE: every}, default)


def _two_percent(grid_p) -> vd.ByReading:
    """C000-2's rule, per reading of the contrasts at which "at psi_A = 20 the error was 2 %" holds: the RMS error
    within [1 %, 3 %] of the micro-raster at P = 0 and at P = 0.5 for both variants (this project's default), or
    also for both variants at every other Fig. 3 contrast (the adversarial reading "C000-2 contrasts" = every Fig. 3
    contrast)."""

    def part(k):
        return InBand(f"steady RMS coordinate error / micro-raster size at psi_A = 20, {k}", 0.01, 0.03, "(ratio)")

    named = ["P=0", "P=0.5 variant 1", "P=0.5 variant 2"]
    every = named + [f"P={p:g} variant {v}" for p in grid_p if p not in (0, 0.5) for v in (1, 2)]
    default = AllOf({k: part(k) for k in named})
    return vd.ByReading("C000-2 contrasts", {C2_EVERY: AllOf({k: part(k) for k in every})}, default)


def fig2_points(grid_p, grid_psi) -> list[float]:
    """The psi_A of C000-3's Fig. 2 parts: the psi grid without the default psi_A where the contrast grid holds the
    default contrast (that point is Fig. 3's, the part "P=0.5")."""
    return [p for p in grid_psi if not (p == PSI_DEFAULT and CONTRAST_DEFAULT in grid_p)]


class _ByReadings(vd.ByReading):
    """A :class:`~tvtrack.verdicts.ByReading` whose rules may be ByReadings on other entries (C000-3: "contrast",
    then "signal-noise scale"): the rule in force at a configuration is followed down to the one that judges."""

    def for_config(self, config):
        return vd.for_config(self.for_value(config.get(self.entry)), config)


def _same_accuracy(grid_p, grid_psi) -> vd.ByReading:
    """C000-3's rule: variant 1 / variant 2 within [0.8, 1.25] at every Fig. 3 contrast and at every Fig. 2 SNR
    (:func:`fig2_points`), by "contrast" and then by "signal-noise scale": with c_s = N0 P/(1-P) (the default) the
    P = 0 part is not checkable and at the register's contrast = 0 the Fig. 2 parts are left out (the same filter
    twice); with c_s = A (eq. (6) as printed) variant 1 models a signal noise at P = 0 too, so every part is judged."""
    identity = NotCheckable(
        "at P = 0 both variants are the same filter (c_s = N0 P/(1-P) = 0: variant 1's signal-noise state is not "
        "observed): the ratio is 1 by construction, at every psi_A"
    )

    def part(k):
        return InBand(f"error variance of variant 1 / of variant 2 at {k}", 0.8, 1.25, "(ratio)")

    fig3 = {f"P={p:g}": part(f"P={p:g}") for p in grid_p}
    same = {k: identity if k == "P=0" else r for k, r in fig3.items()}
    fig2 = {f"psi_A={p:g}": part(f"psi_A={p:g}") for p in fig2_points(grid_p, grid_psi)}
    literal = AllOf({**fig3, **fig2})  # eq. (6) as printed: two filters at every contrast

    def by_scale(consistent: Rule) -> vd.ByReading:
        return _ByReadings("signal-noise scale", {CS_LITERAL: literal}, consistent)

    return _ByReadings("contrast", {0.0: by_scale(AllOf(same))}, by_scale(AllOf({**same, **fig2})))


def claim_rules(sizes: Sizes | None = None) -> dict[str, Rule]:
    """The claim rules of C000-1, -2, -3, -5, -6, -7, -8, -9 for a run of ``sizes`` (:class:`.study.Sizes`: its
    grids name the parts; the defaults if None). C000-4 has its own measurement (:func:`.study.measure_cost`)."""
    sizes = Sizes() if sizes is None else sizes
    band = InBand
    grid_p, grid_psi = sizes.contrast_grid, sizes.psi_grid
    return {
        "C000-1": _convergence(sizes.acquire_by_T),
        "C000-2": _two_percent(grid_p),
        "C000-3": _same_accuracy(grid_p, grid_psi),
        "C000-5": _contrast_threshold(grid_p),
        "C000-6": band(
            "error variance of the filter at P = 0.9 / the potentially achievable variance",
            20.0,
            unit="(ratio)",
        ),
        "C000-7": AllOf(
            {
                "trend": Monotone(
                    "error variance / stationary-noise error variance sigma_x^2*", "contrast P", unit="(ratio)"
                ),
                "measurement vs estimate": Ordering(
                    "single-scan measurement CRLB ratio (P = 0.9 over P = 0)",
                    "estimate variance ratio sigma_x^2 / sigma_x^2* at P = 0.9",
                    ">",
                    "difference",
                    unit="(ratio)",
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
                f"variant {v}": Monotone(f"steady error variance of variant {v}", "psi_A", "decreasing", unit="T^2")
                for v in (1, 2)
            }
        ),
        "C000-4": cost_rule(),
        "C000-10": NotCheckable("no experimental data or conditions are given in the paper"),
    }


#: The readings of C000-4's "needs more computation" (register entry "C000-4 cost measure").
COST_READINGS = ("operation count", "CPU time")


def cost_rule() -> Rule:
    """C000-4, per reading of "needs more computation": the CPU time per step of the compiled filters, variant 1
    over variant 2, above 1 (measured, with the interval of repeated paired timings); the operation count per step
    is not checkable (the notebook shows it)."""
    counted = NotCheckable(
        "counted in arithmetic operations per step, the work is a count of this project's own writing of the "
        "paper's equations (variant 1's two-state covariance against variant 2's one): fixed before any run and "
        "the same on every run, so no run can find otherwise"
    )
    timed = Ordering("variant 1's work per step", "variant 2's", ">", "ratio", unit="(ratio)")
    return vd.ByReading("C000-4 cost measure", {COST_READINGS[1]: timed}, counted)


RULES = claim_rules()
