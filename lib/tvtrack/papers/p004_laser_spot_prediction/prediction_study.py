"""The prediction comparison of notebook 004, with every method tuned the same way.

Every method sees the same measured series and predicts ``steps`` frames ahead; each method's
free setting is chosen by cross-validation over paths (:func:`tvtrack.papers.p004_laser_spot_prediction.predictors.cross_validated_pick`:
the setting with the smallest error on the *other* paths of the fold), never on the paths it is
scored on:

- the paper's growing-memory filter: its floor ``N_f`` from a grid;
- sliding regression (degree 1, 2) and the cubic spline: their window ``L`` from a grid that starts
  at the method's degree + 1 (the fewest samples it can fit: 2 for a line, 3 for a quadratic, 4 for
  the cubic spline; :func:`window_candidates`);
- finite differences (2 and 3 points): nothing to tune;
- MLP and RBF network (``L`` lagged increments): trained on the training paths of each fold, ``L``
  fixed or chosen per fold on the training paths only (:func:`tune_learned_lags`);
- constant-acceleration Kalman filter: its two noise levels by maximum likelihood on the
  training paths of each fold (grids wide enough that the optimum lies inside; :func:`grid_edges`
  reports a fit on an edge);
- Singer-model Kalman filter (exponentially correlated acceleration): its correlation time,
  acceleration variance and measurement variance by maximum likelihood on the training paths
  of each fold;
- Morrison's fading-memory quadratic filter (a principled floor, not a baseline of the paper):
  its discount ``theta`` from a grid.

The "fixed" reading uses ``N_f`` = ``fixed_floor`` and ``L`` = ``fixed_window`` for all paths,
as the first version of the notebook did.

Scores are per-trial, per-path mean squared errors of the ``steps``-ahead prediction against a
reference (the next measured centre, or the truth), over frames ``>= start`` and both axes.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ...estimate import Estimate
from .intervals import ratio_of_means_ci
from .sizes import StudySize

from . import kalman_baselines as kb
from . import learned as lm
from . import predictors as pr

__all__ = [
    "tuned_forecast",
    "PAPER",
    "VARIANT",
    "CLASSICAL",
    "FITTED",
    "FADING",
    "SINGER",
    "CA_KALMAN",
    "MIN_WINDOW",
    "ComparisonSetup",
    "Comparison",
    "PARTS",
    "compare_methods",
    "per_trial_path_mse",
    "comparison_setup",
    "late_rms_ratio",
    "path_quantile",
    "tune_learned_lags",
    "fit_learned_folds",
    "apply_learned_folds",
    "window_candidates",
    "grid_edges",
]

#: The paper's filter.
PAPER = "growing memory (paper)"
#: This project's labelled variant of the paper's floor: only ``g_1 >= g_{N_f,1}``, ``g_2, g_3`` scaled by the same
#: factor.
VARIANT = "growing memory, g1 floor (variant)"
#: Baselines the paper names whose errors it quotes as 2-10 px (finite differences, splines, regression).
CLASSICAL = (
    "finite differences, 2 points",
    "finite differences, 3 points",
    "cubic spline",
    "linear regression deg 1",
    "linear regression deg 2",
)
#: Principled counterpart of the floor (not a baseline of the paper): Morrison's fading-memory filter.
FADING = "fading memory (Morrison)"
#: Singer-model Kalman filter with ML parameters (a Kalman filter whose memory is set by a motion model).
SINGER = "Singer Kalman, ML"
#: The constant-acceleration Kalman filter with ML noise levels.
CA_KALMAN = "CA Kalman, ML noise"
#: Baselines fitted to data: back-propagation MLP and RBF network (the paper names both, 2-3 and
#: 2-4 px), and two Kalman filters with ML parameters standing in for the paper's "Kalman filters"
#: (1-2 px): constant acceleration with white jerk, and Singer's correlated acceleration.
FITTED = ("MLP back-prop", "RBF network", CA_KALMAN, SINGER)
#: The fewest samples each windowed baseline can fit (its degree + 1): where its window search starts.
MIN_WINDOW = {"cubic spline": 4, "linear regression deg 1": 2, "linear regression deg 2": 3}


def window_candidates(min_window: int, grid) -> tuple:
    """Windows a baseline's search tries: every integer from ``min_window`` (its degree + 1) up to
    the grid's smallest value, then the grid values above ``min_window``.

    A grid that starts above a baseline's degree + 1 would deny it its shortest memory, which is
    its optimum when the motion is fast and the measurement clean (a degree-1 fit on 2 samples).
    """
    grid = sorted(int(g) for g in grid)
    return tuple(
        sorted(set(range(int(min_window), max(grid[0], int(min_window)) + 1)) | {g for g in grid if g >= min_window})
    )


def grid_edges(chosen, grid) -> np.ndarray:
    """Where a tuned setting sits on its grid's edge (``-1``: lowest value, ``+1``: highest, 0: inside).

    A fit on an edge may be the grid's limit rather than the method's optimum; the notebook reports it.
    """
    g = np.asarray(grid, dtype=float)
    c = np.asarray(chosen, dtype=float)
    return np.where(np.isclose(c, g.max()), 1, np.where(np.isclose(c, g.min()), -1, 0))


def per_trial_path_mse(forecast, reference, steps: int, start: int) -> np.ndarray:
    """Mean squared ``steps``-ahead error per trial and path, px^2.

    Parameters
    ----------
    forecast : ndarray, shape (trials, paths, axes, T)
    reference : ndarray, broadcastable to ``forecast``; NaN (lost frames) are skipped

    Returns
    -------
    ndarray, shape (trials, paths)
    """
    e = pr.forecast_errors(forecast, reference, steps)[..., start:]
    return np.nanmean(e.reshape(e.shape[0], e.shape[1], -1) ** 2, axis=-1)


@dataclass(frozen=True)
class ComparisonSetup:
    """How the comparison is run (units: frames; see the module text)."""

    steps: int = 1
    start: int = 20
    order: int = 2
    floor_grid: tuple = (3, 4, 5, 7, 10, 15, 20, 30, 50, 100, 200)
    window_grid: tuple = (4, 6, 8, 10, 15, 20, 30)
    theta_grid: tuple = (0.1, 0.2, 0.3, 0.5, 0.6, 0.7, 0.8, 0.9, 0.95)
    fixed_floor: int = 10
    fixed_window: int = 10
    learned_lags: int | None = 10
    learned_kw: dict = field(default_factory=dict)
    lag_grid: tuple = (1, 2, 4, 8, 16)
    lag_tuning_samples: int = 500
    jerk_grid: tuple = tuple(np.logspace(-7, 1, 17))
    meas_var_grid: tuple = tuple(np.logspace(-4, 2, 7))  # px^2: up to 10 px RMS, past any jitter of the register
    singer_tau_grid: tuple = tuple(np.logspace(-2, 3, 11))
    singer_ratio_grid: tuple = tuple(np.logspace(-4, 8, 13))


@dataclass
class Comparison:
    """Result of :func:`compare_methods`.

    Attributes
    ----------
    mse : dict name -> ndarray (trials, paths)
        Cross-validated reading (every method tuned on the other paths), px^2.
    mse_fixed : dict name -> ndarray (trials, paths)
        Fixed reading (``N_f`` = ``fixed_floor``, ``L`` = ``fixed_window``) for the tuned methods.
    chosen : dict name -> ndarray (paths,) or (folds, k)
        The setting each tuned method used on each path (``N_f``, ``L`` or ``theta``); per fold,
        the CA Kalman ``(jerk_psd, meas_var)`` and the Singer ``(tau, accel_var, meas_var)``.
    forecasts : dict name -> ndarray like ``z``
        Cross-validated forecasts (for figures).
    learned_models : dict kind -> list of fitted models per fold
    """

    mse: dict
    mse_fixed: dict
    chosen: dict
    forecasts: dict
    learned_models: dict


#: Floors tried beyond ``floor_grid`` while a fold picks the grid's top (``>= T`` frames: no floor at all, the
#: filter's own limit), so the paper's filter is tuned to its optimum at long horizons too (the floor sat at the
#: old grid's top, 200, at horizon 10).
FLOOR_EXTENSION = (350, 600, 1000)
#: Windows tried beyond ``window_grid`` likewise, so each windowed baseline gets the same tuning effort (clipped to
#: the series' frames as the floors are: a window of ``T`` frames fits every sample so far).
WINDOW_EXTENSION = (45, 70, 100)


def clipped_extension(values, frames: int) -> list:
    """The extension ``values`` (frames) clipped to the series' ``frames``, in increasing order: a floor or window
    of ``frames`` or more is the method's own limit (no floor; every sample so far), so none is tried twice."""
    return sorted({min(int(v), int(frames)) for v in values})


