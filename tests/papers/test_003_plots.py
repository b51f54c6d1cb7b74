"""Figures of paper 003: captions say what the computed numbers say, and each panel carries its own paper value."""

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from tvtrack.papers.p003_rotating_marker_tracker import plots, study  # noqa: E402
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
