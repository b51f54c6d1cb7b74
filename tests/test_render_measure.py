import numpy as np
import pytest
from scipy import integrate, stats

from tvtrack.measure import centroid, crop
from tvtrack.montecarlo import make_rng
from tvtrack.render import (
    box_spot,
    disc_area,
    disc_spot,
    gate_origin,
    gaussian_spot,
    pixel_fractions_gaussian,
    sensor_readout,
)


def test_pixel_fractions_equal_numerical_integrals():
    f = pixel_fractions_gaussian(2.3, 0.8, 6, origin=0)
    expect = [integrate.quad(stats.norm(2.3, 0.8).pdf, u - 0.5, u + 0.5)[0] for u in range(6)]
    assert np.allclose(f, expect, atol=1e-12)


def test_spot_mass_is_flux_times_in_window_fraction():
    img = gaussian_spot([[5.0, 4.0]], (9, 11), 1.2, flux=1000.0)
    inside = (stats.norm.cdf(10.5, 5, 1.2) - stats.norm.cdf(-0.5, 5, 1.2)) * (
        stats.norm.cdf(8.5, 4, 1.2) - stats.norm.cdf(-0.5, 4, 1.2)
    )
    assert img.sum() == pytest.approx(1000.0 * inside, rel=1e-12)


@pytest.mark.parametrize("center", [(7.0, 7.0), (7.5, 6.5), (7.25, 7.8)])
def test_noiseless_gaussian_centroid_is_exact(center):
    # a smooth spot (sigma = 1.5 px) well inside the window: pixel integration leaves the centre
    # unbiased to ~exp(-2 pi^2 sigma^2), far below 1e-6 px, at any sub-pixel position
    c = centroid(gaussian_spot(center, (15, 15), 1.5, 100.0), background=None)
    assert np.allclose(c.xy, center, atol=1e-6)


def test_box_spot_centroid_exact_on_symmetric_positions_and_biased_between():
    for center in [(7.0, 7.0), (7.5, 6.5)]:  # on a pixel centre or edge: symmetric pixel masses
        assert np.allclose(centroid(box_spot(center, (15, 15), 2.3, 1.0), background=None).xy, center, atol=1e-12)
    # between them the sharp-edged box shows the pixel-phase bias of a sampled centroid
    bias = centroid(box_spot((7.25, 7.0), (15, 15), 2.3, 1.0), background=None).xy[0] - 7.25
    assert 1e-3 < abs(bias) < 0.1


@pytest.mark.parametrize("diameter, tolerance", [(4.0, 0.05), (6.5, 0.05), (8.0, 0.01), (16.0, 0.01)])
def test_disc_spot_conserves_flux_within_stated_tolerance(diameter, tolerance):
    # any sub-pixel position, disc wholly inside the window: 5 % for D >= 4 px, 1 % for D >= 8 px
    rng = make_rng(1)
    centers = 20.0 + rng.uniform(-0.5, 0.5, (200, 2))
    img = disc_spot(centers, (41, 41), diameter, flux=250.0)
    assert np.all(np.abs(img.sum(axis=(-2, -1)) / 250.0 - 1) < tolerance)
    # a fully covered pixel reads flux / (pi R^2); the float32 path agrees with float64
    assert img[0].max() == pytest.approx(250.0 / disc_area(diameter), rel=1e-12)
    img32 = disc_spot(centers, (41, 41), diameter, flux=250.0, dtype=np.float32)
    assert img32.dtype == np.float32 and np.allclose(img32, img, atol=1e-4)


@pytest.mark.parametrize("center", [(7.0, 7.0), (7.5, 6.5), (7.5, 7.5)])
def test_centred_disc_spot_centroid_is_exact(center):
    # centred on a pixel centre, edge or corner the coverage is mirror-symmetric: centroid exact
    c = centroid(disc_spot(center, (15, 15), 8.0, 100.0), background=None)
    assert np.allclose(c.xy, center, atol=1e-12)
    with pytest.raises(ValueError, match="diameter"):
        disc_spot(center, (15, 15), 0.0)


def test_gate_crop_renders_the_same_pixels_as_the_full_frame():
    centers = np.array([[[20.3, 11.7], [3.0, 4.2]]])
    full = gaussian_spot(centers, (32, 40), 2.0, 500.0)
    size = (9, 7)
    origin = gate_origin(centers, size)
    origin = np.stack([np.clip(origin[..., 0], 0, 40 - 7), np.clip(origin[..., 1], 0, 32 - 9)], -1)
    direct = gaussian_spot(centers, size, 2.0, 500.0, origin=origin)
    assert np.allclose(crop(full, origin, size), direct)


def test_gate_origin_centres_the_gate():
    assert gate_origin([10.4, 3.6], (5, 5)).tolist() == [8, 2]
    assert gate_origin([10.5, 3.0], (4, 4)).tolist() == [9, 2]  # even size: centre within the middle two pixels


def test_crop_stays_inside_the_frame():
    img = np.arange(100.0).reshape(10, 10)
    out = crop(img, [-3, 8], (4, 4))
    assert out.shape == (4, 4) and out[0, 0] == img[6, 0]


def test_centroid_threshold_and_empty_gate():
    img = np.zeros((2, 9, 9))
    img[0, 4, 6] = 10.0
    c = centroid(img, origin=[[1, 2], [1, 2]], background=0.0, threshold=1.0)
    assert np.allclose(c.xy[0], [7.0, 6.0])
    assert not c.valid[1] and np.isnan(c.xy[1]).all()


def test_sensor_readout_statistics_and_saturation():
    rng = make_rng(0)
    out = sensor_readout(np.full((200, 200), 50.0), rng, background=10.0, read_noise=3.0, gain=2.0)
    assert out.mean() == pytest.approx(30.0, abs=0.05)
    assert out.var() == pytest.approx((60.0 + 9.0) / 4.0, rel=0.03)
    sat = sensor_readout(np.full((4, 4), 1e6), rng, bit_depth=8)
    assert sat.max() == 255 and np.all(sat == np.rint(sat))
    with pytest.raises(ValueError, match="read_noise"):
        sensor_readout(np.ones(3), rng, read_noise=-1)
