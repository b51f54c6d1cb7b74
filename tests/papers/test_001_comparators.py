"""Paper 001's comparators, pinned fast: which training runs each comparator is tuned on (their own seed, white
Gaussian errors, never the test runs), over which grids, scored on which span, the tuned value flagged on a grid edge,
and how each comparator is built (the fixed filters' gain laws, the IMM's models and priors, the VD filter's
threshold, the raised 2nd-order filter's gain index). The filters, the IMM, the mode logic and the measurement draws
are replaced by recorders or run on a scenario of nine frames, so the file takes a few seconds."""

from __future__ import annotations

import dataclasses
import types

import numpy as np
import pytest

from tvtrack.filters.imm import cv_ca_models
from tvtrack.papers.p001_maneuver_occlusion_kf import comparators as C
from tvtrack.papers.p001_maneuver_occlusion_kf import scenario as S

SPANS = S.TUNING_SPANS
CACHED = ("tuned_comparators", "_training", "_scores_without_alpha", "_vd_statistic", "_scores_vd")


@pytest.fixture(autouse=True)
def _cold_caches():
    """Every test starts and ends with the tuning caches empty (a cached result would hide the code under test)."""
    clear = [getattr(getattr(C, name), "cache_clear", lambda: None) for name in CACHED]
    for c in clear:
        c()
    yield
    for c in clear:
        c()


def tiny(n_frames: int = 9) -> S.Scenario:
    """1 frame/s, 9 frames: onset 2, lost at 6 and 7, back at 8; the truth's positions 10 t (x) and -3 t (y)."""
    f = np.arange(n_frames)
    truth = np.zeros((2, n_frames, 3))
    truth[0, :, 0], truth[1, :, 0] = 10.0 * f, -3.0 * f
    truth[:, :, 1] = [[10.0], [-3.0]]
    return S.Scenario(1.0, n_frames, 2, 6, 8, (f < 6) | (f >= 8), truth)


# the frames of each tuning span in the tiny scenario (4 s settled = frame 4), written out by hand
FRAMES = {
    "4 s to loss": [4, 5],
    "onset to loss": [2, 3, 4, 5],
    "visible after 4 s": [4, 5, 8],
    "end of the loss": [7],
    "last frame before the loss": [5],
}


def test_tiny_spans_are_the_hand_frames():
    sc = tiny()
    assert set(FRAMES) == set(SPANS)
    for span, frames in FRAMES.items():
        assert list(np.flatnonzero(S.span_mask(span, sc))) == frames


# ---------------------------------------------------------------------------------------------------------------
# how each comparator is built


def test_fixed_filters_freeze_the_growing_memory_law_and_coast_on_nan(monkeypatch):
    sc = tiny()
    calls = []

    def gains(order, k_bound, n_max=None):
        calls.append(("gains", order, k_bound, n_max))
        return f"G{order}"

    def run(z, gains_):
        calls.append(("run", z.copy(), gains_))
        return np.stack([z * 2.0, z * 3.0], axis=-1)

    monkeypatch.setattr(C, "gain_schedule", gains)
    monkeypatch.setattr(C, "scheduled_filter", run)
    z = np.arange(18.0).reshape(2, 9) + 1.0
    masked = np.where(sc.visible, z, np.nan)
    for name, order in (("fixed 2nd order", 1), ("fixed 3rd order", 2)):
        calls.clear()
        x = C.comparator_positions(name, (7.9,), z, sc, 0.5)
        np.testing.assert_array_equal(x, masked * 2.0)  # the position column
        (_, o, kb, n), (_, zz, g) = calls
        assert (o, kb, n) == (order, 7, 9) and type(kb) is int
        np.testing.assert_array_equal(zz, masked)
        assert g == f"G{order}"


