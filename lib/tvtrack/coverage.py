"""The measured coverage of the interval helpers, and reading it back from an interval.

Each helper of :mod:`tvtrack.montecarlo` states in its ``method`` the coverage its 95 % interval
reached by simulation at the sample size (:data:`COVERAGE`, re-measured by ``tests/test_intervals.py``);
a rule reads that statement (:func:`stated_coverage`, :func:`coverage_reached`) and may widen an interval
that falls short to its nominal level (:func:`widen_to_nominal`). Re-exported by :mod:`tvtrack.montecarlo`.
"""

from __future__ import annotations

import re
from dataclasses import replace

import numpy as np
import scipy  # scipy.stats is imported at its first use (scipy loads submodules lazily)

from .estimate import Estimate

__all__ = [
    "COVERAGE",
    "COVERAGE_FLOOR",
    "coverage_at",
    "coverage_note",
    "stated_coverage",
    "coverage_reached",
    "widen_to_nominal",
]

#: Coverage of the 95 % intervals measured by simulation (2000 experiments per cell, re-measured by
#: ``tests/test_intervals.py``, which fails if a value here drifts): helper -> {n: (skewed, heavy)}.
#: *skewed*: the worst of light to moderately skewed samples (mean of 20 squared normals,
#: exponential, log-normal sigma 0.5; for ratios paired paths whose scale is log-normal sigma 0.5 and
#: a common exponential; for the Student-t mean also normal samples); *heavy*: the worst of heavy tails
#: (log-normal sigma 1, Student t3, means of 20 squared Student-t(3) errors, paths whose scale is
#: log-normal sigma 1). Between tabulated sizes the next smaller size counts; below the smallest the
#: coverage is unmeasured (stated as such, and :func:`coverage_reached` is False). Keys (helpers of
#: :mod:`tvtrack.montecarlo`): ``mean_square`` (``mean_square_ci``, ``rms_ci``: bootstrap-t), ``ratio``
#: (``ratio_ci``: expanded percentile), ``mean t`` (``mean_ci``, ``paired_difference``), ``mean bootstrap-t``.
COVERAGE = {
    "mean_square": {
        5: (0.936, 0.855),
        10: (0.937, 0.839),
        15: (0.936, 0.852),
        30: (0.944, 0.858),
        48: (0.953, 0.837),
        100: (0.936, 0.860),
    },
    "ratio": {
        5: (0.916, 0.914),
        10: (0.941, 0.923),
        15: (0.940, 0.927),
        30: (0.948, 0.927),
        48: (0.937, 0.922),
        100: (0.938, 0.921),
    },
    "mean t": {
        5: (0.882, 0.815),
        10: (0.904, 0.831),
        15: (0.913, 0.842),
        30: (0.924, 0.880),
        48: (0.946, 0.893),
        100: (0.935, 0.909),
    },
    "mean bootstrap-t": {
        5: (0.936, 0.898),
        10: (0.937, 0.896),
        15: (0.936, 0.900),
        30: (0.944, 0.923),
        48: (0.948, 0.926),
        100: (0.936, 0.924),
    },
}
#: A helper whose measured coverage at the sample size falls below this says so (:func:`coverage_reached`).
COVERAGE_FLOOR = 0.93


def coverage_at(helper: str, n: int) -> tuple[float, float]:
    """The measured coverage ``(skewed, heavy)`` of ``helper``'s 95 % interval at ``n`` samples
    (:data:`COVERAGE`, the next smaller tabulated size); NaN below the smallest size measured."""
    table = COVERAGE[helper]
    below = [m for m in sorted(table) if m <= n]
    return table[below[-1]] if below else (float("nan"), float("nan"))


