"""Tests of paper 003's package: rotating-marker scene, discriminators, loops, loss of lock."""

from dataclasses import replace

import numpy as np
import pytest
from scipy import signal

from tvtrack.measure import gate_crop_size
from tvtrack.papers.p003_rotating_marker_tracker.discriminators import (
    edge_discriminator,
    interval_weights,
    polar_errors,
    quadrant_discriminator,
    quadrant_noise,
    quadrant_weights,
    static_characteristic,
    two_emitter_discriminator,
)
from tvtrack.papers.p003_rotating_marker_tracker.lock import (
    CRITERIA,
    LossCriterion,
    first_loss,
    loss_criteria,
)
from tvtrack.papers.p003_rotating_marker_tracker.loops import (
    RotatingGateTracker,
    loop_gains,
    loop_poles,
    run_closed_loop,
    simulate_two_emitter_1d,
)
from tvtrack.papers.p003_rotating_marker_tracker.imaging import RotatingMarkerScene
from tvtrack.papers.p003_rotating_marker_tracker.scene import Scenario, marker_truth, render_spot, run_scenario
from tvtrack.papers.p003_rotating_marker_tracker.backdrop import correlated_background, place_interferers
from tvtrack.render import box_spot, pixel_fractions_box

D, A = 8.0, 12.0


def quadrant_sums(crops, origin, centre, half):
    """The paper's four quadrant integrals ``u1..u4`` (u1: x < x_m, y > y_m; u2: x > x_m, y > y_m; u3: x < x_m,
    y < y_m; u4: x > x_m, y < y_m), each ``half x half`` px, from the pixels' overlaps with each half-gate."""
    rows, cols = crops.shape[-2:]
    cx, cy, ox, oy = centre[:, 0], centre[:, 1], origin[:, 0], origin[:, 1]
    xl, xr = interval_weights(cx - half, cx, cols, ox), interval_weights(cx, cx + half, cols, ox)
    yl, yu = interval_weights(cy - half, cy, rows, oy), interval_weights(cy, cy + half, rows, oy)
    pairs = ((yu, xl), (yu, xr), (yl, xl), (yl, xr))
    return np.stack([np.einsum("ny,nyx,nx->n", wy, crops, wx) for wy, wx in pairs], axis=-1)


def _renderer(spot):
    return lambda c, shape, origin: render_spot(spot, c, shape, D, 1.0, origin)


@pytest.mark.parametrize("spot", ["disc", "square"])
def test_quadrant_discriminator_odd_and_linear_with_predicted_slope(spot):
    offsets = np.array([0.25, 0.5, 1.0, 2.0, 3.0])
    for axis in (0, 1):
        # gate on a pixel centre: the pixel grid is symmetric and the S-curve exactly odd
        pos = static_characteristic(_renderer(spot), offsets, half=A, axis=axis, gate_center=(0.0, 0.0))
        neg = static_characteristic(_renderer(spot), -offsets, half=A, axis=axis, gate_center=(0.0, 0.0))
        assert np.all(pos > 0)  # corrected sign: +grad Pi
        np.testing.assert_allclose(neg, -pos, rtol=1e-9)
        # at a sub-pixel gate position the pixel grid breaks oddness only slightly
        pos = static_characteristic(_renderer(spot), offsets, half=A, axis=axis)
        neg = static_characteristic(_renderer(spot), -offsets, half=A, axis=axis)
        np.testing.assert_allclose(neg, -pos, rtol=0.04)
        slope = pos / offsets
        np.testing.assert_allclose(slope[:3], 2 * D, rtol=0.05)  # linear, slope 2 d D
    # saturates (relay zone) beyond D/2 and vanishes once the spot leaves the gate
    far = static_characteristic(_renderer(spot), [5.0, 7.5, 20.0], half=A)
    assert abs(far[0] - far[1]) < 0.05 * far[0] and abs(far[2]) < 1e-9


def test_quadrant_sums_match_bilinear_form_and_card_layout():
    rng = np.random.default_rng(0)
    crops = rng.normal(size=(6, 26, 26))
    origin = rng.integers(-5, 5, size=(6, 2))
    centre = origin + 12.5 + rng.uniform(-0.5, 0.5, size=(6, 2))
    u = quadrant_sums(crops, origin, centre, A)
    dx, dy, e = quadrant_discriminator(crops, origin, centre, A)
    np.testing.assert_allclose(dx, (u[:, 1] + u[:, 3]) - (u[:, 0] + u[:, 2]))
    np.testing.assert_allclose(dy, (u[:, 0] + u[:, 1]) - (u[:, 2] + u[:, 3]))
    np.testing.assert_allclose(e, u.sum(axis=1))
    # u1 is left, y > y_m: a spot there lights u1 only
    spot = box_spot(centre + [-5.0, 5.0], (26, 26), 2.0, 16.0, origin)
    q = quadrant_sums(spot, origin, centre, A)
    assert np.all(q[:, 0] > 15.9) and np.all(q[:, 1:] < 1e-9)


def test_interval_weights_are_overlaps():
    w = interval_weights(np.array([0.2]), np.array([3.7]), 6, np.array([0]))
    np.testing.assert_allclose(w[0], [0.3, 1, 1, 1, 0.2, 0])
    np.testing.assert_allclose(w.sum(), 3.5)


def test_projected_noise_has_the_pixel_noise_covariance():
    rng = np.random.default_rng(1)
    n, size, sigma = 20000, 26, 0.3
    origin = np.zeros((n, 2), int)
    centre = np.tile([12.8, 12.3], (n, 1))
    pix = sigma * rng.standard_normal((n, size, size))
    dx, dy, _ = quadrant_discriminator(pix, origin, centre, A)
    wy, wx = quadrant_weights(origin, centre, A, (size, size))
    proj = quadrant_noise(wy, wx, sigma, rng)
    c_pix, c_proj = np.cov(np.stack([dx, dy])), np.cov(proj.T)
    np.testing.assert_allclose(np.diag(c_proj), np.diag(c_pix), rtol=0.05)


