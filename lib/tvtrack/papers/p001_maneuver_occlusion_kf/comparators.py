"""C001-4's comparators (Fisenko et al. 2008 compared with textbook filters): fixed 2nd- and 3rd-order filters, the
IMM and the variable-dimension filter, each tuned on its own training runs, and the 2nd-order filter whose gains
are raised at the detection.
"""

from __future__ import annotations

import functools
import itertools

import numpy as np

from ...filters.alphabeta import gain_schedule, scheduled_filter
from ...filters._imm_kernel import imm_states
from ...filters.imm import cv_ca_models
from ...filters.vdf import vd_filter_run
from .scenario import (
    TUNING_SPANS,
    COMPENSATION_COMPARATORS,
    RAISED2_GRID,
    COMPARATORS,
    FIXED2_GRID,
    FIXED3_GRID,
    IMM_Q_CA_GRID,
    IMM_P_STAY_GRID,
    VDF_Q_CA_GRID,
    VDF_WINDOWS,
    FLOORS,
    Scenario,
    config_scenario,
    measurements,
    span_mask,
    run_scheme,
)

__all__ = [
    "comparator_tuning",
    "comparator_positions",
    "tuned_comparators",
    "compensation_bias2",
    "raised_second_order",
    "compensation_comparator",
]


def _imm(z, sc, q_ca, p_stay, coast, sigma) -> np.ndarray:
    """Combined posterior states (..., T, 3) of the CV/CA IMM on the visible measurements: the compiled twin of
    :func:`tvtrack.filters.imm.imm_run` (:mod:`tvtrack.filters._imm_kernel`, 16 times faster, equal to rounding),
    or ``imm_run`` itself without numba."""
    Fs, Qs = cv_ca_models(0.0, q_ca)
    M = np.array([[p_stay, 1 - p_stay], [1 - p_stay, p_stay]])
    zz = np.where(sc.visible, z, np.nan)
    return imm_states(zz, Fs, Qs, sigma**2, M, np.zeros(3), np.diag([1e6, 1e4, 1.0]), [0.5, 0.5], coast=coast)


def comparator_positions(name: str, setting: tuple, z, sc: Scenario, sigma: float) -> np.ndarray:
    """Position estimates (..., T) of one comparator at one setting (its tuned parameters).

    ``"fixed 2nd order"`` / ``"fixed 3rd order"``: ``(k_b,)``, the growing-memory law frozen at ``k_b``, coasting
    while lost; ``"IMM"``: ``(q_ca, p_stay, coast)``, CV/CA with ``q_CV = 0`` (the CV model has no process noise,
    like the paper's TRACK2; 0 is its physical floor, not a grid edge); ``"VD filter"``: ``(q_ca, window,
    threshold)``.
    """
    if name in ("fixed 2nd order", "fixed 3rd order"):
        order = 1 if name == "fixed 2nd order" else 2
        return scheduled_filter(np.where(sc.visible, z, np.nan), gain_schedule(order, int(setting[0]), sc.T))[..., 0]
    if name == "IMM":
        return _imm(z, sc, setting[0], setting[1], setting[2], sigma)[..., 0]
    if name == "VD filter":
        return vd_filter_run(z, sc.visible, 0.0, setting[0], sigma, int(setting[1]), setting[2]).x[..., 0]
    raise ValueError(f"comparator {name!r}; it must be one of {COMPARATORS}")


def _span_ms(xhat, sc: Scenario, channel_truth) -> dict:
    e2 = (xhat - channel_truth) ** 2
    return {span: e2[..., span_mask(span, sc)].mean(axis=(-1, -2)) for span in TUNING_SPANS}


