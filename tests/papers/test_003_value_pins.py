"""Paper 003: every claim's value pinned against an independent computation.

The interference claims are read through :func:`study.measure_interference` with its loss curves replaced by
designed ones (each run of each curve breaks lock between two grid SIRs chosen per curve), so every claim part has
a closed form: a loss share at a named SIR is the share of runs that break above it, a threshold the geometric mean
of the runs' geometric grid midpoints, a ratio the quotient of the two curves' thresholds. The same stand-in
records which scenarios the curves were asked for (the decoy's offset, the gates, the uncompensated tracker). The
tracking claims are re-computed from the study's own raw outputs at a small size, and the scenario's settings from
this project's stated defaults.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from tvtrack.montecarlo import Estimate
from tvtrack.papers.p003_rotating_marker_tracker import study
from tvtrack.papers.p003_rotating_marker_tracker.lock import first_loss
from tvtrack.papers.p003_rotating_marker_tracker.loops import phase_locked_amplitude
from tvtrack.papers.p003_rotating_marker_tracker.register import REGISTER
from tvtrack.papers.p003_rotating_marker_tracker.scene import Scenario, run_scenario, scenario_truth, state_errors

DEFAULT = REGISTER.default()
SIRS = np.asarray(study.SIR_GRID)  # 0.5, 0.75, 1, 4/3, 2, 3, 4.5, 6.75
USIRS = np.asarray(study.UNCOMPENSATED_GRID)  # 1, 2, 4, 8, 16
D = Scenario().diameter  # 8 px
#: Per curve: the grid index k at which each of 6 runs first keeps lock (lost at every SIR below index k).
BREAKS = {
    "rotating 1": (2, 3, 3, 4, 4, 5),
    "rotating 5": (3, 4, 5, 5, 6, 7),
    "static 1": (4, 5, 5, 6, 6, 7),
    "static 5": (5, 6, 6, 7, 7, 7),
    "decoy": (1, 2, 2, 3, 3, 4),
    "gate 1.5": (2, 3, 4, 4, 5, 6),
    "gate 5.0": (4, 4, 5, 6, 7, 7),
    "uncompensated": (1, 2, 2, 3, 3, 4),
}
#: Capture (five interferers, rotating marker): runs captured below this grid index.
CAPTURE = (1, 2, 4, 5, 6, 6)
N = 6


def lost(name, m: int = 8) -> np.ndarray:
    return np.arange(m)[:, None] < np.asarray(BREAKS[name])[None, :]


def thr(name, grid=SIRS) -> float:
    """The geometric-mean breaking SIR: each run at the geometric midpoint of its grid step."""
    k = np.asarray(BREAKS[name])
    return float(np.exp(np.mean((np.log(grid[k - 1]) + np.log(grid[k])) / 2)))


def share(name, sir) -> float:
    """Share of runs that lost lock at the grid SIR ``sir``."""
    i = int(np.argmin(np.abs(SIRS - sir)))
    return float(np.mean(i < np.asarray(BREAKS[name])))


class Curves:
    """Stands in for :func:`study._curve`: designed loss curves, and a log of the scenarios asked for."""

    def __init__(self):
        self.asked = []

    def __call__(self, sc, sirs, n, seed, crit, counts=None, criteria=False):
        self.asked.append((sc, tuple(sirs), counts, crit))
        m = len(sirs)
        if counts is None:
            if sc.kappa == 1.0:
                name = "uncompensated"
            else:
                name = {1.5 * D / 2: "gate 1.5", 5.0 * D / 2: "gate 5.0"}[sc.gate_half]
            return lost(name, m), None
        fam = "rotating" if sc.rotating else "static"
        names = [f"{fam} {c}" if isinstance(c, int) else c[0] for c in counts]
        L = np.stack([lost(nm, m) for nm in names])
        met = np.zeros(L.shape + (3,), bool)
        met[1, :, :, 0] = np.arange(m)[:, None] < np.asarray(CAPTURE)[None, :]
        return L, (met if criteria else None)


@pytest.fixture(scope="module")
def interference():
    curves = Curves()
    mp = pytest.MonkeyPatch()
    mp.setattr(study, "_curve", curves)
    mp.setattr(study, "_together", lambda parts: None)  # the curves come from the stand-in, one by one
    mp.setattr(study, "_bandwidth_ratio", lambda *a: Estimate(0.4, np.nan, 0.3, 0.5, N))
    try:
        out = study.measure_interference(DEFAULT, 0, study.Sizes(trials=N, horizon_s=1.0))
    finally:
        mp.undo()
    return out, curves.asked


def test_c5_c6_c7_read_the_loss_shares_at_the_papers_sirs(interference):
    out, _ = interference
    # C003-5: no loss and no capture with five interferers at SIR 3; C003-6: one interferer, finite at 0.5, loss-free
    # from 2, not lower at 4/3; C003-7: five interferers, loss-free from 3, not lower at 2
    assert out["C003-5"]["no_loss"].value == pytest.approx(share("rotating 5", 3.0))
    assert out["C003-5"]["no_capture"].value == pytest.approx(np.mean(5 < np.asarray(CAPTURE)))
    assert out["C003-6"]["finite"].value == pytest.approx(share("rotating 1", 0.5))
    assert out["C003-6"]["loss_free"].value == pytest.approx(share("rotating 1", 2.0))
    assert out["C003-6"]["not_lower"].value == pytest.approx(share("rotating 1", 4 / 3))
    assert out["C003-7"]["loss_free"].value == pytest.approx(share("rotating 5", 3.0))
    assert out["C003-7"]["not_lower"].value == pytest.approx(share("rotating 5", 2.0))
    # five interferers over one: > 1 (the threshold rises with more interferers)
    assert out["C003-7"]["rise"].value == pytest.approx(thr("rotating 5") / thr("rotating 1"), rel=1e-12)
    assert out["C003-7"]["rise"].value > 1


def test_c12_divides_static_and_decoy_by_the_rotating_marker(interference):
    out, _ = interference
    c12 = out["C003-12"]
    assert c12["one"].value == pytest.approx(thr("static 1") / thr("rotating 1"), rel=1e-12)
    assert c12["five"].value == pytest.approx(thr("static 5") / thr("rotating 5"), rel=1e-12)
    assert c12["imitator"].value == pytest.approx(thr("decoy") / thr("rotating 1"), rel=1e-12)
    assert out["_map"]["static 5"].value == pytest.approx(thr("static 5"), rel=1e-12)


def test_c10_c11_read_the_gates_and_the_compensation(interference):
    out, _ = interference
    c10, c11 = out["C003-10"], out["C003-11"]
    for est, name in zip(c10["gate"], ("gate 1.5", "rotating 5", "gate 5.0")):
        assert est.value == pytest.approx(thr(name), rel=1e-12)
    # compensated SIR_0 threshold (kappa x SIR threshold, kappa = 0.1) over the uncompensated one
    want = 0.1 * thr("rotating 5") / thr("uncompensated", USIRS)
    assert c10["compensation"].value == pytest.approx(want, rel=1e-12)
    assert c11["dynamics"].value == pytest.approx(share("gate 1.5", SIRS[-1]))
    assert c11["selection"].value == pytest.approx(thr("gate 5.0") / thr("rotating 5"), rel=1e-12)
    assert c11["bandwidth"].value == pytest.approx(2.5)  # 0.4 either way from 1: 1 / 0.4


def test_the_curves_are_asked_for_the_cards_scenarios(interference):
    _, asked = interference
    fams = [(sc, counts) for sc, _, counts, _ in asked if counts is not None]
    rot = [c for sc, c in fams if sc.rotating]
    # the law-following decoy rides with the rotating marker, its centre 2 D = 16 px off, no stationary interferer
    assert rot == [(1, 5, ("decoy", 2 * D))]
    static = [sc for sc, c in fams if not sc.rotating]
    assert len(static) == 1 and static[0].gate_half == 1.5 * D and static[0].form == "quadrant"
    single = [sc for sc, _, counts, _ in asked if counts is None]
    gates = sorted(sc.gate_half for sc in single if sc.kappa != 1.0)
    assert gates == [1.5 * D / 2, 5.0 * D / 2] and all(sc.n_interferers == 5 for sc in single)
    unc = [(sc, s) for sc, s, counts, _ in asked if counts is None and sc.kappa == 1.0]
    assert len(unc) == 1 and unc[0][1] == tuple(USIRS)


def test_the_loss_criterion_is_the_gate_half_size_over_half_a_second():
    sc = study.scenario(DEFAULT)
    crit = study.criterion(DEFAULT, sc)
    assert (crit.threshold, crit.window, crit.fraction) == (12.0, 250, 0.5)  # gate half 12 px, 0.5 s at 500 fps
    assert study.criterion({**DEFAULT, "loss_radius": "D/2"}, sc).threshold == 4.0


def test_the_motion_scale_scales_both_axes():
    base = study.scenario(DEFAULT)
    assert (base.x_std, base.y_amplitude, base.y_freq) == (10.0, 20.0, 0.5)  # the defaults: sigma_x 10 px, A_y 20 px
    big = study.scenario({**DEFAULT, "motion_scale": 2.0})
    assert (big.x_std, big.y_amplitude, big.y_freq) == (20.0, 40.0, 0.5)


def test_truth_modulates_radius_and_rate_as_fig_2():
    # r(t) = r0 (1 + a_r sin 2 pi f_r t), omega(t) = omega0 (1 + a_w sin 2 pi f_w t), theta its running integral
    sc = Scenario(duration_s=4.0, radius_mod=0.15, radius_mod_hz=0.25, omega_mod=0.1, omega_mod_hz=0.5)
    tr = scenario_truth(np.random.default_rng(1), 2, sc)
    t = np.arange(sc.n_frames) / sc.fps
    np.testing.assert_allclose(tr.r[1], 12.0 * (1 + 0.15 * np.sin(2 * np.pi * 0.25 * t)), rtol=1e-12)
    w0 = 2 * np.pi * 8.0
    np.testing.assert_allclose(tr.omega[0], w0 * (1 + 0.1 * np.sin(2 * np.pi * 0.5 * t)), rtol=1e-12)
    dth = np.diff(np.unwrap(tr.theta[0]))
    np.testing.assert_allclose(dth, tr.omega[0, :-1] / sc.fps, rtol=0.02)
    np.testing.assert_allclose(np.hypot(*(tr.marker[0] - np.stack([tr.xr[0], tr.yr[0]], -1)).T), tr.r[0])


SMALL = study.Sizes(trials=2, fig1_s=1.2, fig2_s=1.2, transient_s=0.6, horizon_s=1.0)


def test_c2_ripple_trend_is_the_wide_loop_over_the_narrow_loop():
    sc1 = study.scenario(DEFAULT, SMALL, duration_s=SMALL.fig1_s)
    k0 = int(round(SMALL.transient_s * sc1.fps))
    f1 = study._fig1(sc1, 2, 5, k0, study.criterion(DEFAULT, sc1))
    locked = f1["figure"]["locked"]  # mean locked ripple at B_xy = 2, 5, 10, 20 Hz
    assert study.BXY_GRID == (2.0, 5.0, 10.0, 20.0) and study.RIPPLE_TREND == (20.0, 10.0)
    lost = f1["_lock_by_bandwidth"]
    assert lost["10 Hz"].value == lost["20 Hz"].value == 0.0  # both loops keep lock here: the pair reads every run
    assert f1["_ripple_trend"].value == pytest.approx(locked[3] / locked[2], rel=1e-12)  # 20 Hz over 10 Hz, in lock


@pytest.fixture(scope="module")
def fig1_runs():
    """The Fig. 1 batch at a small size: its claim parts, and the truth and history of its runs (caught on their way
    to the claims), with the frame the transient ends at."""
    sc1 = study.scenario(DEFAULT, SMALL, duration_s=SMALL.fig1_s)
    k0 = int(round(SMALL.transient_s * sc1.fps))
    seen = []
    real = study.state_errors

    def catch(tr, h):
        seen.append((tr, h))
        return real(tr, h)

    mp = pytest.MonkeyPatch()
    mp.setattr(study, "state_errors", catch)
    try:
        f1 = study._fig1(sc1, SMALL.trials, 5, k0, study.criterion(DEFAULT, sc1))
    finally:
        mp.undo()
    (tr, h) = seen[0]
    return sc1, k0, f1, tr, h


def _default_block(n_runs: int) -> slice:
    """The runs of the Fig. 1 batch at this project's default coordinate-loop bandwidth (10 Hz)."""
    j = study.BXY_GRID.index(Scenario().b_xy)
    return slice(j * n_runs, (j + 1) * n_runs)


