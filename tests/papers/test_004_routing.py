"""Paper 004: the routing of the measurement (``measure``, ``measure_batch``) and the helpers a claim value passes
through (``prediction_study``'s per-path scores, ``intervals``).

``measure`` renders one scene at the configuration (every entry it leaves out at the register's default), runs the
methods the asked claims read and reduces the run to the claims' values; ``measure_batch`` must give, for every
configuration and seed, what ``measure`` gives, while rendering a scene once for every configuration whose scene
reads the same (the world's entries, the seed, the sizes) and running the methods once for every configuration that
also shares the horizon and the networks' lags and inputs. Here the scene, the methods and the reduction are
replaced by recorders whose answers depend on exactly what the module text says each reads, so a configuration
handed the wrong scene, methods missing for a claim, a claim's value dropped or mixed up with another
configuration's changes a value. The per-path scores are written out from their definitions on hand-built series.
"""

from __future__ import annotations

import os
import sys
from dataclasses import replace

import numpy as np
import pytest
from scipy import stats

from tvtrack.montecarlo import mean_ci
from tvtrack.papers.p004_laser_spot_prediction import intervals, shipping, study
from tvtrack.papers.p004_laser_spot_prediction import prediction_study as ps
from tvtrack.papers.p004_laser_spot_prediction.prediction_study import Comparison
from tvtrack.papers.p004_laser_spot_prediction.register import DEFAULT
from tvtrack.papers.p004_laser_spot_prediction.sizes import StudySize
from tvtrack.papers.p004_laser_spot_prediction.world import camera_for, scene_config

SIZE = StudySize(n_paths=2, n_frames=50)
MEASURE = study.measure.__wrapped__  # beneath the projection onto each claim's DEPENDS
VARIANT = {"floor form": study.VARIANT_FLOOR}


def ahead() -> bool:
    """Whether the scene being rendered is rendered ahead of the groups (by ``_render_scenes``)."""
    frame = sys._getframe(1)
    while frame is not None:
        if "render_scenes" in frame.f_code.co_name or "scene_shipped" in frame.f_code.co_name:
            return True
        frame = frame.f_back
    return False


def scene_of(config: dict, seed: int, size) -> tuple:
    """What a scene reads, as the module text states it: the generator's configuration, the exposure, jitter,
    vibration and camera, with the seed and sizes."""
    return (
        int(seed),
        size,
        scene_config(config, size),
        config.get("exposure", "instant"),
        float(config["jitter"]),
        float(config.get("vibration", 0.0)),
        camera_for(config),
    )


@pytest.fixture
def fake(monkeypatch, tmp_path):
    """The scene, the methods and the reduction replaced by recorders (and the study's caches emptied); every scene
    rendered, in this process or a worker, is written to ``seen["log"]`` with its process id."""
    seen = {"scenes": [], "methods": [], "log": tmp_path / "scenes.txt"}

    def study_run(config, seed, size, traces=None, keep=None):
        seen["scenes"].append((dict(config), seed))
        with open(seen["log"], "a") as f:
            f.write(f"{os.getpid()} {hash(scene_of(config, seed, size))} {int(ahead())}\n")
        none = dict.fromkeys(("camera", "truth", "z_meas", "z", "path_rms", "jitter_rms", "intensity"))
        return study.StudyRun(
            dict(config),
            size,
            scene_of(config, seed, size),
            **none,
            **dict.fromkeys(("centroid_rms", "lost_share", "clipped_share"), 0.0),
        )

    def methods(run, config, seed, parts):
        seen["methods"].append((run.scene, seed, {k: config[k] for k in study.METHOD_ENTRIES}, frozenset(parts)))
        what = (run.scene, seed, *(config[k] for k in study.METHOD_ENTRIES))
        fc = {p: what for p in {"paper", *parts}}
        cmp = Comparison(dict(fc), {}, {}, dict(fc), {})
        return replace(run, config=dict(config), comparison=cmp, forecasts=fc, fixed_forecasts=fc, parts=parts)

    def claim_values(run, seed=0, claims=None):
        out = {}
        for c in study.CLAIM_KEYS[:-1]:
            if claims is None or c in claims:
                reads = ("paper", *study.CLAIM_PARTS[c]) if c in study.CLAIM_PARTS else ()
                reads += ("variant",) if reads and run.config["floor form"] == study.VARIANT_FLOOR else ()
                out[c] = (run.scene, seed, tuple(sorted(run.config.items())), {p: run.forecasts[p] for p in reads})
        if claims is None or "C004-5" in claims:  # C004-5's check, kept by seed as the study keeps it
            study._VARIANCE.setdefault((seed, "check"), seed)
        return out | {study.CENTROID: (run.scene, seed)}

    monkeypatch.setattr(study, "study_run", study_run)
    monkeypatch.setattr(study, "_methods", methods)
    monkeypatch.setattr(study, "claim_values", claim_values)
    study.clear_cache()
    yield seen
    study.clear_cache()