def test_imm_and_vd_settings_reach_their_filters(monkeypatch):
    sc = tiny()
    z = np.ones((3, 2, 9))
    seen = {}

    def imm(z_, sc_, q, p, coast, sigma):
        seen["imm"] = (z_, sc_, q, p, coast, sigma)
        return np.stack([np.full((3, 2, 9), 4.0), np.full((3, 2, 9), 5.0), np.full((3, 2, 9), 6.0)], axis=-1)

    def vdf(*args):
        seen["vdf"] = args
        return types.SimpleNamespace(x=np.stack([np.full((3, 2, 9), 7.0), np.full((3, 2, 9), 8.0)], axis=-1))

    monkeypatch.setattr(C, "_imm", imm)
    monkeypatch.setattr(C, "vd_filter_run", vdf)
    x = C.comparator_positions("IMM", (1e-3, 0.99, "frozen"), z, sc, 0.5)
    assert np.all(x == 4.0) and x.shape == (3, 2, 9)
    assert seen["imm"][0] is z and seen["imm"][1] is sc and seen["imm"][2:] == (1e-3, 0.99, "frozen", 0.5)
    x = C.comparator_positions("VD filter", (1e-5, 10.0, 2.5), z, sc, 0.5)
    assert np.all(x == 7.0) and x.shape == (3, 2, 9)
    z_, vis, q_cv, q_ca, sigma, window, thr = seen["vdf"]
    assert z_ is z and vis is sc.visible
    assert (q_cv, q_ca, sigma, window, thr) == (0.0, 1e-5, 0.5, 10, 2.5) and type(window) is int
    with pytest.raises(ValueError, match="must be one of"):
        C.comparator_positions("Kalman", (1,), z, sc, 0.5)


def test_imm_models_transition_priors_and_coast(monkeypatch):
    sc = tiny()
    z = np.arange(18.0).reshape(2, 9)
    seen = {}

    def models(q_cv, q_ca):
        seen["models"] = (q_cv, q_ca)
        return cv_ca_models(q_cv, q_ca)

    def states(zs, Fs, Qs, R, M, x0, P0, mu0, coast="mix"):
        seen["states"] = (zs, Fs, Qs, R, M, x0, P0, mu0, coast)
        return "combined"

    monkeypatch.setattr(C, "cv_ca_models", models)
    monkeypatch.setattr(C, "imm_states", states)
    assert C._imm(z, sc, 3e-3, 0.95, "mode", 0.5) == "combined"
    assert seen["models"] == (0.0, 3e-3)  # the CV model without process noise
    zs, Fs, Qs, R, M, x0, P0, mu0, coast = seen["states"]
    np.testing.assert_array_equal(zs, np.where(sc.visible, z, np.nan))
    Fr, Qr = cv_ca_models(0.0, 3e-3)
    for a, b in zip((*Fs, *Qs), (*Fr, *Qr)):
        np.testing.assert_array_equal(a, b)
    assert R == pytest.approx(0.25)
    np.testing.assert_allclose(M, [[0.95, 0.05], [0.05, 0.95]], rtol=1e-12)
    np.testing.assert_array_equal(x0, np.zeros(3))
    np.testing.assert_array_equal(P0, np.diag([1e6, 1e4, 1.0]))
    assert list(mu0) == [0.5, 0.5] and coast == "mode"


def test_imm_runs_on_a_few_frames():
    """The real compiled twin on a short straight track: the combined state follows it (not the scale of nan)."""
    sc = tiny()
    x = C.comparator_positions("IMM", (1e-4, 0.99, "mix"), sc.truth[:, :, 0], sc, 1.0)
    assert x.shape == (2, 9)
    np.testing.assert_allclose(x, sc.truth[:, :, 0], atol=0.01)  # coasting along the line through frames 6, 7


# ---------------------------------------------------------------------------------------------------------------
# scoring


def test_span_mean_squares_by_hand():
    sc = tiny()
    truth = sc.truth[None, :, :, 0]
    err = np.arange(2 * 2 * 9, dtype=float).reshape(2, 2, 9) % 7 - 3.0
    ms = C._span_ms(truth + err, sc, truth)
    assert list(ms) == list(SPANS)
    for span, frames in FRAMES.items():
        expect = [np.mean([err[r, c, f] ** 2 for c in (0, 1) for f in frames]) for r in (0, 1)]
        np.testing.assert_allclose(ms[span], expect, rtol=1e-12)


def test_score_reads_the_training_world_and_its_sigma(monkeypatch):
    sc = tiny()
    truth = sc.truth[None, :, :, 0]
    z = np.zeros((2, 2, 9))
    err = np.zeros((2, 2, 9))
    err[0, 0, 5], err[1, 1, 7] = 2.0, 4.0
    seen = []
    monkeypatch.setattr(C, "_training", lambda world: (seen.append(world), (sc, z, truth))[1])

    def positions(name, setting, z_, sc_, sigma):
        seen.append((name, setting, z_ is z, sc_ is sc, sigma))
        return truth + err

    monkeypatch.setattr(C, "comparator_positions", positions)
    world = (1.0, 2, 3, 0.7, "m", "u", "y")
    out = C._score(world, "IMM", (1, 2, "mix"))
    assert seen == [world, ("IMM", (1, 2, "mix"), True, True, 0.7)]
    assert out == pytest.approx(
        {
            "4 s to loss": 4 / 4 / 2,  # run 0: 2² over 2 channels x 2 frames; run 1: 0
            "onset to loss": 4 / 8 / 2,
            "visible after 4 s": 4 / 6 / 2,
            "end of the loss": 16 / 2 / 2,
            "last frame before the loss": 4 / 2 / 2,
        }
    )
    assert all(type(v) is float for v in out.values())


