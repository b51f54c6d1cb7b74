"""Per-test false-alarm rate of a fixed threshold on the statistic S of eq. (14), from its closed form where one
exists (derived here; Fisenko et al. 2008), so that C001-3 never rests on a zero-events bound.

S_t is linear in the measurements: ``S_t = sum_j H[j, t] z_j`` with ``H`` the TRACK2 filter's impulse response
passed through the two windows (:func:`statistic_impulse_response`). Then, for a threshold ``c_t``:

* white Gaussian errors: ``S_t ~ N(0, sigma² sum_j H[j, t]²)``, the rate is ``2 Phi(-c_t / sd_t)`` (exact);
* AR(1) Gaussian errors (lag-one correlation 0.5, stationary): ``sd_t² = sigma² H_t' R H_t``, ``R_ij = 0.5^|i-j|``
  (exact);
* Student-t errors (3 dof, a scale mixture of normals): given each error's chi-square scale S_t is Gaussian, so
  the rate is the mean over drawn scales of ``2 Phi(-c_t / sd_t(scales))`` (conditional Monte Carlo: never zero
  events, its interval from the independent runs);
* quantised errors (a Gaussian of variance sigma² - 1/12 rounded to whole elements): the rounding moves S_t by at
  most ``b_t = sum_j |H[j, t]| / 2``, so the rate lies between ``2 Phi(-(c_t + b_t)/sd_t)`` and
  ``2 Phi(-(c_t - b_t)/sd_t)`` (closed-form bounds; the Monte Carlo estimate is clipped into them).
"""

from __future__ import annotations

import numpy as np
from scipy import stats

from ...filters.alphabeta import scheduled_filter
from ...estimate import Estimate
from ...montecarlo import mean_ci
from .maneuver_detector import window_statistic

__all__ = ["statistic_impulse_response", "closed_form_rate", "closed_form_check", "CLOSED_FORM_MODELS"]

#: Error models whose per-test rate has a closed form (exact), conditional form or closed-form bounds.
CLOSED_FORM_MODELS = {
    "white Gaussian": "exact",
    "AR(1), rho = 0.5": "exact",
    "Student t, 3 dof": "conditional",
    "quantised": "bounds",
}


def statistic_impulse_response(gains, n: int) -> np.ndarray:
    """``H[j, t] = dS_t / dz_j`` of the TRACK2 filter with gain sequence ``gains`` (T, 2) started at frame 0.

    Returns
    -------
    ndarray, shape (T, T)
        Rows: the measurement frame j; columns: the window end t (NaN for ``t < 2n - 1``).
    """
    G = np.asarray(gains, float)
    T = G.shape[0]
    v = scheduled_filter(np.eye(T), G)[..., 1]  # (impulse j, frame t): velocity response
    return window_statistic(v, n)


def _rates(c, sd, mean=0.0) -> np.ndarray:
    """``P(|S| > c)`` for ``S ~ N(mean, sd²)``: ``Phi((mean - c)/sd) + Phi((-mean - c)/sd)`` (``2 Phi(-c/sd)`` at
    mean 0)."""
    c, sd, mean = np.asarray(c, float), np.asarray(sd, float), np.asarray(mean, float)
    return stats.norm.sf((c - mean) / sd) + stats.norm.sf((c + mean) / sd)


def _exact(value: float, n: int) -> Estimate:
    """A closed-form number: its interval is the point (method ``"exact"``, which the verdicts read as such)."""
    return Estimate(value, 0.0, value, value, n, 0.95, "exact")


