"""The study of paper 004 as functions of (configuration, seed): what the explorer calls.

One run (:func:`run_study`) draws ``n_paths`` beam-wander paths from the generator at the
configuration's regime, renders and measures the spot frame by frame, runs the paper's filter and
every baseline (each tuned by cross-validation over paths, :mod:`.prediction_study`) at the
configuration's horizon, and the optimal predictor of the generator's own model. :func:`claim_values`
reduces a run to what each claim's rule reads; :func:`measure` is the explorer's measurement function
and :func:`measure_batch` its batched form, which shares a rendered scene between configurations that
differ only in the networks' lags or a statistic, or in the horizon at a bandwidth set by hand (a calibrated
world is calibrated at its horizon; common random numbers: every stream is from ``SeedSequence(seed)``).

The configuration is a dict with every entry of :data:`.register.REGISTER` (names in :data:`ENTRIES`).
Sizes (paths, frames, grids) are a :class:`StudySize`, fixed for a notebook run. The world a run draws (generator,
camera, exposure, vibration) is :mod:`.world`; the notebook's studies beyond the claims (scores,
measurement budget, model order, horizon) are :mod:`.side_studies`.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ...jobs import fork_pool
from ...projection import as_declared, claim_groups
from . import learned as lm
from . import predictors as pr
from . import shipping
from .cache import BoundedCache
from .beam_wander import BeamWanderConfig, generate_traces, one_frame_motion_rms, optimal_wander_forecast
from .camera import SpotCamera, track_spot
from .prediction_study import (
    CLASSICAL,
    FLOOR_EXTENSION,
    PAPER,
    PARTS,
    VARIANT,
    Comparison,
    WINDOW_EXTENSION,
    clipped_extension,
    comparison_setup,
    tuned_forecast,
    compare_methods,
    late_rms_ratio,
    path_quantile,
    per_trial_path_mse,
    window_candidates,
)
from .derivation import recursion_check, variance_ratios
from .intervals import mean_ci_t, ratio_of_means_ci, root_mean_ci
from .sizes import StudySize
from .timing import frame_time_ms
from .traces import TraceSet
from .world import BASE_SCENE, camera_for, scene_config, traces_on_sensor, vibration
from .operating import BAND_PX, CALIBRATED, JOINT_OUTSIDE_BAND, JOINT_PATHS, joint_factor, table_factors
from .register import DEFAULT, NAMES

#: The ``floor form`` reading under which the paper's filter is this project's variant floor (position gain bounded).
VARIANT_FLOOR = "first gain bounded"

__all__ = [
    "study_run",
    "ENTRIES",
    "CENTROID",
    "NETWORKS",
    "OPTIMAL",
    "StudyRun",
    "scene_config",
    "traces_on_sensor",
    "camera_for",
    "run_study",
    "claim_values",
    "parts_for",
    "measure",
    "measure_batch",
    "vibration",
    "variance_ratios",
    "clear_cache",
]

#: Register entry names the study reads (the configuration dict's keys).
ENTRIES = NAMES  # the register's entry names, in register order
#: The two networks of C004-3b (the paper's back-propagation and RBF networks).
NETWORKS = ("MLP back-prop", "RBF network")
#: The least-squares cubic over a window: the other reading of the paper's "spline extrapolation".
LSQ_CUBIC = "least-squares cubic"
#: The natural cubic spline, extended linearly beyond its last knot: a third reading of "spline extrapolation".
NATURAL_SPLINE = "natural cubic spline"
#: Key of the per-axis RMS centroid (measurement) error in :func:`claim_values`' output, px (not a claim).
CENTROID = "centroid error"
#: The optimal predictor of the generator's own model: a bound, not a method.
OPTIMAL = "optimal (true model)"


@dataclass
class StudyRun:
    """One full-size run (see :func:`run_study`); arrays per (trial=1, path, axis, frame), px."""

    config: dict
    size: StudySize
    scene: BeamWanderConfig
    camera: SpotCamera
    truth: np.ndarray  # (1, P, 2, T) true centres (frame jitter included: the spot really moved)
    z_meas: np.ndarray  # (1, P, 2, T) measured centres, NaN where lost
    z: np.ndarray  # (1, P, 2, T) what the predictors see (lost frames held)
    path_rms: np.ndarray  # (P,) wander RMS per axis
    jitter_rms: np.ndarray  # (P,)
    centroid_rms: float
    lost_share: float
    clipped_share: float
    intensity: np.ndarray  # (P, T)
    track: object = None  # GateTrack of path 0 (figures, recording)
    comparison: object = None
    forecasts: dict | None = None  # cross-validated forecasts, OPTIMAL and the fixed-tuning ones
    fixed_forecasts: dict | None = None
    folds: list | None = None
    draws: int = 0  # sets of paths drawn until the spot stayed on the sensor (0: the paths were given)
    parts: frozenset = frozenset()  # the methods run besides the paper's filter (:data:`ALL_PARTS`)


def run_streams(seed: int):
    """Independent streams (traces, jitter, sensor, models, Monte Carlo, timing) of one run."""
    return np.random.SeedSequence(int(seed)).spawn(6)


def study_run(config: dict, seed: int, size: StudySize, traces: TraceSet | None = None, keep=None) -> StudyRun:
    """One configuration's scene (traces on the sensor, jitter, vibration) tracked by the camera (positions in px)."""
    resolve_operating_point(config)
    s_tr, s_jit, s_sens, _, _, _ = run_streams(seed)
    scene = scene_config(config, size)
    draws = 0
    if traces is None:
        traces, draws = traces_on_sensor(scene, s_tr, config.get("exposure", "instant"))
    xy = traces.centres_px[: size.n_paths, : size.n_frames]
    intensity = traces.intensity[: size.n_paths, : size.n_frames]
    rms = np.asarray(traces.metadata["wander_rms_px"])[: size.n_paths]
    jit = float(config["jitter"]) * one_frame_motion_rms(scene, rms)
    rng_j = np.random.default_rng(s_jit)
    xy = xy + jit[:, None, None] * rng_j.standard_normal(xy.shape)
    xy = xy + vibration(float(config.get("vibration", 0.0)), scene.frame_rate_hz, xy.shape, rng_j)
    cam = camera_for(config)
    trk = track_spot(xy[None], intensity, np.random.default_rng(s_sens), cam, scene.image_size_px, keep=keep)
    z_meas = np.moveaxis(trk.xy, -1, -2)
    truth = np.moveaxis(xy, -1, -2)[None]
    err = z_meas - truth
    return StudyRun(
        config=dict(config),
        size=size,
        scene=scene,
        camera=cam,
        truth=truth,
        z_meas=z_meas,
        z=pr.hold_last(z_meas),
        path_rms=rms,
        jitter_rms=jit,
        centroid_rms=float(np.sqrt(np.nanmean(err**2))),
        lost_share=float(np.mean(~np.isfinite(err))),
        clipped_share=float(np.mean(trk.clipped)),
        intensity=intensity,
        track=trk,
        draws=draws,
    )