def test_projected_noise_has_the_full_pixel_noise_covariance_off_the_diagonal_too():
    """A gate clipped by its crop has correlated Delta_x, Delta_y noise; the projection must
    reproduce the whole 2x2 covariance sigma^2 [sum Wx Wx, sum Wx Wy; ., sum Wy Wy]."""
    rng = np.random.default_rng(11)
    n, size, sigma = 100000, 26, 0.3
    origin = np.zeros((n, 2), int)
    centre = np.tile([5.3, 6.7], (n, 1))  # left and lower halves clipped
    wy, wx = quadrant_weights(origin[:1], centre[:1], A, (size, size))
    w_dx = np.outer(wy[0, 0], wx[0, :, 1])  # full rows x (right - left)
    w_dy = np.outer(wy[0, 1], wx[0, :, 0])  # (upper - lower) x full columns
    exact = sigma**2 * np.array(
        [[np.sum(w_dx * w_dx), np.sum(w_dx * w_dy)], [np.sum(w_dx * w_dy), np.sum(w_dy * w_dy)]]
    )
    assert abs(exact[0, 1]) > 0.05 * np.sqrt(exact[0, 0] * exact[1, 1])  # a real correlation to test
    wy, wx = quadrant_weights(origin, centre, A, (size, size))
    c_proj = np.cov(quadrant_noise(wy, wx, sigma, rng).T)
    pix = sigma * rng.standard_normal((20000, size, size))
    dx, dy, _ = quadrant_discriminator(pix, origin[:20000], centre[:20000], A)
    c_pix = np.cov(np.stack([dx, dy]))
    scale = np.sqrt(exact[0, 0] * exact[1, 1])
    np.testing.assert_allclose(c_proj, exact, atol=0.01 * scale)  # a sign error would miss by 0.17
    np.testing.assert_allclose(c_pix, exact, atol=0.04 * scale)


def test_perfect_background_compensation_leaves_discriminator_unchanged():
    rng = np.random.default_rng(2)
    n, size = 8, gate_crop_size(A)
    origin = rng.integers(20, 40, size=(n, 2))
    centre = origin + 12.3
    s = render_spot("disc", centre + rng.uniform(-2, 2, (n, 2)), (size, size), D, 1.0, origin)
    noise = 0.02 * rng.standard_normal(s.shape)
    F = correlated_background(rng, n, (size, size), 8.0, 0.2)  # background f
    u = s + F + noise
    u_d = u - F  # (19) with f_hat = f
    for form in ("quadrant", "edge"):
        if form == "quadrant":
            a, b = (
                quadrant_discriminator(u_d, origin, centre, A)[:2],
                quadrant_discriminator(s + noise, origin, centre, A)[:2],
            )
        else:
            a, b = edge_discriminator(u_d, origin, centre, D / 2), edge_discriminator(s + noise, origin, centre, D / 2)
        np.testing.assert_allclose(a, b, atol=1e-5)
    # in the scene: kappa = 0 (perfect estimate) gives exactly the scene without background
    T = 3
    truth = marker_truth(
        np.full((n, T), 60.0), np.full((n, T), 60.0), np.full((n, T), 12.0), np.full((n, T), 50.0), np.zeros(n), 0.002
    )
    res = RotatingMarkerScene.static_residual(
        rng,
        n,
        (128, 128),
        kappa=0.0,
        background_std=0.5,
        corr_length=8,
        interferers=np.zeros((n, 0, 2)),
        interferer_brightness=1.0,
        spot="disc",
        diameter=D,
    )
    with_bg = RotatingMarkerScene(truth, (128, 128), "disc", D, 1.0, res)
    without = RotatingMarkerScene(truth, (128, 128), "disc", D, 1.0)
    c = truth.marker[:, 1] + 1.3
    np.testing.assert_array_equal(with_bg.gate_crops(1, c, 26, None)[0], without.gate_crops(1, c, 26, None)[0])


def test_edge_discriminator_is_relay_like_for_a_square_and_nonlinear_for_a_disc():
    sq = static_characteristic(_renderer("square"), [1.5, 2.5, 3.5], form="edge", half=A, a=D / 2)
    assert np.all(sq > 0) and np.ptp(sq) < 0.02 * sq.mean()  # constant: a relay
    disc = static_characteristic(_renderer("disc"), [0.5, 1.5, 3.5], form="edge", half=A, a=D / 2)
    assert np.all(np.diff(disc) > 0) and disc[2] / disc[1] < 1.5  # chord law, far from linear (2.33)


def test_polar_errors_rotate():
    th = np.linspace(0, 6, 7)
    e_r, e_t = polar_errors(np.cos(th), np.sin(th), th)
    np.testing.assert_allclose(e_r, 1.0)
    np.testing.assert_allclose(e_t, 0.0, atol=1e-12)


def test_loop_gains_give_stated_bandwidths_and_stable_poles():
    g = loop_gains(10.0, 0.2, 6.0)
    assert g.k_xy == pytest.approx(2 * np.pi * 10)
    w = 2 * np.pi * 6.0
    h = (g.k1 * 1j * w + g.k2) / (-(w**2) + g.k1 * 1j * w + g.k2)  # type-2 PLL
    assert abs(h) == pytest.approx(1 / np.sqrt(2), rel=1e-3)
    poles = loop_poles(g, 2 * np.pi * 8, 12.0)
    assert np.all(poles.real < 0)
    # without rotation coupling the r loop pole is -K_r
    slow = np.sort(np.abs(poles.real))[0]
    assert slow == pytest.approx(g.k_r, rel=0.1)