def test_compensation_bias2_is_the_squared_mean_over_runs_from_the_onset_to_the_rounded_end():
    sc = dataclasses.replace(tiny(), fps=2.0)  # the same frames at 2 frames/s: the end in seconds times the rate
    err = np.zeros((2, 2, 9))
    err[0, 0, 1], err[0, 0, 2], err[0, 1, 3], err[1, 0, 4], err[1, 1, 5] = 9.0, 1.0, 2.0, 3.0, 5.0
    err[1, 0, 2] = -1.0  # cancels run 0's error at frame 2 in the mean over runs
    x = sc.truth[None, :, :, 0] + err
    # frames 2, 3 (end frame 4.4): means over runs 0 (frame 2), 1 (channel 1, frame 3); 2 channels x 2 frames
    assert C.compensation_bias2(x, sc, 2.2) == pytest.approx(1.0 / 4)
    # frames 2, 3, 4 (end 4.6): and 1.5 at frame 4, channel 0
    assert C.compensation_bias2(x, sc, 2.3) == pytest.approx((1.0 + 2.25) / 6)
    assert type(C.compensation_bias2(x, sc, 2.3)) is float


# ---------------------------------------------------------------------------------------------------------------
# the training runs and the tuning


def test_training_runs_are_white_gaussian_draws_of_their_own_seed():
    world = (5.0, 2, 17, 0.5, "2 s acceleration", "el/frame per s", "v -6, a -0.05")
    sc, z, truth = C._training(world)
    ref = S.config_scenario(
        {
            "frame_rate_hz": 5.0,
            "manoeuvre": "2 s acceleration",
            "accel_unit": "el/frame per s",
            "channel_y": "v -6, a -0.05",
        }
    )
    assert sc.T == ref.T == 125 and sc.onset == ref.onset
    np.testing.assert_array_equal(sc.truth, ref.truth)
    np.testing.assert_array_equal(truth, ref.truth[None, :, :, 0])
    e = np.random.default_rng(17).standard_normal((2, 2, 125))
    np.testing.assert_allclose(z, ref.truth[None, :, :, 0] + 0.5 * e, rtol=0, atol=1e-12)
    assert not z.flags.writeable


def test_grids_default_to_the_stated_grids_and_take_overrides():
    g = C._grids(())
    assert g == {
        "fixed2": S.FIXED2_GRID,
        "fixed3": S.FIXED3_GRID,
        "imm_q_ca": S.IMM_Q_CA_GRID,
        "imm_p_stay": S.IMM_P_STAY_GRID,
        "vdf_q_ca": S.VDF_Q_CA_GRID,
        "vdf_windows": S.VDF_WINDOWS,
    }
    g = C._grids((("fixed3", (3, 9)), ("vdf_windows", (4,))))
    assert g["fixed3"] == (3, 9) and g["vdf_windows"] == (4,) and g["fixed2"] == S.FIXED2_GRID


def test_on_edge_flags_grid_ends_but_not_physical_floors():
    g = C._grids(())
    edge = lambda name, best: C._on_edge(name, best, g)  # noqa: E731
    assert not edge("fixed 2nd order", (2,))  # the 2-point fit's floor
    assert edge("fixed 2nd order", (400,)) and not edge("fixed 2nd order", (5,))
    assert not edge("fixed 3rd order", (3,)) and edge("fixed 3rd order", (400,))
    assert edge("fixed 3rd order", (5,)) is False
    assert edge("IMM", (1e-7, 0.99, "mix")) and edge("IMM", (1e-2, 0.99, "mix"))
    assert edge("IMM", (1e-4, 0.9, "mix")) and edge("IMM", (1e-4, 0.99999, "mode"))
    assert not edge("IMM", (1e-4, 0.99, "mix"))
    assert not edge("VD filter", (1e-5, 2, 3.0))  # window 2 is a floor
    assert edge("VD filter", (1e-5, 25, 3.0)) and edge("VD filter", (1e-8, 5, 3.0)) and edge("VD filter", (1e-2, 5, 3))
    assert not edge("VD filter", (1e-5, 5, 3.0))
    one = C._grids((("fixed2", (50,)), ("imm_q_ca", (1e-3,)), ("imm_p_stay", (0.9, 0.99))))
    assert not C._on_edge("fixed 2nd order", (50,), one)  # a one-value grid has no edge
    assert C._on_edge("IMM", (1e-3, 0.99, "mix"), one) and not C._on_edge("IMM", (1e-3, 0.95, "mix"), one)
    three = C._grids((("fixed2", (5, 2, 10)),))
    assert not C._on_edge("fixed 2nd order", (5,), three)  # the ends are the smallest and largest, not first/last
    assert C._on_edge("fixed 2nd order", (10,), three)
    with pytest.raises(KeyError):
        C._on_edge("Kalman", (1,), g)


