"""The faster scene rendering of study 004 gives the same numbers bit for bit: each optimised function against the
straightforward form it replaced (kept here as the reference), on small scenes."""

import numpy as np
import pytest

from tvtrack.measure import border_statistics, centroid
from tvtrack.render import gate_origin, gaussian_spot, sensor_readout
from tvtrack.papers.p004_laser_spot_prediction.camera import SpotCamera, track_spot
from tvtrack.papers.p004_laser_spot_prediction.spot_centre import soft_window, windowed_centroid


def reference_border_statistics(images):
    a = np.asarray(images, dtype=float)
    border = np.concatenate([a[..., 0, :], a[..., -1, :], a[..., 1:-1, 0], a[..., 1:-1, -1]], axis=-1)
    med = np.median(border, axis=-1)
    return med, 1.4826 * np.median(np.abs(border - med[..., None]), axis=-1)


def reference_windowed_centroid(images, origin=(0, 0), *, window_px, threshold_sigma=3.0, n_iter=4, start=None):
    a = np.asarray(images, dtype=float)
    rows, cols = a.shape[-2:]
    level, rms = reference_border_statistics(a)
    w = a - level[..., None, None]
    w = np.where(w > (threshold_sigma * rms)[..., None, None], w, 0.0)
    batch = a.shape[:-2]
    cx = np.full(batch, (cols - 1) / 2.0)
    cy = np.full(batch, (rows - 1) / 2.0)
    if start is not None:
        st = np.asarray(start, dtype=float) - np.asarray(origin, dtype=float)
        cx, cy = np.broadcast_to(st[..., 0], batch).copy(), np.broadcast_to(st[..., 1], batch).copy()
    half = window_px / 2.0
    xs, ys = np.arange(cols, dtype=float), np.arange(rows, dtype=float)
    for _ in range(n_iter + 1):
        wx, wy = soft_window(cx, half, cols), soft_window(cy, half, rows)
        col_sum = (wy[..., None, :] @ w)[..., 0, :]
        row_sum = (w @ wx[..., :, None])[..., 0]
        mass = np.einsum("...c,...c->...", col_sum, wx)
        valid = mass > 0
        safe = np.where(valid, mass, 1.0)
        cx = np.where(valid, np.einsum("...c,c->...", col_sum * wx, xs) / safe, cx)
        cy = np.where(valid, np.einsum("...r,r->...", row_sum * wy, ys) / safe, cy)
    o = np.asarray(origin, dtype=float)
    xy = np.stack([cx + o[..., 0], cy + o[..., 1]], axis=-1)
    return np.where(valid[..., None], xy, np.nan), mass, valid


def reference_sensor_readout(signal, rng, *, background, read_noise, gain, bit_depth):
    electrons = np.asarray(signal, dtype=float) + background
    electrons = rng.poisson(electrons).astype(float)
    if read_noise > 0:
        electrons = electrons + rng.normal(0.0, read_noise, size=electrons.shape)
    return np.clip(np.rint(electrons / gain), 0, 2**bit_depth - 1)


def reference_track_spot(c, inten, rng, camera, image_size_px):
    """The frame loop as it was: render, read out, measure, move the gate."""
    g = camera.gate_size_px
    xy = np.full(c.shape, np.nan)
    clipped = np.zeros(c.shape[:-1], dtype=bool)
    aim = c[..., 0, :]
    for t in range(c.shape[-2]):
        o = np.clip(gate_origin(aim, (g, g)), 0, image_size_px - g)
        signal = gaussian_spot(c[..., t, :], (g, g), camera.spot_sigma_px, camera.flux_e * inten[..., t], origin=o)
        img = reference_sensor_readout(
            signal,
            rng,
            background=camera.background_dn * camera.gain_e_per_dn,
            read_noise=camera.read_noise_dn * camera.gain_e_per_dn,
            gain=camera.gain_e_per_dn,
            bit_depth=camera.bit_depth,
        )
        if camera.centroid_mode == "windowed":
            m_xy, _, valid = reference_windowed_centroid(
                img, o, window_px=camera.window_px, threshold_sigma=camera.threshold_sigma
            )
        else:
            m = centroid(img, o, background="border", threshold_sigma=camera.threshold_sigma)
            m_xy, valid = m.xy, m.valid
        xy[..., t, :] = m_xy
        clipped[..., t] = np.any(img >= 2**camera.bit_depth - 1, axis=(-2, -1))
        aim = np.where(valid[..., None], m_xy, aim)
    return xy, clipped


def _noisy_gates(shape, seed, read_noise=2.0):
    """Gates holding a spot somewhere inside (and one holding none), read out as the camera does."""
    rng = np.random.default_rng(seed)
    rows, cols = shape[-2:]
    c = np.stack([rng.uniform(2, cols - 3, shape[:-2]), rng.uniform(2, rows - 3, shape[:-2])], axis=-1)
    flux = np.where(rng.uniform(size=shape[:-2]) < 0.1, 0.0, 2e4)  # some gates hold no spot
    sig = gaussian_spot(c, (rows, cols), 3.0, flux)
    return sensor_readout(sig, rng, background=10.0, read_noise=read_noise, bit_depth=8)


