"""Tests of paper 003's cost cuts (issue 43): each faster path gives the same numbers, bit for bit, as the plain one."""

import numpy as np
import pytest

from tvtrack.papers.p003_rotating_marker_tracker.imaging import RotatingMarkerScene


@pytest.mark.parametrize("spot", ["disc", "square"])
def test_spots_rendered_box_by_box_equal_the_whole_crop_render_bit_for_bit(spot):
    rng = np.random.default_rng(4)
    n, size = 200, 26
    scene = RotatingMarkerScene.__new__(RotatingMarkerScene)  # only the spot settings are read
    scene.spot, scene.diameter = spot, 8.0
    crops = rng.normal(size=(n, size, size)).astype(np.float32)
    origin = rng.integers(-50, 50, (n, 2))
    centres = origin + rng.uniform(-12.0, size + 12.0, (n, 2))  # inside, across the edges and outside the crop
    centres[:20] = np.round(centres[:20]) + 0.5 * rng.integers(0, 2, (20, 2))  # on pixel centres and edges
    bright = rng.uniform(0.5, 2.0, n)
    whole = crops + scene._spot(centres, size, origin, bright)
    for threshold in (10**9, 0):  # whole crop, then box by box
        scene.BOX_MIN_PIXELS = {spot: threshold}
        got = crops.copy()
        scene._add_spot(got, centres, origin, bright)
        assert np.array_equal(got, whole), (threshold, np.abs(got - whole).max())
    inside = crops.copy()  # every box inside its crop: the unmasked path
    c_in = origin + rng.uniform(6.0, size - 7.0, (n, 2))
    scene._add_spot(inside, c_in, origin, bright)
    assert np.array_equal(inside, crops + scene._spot(c_in, size, origin, bright))