def _fake_score(table):
    calls = []

    def score(world, name, setting):
        calls.append((world, name, setting))
        return dict(zip(SPANS, table[name][setting]))

    return score, calls


def test_scores_without_alpha_cover_the_grids_and_the_coasts_of_each_best(monkeypatch):
    world = ("w",)
    grids = (("fixed2", (2, 7)), ("fixed3", (3,)), ("imm_q_ca", (1e-3, 1e-2)), ("imm_p_stay", (0.9, 0.99)))
    imm = {
        (1e-3, 0.9, "mix"): (1, 1, 5, 5, 5),
        (1e-3, 0.99, "mix"): (2, 2, 6, 6, 6),
        (1e-2, 0.9, "mix"): (3, 3, 7, 7, 7),
        (1e-2, 0.99, "mix"): (4, 4, 1, 1, 1),
    }
    for (q, p, _), v in list(imm.items()):
        imm[(q, p, "frozen")] = tuple(x + 0.5 for x in v)
        imm[(q, p, "mode")] = tuple(x - 0.5 for x in v)
    table = {
        "fixed 2nd order": {(2,): (1,) * 5, (7,): (2,) * 5},
        "fixed 3rd order": {(3,): (9,) * 5},
        "IMM": imm,
    }
    score, calls = _fake_score(table)
    monkeypatch.setattr(C, "_score", score)
    out = C._scores_without_alpha(world, grids)
    assert list(out) == ["fixed 2nd order", "fixed 3rd order", "IMM"]
    assert list(out["fixed 2nd order"]) == [(2,), (7,)] and list(out["fixed 3rd order"]) == [(3,)]
    assert list(out["IMM"]) == [
        (1e-3, 0.9, "mix"),
        (1e-3, 0.99, "mix"),
        (1e-2, 0.9, "mix"),
        (1e-2, 0.99, "mix"),
        (1e-3, 0.9, "frozen"),  # the best for the first two spans, in span order
        (1e-3, 0.9, "mode"),
        (1e-2, 0.99, "frozen"),  # the best for the other three
        (1e-2, 0.99, "mode"),
    ]
    for name, settings in out.items():
        for st, ms in settings.items():
            assert ms == dict(zip(SPANS, table[name][st]))
    assert {c[0] for c in calls} == {world} and len(calls) == 11  # each setting scored once


def test_scores_without_alpha_default_grids(monkeypatch):
    score = lambda world, name, setting: dict.fromkeys(SPANS, 1.0)  # noqa: E731
    monkeypatch.setattr(C, "_score", score)
    out = C._scores_without_alpha(("w",), ())
    assert list(out["fixed 2nd order"]) == [(k,) for k in S.FIXED2_GRID]
    assert list(out["fixed 3rd order"]) == [(k,) for k in S.FIXED3_GRID]
    mix = [(q, p, "mix") for q in S.IMM_Q_CA_GRID for p in S.IMM_P_STAY_GRID]
    first = (S.IMM_Q_CA_GRID[0], S.IMM_P_STAY_GRID[0])
    assert list(out["IMM"]) == mix + [(*first, "frozen"), (*first, "mode")]  # ties: the first of the grid