def closed_form_rate(
    H, threshold, armed, model: str, sigma_eps: float = 1.0, rng=None, runs: int = 2000, mc=None, mean=None
):
    """Per-test rate of ``|S_t| > threshold_t`` averaged over the armed frames, from the closed form.

    Under an alternative the statistic's mean ``E[S_t] = sum_j H[j, t] x_j`` (``x`` the noise-free measurements)
    shifts the Gaussian part: ``P(|S_t| > c_t) = Phi((mu_t - c_t)/sd_t) + Phi((-mu_t - c_t)/sd_t)``, still exact
    for the Gaussian models (the rate of a rare alarm from its distribution, never from a handful of counted
    alarms), conditional for Student t and bounded for quantised errors (``|S_t - mu_t - G_t| <= b_t``).

    Parameters
    ----------
    H : ndarray, shape (T, T)            :func:`statistic_impulse_response`
    threshold : array_like, shape (T,)   c_t, elements/frame
    armed : array_like of bool, shape (T,)
    model : str                          a key of :data:`CLOSED_FORM_MODELS`
    sigma_eps : float                    measurement-error RMS, elements
    rng : numpy.random.Generator         the chi-square scales of the Student-t model
    runs : int                           independent runs of scales (Student t)
    mc : Estimate, optional              the Monte Carlo rate of the same threshold (quantised: clipped into the
                                         closed-form bounds; required for that model)
    mean : array_like, shape (T,) or (k, T), optional
                                         ``E[S_t]`` under the alternative, elements/frame (k channels: the rate is
                                         averaged over channels and armed frames); default 0 (the null)

    Returns
    -------
    Estimate
        Exact (method ``"exact"``, zero-width interval) for the Gaussian models and where the bounds coincide; conditional Monte Carlo for Student t; for quantised
        errors the Monte Carlo interval intersected with the closed-form bounds.
    """
    armed = np.asarray(armed, bool)
    Ha = np.asarray(H, float)[:, armed]
    c = np.broadcast_to(np.asarray(threshold, float), armed.shape)[armed]
    mu = np.zeros((1, int(armed.sum()))) if mean is None else np.atleast_2d(np.asarray(mean, float))[:, armed]
    s2 = sigma_eps**2
    if model == "white Gaussian":
        r = _rates(c, np.sqrt(s2 * np.sum(Ha**2, axis=0)), mu)
        return _exact(float(r.mean()), int(armed.sum()))
    if model == "AR(1), rho = 0.5":
        lag = np.abs(np.subtract.outer(np.arange(Ha.shape[0]), np.arange(Ha.shape[0])))
        var = s2 * np.einsum("jt,jk,kt->t", Ha, 0.5**lag, Ha)
        return _exact(float(_rates(c, np.sqrt(var), mu).mean()), int(armed.sum()))
    if model == "Student t, 3 dof":
        if rng is None:
            raise ValueError("the Student-t model needs rng (its chi-square scales are drawn)")
        inv_scale = 1.0 / rng.chisquare(3, (runs, Ha.shape[0]))  # error_j = sigma e_j / sqrt(chi2_j)
        sd = np.sqrt(s2 * inv_scale @ Ha**2)  # (runs, armed frames)
        e = mean_ci(_rates(c, sd[:, None, :], mu[None]).reshape(sd.shape[0], -1).mean(axis=1))
        e = Estimate(e.value, e.stderr, max(e.ci_low, 0.0), e.ci_high, e.n, e.confidence, e.method)
        return Estimate(
            e.value,
            e.stderr,
            e.ci_low,
            e.ci_high,
            e.n,
            e.confidence,
            "conditional Monte Carlo (chi-square scales drawn, Gaussian part exact)",
        )
    if model == "quantised":
        if mc is None:
            raise ValueError("the quantised model needs the Monte Carlo estimate 'mc' (the closed form bounds it)")
        sd = np.sqrt((s2 - 1 / 12) * np.sum(Ha**2, axis=0))
        b = 0.5 * np.sum(np.abs(Ha), axis=0)
        lo = float(_rates(c + b, sd, mu).mean())
        hi = float(_rates(np.maximum(c - b, 0.0), sd, mu).mean())
        low = max(lo, mc.ci_low if np.isfinite(mc.ci_low) else lo)
        high = min(hi, mc.ci_high if np.isfinite(mc.ci_high) else hi)
        if low > high:  # the Monte Carlo interval misses the certain bounds (a 5 % event): keep the bounds
            low, high = lo, hi
        if high - low <= 1e-12 * max(abs(high), 1e-300):  # the bounds pin the rate: a closed-form number
            return _exact(0.5 * (lo + hi), int(armed.sum()))
        value = float(np.clip(mc.value, low, high))
        return Estimate(
            value,
            mc.stderr,
            low,
            high,
            mc.n,
            mc.confidence,
            f"{mc.method}, within the closed-form bounds of rounding [{lo:.3g}, {hi:.3g}]",
        )
    raise ValueError(f"measurement-error model {model!r}; it must be one of {tuple(CLOSED_FORM_MODELS)}")


def closed_form_check(closed: Estimate, mc: Estimate) -> dict:
    """The closed form against the Monte Carlo of the same rate: ``{"closed", "monte_carlo", "z"}`` with ``z`` the
    difference in combined standard errors (NaN where the Monte Carlo saw no event: its bound is then only
    checked to contain the closed form, ``"contains"``)."""
    se = float(np.hypot(mc.stderr if np.isfinite(mc.stderr) else 0.0, closed.stderr))
    z = (closed.value - mc.value) / se if se > 0 else float("nan")
    return {"closed": closed, "monte_carlo": mc, "z": z, "contains": bool(mc.ci_low <= closed.value <= mc.ci_high)}
