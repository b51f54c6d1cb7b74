"""001's register read into the simulated scenario and the scheme's settings: each entry's values change exactly the
fields their descriptions name, by the amounts the paper's numbers give, and nothing else.

The fields are those the study's runs hand on: the scenario (:func:`scenario.config_scenario`: 25 frames a second,
25 s, the manoeuvre at 5 s, the loss from 12 s to 22 s, the motion of the paper card's simulation paragraph kept
per frame at every frame rate), the scheme's settings (:func:`scenario.run_scheme`: the bounds, window, threshold,
arming and restart), the measurement model and run sizes of :func:`study.tradeoff_runs` and the span its comparators
are tuned for, and the readings of sigma_S of :func:`study.sigma_s_readings`. The expected values are the card's:
its numbers (k_b2 = 50, n = 25, alpha = 1e-3, sigma_v = 0.0061, sigma_S^2 12.3 times the independence value, lag-1
correlation 0.92, a per-test rate of 0.35) and its formulas, written out here (the growing-memory gains, the Lyapunov
covariance of section 4.2, the sigma_S of section 4.3 and its impulse-response form for time-varying gains), never
computed with the module under test. Beside the map: the scenario runs (every restart, with the covariance, on the
seed's draws), each noise model's errors, each threshold reading, the arming rule and the test cadence, and C001-5's
gain checks and C001-6's coast check on a hand-made scenario. The simulators themselves (the mode logic, the
comparators' tuning) are replaced by recorders, so the file runs in a few seconds.
"""

from __future__ import annotations

import dataclasses
import functools
import math
from types import SimpleNamespace

import numpy as np
import pytest
from scipy import linalg, stats

from tvtrack.papers.p001_maneuver_occlusion_kf import REGISTER, study
from tvtrack.papers.p001_maneuver_occlusion_kf import scenario as scn
from tvtrack.papers.p001_maneuver_occlusion_kf.track_modes import TrackModeConfig

DEFAULT = REGISTER.default()
SIZES = {"sigma_eps": 1.0, "defaults": DEFAULT, "n_trials": 3, "n_tradeoff_trials": 2}
Z3 = 3.2905267314918945  # Phi^-1(1 - alpha / 2) at alpha = 1e-3


# ---------------------------------------------------------------------------------------------------------------
# The card's formulas, written out independently of the module under test
# ---------------------------------------------------------------------------------------------------------------


def _gains2(k):
    """The card's 2nd-order growing-memory gains (kappa1, kappa2) at count k (section 4.1)."""
    k = np.asarray(k, float)
    return np.stack([2 * (2 * k - 1) / (k * (k + 1)), 6 / (k * (k + 1))], axis=-1)


@functools.lru_cache(maxsize=None)
def _card_sigma_s(fps: float, n: int, kb: int, sigma: float = 1.0) -> np.ndarray:
    """sigma_S per frame of the TRACK2 filter of the scenario at ``fps`` (lost from 12 s to 22 s): the velocity
    outputs' linear map from the measurements by propagating the filter on unit impulses, then
    ``sigma * |u^T G|`` with ``u = [1_n; -1_n]`` (section 4.3, time-varying gains); NaN before the windows fill."""
    T = int(round(25 * fps))
    t = np.arange(T) / fps
    vis = (t < 12) | (t >= 22)
    k = np.cumsum(vis)
    K = _gains2(np.minimum(np.maximum(k, 1), kb)) * vis[:, None]
    F = np.array([[1.0, 1.0], [0.0, 1.0]])
    X, V = np.zeros((2, T)), np.zeros((T, T))
    for f in range(T):
        X = F @ X
        innovation = -X[0]
        innovation[f] += 1.0
        X = X + np.outer(K[f], innovation)
        V[f] = X[1]
    out = np.full(T, np.nan)
    for f in range(2 * n - 1, T):
        row = V[f - 2 * n + 1 : f - n + 1].sum(0) - V[f - n + 1 : f + 1].sum(0)
        out[f] = sigma * math.sqrt(row @ row)
    return out


def _card_threshold(fps=25.0, n=25, kb=50, alpha=1e-3, reading="exact", every=1, arm_k=100, sigma=1.0):
    """c(alpha) = sigma_S Phi^-1(1 - alpha / 2) per frame under a reading (section 4.3), with the frames the detector
    does not test (every ``every`` frames from the first armed frame ``arm_k - 1``) at infinity."""
    z = stats.norm.isf(alpha / 2)
    T = int(round(25 * fps))
    if reading == "exact":
        s = _card_sigma_s(fps, n, kb, sigma)
        c = np.where(np.isnan(s), np.inf, z * s)
        c[s == 0] = np.nan  # windows of predicted velocities only (while lost): no test (infinite, checked apart)
    else:
        c = np.full(T, z * _card_stationary(n, kb, sigma)[reading])
    f = np.arange(T)
    c[(f >= arm_k - 1) & ((f - (arm_k - 1)) % every != 0)] = np.inf
    return c