#: What one run can compute beyond the scene and the paper's filter: the comparison's parts
#: (:data:`.prediction_study.PARTS`) and the optimal predictor of the generator's own model (figures only).
ALL_PARTS = PARTS | {"optimal"}
#: The parts each claim's value reads (the paper's filter is always run with the methods; C004-4, C004-5, C004-8
#: and :data:`CENTROID` read no method).
CLAIM_PARTS = {
    "C004-1": frozenset(),
    "C004-2": frozenset(),
    "C004-3": frozenset({"classical"}),
    "C004-3b": frozenset({"learned"}),
    "C004-6": frozenset(),
}
#: Every value :func:`claim_values` can return.
CLAIM_KEYS = ("C004-1", "C004-2", "C004-3", "C004-3b", "C004-4", "C004-5", "C004-6", "C004-8", CENTROID)


def parts_for(claims) -> frozenset | None:
    """The method parts the ``claims`` read (None: no method at all; ``claims`` None: every claim)."""
    asked = CLAIM_PARTS if claims is None else [c for c in claims if c in CLAIM_PARTS]
    if not asked:
        return None
    return frozenset().union(*(CLAIM_PARTS[c] for c in asked))


def _methods(run: StudyRun, config: dict, seed: int, parts=ALL_PARTS) -> StudyRun:
    """The methods on ``run``'s measured series at ``config``'s horizon and lags (re-tuned for it): the paper's
    filter and the ``parts`` of :data:`ALL_PARTS` (each part's numbers are the same whichever others run: only
    the networks draw, from their own stream)."""
    if not np.all(np.isfinite(run.z)):
        raise ValueError("the spot was never measured on some path: nothing to predict")
    parts = frozenset(parts)
    size = run.size
    s = comparison_setup(config, size)
    m = s.steps
    folds = lm.path_folds(size.n_paths, size.n_folds)
    rng = np.random.default_rng(run_streams(seed)[3])
    cmp = compare_methods(run.z, run.z_meas, folds, s, rng, parts=parts & PARTS)
    fc = dict(cmp.forecasts)
    if "optimal" in parts:
        noise = run.centroid_rms**2 + run.jitter_rms**2
        fc[OPTIMAL] = optimal_wander_forecast(run.z, run.scene, run.path_rms, noise, m)
    fixed = dict(fc)
    fixed[PAPER] = pr.growing_memory_forecast(run.z, m, s.order, s.fixed_floor)
    if "variant" in parts:
        fixed[VARIANT] = pr.g1_floor_forecast(run.z, s.fixed_floor, m, s.order)
    if "classical" in parts:
        fixed["cubic spline"] = pr.spline_forecast(run.z, s.fixed_window, m)
        fixed["linear regression deg 1"] = pr.sliding_regression_forecast(run.z, s.fixed_window, 1, m)
        fixed["linear regression deg 2"] = pr.sliding_regression_forecast(run.z, s.fixed_window, 2, m)
        # the other readings of "spline extrapolation", tuned as the interpolating spline (windows from 4, extended
        # alike): a least-squares cubic over the window (not interpolating), the natural spline extended linearly
        readings = {
            LSQ_CUBIC: lambda L: pr.sliding_regression_forecast(run.z, L, 3, m),
            NATURAL_SPLINE: lambda L: pr.natural_spline_forecast(run.z, L, m),
        }
        ext = clipped_extension(WINDOW_EXTENSION, run.z.shape[-1])
        for name, make in readings.items():
            fc[name], _, cmp.chosen[name], _, _ = tuned_forecast(
                window_candidates(4, s.window_grid), make, run.z, run.z_meas, folds, s, more=ext
            )
            fixed[name] = make(s.fixed_window)
    return replace(
        run, config=dict(config), comparison=cmp, forecasts=fc, fixed_forecasts=fixed, folds=folds, parts=parts
    )