@functools.lru_cache(maxsize=64)
def tuned_comparators(
    frame_rate_hz: float,
    n_train: int,
    train_seed: int,
    alpha: float,
    sigma_eps: float = 1.0,
    grids: tuple = (),
    manoeuvre: str = "constant acceleration",
    accel_unit: str = "el/frame²",
    channel_y: str = "v -6, a -0.2",
) -> dict:
    """Each comparator tuned on ``n_train`` training runs of the scenario with white Gaussian errors (their own
    seed, never the test runs) for the lowest position RMS over each span:
    ``{span: {comparator: (setting, training RMS, on_edge)}}``.

    The same effort for every comparator: a grid over its parameters (``FIXED2_GRID``, ``FIXED3_GRID``,
    ``IMM_Q_CA_GRID`` x ``IMM_P_STAY_GRID`` and the best of three ways to coast, ``VDF_Q_CA_GRID`` x
    ``VDF_WINDOWS``; ``grids`` overrides them: pairs (name, values) with names ``fixed2``, ``fixed3``,
    ``imm_q_ca``, ``imm_p_stay``, ``vdf_q_ca``, ``vdf_windows``); ``on_edge`` flags an optimum on a grid edge that is not a physical floor (``FLOORS``).
    Like the paper's scheme, whose thresholds assume white Gaussian errors, the comparators are tuned once for
    white Gaussian errors and then face every measurement-error model untuned. The VD filter's threshold is the
    ``1 - alpha`` quantile of its statistic before the onset (per-test rate alpha, as the paper's detector).

    The scores are cached by exactly what they read: the fixed filters' and the IMM's by the training
    world (frame rate, manoeuvre, acceleration unit, second channel, training runs, grids), the VD filter's by
    that and ``alpha`` (its threshold), its no-detection statistic by the world alone; so configurations that
    differ in alpha, or in entries the tuning never reads, reuse the grid runs (tested equal to a cold run).
    """
    g = _grids(grids)
    world = (float(frame_rate_hz), int(n_train), int(train_seed), float(sigma_eps), manoeuvre, accel_unit, channel_y)
    scores = dict(_scores_without_alpha(world, grids))
    scores["VD filter"] = _scores_vd(world, grids, float(alpha))
    out = {}
    for span in TUNING_SPANS:
        out[span] = {}
        for name, sc_ in scores.items():
            best = min(sc_, key=lambda st: sc_[st][span])
            out[span][name] = (best, float(np.sqrt(sc_[best][span])), _on_edge(name, best, g))
    return out


def _grids(grids: tuple) -> dict:
    return {
        "fixed2": FIXED2_GRID,
        "fixed3": FIXED3_GRID,
        "imm_q_ca": IMM_Q_CA_GRID,
        "imm_p_stay": IMM_P_STAY_GRID,
        "vdf_q_ca": VDF_Q_CA_GRID,
        "vdf_windows": VDF_WINDOWS,
    } | dict(grids)


@functools.lru_cache(maxsize=32)
def _training(world: tuple):
    """The training scenario, measurements (n_train, 2, T) and truth (1, 2, T) of a world
    ``(frame_rate_hz, n_train, train_seed, sigma_eps, manoeuvre, accel_unit, channel_y)``."""
    fps, n_train, train_seed, sigma_eps, manoeuvre, accel_unit, channel_y = world
    sc = config_scenario(
        {"frame_rate_hz": fps, "manoeuvre": manoeuvre, "accel_unit": accel_unit, "channel_y": channel_y}
    )
    z = measurements(sc.truth[:, :, 0], "white Gaussian", n_train, np.random.default_rng(train_seed), sigma_eps)
    z.flags.writeable = False
    return sc, z, sc.truth[None, :, :, 0]


def _score(world: tuple, name: str, setting: tuple) -> dict:
    """Training mean-square position error of one comparator setting over each tuning span."""
    sc, z, truth = _training(world)
    xhat = comparator_positions(name, setting, z, sc, world[3])
    return {k: float(v.mean()) for k, v in _span_ms(xhat, sc, truth).items()}


