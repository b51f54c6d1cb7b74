"""Notebook 004: energy centres of rendered spots (exactness, pixel boundaries) and the gate tracker."""

import numpy as np
import pytest

from tvtrack.measure import centroid
from tvtrack.render import gaussian_spot, gate_origin
from tvtrack.scenes.beam_wander import SpotCamera, track_spot


@pytest.mark.parametrize("cx, cy", [(31.0, 31.0), (20.37, 41.81), (33.5, 28.5), (30.5, 30.0)])
def test_noiseless_symmetric_spot_centroid_exact(cx, cy):
    """A pixel-integrated Gaussian (sigma >= 1 px) far from the edges: centroid exact to 1e-6 px."""
    img = gaussian_spot([cx, cy], (64, 64), 2.0, 1e4)
    c = centroid(img, background=None)
    np.testing.assert_allclose(c.xy, [cx, cy], atol=1e-6)


@pytest.mark.parametrize("cx", [10.5, 11.0, 11.5])
def test_threshold_keeps_symmetric_spot_exact_on_pixel_centres_and_boundaries(cx):
    """Centres on a pixel centre or on a pixel boundary keep the thresholded mask symmetric."""
    img = 5.0 + gaussian_spot([cx, 12.5], (25, 24), 3.0, 2e4)
    c = centroid(img, background=5.0, threshold=2.0)
    np.testing.assert_allclose(c.xy, [cx, 12.5], atol=1e-9)


def test_gate_origin_on_a_boundary_contains_the_spot_symmetrically():
    o = gate_origin(np.array([10.5, 10.5]), (6, 6))  # even gate: centre between the middle pixels
    np.testing.assert_array_equal(o, [8, 8])
    img = gaussian_spot([10.5, 10.5], (6, 6), 1.0, 1.0, origin=o)
    np.testing.assert_allclose(img, img[::-1, ::-1], atol=1e-15)
    np.testing.assert_allclose(centroid(img, o, background=None).xy, [10.5, 10.5], atol=1e-12)


def test_track_spot_noiseless_limit_and_frame_edge():
    """No read noise, huge flux: the tracker follows the truth; a spot near the edge keeps its gate inside."""
    T = 30
    x = np.linspace(64.0, 6.0, T)  # runs towards the left edge
    truth = np.stack([x, 64 + 3 * np.sin(np.arange(T) / 4)], axis=-1)[None]
    cam = SpotCamera(spot_sigma_px=2.0, peak_dn=60000.0, background_dn=0.0, read_noise_dn=0.0,
                     gain_e_per_dn=1.0, bit_depth=16, gate_size_px=15, threshold_sigma=0.0)
    res = track_spot(truth, np.ones((1, T)), np.random.default_rng(0), cam, 128, keep=(0,))
    assert np.all(res.origin >= 0) and np.all(res.origin <= 128 - 15)
    err = res.xy[0, :-3] - truth[0, :-3]  # the last frames lose part of the spot to the edge
    assert np.sqrt(np.mean(err ** 2)) < 0.02
    assert res.gates.shape == (T, 15, 15)


def test_track_spot_is_reproducible_by_seed():
    truth = np.full((2, 5, 2), 40.0)
    a = track_spot(truth, np.ones((2, 5)), np.random.default_rng(3)).xy
    b = track_spot(truth, np.ones((2, 5)), np.random.default_rng(3)).xy
    np.testing.assert_array_equal(a, b)


def test_camera_rejects_bad_parameters():
    with pytest.raises(ValueError, match="gate_size_px"):
        SpotCamera(gate_size_px=30)
    with pytest.raises(ValueError, match="peak_dn"):
        SpotCamera(peak_dn=0.0)