def test_measure_fills_the_configuration_and_runs_the_methods_the_claims_read(fake):
    got = MEASURE({"horizon": 2}, 5, SIZE, claims=["C004-2", "C004-3"])
    cfg = {**DEFAULT, "horizon": 2}
    assert fake["scenes"] == [(cfg, 5)]
    assert fake["methods"] == [
        (
            scene_of(cfg, 5, SIZE),
            5,
            {**{k: DEFAULT[k] for k in study.METHOD_ENTRIES}, "horizon": 2},
            frozenset({"classical"}),
        )
    ]
    assert set(got) == {"C004-2", "C004-3", study.CENTROID} and got["C004-2"][1] == 5
    fake["methods"].clear()
    assert set(MEASURE(dict(DEFAULT), 5, SIZE, claims=["C004-4", "C004-5"])) == {"C004-4", "C004-5", study.CENTROID}
    assert fake["methods"] == []  # no claim asked reads a method
    MEASURE(dict(DEFAULT), 5, SIZE)
    assert fake["methods"][-1][3] == frozenset({"classical", "learned"})  # every claim: both baselines' parts


def test_measure_runs_the_variant_floor_where_the_floor_form_reads_the_paper_s_filter_as_it(fake):
    """The floor read as a bound on the position gain makes the variant the paper's filter: ``measure`` must run it,
    as ``measure_batch`` does (``claim_values`` reads ``fc[VARIANT]`` then)."""
    got = MEASURE({**DEFAULT, **VARIANT}, 5, SIZE, claims=["C004-2"])
    assert fake["methods"][-1][3] == frozenset({"variant"}) and "variant" in got["C004-2"][3]


CONFIGS = [
    dict(DEFAULT),
    {**DEFAULT, "horizon": 2},
    {**DEFAULT, "jitter": 1.0},
    {**DEFAULT, **VARIANT, "tuning": "fixed"},
    {**DEFAULT, "network lags": 10, "spline": "natural cubic"},
    {**DEFAULT, "horizon": 2, "reference": "true centre"},
]
SEEDS = [7, 7, 7, 7, 8, 7]
CLAIMS = [None, {"C004-2", "C004-3"}, {"C004-3b", "C004-4"}, {"C004-1", "C004-6"}, None, {"C004-3", "C004-3b"}]


def test_a_batch_measures_each_configuration_as_measure_does_sharing_scenes_and_methods(fake):
    want = [study.measure(c, s, SIZE, claims=k) for c, s, k in zip(CONFIGS, SEEDS, CLAIMS)]
    fake["scenes"].clear()
    fake["methods"].clear()
    got = study.measure_batch(CONFIGS, SEEDS, SIZE, claims=CLAIMS)
    assert got == want
    assert [list(g) for g in got] == [list(w) for w in want]
    scenes = [scene_of(c, s, SIZE) for c, s in fake["scenes"]]
    assert len(scenes) == len(set(scenes)) == 3  # the default world at seeds 7 and 8, the jitter's at 7
    done = {}
    for scene, seed, entries, parts in fake["methods"]:  # each method part once per scene and method entries
        key = (scene, seed, tuple(entries.values()))
        assert not parts & done.get(key, frozenset())
        done[key] = done.get(key, frozenset()) | parts
    assert set(study.measure_batch(CONFIGS[:1], SEEDS[:1], SIZE)[0]) == set(study.CLAIM_KEYS)  # all claims asked
    assert len(fake["scenes"]) == 3  # the second batch finds its scene and methods kept


