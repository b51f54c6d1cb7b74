"""Monte Carlo simulation of close-object location (one configuration at a time): ULA vs two-stage trajectory algorithms.

One *configuration* (:class:`~.sim_config.Config`, defined with its settings and seeds in :mod:`.sim_config`) is
``(Q, d/sigma, Delta/sigma, m_k, T)`` plus the algorithms to run, the designation errors, the mark
initialisation/association and the number of trials. :func:`run_config` draws its scenes from its own seed
(derived from the run seed and the configuration values, so results do not depend on the number of workers or on
which other configurations are computed), runs the unified location EM
(:func:`tvtrack.papers.p002_unified_location_em.em.unified_location_em`), the two-stage algorithms of
:mod:`tvtrack.papers.p002_unified_location_em.two_stage` and the Poisson CRB of :mod:`tvtrack.bounds.poisson_crb`
on the same samples, and returns the per-trial errors (cached by :mod:`.study`).

Units: errors are in sigma (the PSF standard deviation), after matching the estimated labels to
the truth (all ``Q!`` orders, :func:`~tvtrack.papers.p002_unified_location_em.em.match_labels`).
"""

from __future__ import annotations

import time
from dataclasses import replace
from types import SimpleNamespace

import numpy as np

from tvtrack.bounds.poisson_crb import crb_from_fisher, fisher_linear_motion, position_crb_sum
from tvtrack.papers.p002_unified_location_em.em import match_labels, unified_location_em
from tvtrack.papers.p002_unified_location_em.em_steps import pixel_entries
from tvtrack.papers.p002_unified_location_em.two_stage import centre_of_region_marks, em_marks, fit_lines, propagate
from tvtrack.papers.p002_unified_location_em.model import (
    draw_truth,
    frame_times,
    mixture_weights,
    noise_per_pixel,
    scene_batches,
    scene_geometry,
)

from .sim_config import (
    N_SEED_BLOCKS,
    Config,
    StudySettings,
    scene_key,
    seed_sequence,
)


def errors_vs_truth(theta, truth, sigma_px: float, times):
    """Errors after the best label order, and the swap flag.

    Parameters
    ----------
    theta, truth : ndarray, shape (n, Q, 4)
        Estimated and true states ``(x0, y0, Vx, Vy)``, px and px/frame.
    sigma_px : float
        PSF standard deviation, px (the unit of the errors).
    times : ndarray, shape (T,)

    Returns
    -------
    errors : ndarray, shape (n, Q, 4)
        In sigma and sigma/frame.
    swapped : ndarray of bool, shape (n,)
        The best order is not the identity.
    """
    perm, same = match_labels(theta, truth, times)
    est = np.take_along_axis(theta, perm[..., None], axis=1)
    return (est - truth) / sigma_px, ~same


def bic_orders(
    settings: StudySettings,
    entries,
    designation,
    sigma_px: float,
    photons: float,
    noise_per_pixel: float,
    n_pixels: int,
) -> np.ndarray:
    """BIC ``-2 L + 5 Q' ln(n_photons)`` of ULA fits with ``Q' = 1, 2, 3`` (weights estimated,
    plain EM, at most ``settings.bic_max_iter`` steps); returns shape (n, 3)."""
    n = designation.shape[0]
    n_photons = entries.photons_per_trial()
    d2 = designation[:, :2]
    starts = {
        1: d2.mean(axis=1, keepdims=True),
        2: d2,
        3: np.concatenate([d2, d2.mean(axis=1, keepdims=True) + [sigma_px, 0, 0, 0]], axis=1),
    }
    out = np.empty((n, 3))
    for k, th0 in starts.items():
        p, p0 = mixture_weights(photons, noise_per_pixel, n_pixels, k)
        r = unified_location_em(
            entries, th0, sigma_px, p, p0, tol_px=1e-4 * sigma_px, max_iter=settings.bic_max_iter, estimate_weights=True
        )
        n_par = 5 * k  # motion (4) and weight (1) per object
        out[:, k - 1] = -2 * r.loglik + n_par * np.log(np.maximum(n_photons, 1))
    return out