def test_vd_statistic_is_the_cv_only_statistic_before_the_onset(monkeypatch):
    sc = tiny()
    z = np.zeros((2, 2, 9))
    monkeypatch.setattr(C, "_training", lambda world: (sc, z, None) if world == (1.0, 2, 3, 0.6) else None)
    seen = {}

    def vdf(*args):
        seen["args"] = args
        return types.SimpleNamespace(rho=np.broadcast_to(np.arange(9.0), (2, 2, 9)))

    monkeypatch.setattr(C, "vd_filter_run", vdf)
    rho = C._vd_statistic((1.0, 2, 3, 0.6), 1e-4, 0)
    z_, vis, q_cv, q_ca, sigma, window, thr = seen["args"]
    assert z_ is z and vis is sc.visible and (q_cv, q_ca, sigma, window, thr) == (0.0, 1e-4, 0.6, 0, np.inf)
    np.testing.assert_array_equal(rho[0, 0], [1.0])  # frames window + 1 .. onset - 1
    assert rho.shape == (2, 2, 1)


def test_vd_scores_threshold_from_the_statistic_quantile_and_batch_the_q(monkeypatch):
    sc = tiny()
    truth = sc.truth[None, :, :, 0]
    z = np.full((2, 2, 9), 0.25)
    world = (1.0, 2, 3, 0.6)
    monkeypatch.setattr(C, "_training", lambda w: (sc, z, truth) if w == world else None)
    stat_calls, runs = [], []

    def statistic(w, q, window):
        stat_calls.append((w, q, window))
        return np.arange(101.0) * window

    def vdf(zb, visible, q_cv, q_b, sigma, window, thr):
        runs.append((zb, visible, q_cv, q_b, sigma, window, thr))
        c = (np.arange(q_b.shape[0]) + 1.0)[:, None, None, None] + 10.0 * window
        return types.SimpleNamespace(x=np.stack([truth + c + 0 * zb, 0 * zb + 99.0], axis=-1))

    monkeypatch.setattr(C, "_vd_statistic", statistic)
    monkeypatch.setattr(C, "vd_filter_run", vdf)
    grids = (("vdf_q_ca", (1e-6, 1e-4, 1e-2)), ("vdf_windows", (2, 5)))
    out = C._scores_vd(world, grids, 0.25)
    assert stat_calls == [(world, 1e-6, 2), (world, 1e-6, 5)]  # the statistic reads no q_CA: the first
    assert len(runs) == 2
    for (zb, visible, q_cv, q_b, sigma, window, thr), w in zip(runs, (2, 5)):
        assert zb.shape == (3, 2, 2, 9) and np.all(zb == 0.25) and visible is sc.visible
        assert q_cv == 0.0 and sigma == 0.6 and window == w and type(window) is int
        assert q_b.shape == (3, 1, 1) and list(q_b.ravel()) == [1e-6, 1e-4, 1e-2]
        assert thr == pytest.approx(75.0 * w) and type(thr) is float  # the 1 - alpha quantile
    keys = [(q, w, 75.0 * w) for q in (1e-6, 1e-4, 1e-2) for w in (2, 5)]
    assert list(out) == keys
    for (q, w, _), ms in out.items():
        c = [1e-6, 1e-4, 1e-2].index(q) + 1.0 + 10.0 * w
        assert ms == pytest.approx(dict.fromkeys(SPANS, c * c))


def test_vd_scores_default_grids(monkeypatch):
    sc = tiny()
    truth = sc.truth[None, :, :, 0]
    monkeypatch.setattr(C, "_training", lambda w: (sc, np.zeros((1, 2, 9)), truth))
    monkeypatch.setattr(C, "_vd_statistic", lambda w, q, window: np.zeros(4))
    q_seen = []

    def vdf(zb, visible, q_cv, q_b, *a):
        q_seen.append(q_b)
        return types.SimpleNamespace(x=np.zeros(zb.shape + (2,)))

    monkeypatch.setattr(C, "vd_filter_run", vdf)
    out = C._scores_vd((1.0, 1, 2, 0.5), (), 0.1)
    assert list(out) == [(q, w, 0.0) for q in S.VDF_Q_CA_GRID for w in S.VDF_WINDOWS]
    C._scores_vd((1.0, 1, 2, 0.5), (("vdf_q_ca", (0, 1)),), 0.1)  # a grid written in whole numbers
    assert q_seen[-1].dtype == np.float64 and q_seen[-1].shape == (2, 1, 1)