def _merged(run: StudyRun, more: StudyRun) -> StudyRun:
    """``run`` with the methods of ``more`` (the same scene and setup, other parts) added."""
    a, b = run.comparison, more.comparison
    cmp = Comparison(
        {**a.mse, **b.mse},
        {**a.mse_fixed, **b.mse_fixed},
        {**a.chosen, **b.chosen},
        {**a.forecasts, **b.forecasts},
        {**a.learned_models, **b.learned_models},
    )
    return replace(
        run,
        comparison=cmp,
        forecasts={**run.forecasts, **more.forecasts},
        fixed_forecasts={**run.fixed_forecasts, **more.fixed_forecasts},
        parts=run.parts | more.parts,
    )


def run_study(
    config: dict, seed: int, size: StudySize = StudySize(), traces: TraceSet | None = None, keep=None
) -> StudyRun:
    """One full-size run of the study at ``config`` (every register entry), all draws from ``seed``.

    Parameters
    ----------
    traces : TraceSet, optional
        True centres to use instead of drawing them (the shipped data set, at the default regime).
    keep : tuple, optional
        Batch index whose gate images to keep (figures, recording), e.g. ``(0, 0)``.
    """
    return _methods(study_run(config, seed, size, traces, keep), config, seed)


def claim_values(run: StudyRun, seed: int = 0, claims=None) -> dict:
    """What each claim's rule reads, from one run at its configuration.

    Parameters
    ----------
    claims : iterable of str, optional
        The claims to compute (default: all); :data:`CENTROID` is always returned. A claim's value is the same
        whichever others are asked.

    Returns
    -------
    dict
        ``C004-1`` (mean per-path quantile of the per-axis ``|e|``, px), ``C004-2`` (RMS, px),
        ``C004-3`` / ``C004-3b`` (per baseline: paired ratio of its MSE to the filter's), ``C004-4``
        (recursion vs lstsq), ``C004-5`` (gains and variance), ``C004-6`` (late RMS ratio without / with
        the floor), ``C004-8`` (CPU time per frame / frame interval); and :data:`CENTROID`, the per-axis RMS
        error of the measured centres against the true ones from ``eval_start`` on (px; no claim reads it).
    """
    want = set(CLAIM_KEYS if claims is None else claims)
    c = run.config
    start = run.size.eval_start
    out = _prediction_values(run, want)
    T = run.truth.shape[-1]
    held = c.get("lost frames", "held") == "held"
    if "C004-4" in want:
        z4 = (run.z if held else run.z_meas)[0, :, 0, : min(T, 200)]
        out["C004-4"] = recursion_check(z4, [seed, 4004], float(c.get("frame loss", 0.0)), held)
    if "C004-5" in want:  # each stream is its own: skipping one claim leaves the others' draws as they were
        out["C004-5"] = _variance_check(seed, run.size.n_mc_variance, c.get("C004-5 noise", "Gaussian"))
    if "C004-8" in want:
        rng_t = np.random.default_rng(run_streams(seed)[5])
        out["C004-8"] = frame_time_ms(run, rng_t, c) / (1e3 / run.scene.frame_rate_hz)
    out[CENTROID] = root_mean_ci(np.nanmean((run.z_meas - run.truth)[0, ..., start:] ** 2, axis=(-2, -1)))
    return out