def tuned_forecast(candidates, make, z, ref, folds, s: ComparisonSetup, more=()):
    """Forecast with every candidate setting, pick per fold on the training paths (pooled
    trials), and assemble the cross-validated forecast and per-trial-path MSE. While a fold picks the
    last candidate, the next value of ``more`` is tried too (the grid reaches the method's optimum).

    Parameters
    ----------
    candidates : sequence
        The settings tried (a floor, a window, a lag count...).
    make : callable
        ``make(setting) -> forecast`` (trials, paths, axes, T), px.
    z, ref : numpy.ndarray or float
        The measured series and the reference the MSE is taken against, px.
    folds : sequence
        The cross-validation folds of the paths.
    s : ComparisonSetup
        Horizon (frames) and the first frame scored.
    more : sequence
        Settings beyond ``candidates``, tried in turn while a fold picks the largest.

    Returns
    -------
    tuple
        ``(forecast, per-trial-path MSE (px^2), the setting each path's fold chose, every candidate's forecast,
        every candidate's MSE (candidates, trials, paths))``.
    """
    candidates, more = list(candidates), [c for c in more if c > max(candidates)]
    fcs = [make(c) for c in candidates]
    mse = np.stack([per_trial_path_mse(f, ref, s.steps, s.start) for f in fcs])  # (C, trials, P)
    pick = lm.cross_validated_pick(mse.mean(axis=1), folds)
    while more and np.any(pick == len(candidates) - 1):
        candidates.append(more.pop(0))
        fcs.append(make(candidates[-1]))
        mse = np.concatenate([mse, per_trial_path_mse(fcs[-1], ref, s.steps, s.start)[None]])
        pick = lm.cross_validated_pick(mse.mean(axis=1), folds)
    P = z.shape[1]
    fc = np.stack([fcs[pick[p]][:, p] for p in range(P)], axis=1)
    return fc, mse[pick, :, np.arange(P)].T, np.asarray(candidates)[pick], fcs, mse


