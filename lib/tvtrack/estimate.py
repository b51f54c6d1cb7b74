"""The Monte Carlo estimate: a value with its interval, sample size and how the interval was made
(:mod:`tvtrack.montecarlo` makes them; :mod:`tvtrack.verdicts` decides on them)."""

from __future__ import annotations

from dataclasses import asdict, dataclass

import numpy as np

__all__ = ["Estimate"]


@dataclass(frozen=True)
class Estimate:
    """A Monte Carlo estimate with its uncertainty.

    Attributes
    ----------
    value : float
        Point estimate.
    stderr : float
        Standard error of ``value`` (NaN where not defined).
    ci_low, ci_high : float
        Confidence interval at level ``confidence``.
    n : int
        Number of independent samples behind the estimate.
    confidence : float
        Confidence level of the interval, e.g. 0.95.
    method : str
        How the interval was made (e.g. ``"BCa bootstrap (2000 resamples)"``, ``"Clopper-Pearson"``).
    extrapolated : bool
        The value comes from extrapolating a fit beyond the data (e.g. a logistic tail): it is shown
        but never decides a verdict (:func:`tvtrack.verdicts.is_undecided`).
    sampling_low, sampling_high : float
        Where the interval adds a resolution allowance to its sampling error (a threshold read off a grid known to
        half a grid step, a time known to half a frame): the interval of the sampling error alone (NaN, the
        default, where there is no allowance). Pooling replicates shrinks the sampling error, not the allowance
        (:func:`tvtrack.pooling.pool`).
    signed : Estimate or None
        Where the estimate is a ratio's fold distance from ``fold_reference`` either way
        (:func:`tvtrack.measured.fold_about`): the signed ratio it was folded from (None, the default, elsewhere).
        Replicates pool their signed ratios and fold the pool: folding first would count each replicate's scatter
        about the reference as distance from it.
    fold_reference : float
        The ratio of no change a fold distance is measured from (NaN where ``signed`` is None).
    """

    value: float
    stderr: float
    ci_low: float
    ci_high: float
    n: int
    confidence: float = 0.95
    method: str = ""
    extrapolated: bool = False
    sampling_low: float = float("nan")
    sampling_high: float = float("nan")
    signed: Estimate | None = None
    fold_reference: float = float("nan")

    @property
    def has_allowance(self) -> bool:
        """Whether the interval holds a resolution allowance beside its sampling error (``sampling_low`` and
        ``sampling_high`` given)."""
        return bool(np.isfinite(self.sampling_low) and np.isfinite(self.sampling_high))

    def to_dict(self) -> dict:
        d = {k: (float(v) if isinstance(v, (float, np.floating)) else v) for k, v in asdict(self).items()}
        if not self.has_allowance:  # the sampling interval is written only where there is an allowance
            del d["sampling_low"], d["sampling_high"]
        if self.signed is None:  # the signed ratio is written only where the estimate is its fold distance
            del d["signed"], d["fold_reference"]
        else:
            d["signed"] = self.signed.to_dict()
        return d

    @classmethod
    def exact(cls, value: float, method: str = "exact") -> "Estimate":
        """A number with no Monte Carlo uncertainty (a deterministic computation)."""
        v = float(value)
        return cls(v, 0.0, v, v, 1, 0.95, method)

    def _repr_markdown_(self) -> str:
        return f"{self:.4g}" + (f" ({self.method})" if self.method else "")

    def __format__(self, spec: str) -> str:
        spec = spec or ".3g"
        return (
            f"{self.value:{spec}} [{self.ci_low:{spec}}, {self.ci_high:{spec}}] ({self.confidence:.0%} CI, n={self.n})"
        )