def _card_stationary(n: int, kb: int, sigma: float = 1.0) -> dict:
    """sigma_S of the frozen filter (gains at k_b): the correlated value from the Lyapunov covariance (sections 4.2,
    4.3 (b)), the paper's independence with the filter-output velocity RMS (2 n sigma_v^2) and with the raw
    increments' (4 n sigma^2); and the lag-1 correlation of the output velocity."""
    K = _gains2(kb)
    A = (np.eye(2) - np.outer(K, [1.0, 0.0])) @ np.array([[1.0, 1.0], [0.0, 1.0]])
    P = linalg.solve_discrete_lyapunov(A, sigma**2 * np.outer(K, K))
    r = [(np.linalg.matrix_power(A, m) @ P)[1, 1] for m in range(2 * n)]
    s2 = 2 * (n * r[0] + 2 * sum((n - m) * r[m] for m in range(1, n)))
    s2 -= 2 * sum((n - abs(L - n)) * r[L] for L in range(1, 2 * n))
    return {
        "stationary": math.sqrt(s2),
        "independent": math.sqrt(2 * n * r[0]),
        "raw increments": math.sqrt(4 * n) * sigma,
        "rho": r[1] / r[0],
    }


def _card_sigma_fields(n=25, kb=50, alpha=1e-3, arming="gains at bound", fps=25.0) -> dict:
    """The readings :func:`study.sigma_s_readings` reports, from the card: the exact sigma_S at the first tested
    frame (TRACK2 count k_b2 + 2n with the gains at their bound, 2n + 1 with the windows full, the latter also where
    the former would first test at or after the onset at 5 s), the stationary ones, rho_v(1) and the independence
    threshold's per-test rate 2 Phi(-c_ind / sigma_S)."""
    st = _card_stationary(n, kb)
    z = stats.norm.isf(alpha / 2)
    arm = kb + 2 * n if arming == "gains at bound" else 2 * n + 1
    arm = 2 * n + 1 if arm - 1 >= 5 * fps else arm
    return {
        "sigma_S exact": _exact_at(arm, n, kb),
        "sigma_S stationary": st["stationary"],
        "sigma_S independent": st["independent"],
        "sigma_S raw increments": st["raw increments"],
        "rho_v1": st["rho"],
        "pfa_independent": 2 * stats.norm.sf(z * st["independent"] / st["stationary"]),
    }


def _exact_at(count: int, n: int, kb: int) -> float:
    """sigma_S of a run without loss at TRACK2 count ``count`` (frame count - 1; no loss before 12 s)."""
    assert count - 1 < 12 * 25
    return float(_card_sigma_s(25.0, n, kb)[count - 1])


def _card_truth(fps=25.0, ax=0.2, ay=-0.2, accel_s=None) -> np.ndarray:
    """True (x, v, a) (2, T, 3) of the paper's motion: x0 = 0, 10 (and -6) elements/frame, an acceleration of ``ax``
    (``ay``) elements/frame^2 from 5 s (for ``accel_s`` seconds, then uniform motion), the motion per frame at every
    frame rate ``fps`` (the paper states it per frame) and the times in seconds."""
    t = np.arange(int(round(25 * fps))) / fps
    d = np.clip(t - 5.0, 0, None)
    dc = d if accel_s is None else np.minimum(d, accel_s)
    accelerating = (t >= 5.0) & ((d < accel_s) if accel_s is not None else True)
    out = []
    for v0, a in ((10.0, ax), (-6.0, ay)):
        V, A = v0 * fps, a * fps**2  # elements/s, elements/s^2
        x = V * t + 0.5 * A * dc**2 + A * dc * (d - dc)
        out.append(np.stack([x, (V + A * dc) / fps, np.where(accelerating, A, 0.0) / fps**2], axis=-1))
    return np.stack(out)


def _card_visible(fps=25.0) -> np.ndarray:
    t = np.arange(int(round(25 * fps))) / fps
    return (t < 12) | (t >= 22)


# ---------------------------------------------------------------------------------------------------------------
# The wiring's fields, with the simulators replaced by recorders
# ---------------------------------------------------------------------------------------------------------------

SCHEME = [f.name for f in dataclasses.fields(TrackModeConfig)]


def _record(monkeypatch) -> dict:
    """Replace the measurement draws, the mode logic and the comparators with recorders; the calls land in the
    returned dict."""
    calls: dict = {"runs": [], "positions": []}

    def measurements(truth, model, n, rng, sigma):
        calls["measurements"] = (np.array(truth), model, n, rng, sigma)
        return np.full((n,) + np.shape(truth), 7.0)

    def run_track_modes(z, visible, cfg, sigma, covariance=True):
        calls["runs"].append((z, visible, cfg, sigma, covariance))
        return SimpleNamespace(x=np.zeros(np.shape(z) + (3,)), cfg=cfg)

    def comparator_tuning(config, sizes):
        calls["tuning"] = (config, sizes)
        return {s: {f"tuned for {s}": ((s,), 1.0, False)} for s in scn.TUNING_SPANS}

    def comparator_positions(name, setting, z, sc, sigma):
        calls["positions"].append((name, setting, z, sc, sigma))
        return np.zeros(np.shape(z))

    monkeypatch.setattr(study, "measurements", measurements)
    monkeypatch.setattr(scn, "run_track_modes", run_track_modes)
    monkeypatch.setattr(study, "comparator_tuning", comparator_tuning)
    monkeypatch.setattr(study, "comparator_positions", comparator_positions)
    return calls