def tune_learned_lags(kind: str, z, reference, folds, s: ComparisonSetup, rng: np.random.Generator):
    """The lag count of a learned predictor, chosen per fold by cross-validation on its training paths only.

    The folds' test groups ``G_1..G_K`` (K >= 3) are the units: for every candidate ``L`` of
    ``s.lag_grid`` and group ``g`` a model is trained on ``G_g`` alone (``s.lag_tuning_samples`` pairs at
    most) and scored on every path outside ``G_g``. Fold ``i`` picks the ``L`` with the smallest mean
    squared error over the pairs (``g``, path) with ``g != i`` and the path outside ``G_g`` and ``G_i``:
    models and scores that never touch ``G_i``, the paths fold ``i`` is tested on. Each model sees a
    ``K``-th of the paths (fewer than the final model's ``(K-1)/K``): if anything, a lean toward fewer lags.

    Parameters
    ----------
    z : ndarray, shape (trials, paths, axes, T)
        Complete measured series; only trial 0 is used.
    reference : ndarray, broadcastable to ``z``
        What the forecasts are scored against (measured centres).

    Returns
    -------
    lags : ndarray of int, shape (K,)
        The chosen lag count of each fold.
    loss : ndarray, shape (K, candidates)
        Each fold's tuning loss per candidate, px^2.
    """
    groups = [np.asarray(test) for _, test in folds]
    K, P = len(groups), z.shape[1]
    if K < 3:
        raise ValueError(f"{K} folds: cross-validating the lag count on training paths only needs >= 3 folds")
    grid = tuple(int(L) for L in s.lag_grid)
    seeds = rng.integers(2**31, size=(len(grid), K))
    kw = {**s.learned_kw, "max_samples": s.lag_tuning_samples}
    per_path = np.full((len(grid), K, P), np.nan)  # MSE of the model (L, g) on each path outside G_g
    ref = np.broadcast_to(reference, z.shape)
    for c, L in enumerate(grid):
        for g, grp in enumerate(groups):
            model = lm.fit_learned_predictor(kind, z[0, grp], L, s.steps, seed=int(seeds[c, g]), **kw)
            out = np.setdiff1d(np.arange(P), grp)
            f = lm.learned_forecast(model, z[:1, out])
            per_path[c, g, out] = per_trial_path_mse(f, ref[:1, out], s.steps, s.start)[0]
    loss = np.empty((K, len(grid)))
    for i in range(K):
        use = np.ones((K, P), dtype=bool)
        use[i] = False  # no model trained on the fold's test group
        use[:, groups[i]] = False  # no score on it
        loss[i] = [np.nanmean(per_path[c][use]) for c in range(len(grid))]
    return np.asarray(grid)[np.argmin(loss, axis=1)], loss