def test_noise_free_tracker_locks_static_object_below_0p1_px():
    n, T, dt = 6, 2000, 0.002
    rng = np.random.default_rng(3)
    truth = marker_truth(
        np.full((n, T), 128.3),
        np.full((n, T), 127.6),
        np.full((n, T), 12.0),
        np.full((n, T), 2 * np.pi * 8),
        rng.uniform(0, 2 * np.pi, n),
        dt,
    )
    for spot in ("disc", "square"):
        scene = RotatingMarkerScene(truth, (256, 256), spot, D, 1.0)
        x0 = np.stack(
            [truth.xr[:, 0] + 3, truth.yr[:, 0] - 3, 0.85 * truth.r[:, 0], truth.theta[:, 0] + 0.2, truth.omega[:, 0]],
            axis=1,
        )
        h = run_closed_loop(scene, RotatingGateTracker(x0, loop_gains(), 2 * D), None, gate_half=A)
        assert h.miss[:, -500:].max() < 0.1
        centre_err = np.hypot(h.estimate[:, -500:, 0] - 128.3, h.estimate[:, -500:, 1] - 127.6)
        assert centre_err.max() < 0.1
        assert np.abs(h.estimate[:, -1, 2] - 12.0).max() < 0.1


def test_variant_p_also_locks():
    n, T, dt = 4, 2000, 0.002
    truth = marker_truth(
        np.full((n, T), 128.0),
        np.full((n, T), 128.0),
        np.full((n, T), 12.0),
        np.full((n, T), 2 * np.pi * 8),
        np.zeros(n),
        dt,
    )
    scene = RotatingMarkerScene(truth, (256, 256), "disc", D, 1.0)
    x0 = np.tile([129.0, 127.0, 11.0, 0.1, 2 * np.pi * 8], (n, 1))
    h = run_closed_loop(scene, RotatingGateTracker(x0, loop_gains(), 2 * D, variant="P"), None, gate_half=A)
    assert h.miss[:, -500:].max() < 0.2


def test_loss_criterion_window_catches_capture_that_consecutive_misses():
    T = 1000
    miss = np.zeros((3, T))
    miss[1, 300:] = 30.0
    miss[1, 300::60] = 0.0  # the marker crosses the captured gate once per revolution
    miss[2, 500:520] = 30.0  # a short excursion, not a loss
    win = first_loss(miss, LossCriterion(12.0, 250, 0.5, "window"))
    assert win[0] == -1 and win[2] == -1 and 300 < win[1] < 600
    cons = first_loss(miss, LossCriterion(12.0, 100, kind="consecutive"))
    assert cons[1] == -1  # reset every revolution
    inside = np.ones((3, T), bool)
    inside[0, 700] = False
    assert first_loss(miss, LossCriterion(12.0, 250), inside)[0] == 700
    with pytest.raises(ValueError, match="fraction"):
        LossCriterion(12.0, 250, 1.5)


def test_strong_interferers_cause_a_detected_loss_and_capture():
    rng = np.random.default_rng(4)
    sc = Scenario(duration_s=2.0, n_interferers=5, x_std=0.0, y_amplitude=0.0)
    sir = np.array([0.2] * 4 + [50.0] * 4)
    truth, scene, h = run_scenario(rng, 8, sc, sir, keep_full=False)
    crit = LossCriterion(sc.gate_half, 125)
    loss = first_loss(h.miss, crit, h.inside)
    assert np.all(loss[:4] >= 0) and np.all(loss[4:] == -1)


def test_decoy_brightness_follows_the_sir_of_the_run():
    """The decoy is an interferer: its brightness is d / SIR with the SIR the run was given
    (it used to stay at the scenario's fixed decoy_sir whatever SIR the loss curve asked for)."""
    sc = Scenario(duration_s=0.02, decoy_offset=3 * D, noise_std=0.0, kappa=0.0)
    sir = np.array([1.0, 2.0, 4.0])
    truth, scene, _ = run_scenario(np.random.default_rng(9), 3, sc, sir, keep_full=False)
    for i, s in enumerate(sir):
        img = scene.frame(i, 0)
        yx = np.round(scene.decoys[i, 0, ::-1]).astype(int)
        assert img[yx[0], yx[1]] == pytest.approx(1.0 / s, rel=1e-6)
        ym = np.round(truth.marker[i, 0, ::-1]).astype(int)
        assert img[ym[0], ym[1]] == pytest.approx(1.0, rel=1e-6)


def test_interference_runs_share_their_draws_across_sir_and_markers():
    """Common random numbers: the same trials at every SIR; rotating and static share the motion."""
    from tvtrack.papers.p003_rotating_marker_tracker.scene import interference_runs

    sc = Scenario(duration_s=0.3, n_interferers=1)
    runs = interference_runs(np.random.default_rng(3), 4, sc, [1e9, 1e9, 0.5])
    np.testing.assert_array_equal(runs["miss"][:4], runs["miss"][4:8])  # same SIR, same draws: identical
    assert not np.array_equal(runs["miss"][:4], runs["miss"][8:])  # the SIR does act
    np.testing.assert_array_equal(runs["interferers"][:4], runs["interferers"][8:])
    np.testing.assert_array_equal(runs["trial"], np.tile(np.arange(4), 3))
    rot = run_scenario(np.random.default_rng(3), 4, sc, 2.0)[0]
    sta = run_scenario(np.random.default_rng(3), 4, Scenario(duration_s=0.3, n_interferers=1, rotating=False), 2.0)[0]
    np.testing.assert_array_equal(rot.xr, sta.xr)
    q = run_scenario(np.random.default_rng(3), 4, sc, 2.0)[1].interferers
    np.testing.assert_allclose(np.hypot(*(q[:, 0] - rot.center[:, 0]).T), sc.radius)  # around the object