def test_tuned_comparators_pick_each_span_minimum_and_flag_edges(monkeypatch):
    seen = {}
    base = {
        "fixed 2nd order": {(2,): (4, 9, 16, 1, 1), (5,): (1, 4, 4, 4, 4), (10,): (9, 1, 1, 4, 9)},
        "fixed 3rd order": {(3,): (1,) * 5},
        "IMM": {(1e-3, 0.99, "mix"): (4,) * 5, (1e-3, 0.99, "mode"): (1, 9, 9, 9, 9)},
    }
    vd = {(1e-5, 2, 3.5): (16, 1, 16, 16, 16), (1e-5, 5, 4.5): (1, 16, 1, 1, 1)}

    def without_alpha(world, grids):
        seen["without"] = (world, grids)
        return {n: {st: dict(zip(SPANS, v)) for st, v in d.items()} for n, d in base.items()}

    def with_alpha(world, grids, alpha):
        seen["vd"] = (world, grids, alpha)
        return {st: dict(zip(SPANS, v)) for st, v in vd.items()}

    monkeypatch.setattr(C, "_scores_without_alpha", without_alpha)
    monkeypatch.setattr(C, "_scores_vd", with_alpha)
    grids = (("fixed2", (2, 5, 10)), ("vdf_windows", (2, 5)), ("imm_q_ca", (1e-3,)))
    out = C.tuned_comparators(50, 6.0, 11.0, 1, 0.5, grids, "2 s acceleration", "el/frame per s", "v -6, a -0.05")
    world = (50.0, 6, 11, 0.5, "2 s acceleration", "el/frame per s", "v -6, a -0.05")
    assert seen["without"] == (world, grids) and seen["vd"] == (world, grids, 1.0)
    assert [type(v) for v in seen["without"][0][:4]] == [float, int, int, float] and type(seen["vd"][2]) is float
    assert list(out) == list(SPANS)
    f2 = [out[s]["fixed 2nd order"] for s in SPANS]
    # bound 10 is the overridden grid's top (an edge), 2 its physical floor, 5 inside
    assert f2 == [((5,), 1.0, False), ((10,), 1.0, True), ((10,), 1.0, True), ((2,), 1.0, False), ((2,), 1.0, False)]
    vd_out = [out[s]["VD filter"] for s in SPANS]
    assert [v[0] for v in vd_out] == [(1e-5, 5, 4.5), (1e-5, 2, 3.5), (1e-5, 5, 4.5), (1e-5, 5, 4.5), (1e-5, 5, 4.5)]
    assert [v[2] for v in vd_out] == [True, False, True, True, True]  # window 5 the overridden top, 2 a floor
    assert out["4 s to loss"]["IMM"] == ((1e-3, 0.99, "mode"), 1.0, False)  # one-value q grid, 0.99 inside
    assert out["onset to loss"]["IMM"] == ((1e-3, 0.99, "mix"), 2.0, False)  # the RMS: sqrt of the mean square
    assert out["end of the loss"]["fixed 3rd order"] == ((3,), 1.0, False)
    assert all(type(out[s][n][1]) is float for s in SPANS for n in out[s])


def test_tuned_comparators_default_world(monkeypatch):
    seen = {}
    one = {span: 1.0 for span in SPANS}
    monkeypatch.setattr(
        C, "_scores_without_alpha", lambda world, grids: seen.setdefault("w", world) and {"IMM": {(1e-4, 0.99): one}}
    )
    monkeypatch.setattr(C, "_scores_vd", lambda world, grids, alpha: {(1e-5, 5, 1.0): one})
    out = C.tuned_comparators(25.0, 4, 7, 1e-3)
    assert seen["w"] == (25.0, 4, 7, 1.0, "constant acceleration", "el/frame²", "v -6, a -0.2")
    assert list(out["4 s to loss"]) == ["IMM", "VD filter"]


def test_comparator_tuning_hands_the_configuration_and_sizes_over(monkeypatch):
    seen = []
    monkeypatch.setattr(C, "tuned_comparators", lambda *a: seen.append(a) or "tuned")
    sizes = {"n_train": 6, "train_seed": 9, "sigma_eps": 0.5, "grids": {"fixed2": [2, 5], "vdf_windows": [3]}}
    assert C.comparator_tuning({"frame_rate_hz": 50, "alpha": "0.01"}, sizes) == "tuned"
    assert seen[-1] == (
        50.0,
        6,
        9,
        0.01,
        0.5,
        (("fixed2", (2, 5)), ("vdf_windows", (3,))),
        "constant acceleration",
        "el/frame²",
        "v -6, a -0.2",
    )
    assert type(seen[-1][0]) is float and type(seen[-1][3]) is float
    world = {"manoeuvre": "2 s acceleration", "accel_unit": "el/frame per s", "channel_y": "v -6, a -0.05"}
    C.comparator_tuning({"frame_rate_hz": 25.0, "alpha": 0.1} | world, {"n_train": 1, "train_seed": 2, "sigma_eps": 1})
    assert seen[-1] == (25.0, 1, 2, 0.1, 1, (), "2 s acceleration", "el/frame per s", "v -6, a -0.05")


