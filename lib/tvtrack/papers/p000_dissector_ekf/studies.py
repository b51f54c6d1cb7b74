"""The study drivers behind paper 000's figures (Martyshevsky 1995): Fig. 1, acquisition against the signed initial
offset, Fig. 3 of both variants, the filters' consistency, and the studies beyond the claims (the centroid baseline,
the grid filter over psi_A and P, the T_u and beta_0 sensitivity, the mismatched filter over P).

Every function reads a register configuration and a seed (common random numbers with :func:`.study.measure`, whose
memoised filter runs it reuses) and returns arrays or :class:`~tvtrack.montecarlo.Estimate` values; times in T,
variances in T^2.
"""

from __future__ import annotations

import numpy as np

from ...montecarlo import mean_square_ci, quantile_ci
from ...counts import proportion_ci
from .ekf import consistency, variant1_filter, variant2_filter
from .reference import pcrlb_variance
from .study import (
    BETA_0,
    D11_0,
    D22_0,
    acquired_at,
    filter_errors,
    cfg_message,
    truth_paths,
    phase_nodes,
    ratio_to_star,
    photon_samples,
    operating_scan,
    switch_on_phases,
    bound_time,
    psi_at,
    steady_runs,
)
from .sizes import Sizes

__all__ = ["fig1_curves", "acquisition_vs_offset", "pull_in_range", "consistency_over_psi", "fig3_curves"]


def fig1_curves(config: dict, seed: int, sizes: Sizes) -> dict:
    """Fig. 1: ensemble sigma_x^2(t) of both variants from both initial estimates, the filters' mean D11 and the
    PCRLB, at the configuration's psi_A and contrast. Arrays of shape (n_steps + 1,), T^2."""
    out = {}
    for filt in ("v1", "v2"):
        for init in ("process means", "random N(0, D11(0))"):
            run = filter_errors(config, seed, sizes, config["psi_A"], config["contrast"], filt, init=init)
            out[f"{filt}, {init}"] = run["curve"]
            if init == "process means":
                out[f"{filt} own D11"] = run["d_curve"]
    scan = operating_scan(config, config["psi_A"], config["contrast"], sizes)
    out["PCRLB"] = pcrlb_variance(scan, cfg_message(config), sizes.n_steps, bound_time(config), phase_nodes(sizes))
    return out


def acquisition_vs_offset(config: dict, seed: int, sizes: Sizes, offsets) -> dict:
    """Acquisition against the truth's initial offset X1(0) (T), both variants from the paper's start estimate.

    Returns
    -------
    dict  per variant: ``q90`` (Estimates of the 90 % acquisition time, T; not acquired counts as 2 x duration),
    ``late`` (proportion Estimates of runs not acquired by ``acquire_by_T``) and ``lost`` (fraction of runs out
    of lock at the end of the run), one per offset
    """
    out = {}
    for filt in ("v1", "v2"):
        q90, late, lost = [], [], []
        for off in offsets:
            run = filter_errors(config, seed, sizes, config["psi_A"], config["contrast"], filt, offset=float(off))
            t = acquired_at(config, seed, sizes, filt, run)
            q90.append(quantile_ci(np.where(np.isfinite(t), t, 2 * sizes.duration_T), 0.9))
            late.append(proportion_ci(int(np.sum(t > sizes.acquire_by_T + 1e-9)), t.size))
            lost.append(float(np.mean(~np.isfinite(t))))
        out[filt] = {"q90": q90, "late": late, "lost": lost}
    return out


def consistency_over_psi(config: dict, seed: int, sizes: Sizes) -> dict:
    """Mean steady-state NEES of both variants over the Fig. 2 SNRs, with the truth scored at the interval centre
    (the time the filters' model of a sample refers to) and at its end: 1 for a filter whose D11 describes its error.

    Returns
    -------
    dict  {scoring time: {"variant 1" | "variant 2": [Estimate per psi_A]}}
    """
    out = {}
    for scoring in ("interval centre", "interval end"):
        cfg = {**config, "scoring time": scoring}
        x, pulse, xi, _ = truth_paths(cfg, seed, sizes)
        out[scoring] = {}
        for name in ("v1", "v2"):
            ests = []
            for psi in sizes.psi_grid:
                scan = operating_scan(cfg, psi, cfg["contrast"], sizes)
                y = photon_samples(cfg, seed, scan, pulse, xi)
                phi = switch_on_phases(seed, sizes)
                if name == "v1":
                    filt = variant1_filter(scan, cfg_message(cfg), BETA_0, "consistent", cfg["G22"], phi)
                    d0 = (D11_0, D22_0)
                else:
                    iterations = 1 if cfg["v2 noise at"] == "updated estimate" else 0
                    filt, d0 = variant2_filter(scan, cfg_message(cfg), None, iterations, phi), D11_0
                nees, _ = consistency(filt, y, x, d0, sizes.window())
                ests.append(mean_square_ci(nees))
            out[scoring][f"variant {name[1]}"] = ests
    return out


def pull_in_range(offsets, acq: dict, limit: float = 0.1) -> dict:
    """The pull-in range on each side of the filters' start: walking outward from the smallest offset of each sign,
    the largest offset (T) from which the share of runs not in lock by ``acquire_by_T`` is at most ``limit`` (its
    whole 95 % interval), before the first offset where it is not.

    Returns
    -------
    dict  per variant: ``{"negative": offset or None, "positive": offset or None}`` (None: not even the nearest
    offset on that side)
    """
    offsets = np.asarray(offsets, dtype=float)
    out = {}
    for name, a in acq.items():
        sides = {}
        for side, sign in (("negative", -1.0), ("positive", 1.0)):
            idx = [i for i in np.argsort(sign * offsets) if sign * offsets[i] > 0 or (offsets[i] == 0)]
            edge = None
            for i in idx:
                if a["late"][i].ci_high > limit:
                    break
                edge = float(offsets[i])
            sides[side] = edge
        out[name] = sides
    return out


def fig3_curves(config: dict, seed: int, sizes: Sizes) -> dict:
    """Fig. 3 of both variants over the contrast grid (psi_A from the configuration's contrast convention).

    Returns
    -------
    dict  ``sigma_x^2`` {variant: [Estimate per P]} steady error variance (T^2); ``ratio`` {variant: [Estimate]}
    sigma_x^2 / sigma_x^2* paired on the same runs; ``sigma_x^2*`` [Estimate] the stationary-noise variance;
    ``PCRLB`` [float] the steady posterior Cramer-Rao bound (T^2, the mean over the steady window)
    """
    out = {"sigma_x^2": {}, "ratio": {}, "sigma_x^2*": [], "PCRLB": []}
    psis = [psi_at(config["psi_A"], p, config["contrast convention"]) for p in sizes.contrast_grid]
    for filt in ("v1", "v2"):
        v = f"variant {filt[1]}"
        out["sigma_x^2"][v] = [
            mean_square_ci(steady_runs(config, seed, sizes, s, p, filt)) for s, p in zip(psis, sizes.contrast_grid)
        ]
        out["ratio"][v] = [ratio_to_star(config, seed, sizes, p, filt) for p in sizes.contrast_grid]
    for s, p in zip(psis, sizes.contrast_grid):
        out["sigma_x^2*"].append(mean_square_ci(steady_runs(config, seed, sizes, s, p, "stationary")))
        scan = operating_scan(config, s, p, sizes)
        bound = pcrlb_variance(scan, cfg_message(config), sizes.n_steps, bound_time(config), phase_nodes(sizes))
        out["PCRLB"].append(float(bound[sizes.window()].mean()))
    return out
