"""The tracking claims declare the scene entries that move them, and the entries they leave undeclared do not.

A tracking scene has no interferers but does have the static background: its residual after compensation and
the loss criterion move the tracking claims, so those claims declare them. The interferers' layout did move them
too, through the random stream alone (an even layout drew an angle for no interferer); a scene without interferers
now draws nothing for them."""

import json

import numpy as np
import pytest

from tvtrack.papers.p003_rotating_marker_tracker import study
from tvtrack.papers.p003_rotating_marker_tracker.backdrop import place_interferers
from tvtrack.papers.p003_rotating_marker_tracker.register import DEPENDS, REGISTER

SIZES = study.Sizes(trials=2, fig1_s=0.6, fig2_s=0.5, transient_s=0.1, horizon_s=0.3)


@pytest.mark.parametrize("layout", ["even", "independent"])
def test_no_interferer_draws_nothing_from_the_stream(layout):
    rng = np.random.default_rng(3)
    out = place_interferers(rng, 4, 0, (10.0, 10.0), 5.0, 0.0, layout)
    assert out.shape == (4, 0, 2)
    assert rng.random() == np.random.default_rng(3).random()  # the stream is where it was


def _tracking(**changed):
    out = study.measure_tracking.__wrapped__({**REGISTER.default(), **changed}, 7, sizes=SIZES, claims=["C003-1"])
    return json.dumps(out["C003-1"], sort_keys=True, default=str)


def test_the_background_moves_the_tracking_claims_and_they_declare_it_while_the_interferers_layout_does_not():
    base = _tracking()
    assert _tracking(residual_background=100.0) != base
    assert _tracking(compensation="temporal median") != base
    assert _tracking(interferer_layout="independent") == base
    for cid in ("C003-1", "C003-2", "C003-9"):
        assert {"residual_background", "compensation", "loss_window_s", "loss_radius"} <= set(DEPENDS[cid])
    assert "compensation" in DEPENDS["C003-4"] and "bandwidth_reading" in DEPENDS["C003-11"]
