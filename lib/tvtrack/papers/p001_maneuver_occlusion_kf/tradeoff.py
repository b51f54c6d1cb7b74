"""C001-4 read as Fisenko et al. (2008) write it: the switch "sped up the transient of the dynamic error and
minimised the RMS (СКО) error", two errors the paper keeps apart (Fig. 4's curves 1 and 2 too).

* The **dynamic error** is the non-random part of the position error, its mean over runs at each frame; the part
  ``faster compensation`` compares its mean square from the onset to ``compensation_end_s`` (the compensation
  comparator's over the scheme's).
* The **RMS** the gain law minimises is read by the register entry ``rms_statistic``: the random error (the SD over
  runs at each frame, mean square over ``rms_span``; the paper's СКО, default), the total mean square over the
  span (bias and random together; the earlier reading), or ``|bias| + RMS at 12 s``, the acceptance first set here
  (at the last frame before the loss). Each ``min RMS vs <comparator>`` part is the comparator's value over the
  scheme's.

Every ratio is of functionals of the per-frame mean and second moment over runs, so its interval is the core's
paired bootstrap of column means over runs (:func:`tvtrack.montecarlo.means_bootstrap`: the same resampled runs for
both filters).
"""

from __future__ import annotations

import functools

import numpy as np

from ...estimate import Estimate
from ...montecarlo import means_bootstrap
from .comparators import comparator_tuning, comparator_positions, compensation_comparator
from .scenario import (
    COMPARATORS,
    COMPENSATION_COMPARATORS,
    with_defaults,
    config_scenario,
    measurements,
    run_scheme,
    span_mask,
)

__all__ = [
    "RMS_STATISTICS",
    "error_functional",
    "paired_functional_ratio",
    "measure_tradeoff",
    "switch_share",
    "span_caveat",
    "comparators_caption",
]

#: Readings of "the gain law minimises the RMS error" (register entry ``rms_statistic``).
RMS_STATISTICS = ("random error (SD)", "total mean square", "|bias| + RMS at 12 s")
N_BOOT = 400


def error_functional(m1, m2, kind: str) -> np.ndarray:
    """A statistic of the error from its per-column mean ``m1`` and second moment ``m2`` over runs (..., columns).

    ``"bias²"``: mean over columns of m1² (elements²); ``"random"``: mean of the variance m2 - m1²; ``"total"``:
    mean of m2; ``"|bias| + SD"``: mean over columns of |m1| + sqrt(m2 - m1²) (elements)."""
    var = np.maximum(m2 - m1**2, 0.0)
    if kind == "bias²":
        return np.mean(m1**2, axis=-1)
    if kind == "random":
        return np.mean(var, axis=-1)
    if kind == "total":
        return np.mean(m2, axis=-1)
    if kind == "|bias| + SD":
        return np.mean(np.abs(m1) + np.sqrt(var), axis=-1)
    raise ValueError(f"error functional {kind!r}")


def paired_functional_ratio(err_a, err_b, kind: str, rng: np.random.Generator, n_boot: int = N_BOOT) -> Estimate:
    """``f(err_a) / f(err_b)`` for the functional ``kind`` of :func:`error_functional`, with the core's paired
    bootstrap over runs (:func:`tvtrack.montecarlo.means_bootstrap`: each functional reads the column means of the
    errors and of their squares).

    Parameters
    ----------
    err_a, err_b : ndarray, shape (runs, columns)
        Position errors (elements) of two filters on the same runs; columns are the frames x channels judged.
    """
    a, b = np.asarray(err_a, float), np.asarray(err_b, float)

    def ratio(m1a, m2a, m1b, m2b):
        return error_functional(m1a, m2a, kind) / error_functional(m1b, m2b, kind)

    return means_bootstrap([a, a**2, b, b**2], ratio, rng=rng, n_resamples=n_boot)


def _columns(err, frames) -> np.ndarray:
    """(runs, 2, T) errors -> (runs, 2 x frames) at the selected frames (channels pooled)."""
    return err[..., frames].reshape(err.shape[0], -1)


def measure_tradeoff(config: dict, seed: int, sizes: dict) -> dict:
    """C001-4 in parts (module docstring): ``faster compensation`` and ``min RMS vs <comparator>`` for every
    comparator of :data:`~.scenario.COMPARATORS`, each tuned for the register's span (for ``|bias| + RMS at 12 s``: for
    the mean square at the last frame before the loss). Ratios > 1: the scheme's error is the smaller.

    Config entries read: ``rms_span``, ``rms_statistic``, ``compensation_end_s``, ``compensation_comparator``,
    ``noise``, ``manoeuvre``, ``frame_rate_hz``, ``C001-4 switch`` (with ``switch_s`` when forced) and the scheme's
    entries (:func:`~.scenario.run_scheme`).
    """
    config = with_defaults(config, sizes)
    sc = config_scenario(config)
    sigma, n = sizes["sigma_eps"], sizes["n_tradeoff_trials"]
    z = measurements(sc.truth[:, :, 0], config["noise"], n, np.random.default_rng(seed), sigma)
    truth = sc.truth[None, :, :, 0]
    boot_rng = np.random.default_rng([seed, 4])
    scheme = run_scheme(z, sc, config, sizes, covariance=False, **_switch(config, sc))
    err_s = scheme.x[..., 0] - truth
    comp = config.get("compensation_comparator", COMPENSATION_COMPARATORS[0])
    err_c = compensation_comparator(comp, z, sc, config, sizes, scheme.detection_frame) - truth
    f = sc.frames
    comp_frames = (f >= sc.onset) & (f < int(round(float(config["compensation_end_s"]) * sc.fps)))
    parts = {
        "faster compensation": paired_functional_ratio(
            _columns(err_c, comp_frames), _columns(err_s, comp_frames), "bias²", boot_rng
        )
    }
    stat = config.get("rms_statistic", RMS_STATISTICS[0])
    if stat == "|bias| + RMS at 12 s":
        span, kind = "last frame before the loss", "|bias| + SD"
    else:
        span, kind = config["rms_span"], {"random error (SD)": "random", "total mean square": "total"}[stat]
    frames = span_mask(span, sc)
    tuning = comparator_tuning(config, sizes)[span]
    # the comparators run on the configuration's own scenario (the scheme's truth): its frame rate, manoeuvre,
    # acceleration unit and second channel
    world = tuple(config.get(k, d) for k, d in _WORLD)
    for name in COMPARATORS:
        err = _comparator_errors(
            name, tuning[name][0], seed, config["noise"], float(config["frame_rate_hz"]), n, sigma, world
        )
        parts[f"min RMS vs {name}"] = paired_functional_ratio(
            _columns(err, frames), _columns(err_s, frames), kind, boot_rng
        )
    return {"C001-4": parts}


