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
    """

    value: float
    stderr: float
    ci_low: float
    ci_high: float
    n: int
    confidence: float = 0.95
    method: str = ""
    extrapolated: bool = False

    def to_dict(self) -> dict:
        return {k: (float(v) if isinstance(v, (float, np.floating)) else v) for k, v in asdict(self).items()}

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
