"""Paper 003's compiled frame-loop steps (``._frame_kernels``) against their NumPy twins: the same gate crops and
quadrant weights, bit for bit, and the same closed-loop histories."""

from dataclasses import replace

import numpy as np
import pytest

from tvtrack import jit
from tvtrack.papers.p003_rotating_marker_tracker import discriminators, imaging
from tvtrack.papers.p003_rotating_marker_tracker.lockstep import run_together
from tvtrack.papers.p003_rotating_marker_tracker.scene import Scenario, prepare_interference

pytestmark = pytest.mark.skipif(not jit.enabled(), reason="numba switched off: only the NumPy path runs")


def _numpy_path(monkeypatch):
    monkeypatch.setattr(imaging.jit, "enabled", lambda: False)  # the one switch both modules read
    assert discriminators.jit is imaging.jit


def _scene(exposure: str):
    sc = Scenario(duration_s=0.2, fps=250.0, n_interferers=5, decoy_offset=16.0, exposure=exposure)
    p = prepare_interference([np.random.default_rng([11, 2]) for _ in range(2)], 4, sc, [0.5, 2.0], [{}, {}])
    scene = p.scene
    if exposure == "instant":  # the decoy dark in a third of the trials: lit decoys added to a subset of the crops
        scene.decoy_brightness = np.where(np.arange(scene.n) % 3 == 0, 0.0, scene.decoy_brightness)
        scene._lit = np.flatnonzero(scene.decoy_brightness != 0)
    return scene