def test_seed_reproduces_and_interferers_sit_on_circle():
    sc = Scenario(duration_s=0.2, n_interferers=1)
    a = run_scenario(np.random.default_rng(5), 3, sc, 2.0)[2].miss
    b = run_scenario(np.random.default_rng(5), 3, sc, 2.0)[2].miss
    np.testing.assert_array_equal(a, b)
    q = place_interferers(np.random.default_rng(0), 4, 5, (100.0, 90.0), 12.0)
    np.testing.assert_allclose(np.hypot(q[..., 0] - 100, q[..., 1] - 90), 12.0)
    ang = np.sort(np.mod(np.arctan2(q[0, :, 1] - 90, q[0, :, 0] - 100), 2 * np.pi))
    np.testing.assert_allclose(np.diff(ang), 2 * np.pi / 5)


def test_render_spot_brightness_per_covered_pixel_and_background_correlation():
    for spot in ("disc", "square"):
        img = render_spot(spot, np.array([10.3, 9.8]), (24, 24), D, 2.5)
        assert img.max() == pytest.approx(2.5, rel=1e-12)
    f = correlated_background(np.random.default_rng(6), 4, (128, 128), 8.0, 2.0)
    assert f.std() == pytest.approx(2.0, rel=0.05)
    rho = np.mean(f[:, :, :-8] * f[:, :, 8:]) / f.var()  # at tau = l_c: exp(-1)
    assert rho == pytest.approx(np.exp(-1), abs=0.08)


def test_two_emitter_1d_tracker_follows_and_integral_slope_is_2_sum_c2():
    n, L, beta, a = 3, 256, 12.0, 4.0
    lam = np.array([120.3, 128.0, 131.7])
    line = lambda l: 2 * a * (0.7 * pixel_fractions_box(l - beta, a, L) + 0.4 * pixel_fractions_box(l + beta, a, L))
    # a displacement of 1 px moves each box by 1 px inside its gate: 2 (c1^2 + c2^2) per px
    e = two_emitter_discriminator(
        line(lam + 1.0), 0, lam + 0.0, beta=beta, a=a, c1=0.7, c2=0.4, form="integral", half_gate=12.0
    )
    np.testing.assert_allclose(e, 2 * (0.7**2 + 0.4**2) * 1.0, rtol=0.05)
    e_edge = two_emitter_discriminator(line(lam + 1.0), 0, lam, beta=beta, a=a, c1=0.7, c2=0.4, form="edge")
    assert np.all(e_edge > 0)  # corrected (6) pulls toward truth
    rng = np.random.default_rng(7)
    T, dt = 1500, 0.002
    truth = 128 + 10 * np.sin(2 * np.pi * 0.5 * np.arange(T) * dt) * np.ones((n, 1))
    est = simulate_two_emitter_1d(
        rng,
        truth,
        dt=dt,
        beta=beta,
        a=a,
        f_c=8.0,
        noise_std=0.02,
        form="integral",
        bandwidth=5.0,
        unit_slope=2.0,
        half_gate=12.0,
        lam0=truth[:, 0] + 3,
    )
    assert np.sqrt(np.mean((est[:, 500:] - truth[:, 500:]) ** 2)) < 1.0


def test_bad_inputs_raise_value_errors_naming_the_parameter():
    with pytest.raises(ValueError, match="spot"):
        render_spot("star", np.zeros(2), (4, 4), 2.0)
    with pytest.raises(ValueError, match="kappa"):
        RotatingMarkerScene.static_residual(
            np.random.default_rng(0),
            1,
            (8, 8),
            kappa=2.0,
            background_std=1,
            corr_length=2,
            interferers=np.zeros((1, 0, 2)),
            interferer_brightness=1,
            spot="disc",
            diameter=2,
        )
    with pytest.raises(ValueError, match="b_xy"):
        loop_gains(b_xy=0.0)
    with pytest.raises(ValueError, match="variant"):
        RotatingGateTracker(np.zeros((1, 5)), loop_gains(), 1.0, variant="Q")


def test_rotation_synchronous_error_component():
    """Errors of the wide coordinate loops carry a component at the rotation rate (Fig. 1 text)."""
    rng = np.random.default_rng(8)
    sc = Scenario(duration_s=3.0, x_std=0.0, y_amplitude=0.0)
    truth, scene, h = run_scenario(rng, 6, sc)
    err = h.estimate[:, 500:, 0] - truth.xr[:, 500:]
    f, p = signal.welch(err, fs=sc.fps, nperseg=500, axis=-1)
    p = p.mean(axis=0)
    band = (f > 7) & (f < 9)
    assert p[band].max() > 3 * np.median(p[(f > 2) & (f < 30)])


def test_ekf_step_matches_filterpy():
    from filterpy.kalman import ExtendedKalmanFilter

    from tvtrack.papers.p003_rotating_marker_tracker.ekf import EKFTracker

    x0 = np.array([[100.0, 90.0, 12.0, 0.7, 50.0]])
    P0 = np.diag([4.0, 3.0, 2.0, 0.05, 1.0])
    q, mv, S, dt = np.array([0.1, 0.1, 0.01, 0.0, 0.5]), 0.05, 16.0, 0.002
    ekf = EKFTracker(x0, P0, q, mv, S)
    dx, dy = np.array([8.0]), np.array([-5.0])
    ekf.update(dx, dy, dt)
    ref = ExtendedKalmanFilter(dim_x=5, dim_z=2)
    ref.x, ref.P, ref.R = x0[0].copy(), P0.copy(), mv * np.eye(2)
    th, r = x0[0, 3], x0[0, 2]
    H = np.array([[1, 0, np.cos(th), -r * np.sin(th), 0], [0, 1, np.sin(th), r * np.cos(th), 0]])
    ref.update(np.array([8.0, -5.0]) / S, HJacobian=lambda x: H, Hx=lambda x: np.zeros(2))
    ref.F = np.eye(5)
    ref.F[3, 4] = dt
    ref.Q = np.diag(q * dt)
    ref.predict()
    np.testing.assert_allclose(ekf.state[0], ref.x, rtol=1e-10)
    np.testing.assert_allclose(ekf.P[0], ref.P, rtol=1e-8, atol=1e-12)