def _fields(monkeypatch, config: dict, sizes=SIZES) -> dict:
    """Every field the wiring hands on for ``config``: the scenario's, the scheme's settings (with the covariance
    flag), the measurement model and run size of the trade-off runs, the comparators' tuning span and the
    no-switch filter's bound, and the sigma_S readings."""
    calls = _record(monkeypatch)
    tr = study.tradeoff_runs(config, 11, sizes)
    sc = tr["scenario"]
    out = {f: getattr(sc, f) for f in ("fps", "T", "onset", "f_loss", "f_back", "visible", "truth")}
    ((z, visible, cfg, sigma, covariance),) = calls["runs"]
    out |= {f: getattr(cfg, f) for f in SCHEME} | {"covariance": covariance}
    truth, model, n, _, msigma = calls["measurements"]
    out |= {"noise": model, "n_runs": n}
    (span,) = {k.removeprefix("tuned for ") for k in tr["tuning"]}
    out["span"] = span
    out["no-switch bound"] = calls["positions"][0][1]
    sg = study.sigma_s_readings(config, sizes)
    out |= {f"sigma_S {r}": v for r, v in sg["sigma_S"].items()}
    out |= {"rho_v1": sg["rho_v1"], "pfa_independent": sg["pfa_independent"]}
    # what every run is handed besides the fields: the scenario's own truth, visibility and the run's sigma
    assert np.array_equal(truth, sc.truth[:, :, 0]) and visible is sc.visible
    assert sigma == msigma == sizes["sigma_eps"] and z.shape == (n, 2, sc.T)
    return out


def _same(a, b) -> bool:
    """``a`` equals ``b`` (to rounding); where an expected array ``b`` is NaN, ``a`` is infinite or rounding off 0."""
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        a, b = np.asarray(a), np.asarray(b)
        free = np.isnan(b)
        if a.shape != b.shape or not (np.isinf(a[free]) | (np.abs(a[free]) < 1e-6)).all():
            return False
        return bool(np.allclose(a[~free], b[~free], rtol=1e-9, atol=1e-6))
    if isinstance(a, float) and isinstance(b, float):
        return math.isclose(a, b, rel_tol=1e-9)
    return type(a) is type(b) and a == b


def _changed(monkeypatch, config: dict) -> dict:
    base, got = _fields(monkeypatch, DEFAULT), _fields(monkeypatch, config)
    assert set(base) == set(got)
    return {k: v for k, v in got.items() if not _same(v, base[k])}


# ---------------------------------------------------------------------------------------------------------------
# The map: entry -> {value: the fields it changes, with their values}
# ---------------------------------------------------------------------------------------------------------------

THR = _card_threshold  # the expected threshold arrays, built when a test asks for them


def _sig(**kw) -> dict:
    """The sigma_S readings that differ from the default's at the card's parameters ``kw``."""
    base, new = _card_sigma_fields(), _card_sigma_fields(**kw)
    return {k: v for k, v in new.items() if not math.isclose(v, base[k], rel_tol=1e-9)}


FIELDS = {
    "threshold": {
        "stationary": {"threshold": lambda: THR(reading="stationary")},
        "independent": {"threshold": lambda: THR(reading="independent")},
        "raw increments": {"threshold": lambda: np.full(625, 10 * Z3)},  # sqrt(4 n) sigma: 10 elements/frame
    },
    "alpha": {
        1e-4: {"threshold": lambda: THR(alpha=1e-4), "pfa_independent": lambda: _sig(alpha=1e-4)["pfa_independent"]},
        1e-2: {"threshold": lambda: THR(alpha=1e-2), "pfa_independent": lambda: _sig(alpha=1e-2)["pfa_independent"]},
    },
    "arming": {"windows full": {"arm_k": 51, "sig": lambda: _sig(arming="windows full")}},  # 2 n + 1
    "test_cadence": {
        "every n frames": {"threshold": lambda: THR(every=25)},
        "every 2n frames": {"threshold": lambda: THR(every=50)},
    },
    "window_n": {
        10: {"window": 10, "arm_k": 70, "threshold": lambda: THR(n=10, arm_k=70), "sig": lambda: _sig(n=10)},
        # k_b2 + 2n = 150 would first test after the onset (frame 125): armed when the windows are full, 2n + 1
        50: {"window": 50, "arm_k": 101, "threshold": lambda: THR(n=50, arm_k=101), "sig": lambda: _sig(n=50)},
    },
    "k_bound2": {
        30: {
            "k_bound2": 30,
            "no-switch bound": (30,),
            "arm_k": 80,
            "threshold": lambda: THR(kb=30, arm_k=80),
            "sig": lambda: _sig(kb=30),
        },
        # k_b2 + 2n = 150 would first test after the onset: armed when the windows are full, 2n + 1
        100: {
            "k_bound2": 100,
            "no-switch bound": (100,),
            "arm_k": 51,
            "threshold": lambda: THR(kb=100, arm_k=51),
            "sig": lambda: _sig(kb=100),
        },
    },
    "frame_rate_hz": {
        50.0: {
            "fps": 50.0,
            "T": 1250,
            "onset": 250,
            "f_loss": 600,
            "f_back": 1100,
            "visible": lambda: _card_visible(50.0),
            "truth": lambda: _card_truth(50.0),
            "threshold": lambda: THR(fps=50.0),
        },
    },
    "noise": {m: {"noise": m} for m in ("quantised", "AR(1), rho = 0.5", "Student t, 3 dof")},
    "restart": {"B": {"restart": "B"}, "C": {"restart": "C", "covariance": True}},  # C needs the covariance
    "restart_accel_var": {100.0: {"restart_accel_var": 100.0}, 1e6: {"restart_accel_var": 1e6}},
    "k_bound3": {50: {"k_bound3": 50}, 200: {"k_bound3": 200}},
    "rms_span": {s: {"span": s} for s in ("onset to loss", "visible after 4 s", "end of the loss")},
    "manoeuvre": {"2 s acceleration": {"truth": lambda: _card_truth(accel_s=2.0)}},
    "accel_unit": {"el/frame per s": {"truth": lambda: _card_truth(ax=0.2 / 25, ay=-0.2 / 25)}},  # 0.008 el/frame^2
    "channel_y": {"v -6, a -0.05": {"truth": lambda: _card_truth(ay=-0.05)}},
}
#: entries this wiring does not read: C001-2's alternative, comparator, delay and step (measure_detection), C001-3's
#: sigma (measure_detection), C001-4's statistic, compensation end, comparator and switch (tradeoff.py), the curves'
#: loss, switch time, length and tolerance (curves.py), C001-9's entries (spherical.py)
NOT_READ = {
    "alternative", "ump_comparator", "roc_delay_s", "step_dv", "paper_sigma", "rms_statistic", "compensation_end_s",
    "compensation_comparator", "C001-4 switch", "occlusion", "switch_s", "loss_length_s", "curve_tolerance",
    "extrapolation", "targets", "horizon", "tolerance",
}  # fmt: skip


