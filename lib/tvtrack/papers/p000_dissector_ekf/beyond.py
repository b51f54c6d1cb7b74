"""Studies of paper 000 beyond its claims (the notebook's section 9, "Beyond the paper"): the classical centroid
tracker the introduction criticises, the near-optimal grid filter over psi_A and P (what the EKF approximation
costs), the sensitivity to the pulse duration T_u and to beta_0, and the filter that ignores the signal noise over P.

Every function reads a register configuration and a seed, draws from ``numpy.random.default_rng(seed)`` through
:func:`.study.truth_paths` (common random numbers with the claims, whose memoised runs it reuses) and returns
:class:`~tvtrack.montecarlo.Estimate` values; variances in T^2, times in T.
"""

from __future__ import annotations

import numpy as np

from ...estimate import Estimate
from ...montecarlo import mean_square_ci, ratio_ci
from .baseline import fixed_gain_track, scan_centroids, tune_fixed_gain
from .cost import run_steps_variant1, run_steps_variant2
from .model import scan_at_snr, truth_and_pulse
from .lock_loss import keep_pair
from .reference import grid_filter
from .study import (
    BETA_0,
    D11_0,
    D22_0,
    common_draws,
    cfg_message,
    truth_paths,
    photon_samples,
    operating_scan,
    switch_on_phases,
    steady_runs,
)
from .sizes import Sizes

__all__ = ["centroid_baseline", "grid_over_points", "pulse_and_beta", "mismatched_over_contrast"]

#: Gains the fixed-gain smoother of the centroid baseline is tuned over (least squares on the training half).
GAINS = np.linspace(0.05, 1.0, 20)


def centroid_baseline(config: dict, seed: int, sizes: Sizes) -> dict:
    """The classical tracker (a per-scan centroid discriminator and a least-squares-tuned fixed-gain smoother,
    :mod:`.baseline`) against variant 2 over the Fig. 2 SNRs at the configuration's contrast.

    The gain is tuned on the first half of the runs and both trackers are scored on the second half, at the scan
    ends (the baseline's one estimate per scan) of the steady window.

    Returns
    -------
    dict  ``baseline`` and ``variant 2`` [Estimate per psi_A] steady mean squared error at the scan ends (T^2);
    ``ratio`` [Estimate] baseline / variant 2 on the same runs (those in lock by both, inside :func:`.lock_loss.in_lock`)
    """
    x, pulse, xi, _ = truth_paths(config, seed, sizes)
    per_scan, half = sizes.steps_per_scan, sizes.n_trials // 2
    n_scans = sizes.n_steps // per_scan
    ends = per_scan * np.arange(1, n_scans + 1)
    steady = ends * sizes.dt > sizes.duration_T - sizes.window_T
    f = float(np.exp(-cfg_message(config).alpha))  # the message's transition over one scan
    out = {"baseline": [], "variant 2": [], "ratio": []}
    phi = switch_on_phases(seed, sizes)
    for psi in sizes.psi_grid:
        scan = operating_scan(config, psi, config["contrast"], sizes)
        y = photon_samples(config, seed, scan, pulse, xi)
        z = scan_centroids(scan, y, phi)
        truth = x[:, ends]
        gain = tune_fixed_gain(z[:half], truth[:half], f, GAINS, steady)
        base = ((fixed_gain_track(z[half:], f, gain) - truth[half:]) ** 2)[:, steady].mean(axis=1)
        est = run_steps_variant2(scan, cfg_message(config), y[half:], D11_0, start=phi[half:])[0]
        v2 = ((est[:, ends] - truth[half:]) ** 2)[:, steady].mean(axis=1)
        out["baseline"].append(mean_square_ci(base))
        out["variant 2"].append(mean_square_ci(v2))
        out["ratio"].append(ratio_ci(*keep_pair(base, v2)))  # only the runs in lock inside lock_loss.in_lock
    return out