def test_state_errors_wrap_the_phase():
    from types import SimpleNamespace
    from tvtrack.papers.p003_rotating_marker_tracker.scene import state_errors

    z = np.zeros((1, 2))
    truth = SimpleNamespace(xr=z + 1, yr=z, r=z + 12, theta=np.array([[3.1, -3.1]]), omega=z + 50)
    est = np.stack([z + 1.5, z - 2, z + 11, np.array([[-3.1, 3.1]]), z + 51], axis=-1)
    e = state_errors(truth, SimpleNamespace(estimate=est))
    np.testing.assert_allclose(e[0, :, [0, 1, 2, 4]].T, [[0.5, -2, -1, 1]] * 2)
    np.testing.assert_allclose(e[0, :, 3], [2 * np.pi - 6.2, 6.2 - 2 * np.pi], atol=1e-12)


def test_slope_helpers_match_the_predicted_slopes():
    from tvtrack.papers.p003_rotating_marker_tracker.discriminators import quadrant_slope_fit, two_emitter_slope

    sq = quadrant_slope_fit(_renderer("square"), D, A)
    assert sq["slope_at_zero"] == pytest.approx(2 * D, rel=1e-9)  # pixel edges soften only the ends of +-D/2
    assert sq["fit_slope_halfD"] == pytest.approx(2 * D, rel=0.03) and sq["max_dev_from_line"] < 0.03
    assert quadrant_slope_fit(_renderer("disc"), D, A)["slope_at_zero"] == pytest.approx(2 * D, rel=0.05)
    # integral form: a box of unit brightness moving by one px shifts 2 units across the gate centre
    assert two_emitter_slope(beta=12.0, a=4.0, form="integral", half_gate=12.0) == pytest.approx(2.0, rel=0.05)


def test_phase_locked_amplitude_recovers_a_tone_in_noise_and_ignores_other_frequencies():
    from tvtrack.papers.p003_rotating_marker_tracker.loops import phase_locked_amplitude

    rng = np.random.default_rng(14)
    t = np.arange(5000) / 500.0
    theta = 2 * np.pi * 8 * t + rng.uniform(0, 2 * np.pi, (50, 1))
    err = 0.3 * np.cos(theta - 0.7) + 2.0 + rng.standard_normal((50, t.size))
    a = phase_locked_amplitude(err, theta)
    assert a.mean() == pytest.approx(0.3, abs=0.03)
    control = phase_locked_amplitude(err, 2 * np.pi * 12 * t)  # noise only: a, b ~ N(0, 2/T), Rayleigh mean sqrt(pi/T)
    assert control.mean() == pytest.approx(np.sqrt(np.pi / t.size), rel=0.2)


def test_seeds_batched_together_give_the_same_runs_as_alone():
    from tvtrack.papers.p003_rotating_marker_tracker.scene import interference_runs

    sc = Scenario(duration_s=0.3, n_interferers=5, decoy_offset=16.0)
    g = lambda s: np.random.default_rng([7, s])
    both = interference_runs([g(1), g(2)], 3, sc, [0.7, 2.0])
    for b, s in enumerate((1, 2)):
        alone = interference_runs(g(s), 3, sc, [0.7, 2.0])
        np.testing.assert_array_equal(both["miss"][both["block"] == b], alone["miss"])
        np.testing.assert_array_equal(both["interferers"][both["block"] == b], alone["interferers"])


def test_loss_mechanisms_are_told_apart_on_constructed_histories():
    T, w, radius = 100, 10, 4.0
    q = np.array([[[30.0, 0.0], [-30.0, 0.0], [0.0, 30.0]]] * 5)  # three interferers, five runs
    gate = np.zeros((5, T, 2))
    omega_err = np.zeros((5, T))
    loss = np.array([60, 60, 60, 60, -1])
    gate[0, 50:] = q[0, 0] + 1.0  # sits on one interferer
    gate[1, 50:55] = q[1, 0]  # passed from one to another
    gate[1, 55:60] = q[1, 1]
    omega_err[2, 45:] = 0.5  # rotation lost, no interferer near
    gate[3, 50:] = [10.0, 10.0]  # slid off, rotation held
    miss = np.full((5, T), 20.0)  # off the marker in every window
    met = loss_criteria(loss, gate, q, miss, omega_err, w, radius)
    assert [[c for c, m in zip(CRITERIA, row) if m] for row in met] == [
        ["capture"],
        ["drift among several"],
        ["frequency"],
        [],
        [],
    ]
    # a static marker (omega error NaN) is never a frequency loss
    nan_err = np.full((5, T), np.nan)
    assert not loss_criteria(loss, gate, q, miss, nan_err, w, radius)[2].any()
    # a gate still on a marker that passes over two interferers is not "among several"
    on_marker = miss.copy()
    on_marker[1] = 0.5
    assert not loss_criteria(loss, gate, q, on_marker, omega_err, w, radius)[1].any()