def rendered(seen) -> list[tuple[int, int, int]]:
    """(process id, scene, rendered ahead of the groups) of every scene rendered so far; the log emptied."""
    lines = seen["log"].read_text().split() if seen["log"].exists() else []
    seen["log"].unlink(missing_ok=True)
    return [(int(a), int(b), int(c)) for a, b, c in zip(lines[::3], lines[1::3], lines[2::3])]


def test_a_batch_on_two_workers_gives_what_one_gives_and_keeps_the_scenes(fake):
    one = study.measure_batch(CONFIGS, SEEDS, SIZE, claims=CLAIMS)
    assert {(pid, first) for pid, _, first in rendered(fake)} == {(os.getpid(), 0)}
    study.clear_cache()
    two = study.measure_batch(CONFIGS, SEEDS, SIZE, workers=2, claims=CLAIMS)
    assert two == one
    scenes = rendered(fake)  # the three scenes several groups share: rendered once each, ahead, in the workers
    assert len(scenes) == len({s for _, s, _ in scenes}) == 3 and os.getpid() not in {pid for pid, _, _ in scenes}
    assert all(first for _, _, first in scenes)
    kept = len(fake["scenes"])
    assert study.measure_batch(CONFIGS, SEEDS, SIZE, claims=CLAIMS) == one
    assert len(fake["scenes"]) == kept  # every scene and run came back to this process's cache


def test_the_keys_share_a_scene_only_where_it_reads_the_same_and_methods_only_at_the_same_entries():
    size = StudySize(n_paths=2, n_frames=50)
    base = study._scene_key(dict(DEFAULT), 3, size)
    assert base == ("scene", *scene_of(DEFAULT, 3, size)[1:2], 3, *scene_of(DEFAULT, 3, size)[2:])
    assert study._scene_key({**DEFAULT, "horizon": 2, "tuning": "fixed"}, 3, size) == base
    # a horizon with a table row is another world (calibrated there), unless the bandwidth is set by hand
    assert study._scene_key({**DEFAULT, "horizon": 10}, 3, size) != base
    hand = {**DEFAULT, "bandwidth": 1.0}
    assert study._scene_key({**hand, "horizon": 10}, 3, size) == study._scene_key(hand, 3, size)
    for other in ({"jitter": 4.0}, {"vibration": 1.0}, {"exposure": "interlaced, frame integration"}):
        assert study._scene_key({**DEFAULT, **other}, 3, size) != base
        hand = {**DEFAULT, "bandwidth": 1.0}  # the generator's corners then read neither vibration nor exposure
        assert scene_config({**hand, **other}, size) == scene_config(hand, size)
        assert study._scene_key({**hand, **other}, 3, size) != study._scene_key(hand, 3, size)
    assert study._scene_key(dict(DEFAULT), 4, size) != base
    assert study._key({"a": 1, "b": 2, "c": 3}, ("c", "a")) == (("c", 3), ("a", 1))
    assert study._run_key(dict(DEFAULT), 3, size, {"C004-4"}) == (base, ("scene only",))
    left_out = {k: v for k, v in DEFAULT.items() if k not in ("exposure", "vibration")}  # at their defaults
    assert (DEFAULT["exposure"], DEFAULT["vibration"]) == ("instant", 0.0)
    assert study._scene_key(left_out, 3, size) == base
    methods = (("horizon", 1), ("network lags", "cross-validated"), ("network inputs", "increments"))
    assert study._run_key(dict(DEFAULT), 3, size, {"C004-2"}) == (base, methods)
    assert study._run_key({**DEFAULT, "network lags": 10}, 3, size, None)[1][1] == ("network lags", 10)