# ---------------------------------------------------------------------------------------------------------------
# the compensation comparators


def test_raised_second_order_restarts_the_gain_index_at_the_detection(monkeypatch):
    sc = tiny()
    calls = []

    def gains(order, k_bound, n_max=None):
        calls.append((order, k_bound, n_max))
        return np.stack([np.arange(1.0, n_max + 1), np.zeros(n_max)], axis=-1)  # row k - 1 holds k

    def run(z, G):
        calls.append((z.copy(), G.shape))
        return G  # the position column is the gain index used at each frame

    monkeypatch.setattr(C, "gain_schedule", gains)
    monkeypatch.setattr(C, "scheduled_filter", run)
    z = np.arange(18.0).reshape(1, 2, 9)
    k = C.raised_second_order(z, sc, np.array([[3, -1]]), 4, 5)
    assert calls[0] == (1, 5, 12)
    np.testing.assert_array_equal(calls[1][0], np.where(sc.visible, z, np.nan))
    assert calls[1][1] == (1, 2, 9, 2)
    np.testing.assert_array_equal(k[0, 0], [1, 2, 3, 4, 3, 4, 5, 5, 5])  # bound 4 up to frame 3, then 3, 4, 5 ...
    np.testing.assert_array_equal(k[0, 1], [1, 2, 3, 4, 4, 4, 4, 4, 4])  # never detected: bounded at 4
    calls.clear()
    k = C.raised_second_order(z[0], sc, np.array([0, 8]), 6, 3)
    assert calls[0] == (1, 6, 12)
    np.testing.assert_array_equal(k[0], [1, 3, 3, 3, 3, 3, 3, 3, 3])  # detected at frame 0: restarted at frame 1
    np.testing.assert_array_equal(k[1], [1, 2, 3, 4, 5, 6, 6, 6, 6])


def test_raised_second_order_on_real_gains():
    """On the real gain table a never-detected run is the fixed 2nd-order filter at its bound."""
    sc = tiny()
    z = sc.truth[:, :, 0] + np.array([[0.3, -0.2, 0.1, 0.0, 0.4, -0.1, 0.0, 0.0, 0.2]])
    never = C.raised_second_order(z, sc, np.full(2, -1), 4, 3)
    np.testing.assert_allclose(never, C.comparator_positions("fixed 2nd order", (4,), z, sc, 1.0), rtol=1e-12)


def test_compensation_comparator_without_the_switch(monkeypatch):
    seen = []
    monkeypatch.setattr(C, "comparator_positions", lambda *a: seen.append(a) or "fixed")
    sc = tiny()
    z = np.zeros((1, 2, 9))
    out = C.compensation_comparator(S.COMPENSATION_COMPARATORS[0], z, sc, {"k_bound2": 12.0}, {"sigma_eps": 0.4}, None)
    assert out == "fixed"
    name, setting, z_, sc_, sigma = seen[0]
    assert (name, setting, sigma) == ("fixed 2nd order", (12,), 0.4) and type(setting[0]) is int
    assert z_ is z and sc_ is sc
    with pytest.raises(ValueError, match="must be one of"):
        C.compensation_comparator("raised", z, sc, {"k_bound2": 12}, {"sigma_eps": 0.4}, None)