def _want(d: dict) -> dict:
    out = {}
    for k, v in d.items():
        v = v() if callable(v) else v
        out |= v if k == "sig" else {k: v}
    return out


def _non_default():
    for name in REGISTER.names:
        for v in REGISTER[name].values:
            if v != REGISTER[name].default:
                yield name, v


def test_every_register_entry_is_mapped_here():
    assert set(FIELDS) | NOT_READ == set(REGISTER.names) and not set(FIELDS) & NOT_READ
    for name, values in FIELDS.items():  # every value named is one of the entry's alternatives
        assert set(values) <= set(REGISTER[name].values) - {REGISTER[name].default}, name
    assert len(list(_non_default())) == 53


def test_the_card_formulas_give_the_cards_numbers():
    """The helpers above reproduce the numbers the card prints (k_b2 = 50, n = 25)."""
    st = _card_stationary(25, 50)
    assert st["independent"] / math.sqrt(50) == pytest.approx(0.0061, abs=5e-5)  # sigma_v per frame
    assert (st["stationary"] / st["independent"]) ** 2 == pytest.approx(12.3, abs=0.05)
    assert st["rho"] == pytest.approx(0.92, abs=0.005)
    assert _card_sigma_fields()["pfa_independent"] == pytest.approx(0.35, abs=0.005)
    assert _gains2(4).tolist() == pytest.approx([0.7, 0.3]) and _gains2(50).tolist() == pytest.approx(
        [0.0776, 0.00235], abs=1e-4
    )
    assert stats.norm.isf(5e-4) == pytest.approx(Z3, rel=1e-12)


def test_the_default_fields_have_the_papers_numbers(monkeypatch):
    f = _fields(monkeypatch, DEFAULT)
    # the scenario: 25 Hz for 25 s, the manoeuvre at 5 s, lost from 12 s to 22 s
    assert (f["fps"], f["T"], f["onset"], f["f_loss"], f["f_back"]) == (25.0, 625, 125, 300, 550)
    assert np.array_equal(f["visible"], np.r_[np.ones(300), np.zeros(250), np.ones(75)].astype(bool))
    truth = f["truth"]
    assert truth.shape == (2, 625, 3)
    assert truth[0, 0].tolist() == [0.0, 10.0, 0.0] and truth[1, 0].tolist() == [0.0, -6.0, 0.0]
    assert truth[0, 124].tolist() == [1240.0, 10.0, 0.0] and truth[0, 125].tolist() == [1250.0, 10.0, 0.2]
    assert truth[0, 300].tolist() == pytest.approx([6062.5, 45.0, 0.2])  # 3000 + 0.1 * 175^2
    assert truth[1, 300].tolist() == pytest.approx([-4862.5, -41.0, -0.2])
    assert truth[0, 550, 1] == pytest.approx(95.0)  # "from 10 to 95 el/frame" held to 22 s
    assert np.allclose(truth, _card_truth(), rtol=1e-12, atol=1e-9)
    # the scheme: k_b2 = 50, k_b3 = 100, n = 25, armed at k_b2 + 2n, restart A at k = 3 with the diffuse prior,
    # the exact threshold read by frame, no detection in TRACK3, the trade-off runs without the covariance
    assert (f["k_bound2"], f["k_bound3"], f["window"], f["arm_k"], f["restart"], f["restart_k"]) == (
        50, 100, 25, 100, "A", 3,
    )  # fmt: skip
    assert (f["restart_accel_var"], f["threshold_index"], f["detect_in_track3"]) == (1e4, "frame", False)
    assert (f["threshold_track3"], f["rearm_after_gap"], f["force_switch_k"], f["covariance"]) == (None,) * 3 + (False,)
    thr = f["threshold"]
    assert thr.shape == (625,) and np.isinf(thr[:49]).all() and np.isfinite(thr[49:348]).all()  # windows full at 2n
    assert np.isinf(thr[348:550]).all() and np.isfinite(thr[550:]).all()  # no test while both windows coast
    stationary = Z3 * math.sqrt(12.3 * 50) * 0.0061  # the card's sigma_S, 12.3 times 2 n sigma_v^2
    assert thr[200:300] == pytest.approx(np.full(100, stationary), rel=2e-3)  # converged before the loss
    assert thr[99] > thr[150] and thr[624] > 2 * stationary  # above it at arming, and with the coast's error after
    assert _same(thr, _card_threshold())
    # the trade-off runs: the paper's Gaussian errors, the run size, the span "4 s to loss", the no-switch filter
    assert (f["noise"], f["n_runs"], f["span"], f["no-switch bound"]) == ("white Gaussian", 2, "4 s to loss", (50,))
    # sigma_S readings (elements/frame), the card's section 4.3
    assert f["sigma_S stationary"] == pytest.approx(math.sqrt(12.3 * 50) * 0.0061, rel=2e-3)
    assert f["sigma_S independent"] == pytest.approx(math.sqrt(50) * 0.0061, rel=1e-2)
    assert f["sigma_S raw increments"] == 10.0 and f["rho_v1"] == pytest.approx(0.92, abs=0.005)
    assert f["pfa_independent"] == pytest.approx(0.35, abs=0.005)
    for k, v in _card_sigma_fields().items():
        assert f[k] == pytest.approx(v, rel=1e-9), k
    assert f["sigma_S exact"] > f["sigma_S stationary"]  # the gains not yet settled at arming