# --- the per-path scores (prediction_study.py) and the intervals (intervals.py) -----------------------------------


def series(seed=1, P=4, T=30):
    rng = np.random.default_rng(seed)
    ref = np.cumsum(rng.normal(0, 1, (1, P, 2, T)), axis=-1)
    return ref, ref + rng.normal(0, 1, ref.shape) * np.linspace(0.5, 2, P)[None, :, None, None]


def test_a_path_score_is_the_mean_square_of_the_forecast_steps_ahead_from_the_start_over_both_axes():
    ref, fc = series()
    ref[0, 1, 0, 20] = np.nan  # a lost frame is skipped
    got = ps.per_trial_path_mse(fc, ref, 3, 12)
    want = [
        [
            np.nanmean([(fc[0, p, a, n - 3] - ref[0, p, a, n]) ** 2 for a in (0, 1) for n in range(12, 30)])
            for p in range(4)
        ]
    ]
    np.testing.assert_allclose(got, want, rtol=1e-12)
    q = ps.path_quantile(fc, ref, 2, 5, 0.9)
    e = [np.abs(fc[0, p, :, 3:-2] - ref[0, p, :, 5:]).ravel() for p in range(4)]
    np.testing.assert_allclose(q, [np.nanquantile(x, 0.9) for x in e], rtol=1e-12)


def test_the_late_rms_ratio_is_the_square_root_of_the_paired_ratio_of_late_mean_squares():
    ref, fc = series(P=12, T=40)
    floor = ref + 0.5 * (fc - ref)
    got = ps.late_rms_ratio(fc, floor, ref, 1, 20)
    a = np.mean((fc[0, ..., 19:-1] - ref[0, ..., 20:]) ** 2, axis=(-2, -1))
    b = np.mean((floor[0, ..., 19:-1] - ref[0, ..., 20:]) ** 2, axis=(-2, -1))
    assert got.value == pytest.approx(np.sqrt(a.mean() / b.mean()), rel=1e-12)
    r = intervals.ratio_of_means_ci(a, b)
    assert (got.ci_low, got.ci_high, got.n) == (pytest.approx(np.sqrt(r.ci_low)), pytest.approx(np.sqrt(r.ci_high)), 12)
    assert got.stderr == pytest.approx(r.stderr / (2 * np.sqrt(r.value))) and got.confidence == 0.95
    assert got.method == "square root of the " + r.method


def test_the_comparison_setup_reads_the_horizon_the_lags_the_inputs_and_the_sizes():
    size = replace(SIZE, eval_start=11, floor_grid=(3, 9), window_grid=(5, 7), fixed_floor=9, fixed_window=7)
    size = replace(size, lag_grid=(2, 3), lag_tuning_samples=900, train_samples=600, mlp_hidden_units=5)
    s = ps.comparison_setup({"horizon": 3, "network lags": 10, "network inputs": "absolute centres"}, size)
    assert (s.steps, s.start, s.floor_grid, s.window_grid, s.fixed_floor, s.fixed_window) == (
        3,
        11,
        (3, 9),
        (5, 7),
        9,
        7,
    )
    assert (s.learned_lags, s.lag_grid, s.lag_tuning_samples) == (10, (2, 3), 600)  # tuning samples at most training
    assert s.learned_kw == dict(
        hidden_units=5, rbf_centres=size.rbf_centres, max_samples=600, inputs="absolute centres"
    )
    cv = ps.comparison_setup({"horizon": 1, "network lags": "cross-validated", "network inputs": "increments"}, size)
    assert cv.learned_lags is None and cv.lag_tuning_samples == 600
    assert ps.comparison_setup(dict(DEFAULT), replace(size, lag_tuning_samples=300)).lag_tuning_samples == 300