@functools.lru_cache(maxsize=32)
def _scores_without_alpha(world: tuple, grids: tuple) -> dict:
    """``{comparator: {setting: {span: training mean square}}}`` of the fixed filters and the IMM (their grids do
    not read alpha); the IMM's best settings also with the two other ways to coast."""
    g = _grids(grids)
    cand = {"fixed 2nd order": [(kb,) for kb in g["fixed2"]], "fixed 3rd order": [(kb,) for kb in g["fixed3"]]}
    cand["IMM"] = [(q, p, "mix") for q, p in itertools.product(g["imm_q_ca"], g["imm_p_stay"])]
    scores = {name: {st: _score(world, name, st) for st in settings} for name, settings in cand.items()}
    best = [min(scores["IMM"], key=lambda st: scores["IMM"][st][span]) for span in TUNING_SPANS]
    for q, p, _ in dict.fromkeys(best):  # in span order (a set's order changes with the string hash seed)
        for coast in ("frozen", "mode"):  # three ways to coast at each best process noise
            scores["IMM"][(q, p, coast)] = _score(world, "IMM", (q, p, coast))
    return scores


@functools.lru_cache(maxsize=128)
def _vd_statistic(world: tuple, q_ca: float, window: int) -> np.ndarray:
    """The VD filter's CV-only statistic rho before the onset on the training runs (no detection: it reads neither
    q_CA's effect nor alpha)."""
    sc, z, _ = _training(world)
    return vd_filter_run(z, sc.visible, 0.0, q_ca, world[3], window, np.inf).rho[..., window + 1 : sc.onset]


@functools.lru_cache(maxsize=64)
def _scores_vd(world: tuple, grids: tuple, alpha: float) -> dict:
    """``{setting: {span: training mean square}}`` of the VD filter, its threshold the ``1 - alpha`` quantile of
    its statistic before the onset; every q_CA of a window in one batched run (the per-setting numbers, tested bit
    for bit), the settings in the grid's order (q_CA, then window)."""
    g = _grids(grids)
    sc, z, truth = _training(world)
    qs = tuple(g["vdf_q_ca"])
    by_window = {}
    for w in g["vdf_windows"]:
        thr = float(np.quantile(_vd_statistic(world, qs[0], w), 1 - alpha))
        zb = np.broadcast_to(z, (len(qs),) + z.shape)
        q_b = np.asarray(qs, float).reshape((-1,) + (1,) * z.ndim)[..., 0]
        x = vd_filter_run(zb, sc.visible, 0.0, q_b, world[3], int(w), thr).x[..., 0]
        by_window[w] = (thr, [{k: float(v.mean()) for k, v in _span_ms(xq, sc, truth).items()} for xq in x])
    return {(q, w, by_window[w][0]): by_window[w][1][i] for i, q in enumerate(qs) for w in g["vdf_windows"]}


def _on_edge(name: str, best: tuple, g: dict) -> bool:
    grids = {
        "fixed 2nd order": (g["fixed2"],),
        "fixed 3rd order": (g["fixed3"],),
        "IMM": (g["imm_q_ca"], g["imm_p_stay"]),
        "VD filter": (g["vdf_q_ca"], g["vdf_windows"]),
    }[name]
    return any(len(v_) > 1 and v in (min(v_), max(v_)) and v not in FLOORS[name] for v_, v in zip(grids, best))


def comparator_tuning(config: dict, sizes: dict) -> dict:
    """The comparators tuned for a configuration (:func:`tuned_comparators` on its frame rate, alpha and the run's
    training sizes and grids).

    Parameters
    ----------
    config : dict
        A complete configuration (``frame_rate_hz`` in Hz, ``alpha``).
    sizes : dict
        The run's sizes (``n_train``, ``train_seed``, ``sigma_eps`` and the tuning ``grids``).

    Returns
    -------
    dict
        What :func:`tuned_comparators` returns: per RMS span, each comparator's tuned setting.
    """
    grids = tuple((k, tuple(v)) for k, v in sizes.get("grids", {}).items())
    return tuned_comparators(
        float(config["frame_rate_hz"]),
        sizes["n_train"],
        sizes["train_seed"],
        float(config["alpha"]),
        sizes["sigma_eps"],
        grids,
        config.get("manoeuvre", "constant acceleration"),
        config.get("accel_unit", "el/frame²"),
        config.get("channel_y", "v -6, a -0.2"),
    )