@pytest.mark.parametrize("shape", [(3, 15, 31, 31), (31, 31), (4, 9, 12), (2, 1, 5), (6, 4, 3)])
def test_border_statistics_matches_numpy_median(shape):
    rng = np.random.default_rng(5)
    for a in (np.rint(rng.normal(10, 3, shape)), rng.normal(10, 3, shape)):
        for got, want in zip(border_statistics(a), reference_border_statistics(a)):
            np.testing.assert_array_equal(got, want)
    a = rng.normal(10, 3, shape)
    a[(0,) * (a.ndim - 1)] = np.nan  # a NaN on the border: NumPy's median, NaN
    for got, want in zip(border_statistics(a), reference_border_statistics(a)):
        np.testing.assert_array_equal(got, want)


@pytest.mark.parametrize("read_noise", [2.0, 64.0])
@pytest.mark.parametrize("shape", [(2, 15, 31, 31), (40, 23, 17), (31, 31)])
def test_windowed_centroid_matches_the_reference_bit_for_bit(shape, read_noise):
    img = _noisy_gates(shape, 3, read_noise)
    batch = shape[:-2]
    origin = np.random.default_rng(4).integers(0, 90, batch + (2,))
    side = min(shape[-2:])
    for kw in (dict(window_px=side * 2 / 3), dict(window_px=12.5, n_iter=0), dict(window_px=side, threshold_sigma=0.0)):
        got = windowed_centroid(img, origin, **kw)
        want_xy, want_mass, want_valid = reference_windowed_centroid(img, origin, **kw)
        np.testing.assert_array_equal(got.xy, want_xy)
        np.testing.assert_array_equal(got.mass, want_mass)
        np.testing.assert_array_equal(got.valid, want_valid)
    start = origin + np.array([shape[-1] / 2 + 1.3, shape[-2] / 2 - 2.2])
    got = windowed_centroid(img, origin, window_px=11.0, start=start)
    np.testing.assert_array_equal(got.xy, reference_windowed_centroid(img, origin, window_px=11.0, start=start)[0])


def test_windowed_centroid_of_a_flat_gate_is_invalid_as_before():
    img = np.full((2, 31, 31), 10.0)
    img[1, 12:18, 9:14] += 50.0
    got = windowed_centroid(img, (0, 0), window_px=21.0)
    want_xy, _, want_valid = reference_windowed_centroid(img, (0, 0), window_px=21.0)
    np.testing.assert_array_equal(got.xy, want_xy)
    np.testing.assert_array_equal(got.valid, [False, True])


@pytest.mark.parametrize(
    "camera",
    [
        SpotCamera(centroid_window_px=21.0),
        SpotCamera(centroid_window_px=21.0, read_noise_dn=64.0, bit_depth=16),
        SpotCamera(centroid_mode="gate", read_noise_dn=16.0),
        SpotCamera(centroid_window_px=21.0, spot_sigma_px=0.6),
    ],
)
def test_track_spot_matches_the_reference_frame_loop_bit_for_bit(camera):
    """A small scene (3 paths, 150 frames, a spot near the frame edge): the same centres, clipping and draws."""
    rng = np.random.default_rng(8)
    T = 150
    t = np.arange(T)
    phase = np.arange(3)[:, None]
    c = np.stack([20 + 15 * np.sin(t / 20.0 + phase), 100 + 25 * np.cos(t / 30.0 + 0 * phase)], axis=-1)
    c = c[None] + rng.normal(0, 0.3, (1, 3, T, 2))
    inten = np.exp(rng.normal(0, 0.3, (1, 3, T)))
    trk = track_spot(c, inten, np.random.default_rng(9), camera, 128)
    want_xy, want_clipped = reference_track_spot(c, inten, np.random.default_rng(9), camera, 128)
    np.testing.assert_array_equal(trk.xy, want_xy)
    np.testing.assert_array_equal(trk.clipped, want_clipped)


def test_the_flat_adam_step_trains_the_paper_size_network_as_scikit_learn(monkeypatch):
    """The networks' Adam step on one flat buffer (``learned._FlatAdam``), at the study's 16 hidden units and 16 lags:
    the loss curve, every epoch's validation score and the weights kept are scikit-learn's ``MLPRegressor``'s."""
    from sklearn.neural_network import MLPRegressor

    from tvtrack.papers.p004_laser_spot_prediction import learned

    z = np.cumsum(np.random.default_rng(6).standard_normal((3, 2, 400)), axis=-1) * 0.3
    kw = dict(seed=2, hidden_units=16, max_samples=800)
    fast = learned.fit_learned_predictor("mlp", z, 16, **kw)[-1]
    monkeypatch.setattr(learned, "_mlp_regressor", lambda: MLPRegressor)
    stock = learned.fit_learned_predictor("mlp", z, 16, **kw)[-1]
    assert type(stock) is MLPRegressor and type(fast) is not MLPRegressor
    assert fast.n_iter_ == stock.n_iter_ > 10
    assert fast.loss_curve_ == stock.loss_curve_ and fast.validation_scores_ == stock.validation_scores_
    for u, v in zip(fast.coefs_ + fast.intercepts_, stock.coefs_ + stock.intercepts_):
        np.testing.assert_array_equal(u, v)