def test_the_intervals_treat_each_path_as_one_trial():
    ms = np.array([1.0, 4.0, 2.25, 9.0, 0.25, 1.0])
    got = intervals.root_mean_ci(ms)
    assert got.value == pytest.approx(np.sqrt(ms.mean())) and got.n == 6 and got.ci_low < got.value < got.ci_high
    den = np.array([1.0, 3.0, 2.0, 5.0, 0.5, 4.0])
    r = intervals.ratio_of_means_ci(2 * den, den)  # paired path by path: every resample's ratio is 2
    assert (r.value, r.ci_low, r.ci_high, r.n) == (pytest.approx(2.0), pytest.approx(2.0), pytest.approx(2.0), 6)
    x = np.array([0.1, 0.2, 0.15, 0.3, 2.5, 0.12, 0.18, 0.22])  # skewed: bootstrap-t differs from Student t
    m = intervals.mean_ci_t(x)
    half = stats.t.ppf(0.975, 7) * x.std(ddof=1) / np.sqrt(8)
    assert m.value == pytest.approx(x.mean()) and m.method.startswith("bootstrap-t")
    assert abs(m.ci_high - (x.mean() + half)) > 0.01 and (m.ci_low, m.ci_high) == pytest.approx(
        (mean_ci(x, method="bootstrap-t").ci_low, mean_ci(x, method="bootstrap-t").ci_high)
    )


def test_a_batch_runs_only_the_methods_its_claims_read_and_each_once(fake):
    study.measure_batch([dict(DEFAULT)], [7], SIZE, claims=[{"C004-3", "C004-4"}])
    assert [m[3] for m in fake["methods"]] == [frozenset({"classical"})]
    fake["methods"].clear()
    study.measure_batch([{**DEFAULT, **VARIANT}, dict(DEFAULT)], [3, 4], SIZE, claims=[{"C004-2"}, {"C004-2"}])
    assert sorted(m[3] for m in fake["methods"]) == [frozenset(), frozenset({"variant"})]  # the variant floor's only
    fake["methods"].clear()
    same = [dict(DEFAULT), {**DEFAULT, "reference": "true centre"}, {**DEFAULT, "tuning": "fixed"}]
    study.measure_batch(same, [5, 5, 5], SIZE, claims=[{"C004-2"}, {"C004-2"}, {"C004-2", "C004-3"}])
    assert [m[3] for m in fake["methods"]] == [frozenset(), frozenset({"classical"})]  # kept, then one part added


def test_a_scene_two_groups_share_is_rendered_once_before_they_run(fake):
    configs = [dict(DEFAULT), {**DEFAULT, "horizon": 2}]  # one scene, two runs of the methods
    got = study.measure_batch(configs, [2, 2], SIZE, workers=2, claims=[{"C004-2"}, {"C004-2"}])
    assert rendered(fake) == [(os.getpid(), hash(scene_of(DEFAULT, 2, SIZE)), 1)]  # here, ahead, before the fork
    assert got == [study.measure(c, 2, SIZE, claims={"C004-2"}) for c in configs]
    rendered(fake)  # (measure renders its own)
    jit = {**DEFAULT, "jitter": 1.0}  # two scenes, each two groups': both rendered ahead, in workers
    configs = [dict(DEFAULT), {**DEFAULT, "horizon": 2}, jit, {**jit, "horizon": 2}]
    study.measure_batch(configs, [6] * 4, SIZE, workers=2, claims=[{"C004-2"}] * 4)
    scenes = rendered(fake)
    assert len(scenes) == 2 and all(first and pid != os.getpid() for pid, _, first in scenes)