def coverage_note(helper: str, n: int) -> str:
    """The words an interval's ``method`` carries about its measured coverage (read back by
    :func:`stated_coverage`).

    Parameters
    ----------
    helper : str
        A key of :data:`COVERAGE` (the interval helper, e.g. ``"mean t"``).
    n : int
        The sample size (trials or clusters).

    Returns
    -------
    str
        ``"coverage 0.944 at n = 30 (skewed samples; heavy tails 0.923)"``, or ``"coverage unmeasured at n = ..."``
        below the smallest size measured.
    """
    skewed, heavy = coverage_at(helper, n)
    if np.isnan(skewed):
        return f"coverage unmeasured at n = {n} (below n = {min(COVERAGE[helper])}, the smallest size measured)"
    return f"coverage {skewed:.3f} at n = {n} (skewed samples; heavy tails {heavy:.3f})"


def stated_coverage(estimate) -> float:
    """The coverage an interval's ``method`` states ("coverage 0.91 at n = 15"; NaN for "coverage
    unmeasured"), or its nominal ``confidence`` where the method states none (exact and large-sample
    intervals, and intervals :func:`widen_to_nominal` has widened: "measured coverage ...; widened")."""
    method = getattr(estimate, "method", "") or ""
    if "coverage unmeasured" in method:
        return float("nan")
    if re.search(r"; widened x\d+\.\d+ to ", method):  # widened to its nominal coverage (whatever the digits said)
        return float(estimate.confidence)
    m = re.search(r"(?<!measured )coverage (\d\.\d+)", method)
    return float(m.group(1)) if m else float(estimate.confidence)


def coverage_reached(estimate, floor: float = COVERAGE_FLOOR) -> bool:
    """Whether the interval covers about its nominal level at its sample size (for skewed samples).

    A rule reads this flag: where it is False the interval is narrower than it claims, so the part
    should be widened or left undecided. Heavy tails are not covered by the flag (no interval of a
    mean reaches 95 % on them at small n; see :func:`robust_summary`)."""
    return stated_coverage(estimate) >= floor - 1e-12


def widen_to_nominal(estimate: Estimate, difference: bool = False) -> Estimate:
    """The interval widened so that its measured coverage becomes its nominal one (a rule's way to
    decide on a helper whose :func:`stated_coverage` falls short, instead of refusing).

    Each side is stretched about the value by ``z_{(1+confidence)/2} / z_{(1+stated)/2}`` (on the log
    scale when the interval is positive, where the skewed helpers' intervals are closer to symmetric; on
    the linear scale for a ``difference``, whose interval may reach 0 and beyond); of an interval that holds a
    resolution allowance beside its sampling interval, the sampling interval is stretched (the helper's stated
    coverage is its own) and each side's allowance added back as it was;
    an interval that covers already is returned unchanged. A calibration by the measured coverage on
    skewed samples (:data:`COVERAGE`), not an exact interval: heavy tails stay below nominal.
    """
    stated = stated_coverage(estimate)
    if np.isnan(stated) or stated >= estimate.confidence or not np.isfinite([estimate.ci_low, estimate.ci_high]).all():
        return estimate  # unmeasured coverage cannot be calibrated: the flag stays False
    # scipy.stats.norm.ppf's own function (special.ndtri), without the per-call checks: the same numbers
    f = scipy.special.ndtri(0.5 + estimate.confidence / 2) / scipy.special.ndtri(0.5 + stated / 2)
    v = estimate.value
    log = estimate.ci_low > 0 and v > 0 and not difference

    def stretch(x: float) -> float:
        return float(v * (x / v) ** f if log else v + f * (x - v))

    ends = {"ci_low": stretch(estimate.ci_low), "ci_high": stretch(estimate.ci_high)}
    if estimate.has_allowance:  # the helper's coverage is its sampling interval's: that is widened, each side's
        lo, hi = stretch(estimate.sampling_low), stretch(estimate.sampling_high)  # resolution allowance kept
        ends = {"ci_low": lo - (estimate.sampling_low - estimate.ci_low), "sampling_low": lo}
        ends |= {"ci_high": hi + (estimate.ci_high - estimate.sampling_high), "sampling_high": hi}
    return replace(
        estimate,
        **ends,
        method=f"{estimate.method}; widened x{f:.3f} to {estimate.confidence:.0%}".replace(
            f"coverage {stated:.3f}", f"measured coverage {stated:.3f}"
        ),
    )