#: C004-5's values by (seed, series, noise law): all the check reads (the model's own signal, not the scene), so every
#: configuration of one seed and noise law shares one Monte Carlo run (cleared by :func:`clear_cache`).
_VARIANCE: dict = {}


def _variance_check(seed: int, n_series: int, noise: str) -> dict:
    """:func:`.derivation.variance_ratios` from the seed's own stream, computed once per (seed, series, noise)."""
    key = (int(seed), int(n_series), noise)
    if key not in _VARIANCE:
        _VARIANCE[key] = variance_ratios(np.random.default_rng(run_streams(seed)[4]), n_series, noise=noise)
    return dict(_VARIANCE[key])


def _prediction_values(run: StudyRun, want) -> dict:
    """The values of the prediction claims in ``want`` (C004-1, -2, -3, -3b, -6; see :func:`claim_values`)."""
    want = set(want) & set(CLAIM_PARTS)
    if not want:
        return {}
    c = run.config
    m = int(c["horizon"])
    start = run.size.eval_start
    fc = dict(run.forecasts if c["tuning"] == "cross-validated" else run.fixed_forecasts)
    if c["floor form"] == VARIANT_FLOOR:
        fc[PAPER] = fc[VARIANT]  # the floor read as a bound on the position gain alone
    if c["spline"] == "least-squares cubic":
        fc["cubic spline"] = fc[LSQ_CUBIC]
    elif c["spline"] == "natural cubic":
        fc["cubic spline"] = fc[NATURAL_SPLINE]
    ref = run.z_meas if c["reference"] == "measured centre" else run.truth
    names = {PAPER}.union(*({"C004-3": CLASSICAL, "C004-3b": NETWORKS}.get(k, ()) for k in want))
    mse = {name: per_trial_path_mse(fc[name], ref, m, start)[0] for name in names}
    out = {}
    if "C004-1" in want:
        e = np.abs(pr.forecast_errors(fc[PAPER], ref, m)[0, ..., start:])  # (P, 2, T')
        q = 0.99 if c["C004-1 statistic"] == "99th percentile" else 0.95
        if c["C004-1 statistic"] == "radial 95th percentile":
            e = np.sqrt(np.sum(e**2, axis=1))  # (P, T'): distance from the predicted to the reference centre
        out["C004-1"] = mean_ci_t(np.nanquantile(e.reshape(e.shape[0], -1), q, axis=1))
    if "C004-2" in want:
        out["C004-2"] = root_mean_ci(mse[PAPER] * (2.0 if c.get("C004-2 statistic") == "radial RMS" else 1.0))
    if "C004-3" in want:
        rank = mse  # what C004-3 compares: per-path MSE, or (a reading) per-path q95 of |e|, the tail
        if c["C004-3 statistic"] == "95th percentile":
            rank = {name: path_quantile(fc[name], ref, m, start, 0.95) for name in (PAPER, *CLASSICAL)}
        out["C004-3"] = {b: ratio_of_means_ci(rank[b], rank[PAPER]) for b in CLASSICAL}
    if "C004-3b" in want:
        out["C004-3b"] = {b: ratio_of_means_ci(mse[b], mse[PAPER]) for b in NETWORKS}
    if "C004-6" in want:
        late = max(run.truth.shape[-1] // 2, start)
        out["C004-6"] = late_rms_ratio(pr.growing_memory_forecast(run.z, m, 2, None), fc[PAPER], ref, m, late)
    return out


_CACHE = BoundedCache()  # scenes and runs, within a byte budget (:mod:`.cache`)


def clear_cache() -> None:
    """Forget the scenes, runs and C004-5 checks :func:`measure_batch` keeps between calls of one exploration."""
    _CACHE.clear()
    _VARIANCE.clear()


#: The entries the methods' run reads beyond the scene (the readings of ``tuning``, ``reference`` and the statistic
#: are read off one run).
METHOD_ENTRIES = ("horizon", "network lags", "network inputs")


def _key(config: dict, names) -> tuple:
    return tuple((n, config[n]) for n in names)


def _scene_key(config: dict, seed: int, size: StudySize) -> tuple:
    """What :func:`study_run` reads of a configuration, resolved: the generator's configuration (the bandwidth
    factor resolved, so the band position of a world whose bandwidth is set by hand adds nothing), the exposure,
    jitter, vibration and camera, with the seed and sizes. Configurations with one key have one scene."""
    resolve_operating_point(config)
    return (
        "scene",
        size,
        int(seed),
        scene_config(config, size),
        config.get("exposure", "instant"),
        float(config["jitter"]),
        float(config.get("vibration", 0.0)),
        camera_for(config),
    )


def _measure_group(items, size: StudySize) -> list[dict]:
    """Claim values of (configuration, seed, claims) triples that share one scene (same scene entries and seed).

    The scene is cached by what it reads (:func:`_scene_key`); the methods by that and the entries they read
    (horizon, the networks' lags and inputs), with the parts run so far: a configuration that asks for a part
    not yet run adds it to the cached run (the parts share no draw, so the numbers are those of one run of all)."""
    out = []
    for config, seed, claims in items:
        sk = _scene_key(config, seed, size)
        if sk not in _CACHE:
            _CACHE[sk] = study_run(config, seed, size)
        run = _CACHE[sk]
        parts = parts_for(claims)
        if parts is not None and config["floor form"] == VARIANT_FLOOR:  # the paper's filter read as the variant
            parts = parts | {"variant"}
        if parts is not None:
            rk = sk + _key(config, METHOD_ENTRIES)
            have = _CACHE.get(rk)
            if have is None:
                _CACHE[rk] = _methods(run, config, seed, parts)
            elif not parts <= have.parts:
                _CACHE[rk] = _merged(have, _methods(run, config, seed, parts - have.parts))
            run = _CACHE[rk]
        out.append(claim_values(replace(run, config=dict(config)), seed, claims))
    return out


def _measure_shipped(items, size: StudySize) -> tuple:
    """:func:`_measure_group` in a worker, with the scenes, runs and C004-5 checks it added (the parent keeps them)."""
    runs, checks = dict(_CACHE), set(_VARIANCE)
    out = _measure_group(items, size)
    added = {k: v for k, v in _CACHE.items() if runs.get(k) is not v}
    return out, shipping.dumps((added, {k: v for k, v in _VARIANCE.items() if k not in checks}))  # layouts kept


def _run_key(config: dict, seed: int, size: StudySize, claims) -> tuple:
    """What one group of :func:`measure_batch` shares: the scene (:func:`_scene_key`) and, where the claims read a
    method, the entries the methods' run reads (one cached run of them)."""
    methods = ("scene only",) if parts_for(claims) is None else _key(config, METHOD_ENTRIES)
    return _scene_key(config, seed, size), methods


def _cost(claims) -> float:
    """A group's relative cost, for handing the longest out first: the networks dominate, then the baselines."""
    parts = parts_for(claims)
    return 1.0 if parts is None else 2.0 + 5.0 * ("learned" in parts) + 1.0 * ("classical" in parts)


def _scene_shipped(config: dict, seed: int, size: StudySize) -> bytes:
    return shipping.dumps(study_run(config, seed, size))


def _render_scenes(groups: dict, items: list, size: StudySize, workers: int) -> None:
    """The scenes of the ``groups`` (keyed by :func:`_run_key`) not in the cache, rendered before the groups run and
    kept (layouts too, :mod:`.shipping`), so that groups sharing a scene each find it: side by side in ``workers``
    processes where two or more are missing; one shared by several groups, here. A scene of one group alone is left
    to it."""
    todo, shared = {}, {}
    for (sk, _), batch in zip(groups, items):
        if sk not in _CACHE:
            todo.setdefault(sk, batch[0][:2])
            shared[sk] = shared.get(sk, 0) + 1
    if len(todo) == 1 and max(shared.values()) > 1:
        ((sk, (config, seed)),) = todo.items()
        _CACHE[sk] = study_run(config, seed, size)
    elif len(todo) > 1:
        with fork_pool(workers) as pool:
            blobs = pool.map(_scene_shipped, *zip(*todo.values()), [size] * len(todo))
            for k, blob in zip(todo, blobs):
                _CACHE[k] = shipping.loads(blob)


def measure_batch(configs, seeds, size: StudySize = StudySize(), workers: int = 1, claims=None) -> list[dict]:
    """:func:`measure` of many (configuration, seed) pairs; configurations whose scenes read the same (the
    world's entries resolved, and the seed: :func:`_scene_key`) share one rendered scene, and those that also
    share the horizon and the networks' lags share one run of the methods (``tuning``, ``reference`` and the
    statistic are readings of it).

    Parameters
    ----------
    workers : int
        Processes the groups are spread over (1: this process), longest first; a group shares a scene and one run of
        the methods (:func:`_run_key`), and the scenes several groups share are rendered first (:func:`_render_scenes`).
        Either way the scenes and runs stay in this process's cache (a worker sends back what it added) and serve
        the later calls of the exploration; the numbers are the same for any ``workers``.
    claims : list of (set of str or None), optional
        Per configuration, the claims to compute (None: all); the methods no asked claim reads are not run
        (the explorer's ``claims=``). Each claim's value is the same as when all are asked.
    """
    from .register import DEFAULT, DEPENDS

    # each claim at its configuration projected onto its DEPENDS (entries left out of a smaller exploration, or
    # not declared by the claim, stay at their defaults): one item per distinct projection, merged back below
    asked = [None] * len(configs) if claims is None else list(claims)
    split = [claim_groups(c, k, DEPENDS, DEFAULT) for c, k in zip(configs, asked)]
    configs = [c for gs in split for c, _ in gs]
    claims = [k for gs in split for _, k in gs]
    seeds = [s for gs, s in zip(split, seeds) for _ in gs]
    groups: dict = {}
    for i, (config, seed) in enumerate(zip(configs, seeds)):
        groups.setdefault(_run_key(config, seed, size, claims[i]), []).append(i)
    groups = dict(sorted(groups.items(), key=lambda kv: -sum(_cost(claims[i]) for i in kv[1])))  # longest first
    items = [[(dict(configs[i]), int(seeds[i]), claims[i]) for i in idx] for idx in groups.values()]
    if workers > 1 and len(items) > 1:
        _render_scenes(groups, items, size, workers)
        with fork_pool(workers) as pool:  # forked after the scenes: every worker has them
            shipped = list(pool.map(_measure_shipped, items, [size] * len(items)))
        results = [out for out, _ in shipped]
        for runs, checks in (shipping.loads(blob) for _, blob in shipped):
            _CACHE.update(runs)
            _VARIANCE.update(checks)
    else:
        results = [_measure_group(batch, size) for batch in items]
    flat: list = [None] * len(configs)
    for idx, res in zip(groups.values(), results):
        for i, r in zip(idx, res):
            flat[i] = r
    out, it = [], iter(flat)
    for gs in split:
        out.append({k: v for _ in gs for k, v in next(it).items()})
    return out


def paper_filter_rms(config: dict, seed: int, size, traces_seed: int | None = None, traces=None) -> float:
    """Per-axis RMS error (px) of the paper's filter, floor cross-validated over paths, at ``config``'s horizon
    against the measured centre, on ``size.n_paths`` x ``size.n_frames`` paths of the world ``config``.

    Parameters
    ----------
    config : dict
        Register configuration (entries left out stay at the register's defaults).
    seed : int
        The run's seed (sensor noise; the paths too unless ``traces_seed`` is given).
    size : sizes.StudySize
    traces_seed : int, optional
        Draw the paths with this generator seed at the configuration's scene (e.g. the shipped data set's seed:
        the shipped paths, faster or slower).
    traces : TraceSet, optional
        The paths themselves (their first ``size.n_paths`` x ``size.n_frames``; overrides ``traces_seed``).
    """
    cfg = {**DEFAULT, **config}
    # drawn at the shipped size at least: a smaller run reads their start
    if traces is None and traces_seed is not None:
        scene = scene_config(cfg, size)
        big = replace(scene, n_paths=max(scene.n_paths, BASE_SCENE.n_paths), n_frames=max(scene.n_frames, 1000))
        traces = generate_traces(big, int(traces_seed))
    run = study_run(cfg, seed, size, traces)
    s = comparison_setup(cfg, size)
    folds = lm.path_folds(size.n_paths, size.n_folds)
    _, mse, _, _, _ = tuned_forecast(
        s.floor_grid,
        lambda nf: pr.growing_memory_forecast(run.z, s.steps, s.order, nf),
        run.z,
        run.z_meas,
        folds,
        s,
        more=clipped_extension(FLOOR_EXTENSION, run.z.shape[-1]),
    )
    return float(np.sqrt(np.mean(mse)))


def table_paths_rms(config: dict, n_paths: int, seed: int = 2005, size=None) -> float:
    """:func:`paper_filter_rms` on the first ``n_paths`` of the paths the world table was found on (``seed``,
    ``size``: 15 paths x 500 frames by default, drawn as a run of that size draws them, the spot kept on the sensor):
    the same paths whatever ``n_paths``, so fewer of them cost less and still share the table's draws."""

    size = size or StudySize(n_frames=500)
    cfg = {**DEFAULT, **config}
    traces, _ = traces_on_sensor(scene_config(cfg, size), run_streams(seed)[0], cfg["exposure"])
    return paper_filter_rms(cfg, seed, replace(size, n_paths=int(n_paths)), traces=traces)


def resolve_operating_point(config: dict) -> str | None:
    """Correct the wander's bandwidth of a joint world (two or more tabled world values changed, or a world value
    and the horizon) to the paper's operating point before its scene is drawn (:func:`.operating.joint_factor` on :func:`table_paths_rms`); a
    single world keeps its table row. Idempotent: each world combination is corrected once in a process.

    Returns why the world is outside the paper's operating point (the explorer's ``operating_point``): a joint
    world whose filter errs outside the paper's 1-2 px at the corrected bandwidth
    (:data:`.operating.JOINT_OUTSIDE_BAND`); None otherwise (a bandwidth set by hand is marked by the register)."""
    cfg = {**DEFAULT, **config}
    _, world, rows = table_factors(cfg)
    if cfg["bandwidth"] != CALIBRATED or rows < 2:
        return None
    joint_factor(world, lambda c: table_paths_rms(c, JOINT_PATHS))
    lost = JOINT_OUTSIDE_BAND.get(world)
    return lost and (
        f"the paper's filter errs {lost[1]:.2f} px per axis in this joint world at the bandwidth the correction "
        f"reached, outside the paper's {BAND_PX[0]:g}-{BAND_PX[1]:g} px"
    )


def _declared(args, kwargs):
    """``(DEPENDS, default)``: each claim is measured at its configuration projected onto its DEPENDS."""
    from .register import DEFAULT, DEPENDS

    return DEPENDS, DEFAULT


def measure(config: dict, seed: int, size: StudySize = StudySize(), claims=None) -> dict:
    """The explorer's measurement function: one full-size run at ``config`` with all random draws
    from ``seed``, reduced to what each claim's rule reads (:func:`claim_values`; ``claims``: only those,
    running only the methods they read)."""
    config = {**DEFAULT, **config}
    run = study_run(config, seed, size)
    parts = parts_for(claims)
    if parts is not None:  # the paper's filter read as the variant floor: that part too (as _measure_group runs it)
        run = _methods(run, config, seed, parts | ({"variant"} if config["floor form"] == VARIANT_FLOOR else set()))
    return claim_values(run, seed, claims)


measure = as_declared(CLAIM_KEYS[:-1], _declared)(measure)  # no decorator for mutmut; CENTROID: no claim reads it