def test_a_scene_of_one_group_alone_is_left_to_it_and_one_group_runs_here(fake):
    study.measure_batch([dict(DEFAULT)], [3], SIZE, claims=[{"C004-2"}])  # kept
    rendered(fake)
    configs = [{**DEFAULT, "horizon": 2}, {**DEFAULT, "jitter": 1.0}]  # the kept scene, and one of one group
    study.measure_batch(configs, [3, 3], SIZE, workers=2, claims=[{"C004-2"}, {"C004-2"}])
    ((pid, scene, first),) = rendered(fake)
    assert scene == hash(scene_of(configs[1], 3, SIZE)) and not first and pid != os.getpid()  # by its group
    study.measure_batch([{**DEFAULT, "jitter": 4.0}], [3], SIZE, workers=2, claims=[{"C004-2"}])
    assert [(pid, first) for pid, _, first in rendered(fake)] == [(os.getpid(), 0)]  # one group: no workers


def test_a_worker_ships_back_the_scenes_runs_and_checks_it_added(fake):
    study.measure_batch([dict(DEFAULT)], [1], SIZE, claims=[{"C004-2", "C004-5"}])  # kept before the worker starts
    before, checks = dict(study._CACHE), dict(study._VARIANCE)
    items = [(dict(DEFAULT), 1, {"C004-2"}), ({**DEFAULT, "jitter": 1.0}, 2, {"C004-3", "C004-5"})]
    out, blob = study._measure_shipped(items, SIZE)
    assert out == [MEASURE(c, s, SIZE, claims=k) for c, s, k in items]
    added, new_checks = shipping.loads(blob)
    assert set(added) == set(study._CACHE) - set(before) and len(added) == 2  # the jitter's scene and its run
    assert all(added[k].scene == study._CACHE[k].scene for k in added)
    assert new_checks == {(2, "check"): 2} and (1, "check") in checks


def _bare_run(tag: str, parts: frozenset) -> study.StudyRun:
    """A :class:`study.StudyRun` whose every field names where it came from (no scene is rendered)."""
    cmp = Comparison(*({f"{tag} {k}": f"{tag} {k} value"} for k in ("mse", "fixed", "chosen", "fc", "models")))
    return study.StudyRun(
        {"from": tag}, f"{tag} size", f"{tag} scene", f"{tag} camera", f"{tag} truth", f"{tag} z_meas", f"{tag} z",
        f"{tag} path_rms", f"{tag} jitter", 1.0, 0.1, 0.01, f"{tag} intensity", track=f"{tag} track", comparison=cmp,
        forecasts={f"{tag} forecast": 1, "paper": tag}, fixed_forecasts={f"{tag} fixed": 2}, folds=[tag], draws=3,
        parts=parts,
    )  # fmt: skip


def test_merging_two_method_runs_keeps_the_first_runs_scene_and_adds_the_second_runs_methods():
    """``study._merged``: the methods of ``more`` (the same scene, other parts) added to ``run``: every comparison
    table, the forecasts and the parts are the union; the scene, the measured series and everything else are
    ``run``'s."""
    a, b = _bare_run("a", frozenset({"classical"})), _bare_run("b", frozenset({"learned", "variant"}))
    m = study._merged(a, b)
    for field, k in (("mse", "mse"), ("mse_fixed", "fixed"), ("chosen", "chosen"), ("forecasts", "fc")):
        assert getattr(m.comparison, field) == {f"a {k}": f"a {k} value", f"b {k}": f"b {k} value"}, field
    assert m.comparison.learned_models == {"a models": "a models value", "b models": "b models value"}
    assert m.forecasts == {"a forecast": 1, "b forecast": 1, "paper": "b"}  # the paper's filter: the same either way
    assert m.fixed_forecasts == {"a fixed": 2, "b fixed": 2}
    assert m.parts == frozenset({"classical", "learned", "variant"})
    kept = ("config", "size", "scene", "camera", "truth", "z_meas", "z", "path_rms", "jitter_rms", "intensity")
    assert all(getattr(m, f) == getattr(a, f) for f in (*kept, "track", "folds", "draws", "centroid_rms"))
    assert (m.lost_share, m.clipped_share) == (a.lost_share, a.clipped_share)
    assert (a.parts, a.forecasts) == (frozenset({"classical"}), {"a forecast": 1, "paper": "a"})  # a left as it was