def _phase_response_simulated(freqs, r, gains, a=0.02, T=6000, dt=0.002, w=2 * np.pi * 8):
    """|theta_hat| response at each frequency of a sinusoidal true-phase perturbation, with a linear
    discriminator (Delta = S (marker - gate)) driving the tracker's own update (batched over freqs)."""
    from tvtrack.papers.p003_rotating_marker_tracker.loops import RotatingGateTracker

    f = np.asarray(freqs, float)
    n, S = f.size, 16.0
    x0 = np.tile([128.0, 128.0, r, 0.0, w], (n, 1))
    trk = RotatingGateTracker(x0, gains, S)
    t = np.arange(T) * dt
    p = a * np.sin(2 * np.pi * f[:, None] * t)
    th_true = w * t + p
    th_hat = np.empty((n, T))
    for k in range(T):
        g = trk.gate_center()
        m = 128.0 + r * np.stack([np.cos(th_true[:, k]), np.sin(th_true[:, k])], axis=1)
        th_hat[:, k] = trk.state[:, 3]
        trk.update(S * (m[:, 0] - g[:, 0]), S * (m[:, 1] - g[:, 1]), dt)
    dev = th_hat - w * t  # estimate of p (plus a transient)
    k0 = T // 3
    z = np.mean(dev[:, k0:] * np.exp(-2j * np.pi * f[:, None] * t[k0:]), axis=1) * 2
    return np.abs(z) / a


@pytest.mark.parametrize("r", [6.0, 24.0])
def test_tracker_phase_response_matches_the_coupled_loop_analysis(r):
    # kills the mutation "phase-loop error not divided by the radius estimate": the simulated tracker's
    # phase response must equal the analytic coupled response, whose tangential loop is radius-free in px
    from tvtrack.papers.p003_rotating_marker_tracker.loops import phase_response

    g = loop_gains()
    freqs = [0.5, 1.5, 3.0, 6.0, 12.0]
    sim = _phase_response_simulated(freqs, r, g)
    ana = np.abs(phase_response(g, 2 * np.pi * 8, r, freqs))
    np.testing.assert_allclose(sim, ana, rtol=0.06, atol=0.01)


def test_coupled_phase_loop_realises_less_than_its_design_and_the_retuned_gains_realise_it():
    from tvtrack.papers.p003_rotating_marker_tracker.loops import (
        gains_realising,
        phase_response,
        realised_phase_bandwidth,
    )

    w = 2 * np.pi * 8
    # uncoupled (K_xy -> 0) the response is the type-2 PLL's closed form, -3 dB at the design 6 Hz
    g0 = loop_gains(b_xy=1e-9)
    f = np.array([1.0, 4.0, 6.0, 15.0])
    s = 2j * np.pi * f
    pll = (g0.k1 * s + g0.k2) / (s**2 + g0.k1 * s + g0.k2)
    np.testing.assert_allclose(phase_response(g0, w, 12.0, f), pll, rtol=1e-3, atol=1e-4)
    assert realised_phase_bandwidth(g0, w, 12.0)["bandwidth_hz"] == pytest.approx(6.0, abs=0.05)
    coupled = realised_phase_bandwidth(loop_gains(), w, 12.0)
    assert coupled["bandwidth_hz"] < 4.0 and coupled["peak_gain"] > 1.3
    g6 = gains_realising(10.0, 0.2, 6.0)
    assert realised_phase_bandwidth(g6, w, 12.0)["bandwidth_hz"] == pytest.approx(6.0, abs=0.05)
    sim = _phase_response_simulated([6.0], 12.0, g6)
    assert sim[0] == pytest.approx(1 / np.sqrt(2), abs=0.05)


def test_truth_phase_is_the_integral_of_a_varying_rotation_rate():
    # kills the mutation "truth phase by the omega(t) t approximation" (U3 belongs to the paper's
    # phase loop, never to the truth): theta = phi + int_0^t omega, closed form for the Fig. 2 modulation
    from tvtrack.papers.p003_rotating_marker_tracker.scene import scenario_truth

    sc = Scenario(duration_s=4.0, omega_mod=0.1, omega_mod_hz=0.5, x_std=0.0, y_amplitude=0.0)
    tr = scenario_truth(np.random.default_rng(0), 3, sc)
    w0, m, fm, t = sc.omega0, 0.1, 0.5, tr.t
    exact = tr.theta[:, :1] + w0 * (t + m / (2 * np.pi * fm) * (1 - np.cos(2 * np.pi * fm * t)))
    # the left Riemann sum of the frames differs from the integral by at most max|omega'| t dt / 2
    np.testing.assert_allclose(tr.theta, exact, atol=w0 * m * 2 * np.pi * fm * t[-1] / sc.fps / 2 + 1e-9)
    np.testing.assert_allclose(np.diff(tr.theta, axis=1) * sc.fps, tr.omega[:, :-1], rtol=1e-12)


@pytest.mark.parametrize("phase", [0.0, np.pi, np.pi / 2])
def test_decoy_rotates_at_its_phase_offset_from_the_marker(phase):
    # kills the mutation "the decoy phase ignored": decoy - (its circle's centre) = r e^{i(theta + phase)},
    # so decoy - marker - r (e^{i(theta + phase)} - e^{i theta}) is the constant offset vector of length decoy_offset
    sc = Scenario(duration_s=0.1, decoy_offset=16.0, decoy_phase=phase, x_std=0.0, y_amplitude=0.0)
    tr, scene, _ = run_scenario(np.random.default_rng(1), 2, sc, 2.0, keep_full=False)
    z_marker = (tr.marker[..., 0] - tr.xr) + 1j * (tr.marker[..., 1] - tr.yr)
    z = (scene.decoys[..., 0] - tr.marker[..., 0]) + 1j * (scene.decoys[..., 1] - tr.marker[..., 1])
    off = z - z_marker * (np.exp(1j * phase) - 1)
    np.testing.assert_allclose(np.abs(off), 16.0, atol=1e-6)
    np.testing.assert_allclose(off, off[:, :1] * np.ones_like(off), atol=1e-6)