def test_raised_comparator_is_tuned_on_its_own_training_runs(monkeypatch):
    sc = tiny()
    z = np.zeros((1, 2, 9))
    det = np.array([[4, -1]])
    config = {"k_bound2": 7.0, "compensation_end_s": "8"}
    sizes = {"sigma_eps": 0.7, "n_train": 3, "train_seed": 41}
    log = []

    def draws(truth_pos, model, n, rng, sigma):
        log.append(("draws", truth_pos.copy(), model, n, rng.random(), sigma))
        return "zt"

    def scheme(zt, sc_, config_, sizes_, covariance=True):
        log.append(("scheme", zt, sc_ is sc, config_ is config, sizes_ is sizes, covariance))
        return types.SimpleNamespace(detection_frame="dt")

    def label(v, test, name):
        return v if isinstance(v, str) else name if v is test else "other"

    def raised(z_, sc_, d, k2, kb):
        log.append(("raised", label(z_, z, "test"), sc_ is sc, label(d, det, "det"), k2, kb))
        return ("x", kb, label(z_, z, "test"))

    ms = {3: 5.0, 5: 2.0, 10: 1.5, 20: 4.5, 50: 4.0}

    def comp_ms(x, sc_, end):
        log.append(("ms", x, sc_ is sc, end))
        return ms[x[1]]

    monkeypatch.setattr(C, "measurements", draws)
    monkeypatch.setattr(C, "run_scheme", scheme)
    monkeypatch.setattr(C, "raised_second_order", raised)
    monkeypatch.setattr(C, "compensation_bias2", comp_ms)
    out = C.compensation_comparator(S.COMPENSATION_COMPARATORS[1], z, sc, config, sizes, det)
    assert out == ("x", 10, "test")  # the bound of the lowest dynamic error over the training runs
    (_, truth_pos, model, n, first, sigma), rest = log[0], log[1:]
    np.testing.assert_array_equal(truth_pos, sc.truth[:, :, 0])
    assert (model, n, sigma) == ("white Gaussian", 3, 0.7)
    assert first == np.random.default_rng(42).random()  # train_seed + 1: not the tuning runs of the others
    assert rest[0] == ("scheme", "zt", True, True, True, False)
    tried = [e for e in rest if e[0] == "raised"]
    assert tried[:-1] == [("raised", "zt", True, "dt", 7, b) for b in S.RAISED2_GRID]
    assert tried[-1] == ("raised", "test", True, "det", 7, 10)
    assert all(type(e[4]) is int for e in tried)
    assert [e[3] for e in rest if e[0] == "ms"] == [8.0] * 5
    assert all(e[2] for e in rest if e[0] == "ms")


# ---------------------------------------------------------------------------------------------------------------
# the settings in words


def test_tuning_phrase_words_each_setting():
    assert C.tuning_phrase("fixed 2nd order", (5.0,)) == "gains frozen at frame 5"
    assert C.tuning_phrase("fixed 3rd order", (30,)) == "gains frozen at frame 30"
    assert C.tuning_phrase("IMM", (1e-3, 0.99, "mix")) == (
        "acceleration-model process noise 0.001 el²/frame⁴, probability 0.99 of staying in a model, "
        "coasting with the textbook mixing cycle"
    )
    assert C.tuning_phrase("IMM", (1e-5, 0.9999, "frozen")).endswith(
        "1e-05 el²/frame⁴, probability 0.9999 of staying in a model, coasting without mixing, mode probabilities frozen"
    )
    assert C.tuning_phrase("IMM", (1e-4, 0.9, "mode")).endswith("coasting on the model most probable at the loss")
    assert C.tuning_phrase("IMM", (1e-4, 0.9, "other")).endswith("a model, other")
    assert C.tuning_phrase("VD filter", (1e-6, 10.0, 3.2)) == (
        "acceleration-model process noise 1e-06 el²/frame⁴, detector and restart over 10 frames"
    )


def test_raised_comparator_is_tuned_for_the_measure_it_is_judged_on(monkeypatch):
    sc = tiny()
    truth = sc.truth[None, :, :, 0]
    spread = np.array([1.0, -1.0])[:, None, None]  # two training runs whose errors cancel in the mean over runs
    # bound 3: lag 0.1 and a spread of 2 (total mean square 4.01, dynamic 0.01); the others: lag 1, no spread (1, 1)
    errors = {b: (0.1 + 2.0 * spread) if b == 3 else np.ones((2, 1, 1)) for b in S.RAISED2_GRID}
    monkeypatch.setattr(C, "measurements", lambda *a: "zt")
    monkeypatch.setattr(C, "run_scheme", lambda *a, **k: types.SimpleNamespace(detection_frame="dt"))
    chosen = []

    def raised(z_, sc_, d, k2, kb):
        if isinstance(z_, str):
            return truth + errors[kb] * np.ones((2, 2, 9))
        chosen.append(kb)
        return "test positions"

    monkeypatch.setattr(C, "raised_second_order", raised)
    config = {"k_bound2": 7, "compensation_end_s": 5.0}
    C.compensation_comparator(
        S.COMPENSATION_COMPARATORS[1], None, sc, config, {"sigma_eps": 1, "n_train": 2, "train_seed": 0}, None
    )
    frames = np.arange(sc.onset, 5)
    judged = {b: float(np.mean(np.mean(errors[b] * np.ones((2, 2, 9)), axis=0)[..., frames] ** 2)) for b in errors}
    assert judged[3] == pytest.approx(0.01) and min(judged, key=judged.get) == 3
    assert chosen == [3]  # the total mean square would pick another bound