def compensation_bias2(xhat, sc: Scenario, end_s: float) -> float:
    """Mean square of the dynamic error from the onset to ``end_s``, elements²: the position error's mean over the
    runs (axis 0) at each frame and channel, squared and averaged (the ``"bias²"`` functional ``faster
    compensation`` is judged on, :func:`.tradeoff.error_functional`)."""
    f = sc.frames
    m = (f >= sc.onset) & (f < int(round(end_s * sc.fps)))
    return float(np.mean(((xhat - sc.truth[None, :, :, 0])[..., m].mean(axis=0)) ** 2))


def raised_second_order(z, sc: Scenario, detection_frame, k_bound2: int, k_bound: int) -> np.ndarray:
    """Positions (..., T) of the scheme's TRACK2 filter whose gains are raised, not its order, at
    ``detection_frame`` (..., -1: none): the growing-memory 2nd-order law bounded at ``k_bound2`` up to the detection,
    then restarted at k = 3 and bounded at ``k_bound`` (>= 3); coasting while lost."""
    t = np.arange(sc.T)
    d = np.where(np.asarray(detection_frame) >= 0, detection_frame, sc.T)[..., None]
    k = np.where(t <= d, np.minimum(t + 1, k_bound2), np.minimum(3 + (t - d - 1), k_bound))
    G = gain_schedule(1, max(int(k_bound), int(k_bound2)), sc.T + 3)
    return scheduled_filter(np.where(sc.visible, z, np.nan), G[k - 1])[..., 0]


def compensation_comparator(name: str, z, sc: Scenario, config: dict, sizes: dict, detection_frame) -> np.ndarray:
    """Positions (..., T) of C001-4's compensation comparator ``name`` (``COMPENSATION_COMPARATORS``). The raised
    2nd-order filter's bound is tuned on ``sizes["n_train"]`` training runs (seed ``train_seed + 1``, white Gaussian)
    for the lowest mean square of the dynamic error from the onset to ``compensation_end_s``
    (:func:`compensation_bias2`), the measure it is judged on."""
    k2, sigma = int(config["k_bound2"]), sizes["sigma_eps"]
    if name == COMPENSATION_COMPARATORS[0]:
        return comparator_positions("fixed 2nd order", (k2,), z, sc, sigma)
    if name != COMPENSATION_COMPARATORS[1]:
        raise ValueError(f"compensation comparator {name!r}; it must be one of {COMPENSATION_COMPARATORS}")
    rng = np.random.default_rng(sizes["train_seed"] + 1)
    zt = measurements(sc.truth[:, :, 0], "white Gaussian", sizes["n_train"], rng, sigma)
    dt = run_scheme(zt, sc, config, sizes, covariance=False).detection_frame
    end = float(config["compensation_end_s"])
    kb = min(RAISED2_GRID, key=lambda b: compensation_bias2(raised_second_order(zt, sc, dt, k2, b), sc, end))
    return raised_second_order(z, sc, detection_frame, k2, kb)


_COASTS = {
    "mix": "coasting with the textbook mixing cycle",
    "frozen": "coasting without mixing, mode probabilities frozen",
    "mode": "coasting on the model most probable at the loss",
}


def tuning_phrase(name: str, setting: tuple) -> str:
    """A comparator's tuned setting (:func:`comparator_positions`) in plain words with units."""
    if name in ("fixed 2nd order", "fixed 3rd order"):
        return f"gains frozen at frame {int(setting[0])}"
    if name == "IMM":
        return (
            f"acceleration-model process noise {setting[0]:g} el²/frame⁴, probability {setting[1]:g} of staying in "
            f"a model, {_COASTS.get(setting[2], setting[2])}"
        )
    return f"acceleration-model process noise {setting[0]:g} el²/frame⁴, detector and restart over {int(setting[1])} frames"
