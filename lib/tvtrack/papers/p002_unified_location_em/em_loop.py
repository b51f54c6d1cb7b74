"""The iteration of the unified location EM (:func:`.em.unified_location_em`): EM steps, SQUAREM and the stops.

Savanevich (1999) solves the maximum-likelihood equations (3) by the "splitting" iteration of eqs. (9)-(11);
one step here is an E-step (eq. (10): posterior shares and local means, :mod:`.em_steps`) and the closed-form
M-step (11), optionally with a Gaussian prior (MAP-EM) and the weight and PSF-width updates the paper calls
feasible (:class:`EMModel`). :func:`iterate` runs the steps, plain or SQUAREM-accelerated, on every trial still
iterating and records the iterates in an :class:`EMState` until each trial stops (converged, degenerate or at its
cap).

Trials are independent and vectorised: the working set (:class:`~.em_steps.ActiveEntries`) holds the trials still
iterating plus a few that stopped recently; it is rebuilt (entries regrouped) only when fewer than 60 % of it
still iterate.

Units: pixels (centres at integers, window origin at pixel (0, 0); ``x`` = column, ``y`` = row) and frames.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np

from . import _kernels
from .em_steps import PixelEntries, maximisation_step, sigma_update, ActiveEntries

__all__ = ["CALM", "MapPrior", "EMModel", "EMState", "Step", "iterate"]

#: Successive steps whose Aitken estimate of the remaining gain must be below ``tol_loglik`` before a trial stops (one
#: such step can be a lull of EM's rate while two images split); the compiled loop's own (:mod:`._kernels`).
CALM = _kernels.CALM


def _aitken_gap(ll, prev_ll, prev_rise):
    """Aitken estimate of the log-likelihood still to be gained, shape (n,): with the rises ``r_k = L_k - L_{k-1}``
    of two successive steps and their ratio ``a = r_k / r_{k-1}`` (EM's linear rate), the remaining gain is
    ``r_k a / (1 - a)`` (``inf`` until two rises are known or while the rate is not in [0, 1))."""
    rise = ll - prev_ll
    with np.errstate(divide="ignore", invalid="ignore"):
        a = rise / prev_rise
        gap = np.where((a >= 0) & (a < 1), rise * a / (1 - a), np.inf)
    return np.where(np.isfinite(prev_rise) & np.isfinite(rise), np.maximum(gap, 0.0), np.inf)


@dataclass(frozen=True)
class MapPrior:
    """The Gaussian prior of the MAP-EM, centred on the designation.

    Attributes
    ----------
    mean : ndarray, shape (N, Q, 4)
        Prior means ``(x0, y0, Vx, Vy)`` (the designation), px and px/frame.
    a, c : ndarray, shape (N, Q)
        ``sigma^2`` times the prior precisions of the initial position (``sigma^2 / sd_x^2``, dimensionless) and
        of the velocity (``sigma^2 / sd_v^2``, frame^2): they enter the normal equations of (10) as
        ``(A + a) x0 + B V = D_x + a x0_prior`` and ``B x0 + (C + c) V = D_tx + c V_prior``.
    sigma : ndarray, shape (N, Q)
        The (fixed) PSF standard deviations, px.
    """

    mean: np.ndarray
    a: np.ndarray
    c: np.ndarray
    sigma: np.ndarray

    def rows(self, rows) -> tuple:
        """``(mean, a, c)`` of the trials ``rows`` (index array, shape (n,)), as :func:`~.em_steps.maximisation_step` takes
        them."""
        return tuple(x[rows] for x in (self.mean, self.a, self.c))

    def log_density(self, th, rows) -> np.ndarray:
        """Log prior density of the states ``th`` (n, Q, 4) of the trials ``rows`` (n,), up to a constant, shape
        (n,): ``-sum (a (x0 - x0_prior)^2 + c (V - V_prior)^2) / (2 sigma^2)``."""
        mean, a, c = self.rows(rows)
        sg2 = self.sigma[rows] ** 2
        return -0.5 * (
            (a / sg2)[..., None] * (th[..., :2] - mean[..., :2]) ** 2
            + (c / sg2)[..., None] * (th[..., 2:] - mean[..., 2:]) ** 2
        ).sum(axis=(1, 2))


class Step(NamedTuple):
    """One update of the trials of a working set (n of them): a plain EM step or a SQUAREM cycle.

    Attributes
    ----------
    theta : ndarray, shape (n, Q, 4)
        New states, px and px/frame (the old ones where ``bad``).
    p, sigma : ndarray, shape (n, Q)
        New object weights and PSF standard deviations (px).
    p_noise : ndarray, shape (n,)
        New noise weight.
    loglik : ndarray, shape (n,)
        Log-likelihood (log posterior with a prior) at the states the update started from, nats.
    bad : ndarray of bool, shape (n,)
        The M-step was singular (no weight, or all weight in one frame).
    delta : ndarray, shape (n,)
        The largest change of the update: positions in px, velocities times the frame span, and ``sigma`` (px) and
        ``p`` when they are estimated.
    taken : int
        EM steps (E+M evaluations) the update took.
    """

    theta: np.ndarray
    p: np.ndarray
    p_noise: np.ndarray
    sigma: np.ndarray
    loglik: np.ndarray
    bad: np.ndarray
    delta: np.ndarray
    taken: int


@dataclass(frozen=True)
class EMModel:
    """What one EM step needs besides the iterate: the data, the model's options and the steps to use.

    Attributes
    ----------
    entries : PixelEntries
        The non-zero pixels of every trial.
    times : ndarray, shape (T,)
        Frame times, frames.
    static : bool
        Fit positions only (``V = 0``).
    estimate_weights, estimate_sigma : bool
        Also update ``p_j`` and ``sigma_j`` (the extension the paper calls feasible).
    prior : MapPrior or None
        The MAP-EM prior (None: maximum likelihood).
    span : float
        Frame span ``max(t_max - t_min, 1)``, frames: a velocity change times it is compared with ``tol_px``.
    e_step : callable
        The E-step, compiled (:func:`._kernels.e_step`) or its NumPy twin, chosen once per EM call.
    fast : bool
        Use the compiled M-step where there is no prior.
    """

    entries: PixelEntries
    times: np.ndarray
    static: bool
    estimate_weights: bool
    estimate_sigma: bool
    prior: MapPrior | None
    span: float
    e_step: Callable
    fast: bool

    def log_prior(self, th, rows):
        """Log prior density of ``th`` (n, Q, 4) for the trials ``rows``, shape (n,) (the scalar 0.0 without a
        prior)."""
        if self.prior is None:
            return 0.0
        return self.prior.log_density(th, rows)

    def m_step(self, sums, th, trials):
        """Closed-form M-step (11) (with the prior's terms under MAP-EM): new states (n, Q, 4) and the singular
        flag (n,) from the E-step ``sums`` (n, Q, 7 or 9) of the trials ``trials`` (n,)."""
        if self.prior is None:
            return _kernels.m_step(sums, th, self.static) if self.fast else maximisation_step(sums, th, self.static)
        return maximisation_step(sums, th, self.static, self.prior.rows(trials))

    def step(self, work: ActiveEntries, th, pw, p0, sg, live=None):
        """One EM step (eqs. (10)-(11)) of the working set's trials.

        Parameters
        ----------
        work : ActiveEntries
            The working set (n trials).
        th : ndarray, shape (n, Q, 4)
            States, px and px/frame.
        pw, sg : ndarray, shape (n, Q)
            Object weights and PSF standard deviations (px).
        p0 : ndarray, shape (n,)
            Noise weight.
        live : ndarray of bool, shape (n,), optional
            The trials still iterating (None: all); the E-step may skip the others, whose returns are then not
            meaningful.

        Returns
        -------
        new : ndarray, shape (n, Q, 4)
        pw, p0, sg
            Updated when estimated, else the given ones.
        ll : ndarray, shape (n,)
            Log-likelihood (plus the log prior) at ``th``, nats.
        bad : ndarray of bool, shape (n,)
        """
        sums, ll = self.e_step(work, th, pw, p0, sg, self.times, self.entries.shape, self.estimate_sigma, live)
        new, bad = self.m_step(sums, th, work.trials)
        ll = ll + self.log_prior(th, work.trials)
        if self.estimate_sigma:
            sg = sigma_update(sums, new, sg, bad)
        if self.estimate_weights:
            tot = np.add.reduceat(work.count, work.starts)[:, None]
            pw = np.where(bad[:, None], pw, np.maximum(sums[..., 0] / tot, 1e-12))
            p0 = np.clip(1.0 - pw.sum(axis=1), 0.0, 1.0)
        return new, pw, p0, sg, ll, bad

    def change(self, a, b) -> np.ndarray:
        """Largest change between states ``a`` and ``b`` (n, Q, 4), shape (n,): positions in px, velocities times
        :attr:`span`."""
        d = np.abs(a - b)
        return np.maximum(d[..., :2].max(axis=(1, 2)), self.span * d[..., 2:].max(axis=(1, 2)))


def plain_update(model: EMModel, work: ActiveEntries, th, pw, p0, sg, live=None) -> Step:
    """One plain EM step (eqs. (10)-(11)) of the working set's trials; arguments as :meth:`EMModel.step`."""
    new, pw_n, p0_n, sg_n, ll, bad = model.step(work, th, pw, p0, sg, live)
    delta = model.change(new, th)
    if model.estimate_sigma:
        delta = np.maximum(delta, np.abs(sg_n - sg).max(axis=1))
    if model.estimate_weights:
        delta = np.maximum(delta, np.abs(pw_n - pw).max(axis=1))
    return Step(new, pw_n, p0_n, sg_n, ll, bad, delta, 1)


def squarem_update(model: EMModel, work: ActiveEntries, th, pw, p0, sg, live=None) -> Step:
    """One SQUAREM cycle (Varadhan & Roland 2008, scheme S3 with a monotone safeguard) of the motion states: two EM
    steps, the quadratic extrapolation ``th - 2 alpha r + alpha^2 v`` (``alpha = min(-|r| / |v|, -1)``) and a
    stabilising EM step, kept where the log-likelihood did not fall (else the plain two-step result); arguments as
    :meth:`EMModel.step` (the weights and widths are not updated)."""
    t1, *_, l0, bad1 = model.step(work, th, pw, p0, sg, live)
    t2, *_, l1, bad2 = model.step(work, t1, pw, p0, sg, live)
    r = t1 - th
    v = t2 - t1 - r
    nr = np.sqrt((r**2).sum(axis=(1, 2)))
    nv = np.sqrt((v**2).sum(axis=(1, 2)))
    alpha = np.where(nv > 0, np.minimum(-nr / np.where(nv > 0, nv, 1.0), -1.0), -1.0)
    tx = th - 2 * alpha[:, None, None] * r + alpha[:, None, None] ** 2 * v
    t3, *_, lx, bad3 = model.step(work, tx, pw, p0, sg, live)
    ok = (lx >= l0) & np.isfinite(lx) & ~bad3
    new = np.where(ok[:, None, None], t3, t2)
    delta = np.where(ok, model.change(t3, tx), model.change(t2, t1))
    return Step(new, pw, p0, sg, l0, bad1 | bad2, delta, 3)


@dataclass
class EMState:
    """The iterates and the per-trial bookkeeping of one EM call (N trials, Q objects).

    Attributes
    ----------
    theta : ndarray, shape (N, Q, 4)
        Current states, px and px/frame.
    pw, sigma : ndarray, shape (N, Q)
        Current object weights and PSF standard deviations (px).
    p0 : ndarray, shape (N,)
        Current noise weights.
    loglik : ndarray, shape (N,)
        Log-likelihood (log posterior with a prior) at the start of each trial's last step, nats.
    n_iter : ndarray of int64, shape (N,)
        EM steps taken.
    converged, degenerate : ndarray of bool, shape (N,)
        The stopping rule was met; the trial had no photons or a singular M-step.
    prev_ll, prev_rise, calm : ndarray, shape (N,)
        For ``tol_loglik``: the log-likelihood at the previous step's start, the rise of the step before, and the
        successive steps whose remaining gain was below ``tol_loglik``.
    hist_t, hist_l : list of ndarray
        Per iteration (``history``): copies of ``theta`` (N, Q, 4) and ``loglik`` (N,).
    """

    theta: np.ndarray
    pw: np.ndarray
    p0: np.ndarray
    sigma: np.ndarray
    loglik: np.ndarray
    n_iter: np.ndarray
    converged: np.ndarray
    degenerate: np.ndarray
    prev_ll: np.ndarray
    prev_rise: np.ndarray
    calm: np.ndarray
    hist_t: list = field(default_factory=list)
    hist_l: list = field(default_factory=list)

    @classmethod
    def start(cls, theta0, static: bool, pw, p0, sigma, photons) -> EMState:
        """The state before the first step: ``theta0`` (N, Q, 4; its velocities zeroed when ``static``), the
        weights and widths (the arrays themselves, updated in place) and ``photons`` (N,) per trial (none:
        degenerate from the start)."""
        theta = theta0.copy()
        if static:
            theta[..., 2:] = 0.0
        n = theta.shape[0]
        return cls(
            theta=theta,
            pw=pw,
            p0=p0,
            sigma=sigma,
            loglik=np.zeros(n),
            n_iter=np.zeros(n, dtype=np.int64),
            converged=np.zeros(n, dtype=bool),
            degenerate=photons <= 0,
            prev_ll=np.full(n, -np.inf),
            prev_rise=np.full(n, np.nan),
            calm=np.zeros(n, dtype=np.int64),
        )

    def take(self, active, live, th, step: Step) -> None:
        """Store the update ``step`` of the working set ``active`` (n,) for its trials still iterating (``live``,
        (n,) bool); ``th`` (n, Q, 4) are the states it started from (kept where the M-step was singular)."""
        upd = active[live]
        self.loglik[upd] = step.loglik[live]
        self.theta[upd] = np.where(step.bad[live, None, None], th[live], step.theta[live])
        self.pw[upd], self.p0[upd], self.sigma[upd] = step.p[live], step.p_noise[live], step.sigma[live]
        self.n_iter[upd] += step.taken

    def stopped(self, active, live, step: Step, tol_px: float, tol_loglik: float | None) -> np.ndarray:
        """Which trials of the working set meet the stopping rule after ``step``, shape (n,) bool: no change above
        ``tol_px``, or (``tol_loglik``) an Aitken gap below it on :data:`CALM` successive steps."""
        if tol_loglik is None:
            return (step.delta < tol_px) & ~step.bad & live
        upd = active[live]
        ll = step.loglik
        gap = _aitken_gap(ll, self.prev_ll[active], self.prev_rise[active])
        self.prev_rise[upd] = (ll - self.prev_ll[active])[live]
        self.prev_ll[upd] = ll[live]
        self.calm[upd] = np.where(gap[live] < tol_loglik, self.calm[upd] + 1, 0)
        return (self.calm[active] >= CALM) & ~step.bad & live

    def flag(self, active, live, conv, bad) -> None:
        """Mark the working set's trials that converged (``conv``, (n,) bool) and those still iterating whose M-step
        was singular (``bad``)."""
        self.converged[active[conv]] = True
        self.degenerate[active[bad & live]] = True

    def remember(self) -> None:
        """Append copies of ``theta`` and ``loglik`` to the history."""
        self.hist_t.append(self.theta.copy())
        self.hist_l.append(self.loglik.copy())


def _regroup(entries: PixelEntries, active, work: ActiveEntries, live):
    """The working set after a step: rebuilt from the trials still iterating when fewer than 60 % of it do, else
    unchanged. Returns ``(active, work, live)``."""
    if live.sum() < 0.6 * live.size:
        active = active[live]
        return active, ActiveEntries(entries, active), np.ones(active.size, dtype=bool)
    return active, work, live


def iterate(
    model: EMModel,
    state: EMState,
    *,
    accelerate: str | None,
    tol_px: float,
    tol_loglik: float | None,
    max_iter: int,
    history: bool,
) -> None:
    """Run the EM on every trial of ``state`` that is not degenerate until each converges, turns degenerate or
    takes ``max_iter`` steps; ``state`` is updated in place. Options as :func:`.em.unified_location_em`."""
    update = plain_update if accelerate is None else squarem_update
    active = np.flatnonzero(~state.degenerate)
    work = ActiveEntries(model.entries, active)
    live = np.ones(active.size, dtype=bool)
    while live.any():
        th = state.theta[active]
        step = update(model, work, th, state.pw[active], state.p0[active], state.sigma[active], live)
        state.take(active, live, th, step)
        conv = state.stopped(active, live, step, tol_px, tol_loglik)
        state.flag(active, live, conv, step.bad)
        if history:
            state.remember()
        live &= ~conv & ~step.bad & (state.n_iter[active] < max_iter)
        active, work, live = _regroup(model.entries, active, work, live)
