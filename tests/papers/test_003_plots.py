"""Figures of paper 003: captions say what the computed numbers say, and each panel carries its own paper value."""

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

from tvtrack.papers.p003_rotating_marker_tracker import beyond, plots, study  # noqa: E402
from tvtrack.papers.p003_rotating_marker_tracker.discriminators import quadrant_slope_fit  # noqa: E402
from tvtrack.papers.p003_rotating_marker_tracker.scene import Scenario  # noqa: E402


def test_s_curve_caption_gives_the_computed_slopes_and_their_band_words():
    """The caption once said both quadrant curves sit on the 2dD slope while C003-9 found the disc's +-D/2 fit
    outside its band; now every slope and word comes from quadrant_slope_fit."""
    sc = Scenario()
    fig, caption = plots.s_curves(sc)
    plt.close(fig)
    lo, hi = study.LINEAR_BAND
    for spot in ("square", "disc"):
        s = Scenario(spot=spot, diameter=sc.diameter, gate_half=sc.gate_half)
        fit = quadrant_slope_fit(s.spot_renderer(), sc.diameter, sc.gate_half)
        r = [fit["slope_at_zero"] / s.slope(), fit["fit_slope_halfD"] / s.slope()]
        w = ["inside" if lo <= x <= hi else "outside" for x in r]
        assert f"{spot} {r[0]:.3g} ({w[0]}) and {r[1]:.3g} ({w[1]})" in caption
    assert "disc" in caption and "(outside)" in caption  # the disc's +-D/2 fit (0.84) is outside [0.9, 1.1]


def test_loss_curves_mark_each_panel_with_its_own_paper_threshold():
    sirs = np.array(study.SIR_GRID)
    lost = sirs[:, None] < np.full((1, 4), 1.0)
    curves = [{f"{m}/{k}": lost for m in ("rotating", "static") for k in (1, 5)}]
    fig, caption = plots.loss_curves_figure(curves, sirs, 5.0)
    vlines = [
        {float(x) for ln in ax.lines if len(set(np.ravel(ln.get_xdata()))) == 1 for x in np.ravel(ln.get_xdata())}
        for ax in fig.axes
    ]
    plt.close(fig)
    assert vlines[0] == {2.0} and vlines[1] == {3.0}
    assert "2 with one interferer, 3 with five" in caption


def test_median_example_masks_the_marker_and_leaves_only_the_medians_noise():
    sc = Scenario(n_interferers=5)
    ex = beyond.median_example(3, sc)
    res, q = ex["residual"], ex["interferers"]
    law = sc.noise_std * np.sqrt(np.pi / (2 * ex["n_frames"]))  # the sample median of noise
    assert np.abs(res).max() < 10 * law  # no ring: the marker is masked out of the median
    far = res[:40, :40]  # far from the object
    assert np.std(far) == pytest.approx(law, rel=0.1)
    fig, caption = plots.median_figure(**ex)
    plt.close(fig)
    assert "d / SIR" in caption and q.shape == (5, 2)


def test_bound_and_exposure_figures_state_the_numbers_they_draw():
    from tvtrack.montecarlo import Estimate

    def est(v):
        return Estimate(v, float("nan"), 0.9 * v, 1.1 * v, 6, 0.95, "t")

    cb = {
        "rms": {"loops 10 Hz": est(0.5), "EKF (5 states)": est(0.4), "EKF (velocity)": est(0.3)},
        "bound": {1: 0.1, 8: 0.09},
        "best_loops": {"bandwidth_hz": 10.0, "edge": False},
    }
    fig, caption = plots.bound_figure(cb)
    plt.close(fig)
    assert "at 3 times the bound" in caption and "(loops 10 Hz) at 5 times it" in caption
    thr = {k: est(v) for k, v in (("rotating 1", 0.7), ("rotating 5", 1.0), ("static 1", 1.2), ("static 5", 1.7))}
    res = {"instant": {"thresholds": thr}, "integrated": {"thresholds": {**thr, "static 5": est(4.0)}}, "arc_px": 12.1}
    fig, caption = plots.exposure_figure(res)
    plt.close(fig)
    assert "separated by the exposure: static 5." in caption and "12.1 px" in caption