def _crops(scene, frames, seed):
    """Crops at frames in any order, of all trials or a subset, gates near the marker, far from it, across the
    image's edge and outside it (boxes inside, across and outside their crops), with pixel noise."""
    rng, out = np.random.default_rng(seed), []
    for i, k in enumerate(frames):
        trials = np.arange(scene.n) if i % 2 else np.sort(rng.choice(scene.n, scene.n // 2, replace=False))
        c = scene.truth.marker[trials, k] + rng.normal(0.0, 8.0, (trials.size, 2))
        c[::5] = rng.uniform(-30.0, 290.0, (c[::5].shape[0], 2))  # some gates far off, some outside the image
        size = (14, 26, 42)[i % 3]
        noise = np.random.default_rng([seed, i])
        out.append(scene.gate_crops(k, c, size, noise, None if i % 2 else trials))
    return out


@pytest.mark.parametrize("exposure", ["instant", "integrated"])
def test_compiled_gate_crops_equal_the_numpy_twin_bit_for_bit(exposure, monkeypatch):
    frames = (40, 3, 17, 16, 49, 0, 33)
    compiled = _crops(_scene(exposure), frames, 1)
    _numpy_path(monkeypatch)
    twin = _crops(_scene(exposure), frames, 1)
    partial = 0
    for (a, oa, ia), (b, ob, ib) in zip(compiled, twin):
        assert a.dtype == b.dtype == np.float32 and np.array_equal(a, b)
        assert np.array_equal(oa, ob) and np.array_equal(ia, ib)
        partial += int((~ia).sum())
    assert partial > 0  # gates outside the image were read (their crops from the zero padding)


def test_compiled_crops_give_the_numpy_twins_closed_loop_histories(monkeypatch):
    """Runs side by side (rotating with a decoy block, static, another gate, no compensation) with the compiled
    crops and with the twin: every history the same, bit for bit."""
    base = Scenario(duration_s=0.16, n_interferers=5)
    sirs, g = [0.5, 2.0], lambda s: np.random.default_rng([s, 3])

    def batches():
        return [
            prepare_interference(
                [g(10) for _ in range(2)], 3, base, sirs, [{"n_interferers": 1}, {"decoy_offset": 16.0}]
            ),
            prepare_interference([g(11)], 3, replace(base, rotating=False), sirs),
            prepare_interference([g(12)], 3, replace(base, gate_half=6.0), sirs),
        ]

    compiled = [h for _, _, h in run_together(batches())]
    _numpy_path(monkeypatch)
    twin = [h for _, _, h in run_together(batches())]
    for a, b in zip(compiled, twin):
        for f in ("gate", "miss", "inside", "omega"):
            assert np.array_equal(getattr(a, f), getattr(b, f), equal_nan=True), f


@pytest.mark.parametrize("size", [14, 26, 42])
def test_compiled_quadrant_weights_equal_the_numpy_twin_bit_for_bit(size, monkeypatch):
    """Gate centres inside the crop, on pixel centres and edges, across its edges and far outside it (every
    coverage clipped to 0 or 1), a NaN centre, half-sizes of a few pixels to more than the crop."""
    rng = np.random.default_rng(size)
    n = 300
    origin = rng.integers(-60, 300, (n, 2))
    centre = origin + rng.uniform(-20.0, size + 20.0, (n, 2))
    centre[:40] = np.round(centre[:40]) + 0.5 * rng.integers(0, 2, (40, 2))  # on pixel centres and edges
    centre[40] = np.nan
    for half in (3.0, 6.5, size / 2, 2.0 * size):
        got = discriminators.quadrant_weights(origin, centre, half, (size, size), np.float32)
        with monkeypatch.context() as m:
            _numpy_path(m)
            want = discriminators.quadrant_weights(origin, centre, half, (size, size), np.float32)
        for a, b in zip(got, want):
            assert a.dtype == b.dtype == np.float32 and a.shape == b.shape
            assert np.array_equal(a, b, equal_nan=True), (half, np.nanmax(np.abs(a - b)))
        assert np.isnan(got[0][40]).all() and not np.isnan(got[0][41:]).any()
    shifted = origin + 0.25  # an origin off the pixel grid is the NumPy path's alone (the kernel takes integers)
    got = discriminators.quadrant_weights(shifted, centre, 3.0, (size, size), np.float32)
    with monkeypatch.context() as m:
        _numpy_path(m)
        want = discriminators.quadrant_weights(shifted, centre, 3.0, (size, size), np.float32)
    assert all(np.array_equal(a, b, equal_nan=True) for a, b in zip(got, want))


def _both_paths(monkeypatch, fn, *args):
    """``fn(*args)`` on the compiled path, then on the NumPy twin: the two outcomes (a value, or the exception's
    type)."""

    def outcome():
        try:
            return fn(*args)
        except (IndexError, ValueError) as e:
            return type(e)

    compiled = outcome()
    with monkeypatch.context() as m:
        _numpy_path(m)
        return compiled, outcome()


@pytest.mark.parametrize("size", [1, 4, 8, 9])
def test_crops_smaller_than_the_spot_box_are_the_same_both_ways(size, monkeypatch):
    """A gate smaller than the spot's 9-px box (D = 8): the twin added no box to such a crop (its window view raised);
    both paths give the pixels of a large crop at the same image positions, every box clipped to its crop."""
    scene = _scene("instant")
    k = 21
    c = scene.truth.marker[:, k] + np.random.default_rng(5).normal(0.0, 3.0, (scene.n, 2))
    compiled, twin = _both_paths(monkeypatch, scene.gate_crops, k, c, size, None)
    big, bo, _ = scene.gate_crops(k, c, 26, None)
    for crops, origin, _ in (compiled, twin):
        assert crops.shape == (scene.n, size, size) and crops.any()
        for i, ((x, y), (bx, by)) in enumerate(zip(origin, bo)):
            assert np.array_equal(crops[i], big[i, y - by : y - by + size, x - bx : x - bx + size])
    assert all(np.array_equal(a, b) for a, b in zip(compiled, twin))


def test_a_bad_crop_request_is_the_same_error_both_ways_and_a_mask_reads_its_trials(monkeypatch):
    """The compiled crops do not check their indices (an index past the trials read memory it does not own): the
    request is checked for both paths. A trial index out of range or not an integer, a crop side of 0 or wider than the
    padded image, and centres that do not broadcast to one per trial are the same error both ways; a boolean mask
    reads its true trials, and one centre serves every trial, as NumPy's indexing has it."""
    scene = _scene("instant")
    k, c = 7, scene.truth.marker[:, 7]
    side = scene._padded.shape[1]
    bad = [
        (c[:1], 26, [scene.n]),
        (c[:1], 26, [-scene.n - 1]),
        (c[:1], 26, [0.0]),
        (c, 0, None),
        (c, side + 2, None),
        (c[:3], 26, [0, 1]),
    ]
    for centres, size, trials in bad:
        compiled, twin = _both_paths(monkeypatch, scene.gate_crops, k, centres, size, None, trials)
        assert compiled is twin and twin in (IndexError, ValueError), (size, trials, compiled, twin)
    mask = np.arange(scene.n) % 2 == 0
    for centres, trials in ((c[mask], mask), (c[:1], np.flatnonzero(mask)), (c[:1], None)):
        compiled, twin = _both_paths(monkeypatch, scene.gate_crops, k, centres, 26, None, trials)
        assert all(np.array_equal(a, b) for a, b in zip(compiled, twin))
    by_mask = scene.gate_crops(k, c[mask], 26, None, mask)[0]
    assert np.array_equal(by_mask, scene.gate_crops(k, c[mask], 26, None, np.flatnonzero(mask))[0])


def test_unsigned_origins_keep_the_numpy_weights(monkeypatch):
    """An unsigned origin past int64's range would wrap in the kernel's integer cast: such origins keep the NumPy
    path, as float origins do."""
    origin = np.array([[2**63, 0]], dtype=np.uint64)  # the centre's pixel, 3000 px of half-size: every weight 1
    args = (origin, np.array([[2.0**63, 1.0]]), 3000.0, (3, 3), np.float32)
    compiled, twin = _both_paths(monkeypatch, discriminators.quadrant_weights, *args)
    assert all(np.array_equal(a, b) for a, b in zip(compiled, twin))
    assert np.all(compiled[1][0, :, 0] == 1.0)