def switch_share(config: dict, seed: int, sizes: dict) -> dict:
    """How much of the scheme's random error C001-4 reads is the spread of the detection time.

    On the runs of :func:`measure_tradeoff` (same seed, same draws), the scheme with its detector's switch and with
    the switch forced at ``switch_s`` (the paper's 5.5 s, as Fig. 4 is computed): the ratio of their random errors
    (mean over the RMS span of the variance over runs, forced over detected, paired bootstrap) and
    ``share = 1 - ratio``, the part of the detected scheme's random mean square that the detection time's spread
    adds (the rest is the gain law's).

    Returns
    -------
    dict
        ``{"forced / detected": Estimate, "share": float}`` (dimensionless).
    """
    config = with_defaults(config, sizes)
    sc = config_scenario(config)
    z = measurements(
        sc.truth[:, :, 0], config["noise"], sizes["n_tradeoff_trials"], np.random.default_rng(seed), sizes["sigma_eps"]
    )
    truth = sc.truth[None, :, :, 0]
    frames = span_mask(config["rms_span"], sc)
    errs = [
        _columns(
            run_scheme(z, sc, config, sizes, covariance=False, **_switch(config | {"C001-4 switch": r}, sc)).x[..., 0]
            - truth,
            frames,
        )
        for r in ("forced at the detection time", "detected")
    ]
    ratio = paired_functional_ratio(*errs, "random", np.random.default_rng([seed, 5]))
    return {"forced / detected": ratio, "share": 1.0 - ratio.value}


def _switch(config: dict, sc) -> dict:
    """The scheme's switch under the reading ``C001-4 switch``: when its detector fires (``{}``), or forced at
    ``switch_s`` (the paper's detection time, 5.5 s), as Fig. 4 is computed here (:func:`.curves.forced_output`)."""
    if config.get("C001-4 switch", "detected") == "detected":
        return {}
    return {"force_switch_k": int(round(float(config["switch_s"]) * sc.fps)) + 1}


#: The scenario entries besides the frame rate (:func:`~.scenario.config_scenario`) with their defaults.
_WORLD = (("manoeuvre", "constant acceleration"), ("accel_unit", "el/frame²"), ("channel_y", "v -6, a -0.2"))


@functools.lru_cache(maxsize=64)
def _comparator_errors(name, setting, seed, noise, frame_rate_hz, n, sigma_eps, world) -> np.ndarray:
    """Position errors (runs, 2, T) of a tuned comparator on the test runs of ``seed`` (the draws of
    :func:`measure_tradeoff`), cached: the scheme's own entries (restart, k_b3 ...) do not change them. ``world``:
    the values of the scenario entries ``_WORLD`` (the same truth as the scheme's)."""
    sc = config_scenario({"frame_rate_hz": frame_rate_hz} | {k: v for (k, _), v in zip(_WORLD, world)})
    z = measurements(sc.truth[:, :, 0], noise, n, np.random.default_rng(seed), sigma_eps)
    return comparator_positions(name, setting, z, sc, sigma_eps) - sc.truth[None, :, :, 0]


def span_caveat(register) -> str:
    """C001-4's caveat: the span its minimum-RMS parts are taken over (the rule's "C001-4's RMS span"),
    in the register's words at its default, set apart from the compensation interval of its faster-compensation
    part (entries ``rms_span`` and ``compensation_end_s``)."""
    span, end = register["rms_span"], register["compensation_end_s"]
    return (
        f"C001-4's RMS span, over which its minimum-RMS parts are taken, is "
        f"{span.phrase(span.default)} at this run's default, not the interval its faster-compensation part "
        f"scores ({end.phrase(end.default)})"
    )


def comparators_caption(register) -> str:
    """The caption of C001-4's comparators figure: panel (a)'s RMS over runs includes the bias (dynamic error),
    panel (b)'s minimum-RMS ratios use the register's default RMS statistic, said in its words."""
    stat, span = register["rms_statistic"], register["rms_span"]
    return (
        "C001-4: (a) position RMS error over time (both channels; the root mean square over runs of the error, "
        "dynamic error (bias) and random error together) of the scheme, the 2nd-order filter without the switch "
        "and every tuned comparator; (b) each part's ratio, the comparator's error over the scheme's, pooled over "
        "the replicates with 95 % intervals: for the faster compensation the dynamic error's mean square, for the "
        f"minimum-RMS parts the register's default statistic ({stat.phrase(stat.default)}; "
        f"{span.phrase(span.default)}), not panel (a)'s RMS."
    )