def test_c1_x_error_is_read_after_the_transient(fig1_runs):
    """C003-1: "post-transient (t > 2 s) RMS of x_r_hat - x_r ... < D/2 = 4 px": the RMS of the x error over the
    frames from round(transient_s * fps) on, on the runs at the default (10 Hz) coordinate loops, not over the whole
    run with its initial transient."""
    sc1, k0, f1, tr, h = fig1_runs
    ex = state_errors(tr, h)[_default_block(SMALL.trials), :, 0]
    after = np.sqrt(np.mean(np.mean(ex[:, k0:] ** 2, axis=1)))
    whole = np.sqrt(np.mean(np.mean(ex**2, axis=1)))
    assert abs(whole - after) > 0.05 * after  # the transient weighs: the two readings differ at this size
    assert f1["C003-1"]["x_r"].value == pytest.approx(after, rel=1e-9)


def test_c2_near_part_is_the_locked_amplitude_over_the_near_control(fig1_runs):
    """C003-2: "clear local maximum within f_rot +- 1 Hz, holding >= 10 % of the error power": the post-transient x
    error's amplitude locked to the marker's rotation is the numerator, the amplitude locked to a control at
    f_rot + 1 Hz the denominator (the rule asks locked > control), on the runs at the default coordinate loops."""
    sc1, k0, f1, tr, h = fig1_runs
    sel = _default_block(SMALL.trials)
    ex, th = state_errors(tr, h)[sel, k0:, 0], tr.theta[sel, k0:]
    locked = phase_locked_amplitude(ex, th)
    near = phase_locked_amplitude(ex, th * (sc1.rotation_hz + 1.0) / sc1.rotation_hz)
    assert np.mean(locked) != pytest.approx(np.mean(near), rel=0.05)  # the order of the quotient is visible
    assert f1["C003-2"]["near"].value == pytest.approx(np.mean(locked) / np.mean(near), rel=1e-9)