@pytest.mark.parametrize("name, value", list(_non_default()))
def test_each_value_changes_the_fields_it_names_and_no_other(monkeypatch, name, value):
    want = _want(FIELDS.get(name, {}).get(value, {}))
    got = _changed(monkeypatch, {**DEFAULT, name: value})
    assert set(got) == set(want), (name, value)
    for k, v in want.items():
        assert _same(got[k], v), (name, value, k)
    assert bool(want) == (name not in NOT_READ)


def test_an_absent_entry_reads_the_default_of_the_sizes(monkeypatch):
    assert all(_same(a, b) for a, b in zip(_fields(monkeypatch, {}).values(), _fields(monkeypatch, DEFAULT).values()))
    other = {**DEFAULT, "k_bound2": 30, "rms_span": "onset to loss", "frame_rate_hz": 50.0}
    sizes = {**SIZES, "defaults": other}
    got = _fields(monkeypatch, {"window_n": 10}, sizes)
    assert (got["k_bound2"], got["span"], got["fps"], got["window"], got["arm_k"]) == (
        30,
        "onset to loss",
        50.0,
        10,
        50,
    )
    assert study.sigma_s_readings({"window_n": 10}, sizes)["sigma_S"]["raw increments"] == pytest.approx(math.sqrt(40))
    # the scenario's own entries are read with their defaults when a configuration leaves them out
    bare = scn.config_scenario({"frame_rate_hz": 25.0})
    assert np.array_equal(bare.truth, scn.config_scenario(DEFAULT).truth)
    assert np.allclose(bare.truth, _card_truth(), rtol=1e-12, atol=1e-9)


def test_with_defaults_lets_the_configuration_win():
    assert scn.with_defaults({"alpha": 0.01}, {"defaults": {"alpha": 1e-3, "window_n": 25}}) == {
        "alpha": 0.01,
        "window_n": 25,
    }
    assert scn.with_defaults({"alpha": 0.01}, {}) == {"alpha": 0.01}


def test_the_scenario_defaults_are_the_cards():
    sc = scn.scenario()
    assert (sc.fps, sc.T, sc.onset, sc.f_loss, sc.f_back) == (25.0, 625, 125, 300, 550)
    assert np.array_equal(sc.visible, _card_visible()) and np.allclose(sc.truth, _card_truth(), atol=1e-9)
    assert np.array_equal(sc.frames, np.arange(625))
    short = scn.scenario(10.0, duration_s=3.0, maneuver_s=1.0, loss_s=1.5, reappear_s=2.5, motion=((1.0, 0.5),))
    assert (short.fps, short.T, short.onset, short.f_loss, short.f_back) == (10.0, 30, 10, 15, 25)
    assert short.truth.shape == (1, 30, 3)
    # 1 el/frame and 0.5 el/frame^2 stay per frame at 10 Hz (the paper's motion is per frame); the onset at 1 s is frame 10
    assert short.truth[0, 12].tolist() == pytest.approx([12.0 + 0.5 * 0.5 * 4, 1.0 + 0.5 * 2, 0.5])
    # an acceleration lasting one frame (0.1 s): at the onset only
    one = scn.scenario(10.0, duration_s=3.0, maneuver_s=1.0, motion=((1.0, 0.5),), accel_duration_s=0.1)
    assert np.allclose(one.truth[0, 9:12], [[9.0, 1.0, 0.0], [10.0, 1.0, 0.5], [11.0 + 0.5 / 2, 1.5, 0.0]])
    # an acceleration lasting 0.4 s (4 frames) from frame 10: then uniform at 1 + 4 * 0.5 el/frame
    ended = scn.scenario(10.0, duration_s=3.0, maneuver_s=1.0, motion=((1.0, 0.5),), accel_duration_s=0.4)
    assert ended.truth[0, 13].tolist() == pytest.approx([13.0 + 0.5 * 0.5 * 9, 1.0 + 3 * 0.5, 0.5])
    assert ended.truth[0, 14].tolist() == pytest.approx([14.0 + 0.5 * 0.5 * 16, 1.0 + 4 * 0.5, 0.0])
    assert ended.truth[0, 20].tolist() == pytest.approx([20.0 + 0.5 * (0.5 * 16 + 4 * 6), 3.0, 0.0])
    assert ended.truth[0, 9].tolist() == pytest.approx([9.0, 1.0, 0.0])
    two = scn.config_scenario({**DEFAULT, "manoeuvre": "2 s acceleration"})  # uniform motion before the onset, exactly
    f = np.arange(125.0)
    assert np.array_equal(
        two.truth[:, :125], np.stack([np.stack([v * f, np.full(125, v), 0 * f], -1) for v in (10, -6)])
    )