def grid_over_points(config: dict, seed: int, sizes: Sizes, psis, contrasts) -> dict:
    """Variant 2 over the near-optimal grid (point-mass) filter on the same ``sizes.grid_trials`` runs: over
    ``psis`` at the configuration's contrast and over ``contrasts`` at its psi_A (the cost of the EKF's Gaussian
    approximation).

    Returns
    -------
    dict  ``over psi_A`` and ``over P``: [Estimate] steady variance of variant 2 / of the grid filter (paired)
    """
    x, pulse, xi, _ = truth_paths(config, seed, sizes)
    m, message = min(sizes.grid_trials, sizes.n_trials), cfg_message(config)
    window = sizes.window()

    def ratio(psi, p):
        scan = operating_scan(config, psi, p, sizes)
        y = photon_samples(config, seed, scan, pulse, xi)[:m]
        g = grid_filter(scan, message, 0.5, sizes.grid_points, switch_on_phases(seed, sizes)[:m]).run(
            y, 0.0, message.sigma**2
        )
        g = g.mean
        grid = ((x[:m] - g) ** 2)[:, window].mean(axis=1)
        return ratio_ci(steady_runs(config, seed, sizes, psi, p, "v2")[:m], grid)

    return {
        "over psi_A": [ratio(psi, config["contrast"]) for psi in psis],
        "over P": [ratio(config["psi_A"], p) for p in contrasts],
    }


def pulse_and_beta(config: dict, seed: int, sizes: Sizes, durations, betas, contrast: float = 0.9) -> dict:
    """Sensitivity at the configuration's psi_A and ``contrast``: both variants' sigma_x^2 / sigma_x^2* for each
    pulse duration T_u (T; sigma_x^2* at the same T_u), and variant 1's for each beta_0 (1/T) at the paper's T_u.

    Returns
    -------
    dict  ``T_u`` {variant: [Estimate per duration]}; ``beta_0`` [Estimate per beta] (variant 1)
    """
    noises, phi = common_draws(seed, sizes), switch_on_phases(seed, sizes)
    score = "interval_centre" if config["scoring time"] == "interval centre" else "interval_end"
    message, window = cfg_message(config), sizes.window()
    sig = "per_sample" if config["sigma_sh"] == "per sample" else "unit_bandwidth"

    def runs(tu):
        geometry = scan_at_snr(1.0, 0.0, sizes.dt, tu)
        x, pulse = truth_and_pulse(geometry, message, noises, config["sample model"], score, None, phi)

        def steady(p, filt, beta=BETA_0):
            scan = scan_at_snr(config["psi_A"], p, sizes.dt, tu, sig)
            y = photon_samples(config, seed, scan, pulse, noises["xi"])
            if filt == "v1":
                e = run_steps_variant1(scan, message, y, (D11_0, D22_0), None, beta, config["G22"], start=phi)[0]
            else:
                e = run_steps_variant2(scan, message, y, D11_0, start=phi)[0]
            return ((x - e) ** 2)[:, window].mean(axis=1)

        return steady

    out = {"T_u": {"variant 1": [], "variant 2": []}, "beta_0": []}
    for tu in durations:
        steady = runs(tu)
        star = steady(0.0, "v2")
        for filt in ("v1", "v2"):
            out["T_u"][f"variant {filt[1]}"].append(ratio_ci(steady(contrast, filt), star))
    steady = runs(0.5)
    star = steady(0.0, "v2")
    out["beta_0"] = [ratio_ci(steady(contrast, "v1", beta), star) for beta in betas]
    return out


def mismatched_over_contrast(config: dict, seed: int, sizes: Sizes) -> dict:
    """The filter that ignores the signal noise (variant 2 assuming P = 0) over the matched variant 2, and over
    sigma_x^2*, at each contrast of the Fig. 3 grid (the configuration's psi_A, fixed N0), paired on the same runs.

    Returns
    -------
    dict  ``mismatched / matched`` and ``mismatched / sigma_x^2*``: [Estimate per P] (1 at P = 0, exactly)
    """
    out = {"mismatched / matched": [], "mismatched / sigma_x^2*": []}
    psi = config["psi_A"]
    for p in sizes.contrast_grid:
        ign = steady_runs(config, seed, sizes, psi, p, "ignoring")
        for key, ref in (("mismatched / matched", "v2"), ("mismatched / sigma_x^2*", "stationary")):
            b = steady_runs(config, seed, sizes, psi, p, ref)
            same = np.allclose(ign, b, rtol=1e-9, atol=0.0)
            out[key].append(Estimate(1.0, 0.0, 1.0, 1.0, ign.size, 0.95, "exact") if same else ratio_ci(ign, b))
    return out