def test_c3_rate_error_is_relative_to_the_nominal_rate():
    sc2 = replace(study.scenario(DEFAULT, SMALL, duration_s=SMALL.fig2_s), omega_mod=0.1, radius_mod=0.15)
    k2 = 200
    f2 = study._fig2(sc2, 1, 5, k2)
    fig = f2["figure"]
    w0 = 2 * np.pi * 8.0  # rad/s: C003-3's omega error is a fraction of it (the paper's per cent of omega)
    rel = (fig["omega_hat"] - fig["omega"])[k2:] / w0
    assert f2["C003-3"]["omega"].value == pytest.approx(np.sqrt(np.mean(rel**2)), rel=1e-9)
    assert f2["C003-3"]["r"].value == pytest.approx(np.sqrt(np.mean((fig["r_hat"] - fig["r"])[k2:] ** 2)), rel=1e-9)


def test_c4_compensation_part_is_the_uncompensated_loss_share_minus_the_compensated():
    sc1 = study.scenario(DEFAULT, SMALL, duration_s=2.0)  # long enough for the raw background to break lock
    k0 = int(round(SMALL.transient_s * sc1.fps))
    crit = study.criterion(DEFAULT, sc1)
    part, _ = study._background_sweep(sc1, 1, 3, k0, crit)

    def lost_alone(**kw):  # the case run on its own, on the sweep's draws (stream 3)
        h = run_scenario(np.random.default_rng([3, 3]), 1, replace(sc1, **kw), keep_full=False)[2]
        return (first_loss(h.miss, crit, h.inside) >= 0).astype(float)

    comp = lost_alone(background_std=1.0 / (sc1.kappa * 50.0), corr_length=8.0)
    raw = lost_alone(kappa=1.0, background_std=1.0 / 5.0, corr_length=8.0)  # no compensation, d / sigma_f = 5
    assert part["compensation"].value == pytest.approx(np.mean(raw - comp))
    assert np.mean(raw) == 1.0  # the raw background breaks lock: the ablation is not vacuous