def test_scenario_refuses_a_rotation_at_or_above_the_frame_rate_nyquist():
    with pytest.raises(ValueError, match="Nyquist"):
        Scenario(fps=500.0, rotation_hz=250.0)
    with pytest.raises(ValueError, match="Nyquist"):
        Scenario(fps=100.0, rotation_hz=60.0)
    Scenario(fps=500.0, rotation_hz=249.0)


def test_motion_kinds_share_the_rms_and_the_card_draws():
    from tvtrack.papers.p003_rotating_marker_tracker.scene import object_motion

    out = {
        k: object_motion(np.random.default_rng(4), 400, 5000, 0.002, kind=k) for k in ("card", "sinusoids", "random")
    }
    for k, (x, y) in out.items():
        assert np.sqrt(np.mean((x - 128) ** 2)) == pytest.approx(10.0, rel=0.15), k
        assert np.sqrt(np.mean((y - 128) ** 2)) == pytest.approx(20 / np.sqrt(2), rel=0.15), k
    np.testing.assert_array_equal(out["card"][0], out["random"][0])  # x: the same OU draws
    with pytest.raises(ValueError, match="motion"):
        Scenario(motion="zigzag")


def test_edge_slew_normalisation_matches_the_quadrant_saturation():
    from tvtrack.papers.p003_rotating_marker_tracker.discriminators import static_characteristic

    for spot in ("disc", "square"):
        sc = Scenario(spot=spot, form="edge", edge_norm="slew")
        q = Scenario(spot=spot)
        off = np.linspace(0, sc.gate_half, 49)
        e = static_characteristic(sc.spot_renderer(), off, form="edge", half=sc.gate_half, a=sc.diameter / 2)
        qq = static_characteristic(q.spot_renderer(), off, form="quadrant", half=q.gate_half)
        assert np.max(e) / sc.slope() == pytest.approx(np.max(qq) / q.slope(), rel=1e-9)
        assert sc.slope() < Scenario(spot=spot, form="edge").slope()


def test_per_trial_gains_batch_equals_separate_runs():
    from tvtrack.papers.p003_rotating_marker_tracker.loops import stack_gains

    sc = Scenario(duration_s=0.3)
    gs = [loop_gains(b_xy=b) for b in (5.0, 20.0)]
    _, _, hb = run_scenario(
        [np.random.default_rng(7), np.random.default_rng(7)], 4, sc, gains=stack_gains(gs, 2), n_common=2
    )
    for j, g in enumerate(gs):
        _, _, h = run_scenario(np.random.default_rng(7), 2, sc, gains=g)
        np.testing.assert_allclose(hb.estimate[2 * j : 2 * j + 2], h.estimate, rtol=1e-5, atol=1e-4)


def test_scene_blocks_in_one_batch_equal_separate_runs():
    from tvtrack.papers.p003_rotating_marker_tracker.scene import interference_runs

    sc = Scenario(duration_s=0.3)
    sirs = [1.0, 3.0]
    both = interference_runs(
        [np.random.default_rng(5), np.random.default_rng(5)],
        2,
        sc,
        sirs,
        blocks=[{"n_interferers": 1}, {"n_interferers": 5, "kappa": 0.2}],
    )
    for b, over in enumerate(({"n_interferers": 1}, {"n_interferers": 5, "kappa": 0.2})):
        alone = interference_runs(np.random.default_rng(5), 2, replace(sc, **over), sirs)
        sel = both["block"] == b
        np.testing.assert_allclose(both["miss"][sel], alone["miss"], rtol=1e-4, atol=1e-3)
        np.testing.assert_allclose(both["interferers"][sel][:, : over["n_interferers"]], alone["interferers"])


def test_loss_criteria_do_not_depend_on_an_order_and_capture_is_counted_once():
    T, w, radius = 100, 10, 4.0
    q = np.array([[[30.0, 0.0], [-30.0, 0.0]]] * 3)
    gate = np.zeros((3, T, 2))
    omega_err = np.zeros((3, T))
    loss = np.array([60, 60, -1])
    gate[0, 50:] = q[0, 0]  # sits on an interferer ...
    omega_err[0, 45:] = 0.5  # ... and has lost the rotation: both criteria
    gate[1, 50:] = q[1, 0]
    miss = np.full((3, T), 20.0)
    met = loss_criteria(loss, gate, q, miss, omega_err, w, radius)
    assert dict(zip(CRITERIA, met[0])) == {"capture": True, "drift among several": False, "frequency": True}
    assert met[1].tolist() == [True, False, False] and not met[2].any()
    # the order of the interferers changes nothing
    flipped = loss_criteria(loss, gate, q[:, ::-1], miss, omega_err, w, radius)
    np.testing.assert_array_equal(flipped, met)


def test_interferer_size_scales_its_flux_at_the_same_sir():
    from tvtrack.papers.p003_rotating_marker_tracker.scene import build_scene

    truth = marker_truth(
        np.full((1, 3), 128.0), np.full((1, 3), 128.0), np.full((1, 3), 12.0), np.full((1, 3), 50.0), np.zeros(1), 0.002
    )
    flux = {}
    for d in (None, 16.0):
        sc = build_scene(np.random.default_rng(2), truth, kappa=0.0, n_interferers=1, sir=2.0, interferer_diameter=d)
        flux[d] = sc._padded.sum()
    assert flux[None] == pytest.approx(np.pi * 16 / 2.0, rel=0.02)  # disc D = 8 at brightness 1/2
    assert flux[16.0] / flux[None] == pytest.approx(4.0, rel=0.03)