def test_the_runs_sigma_scales_the_thresholds_and_the_readings(monkeypatch):
    sizes = {**SIZES, "sigma_eps": 2.0}
    calls = _record(monkeypatch)
    study.tradeoff_runs(DEFAULT, 3, sizes)
    ((_, _, cfg, sigma, _),) = calls["runs"]
    assert sigma == 2.0 and calls["measurements"][4] == 2.0 and calls["positions"][0][4] == 2.0
    assert _same(cfg.threshold, _card_threshold(sigma=2.0))
    sg = study.sigma_s_readings(DEFAULT, sizes)
    for r, v in _card_sigma_fields().items():
        if r.startswith("sigma_S"):
            assert sg["sigma_S"][r.removeprefix("sigma_S ")] == pytest.approx(2 * v, rel=1e-9), r
    assert sg["rho_v1"] == pytest.approx(_card_stationary(25, 50)["rho"], rel=1e-9)
    assert sg["pfa_independent"] == pytest.approx(_card_sigma_fields()["pfa_independent"], rel=1e-9)


def test_the_tradeoff_runs_hand_each_filter_the_same_runs(monkeypatch):
    calls = _record(monkeypatch)
    cfg = {"rms_span": "end of the loss", "k_bound2": 30}
    tr = study.tradeoff_runs(cfg, 5, SIZES)
    assert calls["tuning"][0] == {**DEFAULT, **cfg} and calls["tuning"][1] is SIZES  # tuned on the completed config
    truth, model, n, rng, sigma = calls["measurements"]
    assert (model, n, sigma) == ("white Gaussian", 2, 1.0)
    assert rng.bit_generator.state == np.random.default_rng(5).bit_generator.state  # the run's seed, no draw yet
    z = tr["z"]
    assert z.shape == (2, 2, 625) and (z == 7.0).all()
    assert [(p[0], p[1]) for p in calls["positions"]] == [
        ("fixed 2nd order", (30,)),
        ("tuned for end of the loss", ("end of the loss",)),
    ]
    assert all(p[2] is z and p[3] is tr["scenario"] and p[4] == 1.0 for p in calls["positions"])
    assert calls["runs"][0][0] is z and calls["runs"][0][4] is False
    assert set(tr["positions"]) == {"adaptive", "2nd order without the switch", "tuned for end of the loss"}
    assert tr["tuning"] == {"tuned for end of the loss": (("end of the loss",), 1.0, False)}
    assert all(p.shape == (2, 2, 625) for p in tr["positions"].values())
    assert set(tr) == {"scenario", "positions", "tuning", "z"}


def test_the_adaptive_positions_are_the_schemes_first_state(monkeypatch):
    _record(monkeypatch)

    def run_track_modes(z, visible, cfg, sigma, covariance=True):
        x = np.zeros(np.shape(z) + (3,))
        x[..., 0], x[..., 1] = 1.5, -4.0
        return SimpleNamespace(x=x)

    monkeypatch.setattr(scn, "run_track_modes", run_track_modes)
    tr = study.tradeoff_runs(DEFAULT, 5, SIZES)
    assert (tr["positions"]["adaptive"] == 1.5).all() and tr["positions"]["adaptive"].shape == (2, 2, 625)


def test_the_scenario_runs_run_every_restart_with_the_covariance(monkeypatch):
    calls = _record(monkeypatch)
    monkeypatch.setattr(study, "measurements", scn.measurements)  # the real draws: the seed and sigma pinned
    cfg = {"restart": "B", "k_bound3": 50, "noise": "white Gaussian"}
    sizes = {**SIZES, "sigma_eps": 2.0}
    r = study.scenario_runs(cfg, 9, sizes)
    sc = r["scenario"]
    e = np.random.default_rng(9).standard_normal((3, 2, 625))
    assert np.allclose(r["z"], sc.truth[:, :, 0] + 2.0 * e, rtol=0, atol=1e-9)
    assert list(r["outs"]) == ["A", "B", "C"] and set(r) == {"scenario", "z", "outs"}
    for (z, visible, c, sigma, covariance), restart in zip(calls["runs"], "ABC"):
        assert z is r["z"] and visible is sc.visible and sigma == 2.0 and covariance is True
        assert (c.restart, c.k_bound3, c.k_bound2, c.window, c.arm_k) == (restart, 50, 50, 25, 100)
        assert r["outs"][restart].cfg is c
    calls["runs"].clear()
    only = study.scenario_runs({"noise": "quantised"}, 9, SIZES, restarts=("C",))
    assert list(only["outs"]) == ["C"] and [c[2].restart for c in calls["runs"]] == ["C"]
    assert np.array_equal(only["z"], np.round(sc.truth[:, :, 0] + math.sqrt(11 / 12) * e))
    assert only["z"].shape == (3, 2, 625)


