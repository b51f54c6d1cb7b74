"""Unified location algorithm (ULA): multi-frame EM for the linear motion of close objects.

Savanevich (1999) estimates the linear-motion states ``theta_j = (x0_j, y0_j, Vx_j, Vy_j)``
of ``Q`` objects directly from the photon counts of ``T`` CCD frames. The pixel probability
(U1, with eq. (2) normalised here so that ``p_o + sum_j p_j = 1``) is

    v_ikl = p_o / M + sum_j p_j F_xji(mu_xjl) F_yjk(mu_yjl),   mu_xjl = x0_j + Vx_j t_l,

and the maximum-likelihood equations (3) are solved by the "splitting" iteration of eqs. (9)-(11),
which is the EM algorithm for binned Gaussian-mixture data:

* E-step: ``lambda_jikl = p_j F_jikl / v_ikl`` (the posterior probability that a photon counted
  in pixel (i, k) of frame l came from object j; eqs. (10) text) and the *local means* (U6),
  the truncated-normal means of the landing coordinate inside the pixel;
* M-step: per object and axis the weighted least-squares line through the local means, eq. (11),
  with two corrections made here: the sign in (10) is ``D - x0 A - V B = 0`` and the velocity row of
  (11) uses the *new* ``x0``.

Counts ``n_ikl`` are used in place of the frequencies ``v*_ikl`` (derived here from the likelihood
behind (3)); the two coincide when every frame holds the same number of photons.

The 1-D pixel fractions and local means are tabulated once per (trial, frame, object) from the pixel
edges (``Q T (rows + cols)`` normal-CDF evaluations), and only pixels with a non-zero count enter the
splitting and the sums, so the work per iteration is ``O(Q T (rows + cols) + Q nnz)``, not
``O(Q T rows cols)``. Trials are independent and vectorised: every pixel entry carries its trial
index; sums per trial use :func:`numpy.add.reduceat` over the trial-sorted entries, and converged
trials are dropped from the working set. With numba, the maximum-likelihood EM with fixed weights and widths
runs compiled one trial at a time instead (:func:`._kernels.em_trials`; the same numbers bit for bit).

Units: pixels (centres at integers, window origin at pixel (0, 0); ``x`` = column, ``y`` = row)
and frames, as in :mod:`tvtrack.papers.p002_unified_location_em.model`.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass, field

import numpy as np
from scipy.special import ndtr

from tvtrack import jit

from . import _kernels
from .em_loop import EMModel, EMState, MapPrior, iterate
from .em_steps import (
    PixelEntries,
    ActiveEntries,
    check_entries,
    expectation_step,
    expectation_step_numpy,
)
from .model import pixel_probabilities

__all__ = [
    "PixelEntries",
    "EMResult",
    "unified_location_em",
    "match_labels",
    "track_distance",
    "responsibility_maps",
    "log_likelihood",
]

_TINY = 1e-300


@dataclass
class EMResult:
    """Output of :func:`unified_location_em`; every array has trials on the leading axis.

    Attributes
    ----------
    theta : ndarray, shape (N, Q, 4)
        Estimates ``(x0, y0, Vx, Vy)`` (px, px/frame); never NaN (a failed trial keeps its last
        finite iterate and carries a flag).
    p : ndarray, shape (N, Q)
        Object weights (given, or estimated when ``estimate_weights``).
    p_noise : ndarray, shape (N,)
    sigma : ndarray, shape (N, Q)
        PSF standard deviations (px; given, or estimated when ``estimate_sigma``).
    loglik : ndarray, shape (N,)
        ``sum n_ikl ln v_ikl`` at ``theta`` (multinomial log-likelihood up to a constant).
    n_iter : ndarray of int, shape (N,)
        EM steps (E+M evaluations) taken, accelerated or not.
    converged : ndarray of bool, shape (N,)
        The stopping rule was met.
    cap_hit : ndarray of bool
        ``max_iter`` reached without meeting the stopping rule.
    degenerate : ndarray of bool
        No photons, or an object got no weight, or the line fit is singular (all weight in one
        frame): the estimate stays at the last good iterate.
    merged : ndarray of bool
        Two estimated tracks closer than ``merge_px`` in root-mean-square over the frames
        (:func:`track_distance`; includes coincident designations, which EM can never split: the posterior
        shares stay equal). Crossing tracks, close at one frame only, are not merged.
    swapped : ndarray of bool
        The estimates match the *initial* labels better in another order (label swap relative
        to the designation; a swap relative to the truth is found with :func:`match_labels`).
    left_frame : ndarray of bool
        An estimated object keeps less than ``min_in_frame_mass`` of its PSF inside the window in
        some frame (the closed form (11) assumes the whole PSF is observed).
    history_theta, history_loglik : list of ndarray
        Per iteration (only with ``history=True``): theta (N, Q, 4) and the log-likelihood at
        the theta used in that E-step (N,); converged trials repeat their last value.
    """

    theta: np.ndarray
    p: np.ndarray
    p_noise: np.ndarray
    sigma: np.ndarray
    loglik: np.ndarray
    n_iter: np.ndarray
    converged: np.ndarray
    cap_hit: np.ndarray
    degenerate: np.ndarray
    merged: np.ndarray
    swapped: np.ndarray
    left_frame: np.ndarray
    history_theta: list = field(default_factory=list)
    history_loglik: list = field(default_factory=list)

    @property
    def failed(self) -> np.ndarray:
        """Any flag raised, shape (N,)."""
        return self.cap_hit | self.degenerate | self.merged | self.swapped | self.left_frame


def match_labels(estimate, reference, times=None):
    """Label order of ``estimate`` that best matches ``reference``: the minimum over all ``Q!`` orders of the
    squared distance between the estimated and the reference positions summed over every frame time.

    Matching over the whole trajectory (not at one epoch) keeps crossing tracks apart: at the frame where two
    tracks cross, their positions coincide and any order fits equally well there (matched at the mean
    frame time, 26 % of crossing pairs estimated to 0.05 px were declared swapped).

    Parameters
    ----------
    estimate, reference : ndarray, shape (N, Q, 4)
        States ``(x0, y0, Vx, Vy)``, px and px/frame.
    times : ndarray, shape (T,), optional
        Frame times; the positions are compared at every one of them (default: ``t = 0`` only).

    Returns
    -------
    perm : ndarray of int, shape (N, Q)
        ``estimate[n, perm[n]]`` is matched to ``reference[n]``.
    identity : ndarray of bool, shape (N,)
        The best order is the given one.
    """
    est = np.asarray(estimate, dtype=float)
    ref = np.asarray(reference, dtype=float)
    if est.shape != ref.shape or est.ndim != 3 or est.shape[-1] != 4:
        raise ValueError(f"estimate {est.shape} and reference {ref.shape} must both be (N, Q, 4)")
    q = est.shape[1]
    if q > 7:
        raise ValueError(f"Q = {q} objects; label matching enumerates Q! orders and allows Q <= 7")
    t = np.zeros(1) if times is None else np.asarray(times, dtype=float).ravel()
    perms = np.array(list(itertools.permutations(range(q))))  # (P, Q), identity first
    diff = est[:, perms] - ref[:, None]  # (N, P, Q, 4)
    # sum over frames of |dp + t dv|^2 = T |dp|^2 + 2 (sum t) dp.dv + (sum t^2) |dv|^2
    dp, dv = diff[..., :2], diff[..., 2:]
    cost = (t.size * dp**2 + 2 * t.sum() * dp * dv + (t**2).sum() * dv**2).sum(axis=(-1, -2))  # (N, P)
    best = cost.argmin(axis=1)
    # ties (e.g. merged objects) keep the given order
    best = np.where(cost[np.arange(len(best)), best] < cost[:, 0], best, 0)
    return perms[best], best == 0


def track_distance(theta, times) -> np.ndarray:
    """Root-mean-square distance over the frames between every pair of tracks, shape (N, Q (Q - 1) / 2), px.

    Two tracks that merely cross (close at one frame) are far apart by this measure; two tracks that EM merged
    into one (the same positions in every frame) are not."""
    theta = np.asarray(theta, dtype=float)
    t = np.asarray(times, dtype=float)[None, :, None, None]
    pos = theta[:, None, :, :2] + t * theta[:, None, :, 2:]  # (N, T, Q, 2)
    iu = np.triu_indices(theta.shape[1], 1)
    d2 = ((pos[:, :, iu[0]] - pos[:, :, iu[1]]) ** 2).sum(axis=-1)  # (N, T, pairs)
    return np.sqrt(d2.mean(axis=1))


def _in_frame_mass(theta, sigma, times, shape):
    """Smallest in-window PSF mass over objects and frames, shape (N,)."""
    rows, cols = shape
    t = times[None, None, :]
    s = sigma[..., None]
    mux = theta[..., 0:1] + theta[..., 2:3] * t
    muy = theta[..., 1:2] + theta[..., 3:4] * t
    fx = ndtr((cols - 0.5 - mux) / s) - ndtr((-0.5 - mux) / s)
    fy = ndtr((rows - 0.5 - muy) / s) - ndtr((-0.5 - muy) / s)
    return (fx * fy).min(axis=(1, 2))


def _broadcast(value, shape, name, positive: bool):
    arr = np.asarray(value, dtype=float)
    try:
        arr = np.broadcast_to(arr, shape).copy()
    except ValueError:
        raise ValueError(f"{name} has shape {arr.shape}; it must broadcast to {shape}") from None
    bad_sign = (arr <= 0).any() if positive else (arr < 0).any()
    if not np.isfinite(arr).all() or bad_sign:
        raise ValueError(f"{name} = {value!r} must be finite and {'> 0' if positive else '>= 0'}")
    return arr


def unified_location_em(
    entries: PixelEntries,
    theta0,
    sigma_px,
    p,
    p_noise,
    *,
    times=None,
    motion: str = "linear",
    tol_px: float = 1e-6,
    max_iter: int = 5000,
    accelerate: str | None = None,
    estimate_weights: bool = False,
    estimate_sigma: bool = False,
    merge_px: float = 0.05,
    min_in_frame_mass: float = 0.99,
    history: bool = False,
    prior_sd=None,
    tol_loglik: float | None = None,
) -> EMResult:
    """Maximum-likelihood linear-motion states of ``Q`` objects from all ``T`` frames at once.

    Parameters
    ----------
    entries : PixelEntries
        Non-zero pixels of the count tensor (:func:`pixel_entries`; for per-frame marks use
        :func:`per_frame_entries` with ``motion="static"``); a hand-built one must be sorted by trial, with its
        indices inside ``n_trials``, ``n_frames`` and ``shape`` and counts >= 0 (else ``ValueError``).
    theta0 : array_like, shape (N, Q, 4)
        Initialisation (the target designation), px and px/frame.
    sigma_px : float or array_like, shape (Q,) or (N, Q)
        PSF standard deviations (px, > 0); the starting values when ``estimate_sigma``.
    p : array_like, shape (Q,) or (N, Q)
        Object weights ``p_j`` (> 0), with ``p_noise + sum_j p_j = 1``.
    p_noise : float or array_like, shape (N,)
        Noise weight ``p_o`` (>= 0).
    times : array_like, shape (T,), optional
        Frame times (default ``0..T-1``).
    motion : {"linear", "static"}
        ``"static"`` fits positions only (``V = 0``): the iterative mark formation of ref. [5]
        when applied to one frame.
    tol_px : float
        Stop a trial when no position changes by more than ``tol_px`` and no velocity by more
        than ``tol_px / (t_max - t_min)`` in one EM step (also ``sigma`` and ``p`` when they are
        estimated). > 0.
    max_iter : int
        Cap on EM steps per trial (>= 1).
    accelerate : {None, "squarem"}
        SQUAREM (Varadhan & Roland 2008, scheme S3 with a monotone safeguard): two EM steps,
        a quadratic extrapolation and a stabilising EM step, kept only where the
        log-likelihood did not fall; otherwise the plain two-step result is kept. Only for the
        motion parameters (not with ``estimate_weights``/``estimate_sigma``).
    estimate_weights, estimate_sigma : bool
        Also update ``p_j`` (``sum w_j / sum n``) and ``sigma_j`` (truncated second moments),
        the extension the paper calls feasible (text after eq. (3)).
    merge_px : float
        Root-mean-square distance over the frames (px) below which two estimated tracks count as merged (>= 0).
    min_in_frame_mass : float
        In-window PSF mass below which an object counts as having left the frame, in (0, 1].
    history : bool
        Keep theta and the log-likelihood of every iteration (for tests and recordings).
    tol_loglik : float, optional
        Stop a trial instead when the log-likelihood it can still gain is below ``tol_loglik`` (nats, > 0;
        ``tol_px`` is then not used), the remaining gain estimated by Aitken's extrapolation of the last two
        rises (EM converges linearly: ``L* - L_k ~ r_k a / (1 - a)``, ``a = r_k / r_{k-1}``; Lindsay 1995,
        McNicholas et al. 2010). The gap to the maximum is half the squared stopping error in units of the
        estimate's own standard error (``L* - L ~ delta' I delta / 2``), whatever the number of frames the
        likelihood pools and whatever EM's rate: the same ``tol_loglik`` stops a joint estimate over ``T``
        frames and a one-frame mark at the same distance from their maxima relative to their own spread. That
        is not the same error added to a track: the marks' stopping errors all lean towards their starts and do
        not average out over a line fit of ``T`` marks (the register's "EM stopping" gives it measured). The
        estimate must hold on :data:`CALM` successive steps.
    prior_sd : (float, float), optional
        MAP-EM: a Gaussian prior centred on ``theta0`` (the designation) with standard deviations
        ``(position px, velocity px/frame)`` per coordinate; a velocity sd of 0 fixes the velocity
        at ``theta0``'s (up to 1e-9 px/frame). The SQUAREM safeguard and ``history`` then use the log
        posterior; the returned ``loglik`` is the log-likelihood. Linear motion with fixed sigma only.

    Returns
    -------
    EMResult
    """
    theta0 = _checked_start(entries, theta0)
    _check_options(
        motion, tol_px, max_iter, tol_loglik, accelerate, estimate_weights, estimate_sigma, merge_px, min_in_frame_mass
    )
    n, q = theta0.shape[:2]
    times = _frame_times(times, entries.n_frames)
    static = motion == "static"
    sigma, pw, p0 = _mixture(sigma_px, p, p_noise, (n, q))
    span = max(float(times.max() - times.min()), 1.0)
    prior = _map_prior(prior_sd, theta0, sigma, static, estimate_sigma)
    fast = jit.enabled()  # compiled steps (:mod:`._kernels`) or their NumPy twins, the switch read once
    model = EMModel(
        entries=entries,
        times=times,
        static=static,
        estimate_weights=estimate_weights,
        estimate_sigma=estimate_sigma,
        prior=prior,
        span=span,
        e_step=_kernels.e_step if fast else expectation_step_numpy,
        fast=fast,
    )
    photons = entries.photons_per_trial()
    state = EMState.start(theta0, static, pw, p0, sigma, photons)
    stop = dict(accelerate=accelerate, tol_px=tol_px, tol_loglik=tol_loglik, max_iter=max_iter)
    # the plain ML EM runs compiled one trial at a time (the same numbers, without NumPy's per-pass cost)
    compiled = fast and prior is None and not (estimate_weights or estimate_sigma or history)
    # (it also sets the final log-likelihood, as :func:`_final_loglik` does after the vectorised loop)
    if not (compiled and _kernels.em_trials(entries, times, static, span, state, **stop)):
        iterate(model, state, **stop, history=history)
        _final_loglik(entries, state, times, photons)
    return _result(state, theta0, times, entries.shape, max_iter, merge_px, min_in_frame_mass)


def _checked_start(entries: PixelEntries, theta0) -> np.ndarray:
    """``theta0`` as a float array, shape (N, Q, 4) with ``N = entries.n_trials`` (px, px/frame), checked finite,
    after the entries (:func:`.em_steps.check_entries`: the compiled steps index their tables with them unchecked)."""
    check_entries(entries)
    theta0 = np.asarray(theta0, dtype=float)
    if theta0.ndim != 3 or theta0.shape[-1] != 4 or theta0.shape[0] != entries.n_trials:
        raise ValueError(f"theta0 has shape {theta0.shape}; it must be ({entries.n_trials}, Q, 4)")
    if not np.isfinite(theta0).all():
        raise ValueError("theta0 must be finite")
    return theta0


def _check_options(
    motion, tol_px, max_iter, tol_loglik, accelerate, estimate_weights, estimate_sigma, merge_px, min_in_frame_mass
) -> None:
    """Raise ``ValueError`` for an option of :func:`unified_location_em` out of its range (see there)."""
    if motion not in ("linear", "static"):
        raise ValueError(f"motion = {motion!r} must be 'linear' or 'static'")
    if not tol_px > 0:
        raise ValueError(f"tol_px = {tol_px} must be > 0")
    if max_iter < 1:
        raise ValueError(f"max_iter = {max_iter} must be >= 1")
    if tol_loglik is not None and not tol_loglik > 0:
        raise ValueError(f"tol_loglik = {tol_loglik} must be > 0 (or None)")
    if accelerate not in (None, "squarem"):
        raise ValueError(f"accelerate = {accelerate!r} must be None or 'squarem'")
    if accelerate and (estimate_weights or estimate_sigma):
        raise ValueError(
            "accelerate = 'squarem' extrapolates the motion states only; it cannot be "
            "combined with estimate_weights or estimate_sigma"
        )
    if merge_px < 0:
        raise ValueError(f"merge_px = {merge_px} must be >= 0")
    if not 0 < min_in_frame_mass <= 1:
        raise ValueError(f"min_in_frame_mass = {min_in_frame_mass} must be in (0, 1]")


def _frame_times(times, n_frames: int) -> np.ndarray:
    """Frame times, shape (T,), frames: ``times`` checked against ``n_frames`` (default ``0..T-1``)."""
    times = np.arange(n_frames, dtype=float) if times is None else np.asarray(times, float)
    if times.shape != (n_frames,):
        raise ValueError(f"times has shape {times.shape}; it must be ({n_frames},)")
    return times


def _mixture(sigma_px, p, p_noise, shape):
    """Per-trial PSF widths (px) and weights of the mixture (U1), ``(sigma (N, Q), p (N, Q), p_noise (N,))`` for
    ``shape = (N, Q)``, checked positive (``p_noise`` >= 0) and summing to one (``p_noise + sum_j p_j = 1``, eq.
    (2)); fresh arrays (the EM updates them in place)."""
    n, q = shape
    sigma = _broadcast(sigma_px, (n, q), "sigma_px", positive=True)
    pw = _broadcast(p, (n, q), "p", positive=True)
    p0 = _broadcast(p_noise, (n,), "p_noise", positive=False)
    if np.any(np.abs(pw.sum(axis=1) + p0 - 1.0) > 1e-9):
        raise ValueError("weights must satisfy p_noise + sum(p) = 1")
    return sigma, pw, p0


def _map_prior(prior_sd, theta0, sigma, static: bool, estimate_sigma: bool) -> MapPrior | None:
    """The MAP-EM prior of ``prior_sd = (position sd px, velocity sd px/frame)`` centred on ``theta0`` (N, Q, 4),
    with the PSF widths ``sigma`` (N, Q, px); None without ``prior_sd``. A velocity sd of 0 is taken as 1e-9
    px/frame."""
    if prior_sd is None:
        return None
    sd_x, sd_v = (float(v) for v in prior_sd)
    if not (sd_x > 0 and sd_v >= 0) or static or estimate_sigma:
        raise ValueError(
            f"prior_sd = {prior_sd}: needs position sd > 0, velocity sd >= 0, linear motion and fixed sigma"
        )
    return MapPrior(mean=theta0, a=sigma**2 / sd_x**2, c=sigma**2 / max(sd_v, 1e-9) ** 2, sigma=sigma)


def _final_loglik(entries: PixelEntries, state: EMState, times, photons) -> None:
    """Set ``state.loglik`` to the log-likelihood ``sum n_ikl ln v_ikl`` (eq. (3)) at the returned estimates of the
    trials with photons (``photons``, shape (N,), their total counts; the prior's term left out)."""
    live = np.flatnonzero(photons > 0)
    if live.size:
        _, state.loglik[live] = expectation_step(
            ActiveEntries(entries, live),
            state.theta[live],
            state.pw[live],
            state.p0[live],
            state.sigma[live],
            times,
            entries.shape,
            False,
        )


def _result(state: EMState, theta0, times, shape, max_iter: int, merge_px: float, min_in_frame_mass: float):
    """The :class:`EMResult` of a finished ``state``, with the flags: cap hit, merged tracks (closer than
    ``merge_px`` px in RMS over the frames), labels swapped against ``theta0`` (N, Q, 4) and objects that left the
    window ``shape`` (less than ``min_in_frame_mass`` of the PSF inside in some frame)."""
    theta, n, q = state.theta, theta0.shape[0], theta0.shape[1]
    cap_hit = ~state.converged & ~state.degenerate & (state.n_iter >= max_iter)
    merged = (track_distance(theta, times) < merge_px).any(axis=1) if q > 1 else np.zeros(n, dtype=bool)
    if q > 1:
        _, same = match_labels(theta, theta0, times)
        swapped = ~same & ~merged
    else:
        swapped = np.zeros(n, dtype=bool)
    left = _in_frame_mass(theta, state.sigma, times, shape) < min_in_frame_mass
    return EMResult(
        theta=theta,
        p=state.pw,
        p_noise=state.p0,
        sigma=state.sigma,
        loglik=state.loglik,
        n_iter=state.n_iter,
        converged=state.converged,
        cap_hit=cap_hit,
        degenerate=state.degenerate,
        merged=merged,
        swapped=swapped,
        left_frame=left,
        history_theta=state.hist_t,
        history_loglik=state.hist_l,
    )


def log_likelihood(counts, theta, times, sigma_px, p, p_noise) -> np.ndarray:
    """Dense ``sum n_ikl ln v_ikl`` (eq. (3)'s objective) for one or more trials.

    Parameters
    ----------
    counts : ndarray, shape (N, T, rows, cols)
    theta : ndarray, shape (N, Q, 4)
    p : array_like, shape (Q,) ; p_noise : float

    Returns
    -------
    ndarray, shape (N,)
    """
    counts = np.asarray(counts, dtype=float)
    F = pixel_probabilities(theta, times, counts.shape[-2:], sigma_px)  # (N, Q, T, R, C)
    v = p_noise / (counts.shape[-1] * counts.shape[-2]) + np.einsum("q,nqtrc->ntrc", np.asarray(p, float), F)
    return (counts * np.log(np.maximum(v, _TINY))).sum(axis=(1, 2, 3))


def responsibility_maps(theta, times, shape, sigma_px, p, p_noise) -> np.ndarray:
    """Posterior shares ``lambda_jikl`` (objects first, noise last) of one trial, as images.

    Parameters
    ----------
    theta : ndarray, shape (Q, 4)

    Returns
    -------
    ndarray, shape (Q + 1, T, rows, cols)
        Sums to 1 over the first axis in every pixel.
    """
    theta = np.asarray(theta, dtype=float)
    F = pixel_probabilities(theta, times, shape, sigma_px)  # (Q, T, R, C)
    pv = np.asarray(p, dtype=float)[:, None, None, None] * F
    noise = np.full((1,) + F.shape[1:], p_noise / (shape[0] * shape[1]))
    parts = np.concatenate([pv, noise], axis=0)
    return parts / parts.sum(axis=0, keepdims=True)