def _seeded_batches(settings: StudySettings, cfg: Config, g, noise_pp: float):
    """The configuration's scene batches, all from the seed ``settings.seed`` and the configuration's scene
    values (:data:`N_SEED_BLOCKS` is 1). Yields ``(batch, seed)``."""
    s, seed = g.sigma_px, settings.seed
    sizes = np.diff(np.linspace(0, cfg.n, N_SEED_BLOCKS + 1).round().astype(int))
    for k, n_k in enumerate(sizes):
        rng = np.random.default_rng(seed_sequence(seed + k, scene_key(cfg)))
        for b in scene_batches(
            rng,
            g,
            int(n_k),
            cfg.T,
            cfg.m,
            noise_pp,
            cfg.dsd * s,
            cfg.vsd * s,
            settings.photon_model,
            batch_size=max(1, int(4e6 // (cfg.T * g.n_pixels))),
        ):
            yield b, seed + k


def centre_gate_half_px(gate_half_sigma: float, sigma_px: float) -> float:
    """Half-size (px) of the centre-of-region gate: ``gate_half_sigma`` PSF widths, but at least 1.5 px, so
    that with coarse pixels the gate is 3 x 3 pixels and the centroid can move off the central pixel."""
    return max(gate_half_sigma * sigma_px, 1.5)


def map_prior_sd(velocity_knowledge: str, dsd: float, vsd: float, sigma_px: float) -> tuple[float, float]:
    """Prior standard deviations ``(position px, velocity px/frame)`` of the MAP-ULA.

    The position prior is the designation's own error model (``dsd`` sigma per coordinate; at least 1e-6).
    The velocity is free (``inf``) unless ``velocity_knowledge == "designated"``, where the prior sd is the
    designation's velocity error ``vsd`` (sigma per frame; 0 fixes it). The default, free, keeps the MAP-ULA
    from knowing what its two-stage comparator does not (a zero sd pinned it to the truth)."""
    if velocity_knowledge not in ("free", "designated"):
        raise ValueError(f"velocity_knowledge = {velocity_knowledge!r} must be 'free' or 'designated'")
    v = np.inf if velocity_knowledge == "free" else vsd * sigma_px
    return max(dsd, 1e-6) * sigma_px, v


def track_velocities(velocity_sigma, tracks: str, q: int, d: float, T: int):
    """Per-object velocities (sigma/frame), shape (Q, 2): the common velocity (``"parallel"``), or for two objects
    object 2's y velocity lowered by ``2 d / (T - 1)`` (``"crossing"``: they start ``d`` apart and end ``d`` apart
    on the other side, crossing at mid-sequence) or raised by it (``"diverging"``: they start ``d`` apart and end
    ``3 d`` apart, like satellites separating after their release from one launcher, the paper's example)."""
    if tracks not in ("parallel", "crossing", "diverging"):
        raise ValueError(f"tracks = {tracks!r} must be 'parallel', 'crossing' or 'diverging'")
    v = np.tile(np.asarray(velocity_sigma, dtype=float), (q, 1))
    if tracks != "parallel" and q == 2 and T > 1:
        v[1, 1] += (-2.0 if tracks == "crossing" else 2.0) * d / (T - 1)
    return v


def multi_start_gap(entries, designation, sigma_px, p, p0, tol_px, max_iter, accel, rng, n_starts: int = 4):
    """Log-likelihood by which the ULA started at the designation ends below the best of ``n_starts`` starts
    (the designation and ``n_starts - 1`` starts with every position moved by N(0, sigma^2)), shape (n,): zero
    where the designation start reaches the best local maximum found, positive where it stops at a lower one."""
    lls = []
    for k in range(n_starts):
        start = designation.copy()
        if k:
            start[..., :2] += rng.normal(scale=sigma_px, size=start[..., :2].shape)
        lls.append(
            unified_location_em(
                entries, start, sigma_px, p, p0, tol_px=tol_px, max_iter=max_iter, accelerate=accel
            ).loglik
        )
    lls = np.array(lls)
    return lls.max(axis=0) - lls[0]


def _fallback(marks, designation, init: str) -> np.ndarray:
    """The state a line fit returns where it has too few marks (flagged invalid): the designation,
    or for the designation-free start (``init = "moments"``) a still object at the mean mark."""
    if init != "moments":
        return designation
    return np.concatenate([marks.xy.mean(axis=1), np.zeros_like(marks.xy[:, 0])], axis=-1)


def run_config(settings: StudySettings, cfg: Config) -> dict:
    """Monte Carlo of one configuration.

    Returns
    -------
    dict
        Per algorithm letter run: ``ula``/``plain``/``map``/``em``/``cr`` errors (n, Q, 4) in sigma,
        ``*_flags`` (n, k) bool with columns :data:`FLAG_NAMES`, ``*_iter`` (n,) EM steps
        (``em_iter``, ``em_plain_iter``: summed over frames), ``plain_cap`` / ``em_plain_cap`` (n,) the plain EM's
        iteration cap hit (marks: in some frame), ``ula_loglik`` (n,), ``bic`` (n, 3), ``truth`` (n, Q, 4) px;
        ``timing`` (wall seconds per algorithm), with the letter ``r`` the bounds of :func:`_bounds`
        (``crb_pos``, ``crb_vel``, ``crb_x0``, ``bcrb_pos``, ``bcrb_vel``), ``seed`` (n,) the seed of each trial's
        block, ``T`` and ``shape``. The algorithms run by family (:func:`_run_ula`, :func:`_run_marks`,
        :func:`_run_extras`) on each block of scenes.
    """
    s_ = replace(settings, **dict(cfg.variant))
    shared = _config_inputs(s_, cfg)
    out = {k: [] for k in _OUTPUTS}
    timing = dict.fromkeys(_TIMED, 0.0)
    block_seed = []
    for b, block in _seeded_batches(s_, cfg, shared.g, shared.noise_pp):
        block_seed.append(np.full(len(b.truth), block))
        out["truth"].append(b.truth)
        x = SimpleNamespace(**vars(shared), b=b, block=block, ent=pixel_entries(b.counts))
        _run_ula(x, out, timing)
        _run_marks(x, out, timing)
        _run_extras(x, out)
    res = {k: np.concatenate(v) for k, v in out.items() if v}
    res["seed"] = np.concatenate(block_seed)
    res["T"] = cfg.T
    res["timing"] = timing
    if "r" in cfg.algs:
        res.update(_bounds(s_, cfg, shared.g, shared.times, shared.noise_pp))
    res["shape"] = shared.g.shape
    return res


#: The per-trial outputs of :func:`run_config`, in the order of its result (each algorithm run fills its own).
_OUTPUTS = (
    "truth",
    "ula",
    "ula_flags",
    "ula_iter",
    "plain",
    "plain_iter",
    "plain_cap",
    "map",
    "em",
    "em_vd",
    "em_flags",
    "em_iter",
    "em_plain_iter",
    "em_plain_cap",
    "cr",
    "cr_flags",
    "bic",
    "ula_loglik",
    "ms_gap",
    "ula_w",
    "ula_vd",
    "ula_q1",
)
#: The algorithms whose wall time (s) :func:`run_config` reports under ``timing``.
_TIMED = ("ula", "plain", "map", "em", "em_plain", "cr")


def _config_inputs(s_: StudySettings, cfg: Config) -> SimpleNamespace:
    """What every block of scenes of a configuration shares: the settings ``s_`` (with the configuration's variant)
    and ``cfg``, the scene geometry ``g``, the PSF width ``s`` (px), the noise ``noise_pp`` (photons per pixel =
    density x pixel area), the mixture weights ``p`` (Q,) and ``p0`` (eq. (2)), the EM tolerance ``tol`` (px), the
    acceleration ``accel`` (None or ``"squarem"``) and the frame times ``times`` (T,)."""
    q, d, T = cfg.q, cfg.d, cfg.T
    g = scene_geometry(q, T, d, cfg.pix, track_velocities(s_.velocity_sigma, s_.tracks, q, d, T), s_.margin_sigma)
    s = g.sigma_px
    noise_pp = noise_per_pixel(s_.noise_density, s)
    p, p0 = mixture_weights(cfg.m, noise_pp, g.n_pixels, q)
    return SimpleNamespace(
        s_=s_,
        cfg=cfg,
        s=s,
        p=p,
        p0=p0,
        tol=s_.tol_sigma * s,
        accel=None if s_.accelerate == "none" else "squarem",
        times=frame_times(T),
        g=g,
        noise_pp=noise_pp,
    )


def _run_ula(x, out: dict, timing: dict) -> None:
    """The ULA and its variants on one block of scenes: ``u`` (accelerated as set), ``p`` (plain EM, the iteration
    counts) and ``m`` (MAP-ULA); results appended to ``out``, wall seconds added to ``timing``."""
    s_, cfg, b, ent, s, p, p0, tol, accel, times = x.s_, x.cfg, x.b, x.ent, x.s, x.p, x.p0, x.tol, x.accel, x.times
    algs = cfg.algs
    dsd, vsd = cfg.dsd, cfg.vsd
    em_args, em_kw = (
        (b.designation, s, p, p0),
        dict(tol_px=tol, max_iter=s_.max_iter, tol_loglik=s_.tol_loglik),
    )  # common to every ULA variant
    if "u" in algs:
        t0 = time.perf_counter()
        r = unified_location_em(ent, *em_args, **em_kw, accelerate=accel, merge_px=s_.merge_sigma * s)
        timing["ula"] += time.perf_counter() - t0
        e, sw = errors_vs_truth(r.theta, b.truth, s, times)
        out["ula"].append(e)
        out["ula_iter"].append(r.n_iter)
        out["ula_loglik"].append(r.loglik)
        out["ula_flags"].append(np.stack([sw, r.merged, r.cap_hit, r.degenerate, r.left_frame], axis=1))
    if "p" in algs:
        t0 = time.perf_counter()
        r = unified_location_em(ent, *em_args, **em_kw)
        timing["plain"] += time.perf_counter() - t0
        out["plain"].append(errors_vs_truth(r.theta, b.truth, s, times)[0])
        out["plain_iter"].append(r.n_iter)
        out["plain_cap"].append(r.cap_hit)
    if "m" in algs:
        t0 = time.perf_counter()
        prior = map_prior_sd(s_.velocity_knowledge, dsd, vsd, s)
        r = unified_location_em(ent, *em_args, **em_kw, accelerate=accel, prior_sd=prior)
        timing["map"] += time.perf_counter() - t0
        out["map"].append(errors_vs_truth(r.theta, b.truth, s, times)[0])


def _run_marks(x, out: dict, timing: dict) -> None:
    """The two-stage algorithms on one block of scenes: ``e`` (iterative marks, with the line fit and its twin that
    keeps the designated velocity), ``q`` (iterative marks by plain EM, the iteration counts) and ``c``
    (centre-of-region marks)."""
    s_, cfg, b, s, p, p0, tol, accel, times = x.s_, x.cfg, x.b, x.s, x.p, x.p0, x.tol, x.accel, x.times
    algs = cfg.algs
    init, assoc = cfg.init, cfg.assoc
    mark_args = dict(
        init=s_.mark_init if init is None else init,
        association=s_.mark_association if assoc is None else assoc,
        tol_px=tol,
        max_iter=s_.max_iter,
        tol_loglik=s_.tol_loglik,
    )
    if "e" in algs:
        t0 = time.perf_counter()
        mk = em_marks(b.counts, b.designation, times, s, p, p0, accelerate=accel, **mark_args)
        fit = fit_lines(mk, times, _fallback(mk, b.designation, mark_args["init"]))
        timing["em"] += time.perf_counter() - t0
        # the two-stage twin of a MAP-ULA that knows the designated velocity: the line keeps that velocity
        fit_v = fit_lines(mk, times, b.designation, velocity=b.designation[..., 2:])
        out["em_vd"].append(errors_vs_truth(fit_v.theta, b.truth, s, times)[0])
        e, sw = errors_vs_truth(fit.theta, b.truth, s, times)
        out["em"].append(e)
        out["em_iter"].append(mk.n_iter.sum(axis=1))
        out["em_flags"].append(
            np.stack([sw, (~fit.valid).any(axis=1), mk.cap_hit.any(axis=1), (~mk.valid).any(axis=(1, 2))], axis=1)
        )
    if "q" in algs:
        t0 = time.perf_counter()
        mk = em_marks(b.counts, b.designation, times, s, p, p0, **mark_args)
        timing["em_plain"] += time.perf_counter() - t0
        out["em_plain_iter"].append(mk.n_iter.sum(axis=1))
        out["em_plain_cap"].append(mk.cap_hit.any(axis=1))
    if "c" in algs:
        t0 = time.perf_counter()
        mk = centre_of_region_marks(
            b.counts, propagate(b.designation, times), centre_gate_half_px(s_.gate_half_sigma, s)
        )
        fit = fit_lines(mk, times, b.designation)
        timing["cr"] += time.perf_counter() - t0
        e, sw = errors_vs_truth(fit.theta, b.truth, s, times)
        out["cr"].append(e)
        out["cr_flags"].append(np.stack([sw, (~fit.valid).any(axis=1)], axis=1))


def _run_extras(x, out: dict) -> None:
    """The studies beyond the comparison on one block of scenes: ``k`` (the ML ULA given the designated
    velocity), ``1`` (one track fitted to the pair), ``w`` (weights and sigma estimated), ``s`` (multi-start
    gap) and ``b`` (BIC orders)."""
    s_, cfg, b, ent, s, p, p0, tol, accel, times = x.s_, x.cfg, x.b, x.ent, x.s, x.p, x.p0, x.tol, x.accel, x.times
    algs = cfg.algs
    q, m, vsd = cfg.q, cfg.m, cfg.vsd
    g, noise_pp, block = x.g, x.noise_pp, x.block

    def em(designation, p_, p0_, **options):
        return unified_location_em(ent, designation, s, p_, p0_, tol_px=tol, max_iter=s_.max_iter, **options)

    if "k" in algs:  # the ML ULA given the designated velocity (its error vsd as the only prior)
        r = em(b.designation, p, p0, accelerate=accel, prior_sd=(1e6 * s, vsd * s))
        out["ula_vd"].append(errors_vs_truth(r.theta, b.truth, s, times)[0])
    if "1" in algs:  # the wrong number of objects: one track fitted to the pair (a study beyond the paper)
        p1, p01 = mixture_weights(q * m, noise_pp, g.n_pixels, 1)
        r = em(b.designation.mean(axis=1, keepdims=True), p1, p01, accelerate=accel)
        out["ula_q1"].append((r.theta - b.truth.mean(axis=1, keepdims=True)) / s)
    if "w" in algs:
        r = em(b.designation, p, p0, estimate_weights=True, estimate_sigma=True)
        out["ula_w"].append(errors_vs_truth(r.theta, b.truth, s, times)[0])
    if "s" in algs:
        ms_rng = np.random.default_rng(seed_sequence(block, scene_key(cfg) + ("ms",)))
        out["ms_gap"].append(multi_start_gap(ent, b.designation, s, p, p0, tol, s_.max_iter, accel, ms_rng))
    if "b" in algs:
        out["bic"].append(bic_orders(s_, ent, b.designation, s, m, noise_pp, g.n_pixels))


def _bounds(s_: StudySettings, cfg: Config, g, times, noise_pp: float) -> dict:
    """The bounds of one configuration (letter ``r``; sigma^2): ``crb_pos`` / ``crb_vel`` (trace of the position /
    velocity block of the CRB, averaged over the sub-pixel phase), ``crb_x0`` (the bound on x_o of the first object
    alone) and ``bcrb_pos`` / ``bcrb_vel`` (the van Trees bound with the designation as the positions' prior)."""
    q, m, dsd, s = cfg.q, cfg.m, cfg.dsd, g.sigma_px
    res = {}
    # CRB averaged over the sub-pixel phase (the Monte Carlo averages over it too)
    th = draw_truth(np.random.default_rng(seed_sequence(s_.seed, scene_key(cfg) + ("crb",))), s_.crb_phases, g)
    fim = fisher_linear_motion(th, times, g.shape, s, m, noise_pp)
    crb = crb_from_fisher(fim)
    # van Trees (Bayesian) bound with the designation as the prior of the initial positions (velocity free): it
    # holds for biased estimators too, e.g. ones that stay near their start where the pixels cannot resolve
    jp = np.zeros(4 * q)
    jp[np.arange(4 * q) % 4 < 2] = 1.0 / max(dsd * s, 1e-9) ** 2
    bcrb = np.linalg.inv(fim.mean(axis=0) + np.diag(jp))
    bd = np.diagonal(bcrb).reshape(q, 4)
    res["bcrb_pos"] = float(bd[:, :2].sum()) / s**2
    res["bcrb_vel"] = float(bd[:, 2:].sum()) / s**2
    res["crb_pos"] = float(np.mean(position_crb_sum(crb))) / s**2
    diag = np.diagonal(crb, axis1=-2, axis2=-1).reshape(-1, q, 4)
    res["crb_vel"] = float(np.mean(diag[..., 2:].sum(axis=(1, 2)))) / s**2
    res["crb_x0"] = float(np.mean(diag[:, 0, 0])) / s**2
    return res