def test_run_scheme_lets_the_caller_replace_a_setting(monkeypatch):
    calls = _record(monkeypatch)
    sc = scn.config_scenario(DEFAULT)
    z = np.zeros((1, 2, 625))
    scn.run_scheme(z, sc, DEFAULT, SIZES, covariance=False, force_switch_k=139, restart="B")
    scn.run_scheme(z, sc, {**DEFAULT, "restart": "C"}, SIZES, covariance=False)
    scn.run_scheme(z, sc, DEFAULT, SIZES)
    (_, _, a, _, cov_a), (_, _, c, _, cov_c), (_, _, d, _, cov_d) = calls["runs"]
    assert (a.force_switch_k, a.restart, a.k_bound3, cov_a) == (139, "B", 100, False)
    assert (c.restart, c.force_switch_k, cov_c) == ("C", None, True)  # restart C always runs the covariance
    assert (d.restart, cov_d) == ("A", True)  # covariance unless told
    cfg = scn._scheme_config({**DEFAULT, "k_bound3": 200}, sc, SIZES, window=10)
    assert (cfg.window, cfg.k_bound3, cfg.arm_k) == (10, 200, 100)  # the override replaces the field only


def test_arming_reads_the_rule_and_falls_back_before_the_onset():
    assert scn.arming_count("gains at bound", 50, 25, 125) == (100, "gains at bound")
    assert scn.arming_count("windows full", 50, 25, 125) == (51, "windows full")
    assert scn.arming_count("gains at bound", 75, 25, 125) == (125, "gains at bound")  # tests at frame 124
    fallback = scn.arming_count("gains at bound", 76, 25, 125)
    assert fallback[0] == 51 and fallback[1].startswith("windows full")
    assert scn.arming_count("windows full", 10, 62, 125) == (125, "windows full")
    assert scn.arming_count("windows full", 10, 63, 125)[0] == 127
    with pytest.raises(ValueError, match="arming rule"):
        scn.arming_count("never", 50, 25, 125)


def test_the_cadence_leaves_the_tested_frames_only():
    c = scn.cadence_threshold(np.arange(1.0, 13.0), "every n frames", 3, 4)
    assert c.tolist() == [1.0, 2.0, 3.0, 4.0, np.inf, np.inf, 7.0, np.inf, np.inf, 10.0, np.inf, np.inf]
    c = scn.cadence_threshold(np.arange(1.0, 13.0), "every 2n frames", 2, 3)
    assert c.tolist() == [1.0, 2.0, 3.0, np.inf, np.inf, np.inf, 7.0, np.inf, np.inf, np.inf, 11.0, np.inf]
    assert scn.cadence_threshold([1, 2, 3], "every frame", 5, 1).tolist() == [1.0, 2.0, 3.0]
    with pytest.raises(ValueError, match="test cadence"):
        scn.cadence_threshold([1.0], "sometimes", 3, 4)


def test_each_threshold_reading_is_the_cards():
    vis = np.ones(120, bool)
    for reading in ("stationary", "independent", "raw increments"):
        c = scn.detector_threshold(reading, vis, 50, 25, 1e-3)
        assert c.shape == (120,) and c == pytest.approx(np.full(120, Z3 * _card_stationary(25, 50)[reading]))
    twice = scn.detector_threshold("stationary", vis, 50, 25, 1e-3, 2.0)
    assert twice == pytest.approx(np.full(120, 2 * Z3 * _card_stationary(25, 50)["stationary"]))
    assert scn.detector_threshold("raw increments", vis[:7], 50, 25, 1e-3, 2.0).tolist() == pytest.approx([20 * Z3] * 7)
    exact = scn.detector_threshold("exact", _card_visible(), 50, 25, 1e-3, 2.0)
    assert _same(exact, _card_threshold(sigma=2.0))
    with pytest.raises(ValueError, match="threshold reading"):
        scn.detector_threshold("guessed", vis, 50, 25, 1e-3)


def test_each_noise_model_is_the_one_its_value_names():
    truth = np.array([[0.2, 1.7, -3.4, 8.0, 0.49], [5.0, 5.5, 6.0, 6.5, 7.0]])
    e = np.random.default_rng(4).standard_normal((3, 2, 5))
    got = {m: scn.measurements(truth, m, 3, np.random.default_rng(4), 1.5) for m in scn.NOISE_MODELS}
    assert np.allclose(got["white Gaussian"], truth + 1.5 * e, rtol=0, atol=1e-12)
    assert np.array_equal(got["quantised"], np.round(truth + math.sqrt(1.5**2 - 1 / 12) * e))
    x = np.empty_like(e)  # AR(1), rho = 0.5, stationary from the first frame, RMS 1.5
    x[..., 0] = e[..., 0]
    for t in range(1, 5):
        x[..., t] = 0.5 * x[..., t - 1] + math.sqrt(0.75) * e[..., t]
    assert np.allclose(got["AR(1), rho = 0.5"], truth + 1.5 * x, rtol=0, atol=1e-12)
    rng = np.random.default_rng(4)
    e2, chi2 = rng.standard_normal((3, 2, 5)), rng.chisquare(3, (3, 2, 5))  # t(3) scaled to RMS 1.5
    assert np.allclose(got["Student t, 3 dof"], truth + 1.5 * math.sqrt(1 / 3) * e2 / np.sqrt(chi2 / 3), atol=1e-12)
    for m in scn.NOISE_MODELS:  # the stream goes on after the model's own draws only (common random numbers)
        rng, ref = np.random.default_rng(8), np.random.default_rng(8)
        scn.measurements(truth, m, 3, rng, 1.5)
        ref.standard_normal((3, 2, 5))
        if m == "Student t, 3 dof":
            ref.chisquare(3, (3, 2, 5))
        assert rng.standard_normal() == ref.standard_normal(), m
    assert np.array_equal(scn.measurements(truth, "quantised", 2, np.random.default_rng(1), 0.2), np.round([truth] * 2))
    assert scn.measurements([1.0, 2.0], "white Gaussian", 4, np.random.default_rng(0)).shape == (4, 2)
    one = scn.measurements([1.0, 2.0], "white Gaussian", 1, np.random.default_rng(0))  # sigma 1 unless told
    assert np.allclose(one, np.array([1.0, 2.0]) + np.random.default_rng(0).standard_normal((1, 2)), atol=1e-12)
    with pytest.raises(ValueError, match="measurement-error model"):
        scn.measurements(truth, "uniform", 1, np.random.default_rng(0))