@pytest.mark.parametrize("spot", ["disc", "square"])
def test_centroid_discriminator_reads_the_offset_of_a_spot_inside_the_gate(spot):
    off = np.array([-3.0, -1.0, -0.25, 0.25, 1.0, 3.0])
    for axis in (0, 1):
        out = static_characteristic(_renderer(spot), off, form="centroid", half=A, axis=axis)
        np.testing.assert_allclose(out, off, atol=0.03)  # slope 1, pixel locking below 0.03 px


def test_static_marker_with_a_centroid_tracker_locks():
    # no background: the window's first moment reads the spot alone (a residual background biases a centroid)
    sc = Scenario(duration_s=2.0, rotating=False, form="centroid", x_std=0.0, y_amplitude=0.0, background_std=0.0)
    _, _, h = run_scenario(np.random.default_rng(0), 3, sc, noise="pixel")
    assert np.sqrt(np.mean(h.miss[:, -250:] ** 2)) < 0.2 and sc.slope() == 1.0


def test_the_objects_y_phase_is_drawn_per_run_so_interferers_are_not_always_crossed_at_full_speed():
    """With a fixed y phase every run starts (and has its interferers placed) where the sinusoid is
    steepest. Each run's phase, recovered from its path, must be spread uniformly over the circle."""
    from scipy import stats

    from tvtrack.papers.p003_rotating_marker_tracker.scene import scenario_truth

    sc = Scenario(duration_s=0.1)
    tr = scenario_truth(np.random.default_rng(40), 400, sc)
    c, w = sc.image_size / 2, 2 * np.pi * sc.y_freq
    t = tr.t[None, :]
    # least squares of y - c on sin(w t), cos(w t): amplitude cos(psi), sin(psi) times y_amplitude
    basis = np.stack([np.sin(w * t[0]), np.cos(w * t[0])], axis=1)
    coef = np.linalg.lstsq(basis, (tr.yr - c).T, rcond=None)[0]
    psi = np.mod(np.arctan2(coef[1], coef[0]), 2 * np.pi)
    np.testing.assert_allclose(np.hypot(*coef), sc.y_amplitude, rtol=1e-6)
    assert stats.kstest(psi / (2 * np.pi), "uniform").pvalue > 0.01
    # the start point's speed: a third of the runs start below half the full speed (|cos psi| < 1/2)
    slow = np.mean(np.abs(np.cos(psi)) < 0.5)
    assert 0.25 < slow < 0.42
    # the interferers are placed about each run's own start, which now moves along the path with the phase
    assert np.std(tr.center[:, 0, 1]) == pytest.approx(sc.y_amplitude / np.sqrt(2), rel=0.15)
    # a fixed phase is still available as an explicit choice (and reproduces its phase in every run)
    fixed = scenario_truth(np.random.default_rng(40), 5, replace(sc, y_phase=0.3))
    np.testing.assert_allclose(fixed.yr[:, 0], c + sc.y_amplitude * np.sin(0.3))


def test_omega_estimate_response_matches_the_simulated_tracker_and_the_uncoupled_pll():
    """C003-3's '6 Hz for omega' read on the rate estimate: |omega_hat / omega| of the coupled loop against the
    tracker simulated with a sinusoidal rate perturbation, and the PLL's K2 / (s^2 + K1 s + K2) when uncoupled."""
    from tvtrack.papers.p003_rotating_marker_tracker.loops import (
        RotatingGateTracker,
        gains_realising,
        omega_bandwidth,
        omega_response,
    )

    w, r, S, dt, T, a = 2 * np.pi * 8, 12.0, 16.0, 0.002, 6000, 0.02
    f = np.array([1.0, 3.0, 6.0])
    for g in (loop_gains(), gains_realising(10.0, 0.2, 6.0)):
        trk = RotatingGateTracker(np.tile([128.0, 128.0, r, 0.0, w], (f.size, 1)), g, S)
        t = np.arange(T) * dt
        th_true = w * t + a * np.sin(2 * np.pi * f[:, None] * t)
        om_hat = np.empty((f.size, T))
        for k in range(T):
            gc = trk.gate_center()
            m = 128.0 + r * np.stack([np.cos(th_true[:, k]), np.sin(th_true[:, k])], axis=1)
            om_hat[:, k] = trk.state[:, 4]
            trk.update(S * (m[:, 0] - gc[:, 0]), S * (m[:, 1] - gc[:, 1]), dt)
        k0 = T // 3
        z = 2 * np.mean((om_hat[:, k0:] - w) * np.exp(-2j * np.pi * f[:, None] * t[k0:]), axis=1)
        sim = np.abs(z) / (a * 2 * np.pi * f)  # the true rate's deviation has amplitude a 2 pi f
        np.testing.assert_allclose(sim, np.abs(omega_response(g, w, r, f)), rtol=0.06, atol=0.01)
    # uncoupled: the type-2 PLL's rate response
    g0 = loop_gains(b_xy=1e-9)
    s = 2j * np.pi * f
    np.testing.assert_allclose(omega_response(g0, w, r, f), g0.k2 / (s**2 + g0.k1 * s + g0.k2), rtol=1e-6)
    # the designed loop passes far less of a 6 Hz rate change than the retuned one (~0.09 and ~0.46)
    d, q = omega_bandwidth(loop_gains(), w, r), omega_bandwidth(gains_realising(10.0, 0.2, 6.0), w, r)
    assert 0.06 < d["gain_at"] < 0.11 and 0.38 < q["gain_at"] < 0.5
    assert d["bandwidth_hz"] < q["bandwidth_hz"] < 6.0
