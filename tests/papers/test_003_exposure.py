"""Tests of paper 003's exposure model (the marker smeared over the frame) and the static baseline's matching."""

import numpy as np
import pytest

from tvtrack.papers.p003_rotating_marker_tracker.imaging import RotatingMarkerScene
from tvtrack.papers.p003_rotating_marker_tracker.scene import Scenario, marker_truth, run_scenario

FPS, R, OMEGA, PHI = 50.0, 12.0, 2 * np.pi * 8.0, 0.3


def _crop(m: int, r: float = R, omega: float = OMEGA, size: int = 48):
    truth = marker_truth(np.full((1, 3), 128.0), np.full((1, 3), 128.0), r, omega, np.array([PHI]), 1 / FPS)
    scene = RotatingMarkerScene(truth, (256, 256), "disc", 8.0, 1.0, exposure_steps=m)
    crops, origin, _ = scene.gate_crops(1, np.array([[128.0, 128.0]]), size, None)
    return crops[0].astype(float), origin[0], truth


def _centroid(crop, origin):
    ys, xs = np.mgrid[: crop.shape[0], : crop.shape[1]]
    w = crop / crop.sum()
    return np.array([(w * (xs + origin[0])).sum(), (w * (ys + origin[1])).sum()])


def test_integrated_exposure_smears_the_marker_onto_its_arc():
    """The mean of m renders at the sub-frame phases theta_k + omega tau_j has its centroid on the chord of the arc
    swept in one frame, at r sin(m b/2) / (m sin(b/2)) from the centre (b = omega dt / m), and the same energy."""
    m = Scenario(fps=FPS, exposure="integrated").exposure_steps
    assert m == int(np.ceil(2 * OMEGA * R / FPS)) + 1
    inst, o, truth = _crop(1)
    smear, _, _ = _crop(m)
    assert smear.sum() == pytest.approx(inst.sum(), rel=0.01)  # the disc renderer's flux is exact within 1 %
    b = OMEGA / FPS / m
    rho = R * np.sin(m * b / 2) / (m * np.sin(b / 2))
    th = truth.theta[0, 1]
    np.testing.assert_allclose(_centroid(smear, o), 128 + rho * np.array([np.cos(th), np.sin(th)]), atol=0.03)
    np.testing.assert_allclose(_centroid(inst, o), 128 + R * np.array([np.cos(th), np.sin(th)]), atol=0.03)
    # a pixel on the arc's middle is covered while the spot's centre is within D/2 of it: D / arc of the frame
    assert smear.max() == pytest.approx(8.0 / (OMEGA * R / FPS), abs=0.03)


def test_integrated_exposure_of_a_still_marker_is_the_instant_one():
    inst, _, _ = _crop(1, r=0.0, omega=0.0)
    np.testing.assert_allclose(_crop(9, r=0.0, omega=0.0)[0], inst, atol=1e-6)


@pytest.mark.parametrize("exposure", ["instant", "integrated"])
def test_static_baseline_gets_the_rotating_markers_photons(exposure):
    """Matched exposure: the static baseline is the same emitter held still, so at every frame its spot carries the
    rotating marker's energy, under the same sensor noise and exposure model."""
    sums = {}
    for rotating in (True, False):
        sc = Scenario(fps=FPS, duration_s=0.2, rotating=rotating, exposure=exposure, background_std=0.0, noise_std=0.0)
        _, scene, _ = run_scenario(np.random.default_rng(1), 2, sc)
        crops, _, _ = scene.gate_crops(3, scene.truth.marker[:, 3], 60, None)
        sums[rotating] = crops.sum(axis=(1, 2))
    np.testing.assert_allclose(sums[True], sums[False], rtol=0.01)  # the disc renderer's flux within 1 %
    np.testing.assert_allclose(sums[True], np.pi * 16, rtol=0.01)  # d pi D^2 / 4 with d = 1, D = 8


# ---------------------------------------------------------------------------------------------- temporal median


def _still_truth(n_frames, r=R, omega=OMEGA, fps=500.0):
    return marker_truth(
        np.full((1, n_frames), 128.0), np.full((1, n_frames), 128.0), r, omega, np.array([PHI]), 1 / fps
    )


def _residual(scene):
    m = scene.MARGIN
    return scene._padded[:, m:-m, m:-m].astype(float)


def test_median_compensation_cancels_the_background_and_keeps_the_interferers_at_the_papers_sir():
    """Noise-free, object still: the median (marker masked) removes the background exactly, and each interferer keeps
    d / SIR, the paper's SIR after compensation (l. 198), as under kappa compensation. A median that also removed the
    interferers (as before) left no SIR to set: every SIR the same scene."""
    from tvtrack.papers.p003_rotating_marker_tracker.scene import build_scene

    truth = _still_truth(200)
    kw = dict(noise_std=0.0, background_std=0.2, n_interferers=5, sir=2.0, median_frames=125)
    med = build_scene(np.random.default_rng(2), truth, compensation="median", **kw)
    kap = build_scene(np.random.default_rng(2), truth, compensation="kappa", **{**kw, "background_std": 0.0})
    np.testing.assert_allclose(_residual(med), _residual(kap), atol=1e-6)  # the interferers, nothing else
    assert _residual(med).max() == pytest.approx(0.5, abs=1e-6)  # d / SIR per covered pixel
    dim = build_scene(np.random.default_rng(2), truth, compensation="median", **{**kw, "sir": 4.0})
    assert _residual(dim).max() == pytest.approx(0.25, abs=1e-6)  # the SIR reaches the median's scene


def test_median_compensation_keeps_a_marker_that_stood_still_for_either_marker():
    """Eq. (19) subtracts f, the scene without the object: the median masks the object's own marker, so a
    non-rotating marker on a still object (the static comparator of C003-12 on a hovering object) is not taken away,
    and the rotating marker leaves no ring: noise-free, the residual is zero everywhere."""
    from tvtrack.papers.p003_rotating_marker_tracker.backdrop import median_residual

    for r, omega in ((0.0, 0.0), (R, OMEGA)):
        truth = _still_truth(51, r=r, omega=omega)
        res = median_residual(np.random.default_rng(0), truth, 51, (256, 256), "disc", 8.0, 1.0, 0.0)
        assert np.abs(res).max() == 0.0, (r, omega)


def test_median_residual_is_the_sample_median_of_the_noise_the_marker_leaves_free():
    """With noise sigma and N frames: pixels the marker never reaches read the median of N normals (standard
    deviation sigma sqrt(pi / 2N)); pixels on the marker's circle read the median of the frames it leaves them
    free (no ring: the marker is masked), close to the same law."""
    from tvtrack.papers.p003_rotating_marker_tracker.backdrop import median_residual

    N, sigma = 1001, 0.02
    truth = _still_truth(N)
    res = median_residual(np.random.default_rng(3), truth, N, (256, 256), "disc", 8.0, 1.0, sigma)[0]
    ys, xs = np.mgrid[:256, :256]
    rho = np.hypot(xs - 128.0, ys - 128.0)
    law = sigma * np.sqrt(np.pi / (2 * N))
    inner = rho < R - 8.0  # inside the box, never covered: exact medians of noise
    assert res[inner].std() == pytest.approx(law, rel=0.1)
    ring = np.abs(rho - R) < 1.0
    assert abs(res[ring].mean()) < 3 * law and res[ring].std() == pytest.approx(law, rel=0.25)