def fit_learned_folds(kind: str, z, folds, s: ComparisonSetup, rng: np.random.Generator, lags=None) -> list:
    """One learned predictor per fold, trained on the first trial of its training paths, with ``lags[i]``
    lagged inputs in fold ``i`` (default ``s.learned_lags`` in every fold)."""
    lags = [s.learned_lags] * len(folds) if lags is None else [int(L) for L in lags]
    return [
        lm.fit_learned_predictor(kind, z[0, train], L, s.steps, seed=int(rng.integers(2**31)), **s.learned_kw)
        for (train, _), L in zip(folds, lags)
    ]


def apply_learned_folds(models, z, folds) -> np.ndarray:
    """Forecasts of each fold's model on its test paths (all trials)."""
    out = np.full(z.shape, np.nan)
    for model, (_, test) in zip(models, folds):
        out[:, test] = lm.learned_forecast(model, z[:, test])
    return out


#: The parts of :func:`compare_methods` beyond the paper's filter (always run): the variant floor, the
#: classical baselines (finite differences, cubic spline, regression), Morrison's fading memory, the networks
#: and the two ML Kalman filters.
PARTS = frozenset({"variant", "classical", "fading", "learned", "kalman"})


def compare_methods(
    z,
    reference,
    folds,
    setup: ComparisonSetup,
    rng: np.random.Generator,
    learned_models: dict | None = None,
    learned: bool = True,
    parts=None,
    kalman_fits=None,
) -> Comparison:
    """Every method on the same series, tuned by cross-validation over paths.

    Parameters
    ----------
    z : ndarray, shape (trials, paths, axes, T)
        Complete measured series (lost frames held), px.
    reference : ndarray, broadcastable to ``z``
        What the predictions are scored against (measured centres with NaN for lost frames, or truth).
    folds : list of (train, test)
        :func:`tvtrack.papers.p004_laser_spot_prediction.predictors.path_folds`.
    rng : numpy.random.Generator
        Seeds of the learned models (only they draw from it).
    learned_models : dict, optional
        Pre-trained ``{"mlp": [...], "rbf": [...]}`` per fold to apply instead of training here
        (train/test mismatch: models trained in another regime).
    learned : bool
        Include the MLP and RBF network.
    parts : iterable of str, optional
        Which of :data:`PARTS` to run besides the paper's filter (default: all; ``learned=False`` drops
        "learned"). Each part's numbers are the same whichever other parts run (no part shares a draw).
    kalman_fits : (ca, singer), optional
        The Kalman filters' per-fold ML parameters (``chosen`` of an earlier comparison on the same series and
        folds: the fits read no horizon); None: fitted here.

    Returns
    -------
    Comparison
    """
    parts = PARTS if parts is None else frozenset(parts)
    if not parts <= PARTS:
        raise ValueError(f"parameter 'parts' has {sorted(set(parts) - PARTS)}; they must be among {sorted(PARTS)}")
    s = setup
    m = s.steps
    mse, fixed, chosen, fcs = {}, {}, {}, {}
    more = clipped_extension(FLOOR_EXTENSION, z.shape[-1])
    fcs[PAPER], mse[PAPER], chosen[PAPER], _, _ = tuned_forecast(
        s.floor_grid, lambda nf: pr.growing_memory_forecast(z, m, s.order, nf), z, reference, folds, s, more=more
    )
    if "variant" in parts:  # the variant floor, tuned alike
        fcs[VARIANT], mse[VARIANT], chosen[VARIANT], _, _ = tuned_forecast(
            s.floor_grid, lambda nf: pr.g1_floor_forecast(z, nf, m, s.order), z, reference, folds, s, more=more
        )
        fixed[VARIANT] = per_trial_path_mse(pr.g1_floor_forecast(z, s.fixed_floor, m, s.order), reference, m, s.start)
    fixed[PAPER] = per_trial_path_mse(pr.growing_memory_forecast(z, m, s.order, s.fixed_floor), reference, m, s.start)
    if "classical" in parts:
        _classical(z, reference, folds, s, (mse, fixed, chosen, fcs))
    if "fading" in parts:
        fcs[FADING], mse[FADING], chosen[FADING], _, _ = tuned_forecast(
            s.theta_grid, lambda th: pr.fading_memory_forecast(z, th, m), z, reference, folds, s
        )
        fixed[FADING] = mse[FADING]
    models = {}
    if learned and "learned" in parts:
        models = _learned(z, reference, folds, s, rng, learned_models, (mse, fixed, chosen, fcs))
    if "kalman" in parts:
        _kalman(z, reference, folds, s, (mse, fixed, chosen, fcs), kalman_fits)
    return Comparison(mse, fixed, chosen, fcs, models)