def _small_scenario():
    """Ten frames, lost from frame 5 to frame 8 (frames 5, 6, 7)."""
    f = np.arange(10)
    truth = np.stack([np.stack([2.0 * f + 1, np.full(10, 2.0), np.zeros(10)], -1)] * 2)
    return scn.Scenario(25.0, 10, 2, 5, 8, (f < 5) | (f >= 8), truth)


def test_the_gain_checks_count_increases_outside_the_switches_and_the_bound():
    sc = _small_scenario()
    bound = 0.95  # the card's 3rd-order kappa1 at k = 4, the bound k_b3 = 4 handed to the check
    k1 = np.zeros((2, 2, 10))
    k1[:] = [0.9, 0.8, 0.7, 0.6, 0.5, 0.0, 0.0, 0.0, 0.5, 0.4]  # decreasing, 0 while lost
    k1[0, 0, 2:5] = [1.0, 0.97, bound]  # a switch after frame 1, then down to the bound before the loss
    k1[0, 1, 3:5] = [0.75, 0.6]  # an increase outside a switch
    k1[1, 0, 1:5] = [1.0, 0.99, 0.97, bound]  # switched after frame 0, at the bound
    k1[1, 1, 1:5] = [1.0, 0.99, 0.97, bound * 1.01]  # switched, not at the bound
    gains = np.zeros((2, 2, 10, 3))
    gains[..., 0] = k1
    det = np.array([[1, 3], [0, 0]])
    out = SimpleNamespace(gains=gains, detection_frame=det)
    got = study.gain_checks(out, sc, 4)
    # increases: [0, 0] none outside its switch (frame 1 -> 2); [0, 1] frame 2 -> 3 (its switch is 3 -> 4, which
    # is a decrease); the lost frames' return (7 -> 8, not both visible) is not counted; the others switch once
    assert got == {"increases_outside_switches": 1, "long_enough": 2, "at_bound": 1}
    # switched at least k_b3 = 4 frames before the loss (frame 5 - 1 - det >= 4): det 0 only; with k_b3 = 3 det 1
    # too, and the bound is kappa1(3) = 1 (the card's table), which no run sits at
    assert study.gain_checks(out, sc, 3) == {"increases_outside_switches": 1, "long_enough": 3, "at_bound": 0}
    none = SimpleNamespace(gains=gains, detection_frame=np.full((2, 2), -1))
    assert study.gain_checks(none, sc, 4) == {"increases_outside_switches": 4, "long_enough": 0, "at_bound": 0}
    rising = gains.copy()
    rising[..., 9, 0] = 0.6  # an increase from frame 8 to 9 in every run
    assert (
        study.gain_checks(SimpleNamespace(gains=rising, detection_frame=np.full((2, 2), -1)), sc, 4)[
            "increases_outside_switches"
        ]
        == 8
    )
    late = SimpleNamespace(gains=rising, detection_frame=np.full((2, 2), 9))  # the last frame: its switch is 8 -> 9
    assert study.gain_checks(late, sc, 4)["increases_outside_switches"] == 4
    tiny = np.zeros((1, 1, 10, 3))
    tiny[..., 3, 0] = 1e-15  # an increase of 1e-15 is rounding, not an increase
    tiny[..., 4, 0] = 3e-15
    assert (
        study.gain_checks(SimpleNamespace(gains=tiny, detection_frame=np.array([[-1]])), sc, 4)[
            "increases_outside_switches"
        ]
        == 1
    )


def test_the_coast_check_compares_the_loss_with_f_to_the_m():
    sc = _small_scenario()
    eps = np.array([1.0, 0.5, 0.2])  # error at the last seen frame (4)
    err = np.zeros((2, 2, 10, 3))
    err[..., 4, :] = eps
    for m in (1, 2, 3):  # (E2): x + m v + m^2 / 2 a, v + m a, a
        err[..., 4 + m, :] = [1.0 + 0.5 * m + 0.1 * m**2, 0.5 + 0.2 * m, 0.2]
    err[..., 8, :] = 50.0  # back in view: not compared
    err[..., 3, :] = -7.0  # before the last seen frame: not read
    x = sc.truth[None] + err
    got = study.coast_check(SimpleNamespace(x=x), sc)
    assert got["max_abs_deviation"] == pytest.approx(0.0, abs=1e-12)
    assert got["error_scale"] == pytest.approx(1.0 + 1.5 + 0.9)  # the position after 3 frames
    x[1, 0, 6, 1] += 0.25
    x[0, 1, 7, 0] -= 0.125
    got = study.coast_check(SimpleNamespace(x=x), sc)
    assert got["max_abs_deviation"] == pytest.approx(0.25) and got["error_scale"] == pytest.approx(3.4)
    x[0, 0, 5, 2] += 4.0  # the largest error while lost
    assert study.coast_check(SimpleNamespace(x=x), sc) == pytest.approx({"max_abs_deviation": 4.0, "error_scale": 4.2})