def _classical(z, reference, folds, s: ComparisonSetup, out) -> None:
    """The paper's classical baselines into ``out`` = (mse, fixed, chosen, forecasts): finite differences of 2 and
    3 points, the cubic spline and regression of degree 1 and 2 (windows cross-validated)."""
    mse, fixed, chosen, fcs = out
    m = s.steps
    fcs["finite differences, 2 points"] = pr.sliding_regression_forecast(z, 2, 1, m)
    fcs["finite differences, 3 points"] = pr.sliding_regression_forecast(z, 3, 2, m)
    for name in ("finite differences, 2 points", "finite differences, 3 points"):
        mse[name] = fixed[name] = per_trial_path_mse(fcs[name], reference, m, s.start)
    windowed = {
        "cubic spline": lambda L: pr.spline_forecast(z, L, m),
        "linear regression deg 1": lambda L: pr.sliding_regression_forecast(z, L, 1, m),
        "linear regression deg 2": lambda L: pr.sliding_regression_forecast(z, L, 2, m),
    }
    more = clipped_extension(WINDOW_EXTENSION, z.shape[-1])
    for name, make in windowed.items():
        fcs[name], mse[name], chosen[name], _, _ = tuned_forecast(
            window_candidates(MIN_WINDOW[name], s.window_grid), make, z, reference, folds, s, more=more
        )
        fixed[name] = per_trial_path_mse(make(s.fixed_window), reference, m, s.start)


def _learned(z, reference, folds, s: ComparisonSetup, rng, learned_models, out) -> dict:
    """The MLP and RBF network into ``out`` (their lag counts cross-validated when ``s.learned_lags`` is None);
    returns the fitted models per kind."""
    mse, fixed, chosen, fcs = out
    models = {}
    for kind, name in (("mlp", "MLP back-prop"), ("rbf", "RBF network")):
        lags = None
        if learned_models is None and s.learned_lags is None:  # cross-validated on the training paths
            lags, _ = tune_learned_lags(kind, z, reference, folds, s, rng)
            chosen[name] = lags
        models[kind] = (
            learned_models[kind] if learned_models is not None else fit_learned_folds(kind, z, folds, s, rng, lags)
        )
        fcs[name] = apply_learned_folds(models[kind], z, folds)
        mse[name] = fixed[name] = per_trial_path_mse(fcs[name], reference, s.steps, s.start)
    return models


def _kalman(z, reference, folds, s: ComparisonSetup, out, fitted=None) -> None:
    """The constant-acceleration and Singer Kalman filters, noise fitted by maximum likelihood per fold (or the
    ``fitted`` (ca, singer) parameters), into ``out``."""
    mse, fixed, chosen, fcs = out
    m = s.steps
    if fitted is None:
        fitted = (
            kb.fit_constant_acceleration_folds(z[0], folds, s.jerk_grid, s.meas_var_grid),
            kb.fit_singer_folds(z[0], folds, s.singer_tau_grid, s.singer_ratio_grid),
        )
    fits, singer_fits = fitted
    fcs[CA_KALMAN] = kb.constant_acceleration_forecast(z, fits, folds, m)
    mse[CA_KALMAN] = fixed[CA_KALMAN] = per_trial_path_mse(fcs[CA_KALMAN], reference, m, s.start)
    chosen[CA_KALMAN] = np.array(fits)
    fcs[SINGER] = kb.singer_forecast(z, singer_fits, folds, m)
    mse[SINGER] = fixed[SINGER] = per_trial_path_mse(fcs[SINGER], reference, m, s.start)
    chosen[SINGER] = np.array(singer_fits)


def late_rms_ratio(fc_nofloor, fc_floor, reference, steps: int, late_start: int) -> Estimate:
    """RMS over the late frames without / with the floor: square root of the paired ratio of per-path
    mean squares (:func:`ratio_of_means_ci`)."""
    a = per_trial_path_mse(fc_nofloor, reference, steps, late_start)[0]
    b = per_trial_path_mse(fc_floor, reference, steps, late_start)[0]
    r = ratio_of_means_ci(a, b)
    return Estimate(
        float(np.sqrt(r.value)),
        r.stderr / (2 * np.sqrt(r.value)),
        float(np.sqrt(r.ci_low)),
        float(np.sqrt(r.ci_high)),
        r.n,
        r.confidence,
        "square root of the " + r.method,
    )


def path_quantile(forecast, reference, steps: int, start: int, q: float) -> np.ndarray:
    """Per path: the ``q`` quantile of the per-axis ``|e|`` over both axes and the frames from
    ``start`` on, px; shape (P,)."""
    e = np.abs(pr.forecast_errors(forecast, reference, steps)[0, ..., start:])
    return np.nanquantile(e.reshape(e.shape[0], -1), q, axis=1)


def comparison_setup(config: dict, size: StudySize) -> ComparisonSetup:
    """The forecast comparison's settings (horizon in frames, tuning grids, folds) of a configuration and size."""
    return ComparisonSetup(
        steps=int(config["horizon"]),
        start=size.eval_start,
        floor_grid=tuple(size.floor_grid),
        window_grid=tuple(size.window_grid),
        fixed_floor=size.fixed_floor,
        fixed_window=size.fixed_window,
        learned_lags=None if config["network lags"] == "cross-validated" else int(config["network lags"]),
        lag_grid=tuple(size.lag_grid),
        lag_tuning_samples=min(size.lag_tuning_samples, size.train_samples),
        learned_kw=dict(
            hidden_units=size.mlp_hidden_units,
            rbf_centres=size.rbf_centres,
            max_samples=size.train_samples,
            inputs=config["network inputs"],
        ),
    )
