"""Notebook 003, C003-2: the ripple's trend with the loop bandwidth is read over the loops that keep lock."""

import numpy as np
import pytest

from tvtrack.montecarlo import ratio_ci
from tvtrack.papers.p003_rotating_marker_tracker import study
from tvtrack.papers.p003_rotating_marker_tracker.estimators import grid_in_lock
from tvtrack.papers.p003_rotating_marker_tracker.prose import lost_points
from tvtrack.papers.p003_rotating_marker_tracker.register import REGISTER
from tvtrack.papers.p003_rotating_marker_tracker import memo


@pytest.fixture(autouse=True)
def _fresh_memo():
    memo.clear_cache()
    yield
    memo.clear_cache()


def test_a_lost_grid_point_is_reported_and_left_out_of_the_trend():
    """Planted: the narrowest loop loses lock in every run with a large error; among the others the ripple grows
    with the bandwidth. The trend keeps three points, each on its runs in lock; the lost point is counted; the pair
    is read on the runs in lock at both points."""
    rng = np.random.default_rng(4)
    n, grid = 12, (2.0, 5.0, 10.0, 20.0)
    lost = np.zeros((4, n), bool)
    lost[0] = True
    lost[3, :2] = True  # two lost runs at 20 Hz: 2 of 12 is above the 10 % limit, so 20 Hz is not read
    ripple = np.stack([np.full(n, 9.0), np.full(n, 1.0), np.full(n, 2.0), np.full(n, 4.0)]) * rng.uniform(
        0.9, 1.1, (4, n)
    )
    control = np.ones((4, n))
    w = grid_in_lock(lost, ripple, control, grid, (20.0, 10.0))
    assert w["read"] == [5.0, 10.0]
    assert [e.value for e in w["trend"]] == pytest.approx([ratio_ci(ripple[i], control[i]).value for i in (1, 2)])
    assert w["lost"]["2 Hz"].value == 1.0 and w["lost"]["20 Hz"].value == pytest.approx(2 / 12)
    assert np.isnan(w["pair"].value)  # 20 Hz is lost: no pair
    lost[3] = False
    w = grid_in_lock(lost, ripple, control, grid, (20.0, 10.0))
    assert w["read"] == [5.0, 10.0, 20.0] and w["pair"].value == pytest.approx(2.0, rel=0.1)
    assert "2 Hz (share of runs that lost lock 1" in lost_points(w["lost"])


def test_the_default_loop_ripple_grows_with_the_bandwidth_among_loops_in_lock():
    """At the default the 2 Hz loop loses lock in every run; read against it, the paper's 10 Hz ripple looked
    smaller than at 2 Hz (10/2 Hz = 0.44 here: the lost loop's error, not a ripple). Over the loops in lock the
    locked ripple grows with the bandwidth (20/10 Hz about 1.3-1.5 over seeds 11-13 at 20 runs, each interval
    above 1), as the paper's explanation asks. Six runs were too few: the interval's lower end crossed 1 with the
    draws (seed 11 gave 1.30 [0.76, 2.71] once the scene stopped drawing for interferers it does not have)."""
    t = study.measure_tracking(REGISTER.default(), 11, study.Sizes(trials=20), claims={"C003-2"})
    assert t["_lock_by_bandwidth"]["2 Hz"].value == 1.0
    assert all(t["_lock_by_bandwidth"][f"{b:g} Hz"].value == 0.0 for b in (5.0, 10.0, 20.0))
    assert len(t["C003-2"]["wide_loops"]) == 3
    assert study.RIPPLE_TREND == (20.0, 10.0)
    assert t["_ripple_trend"].value > 1.2 and t["_ripple_trend"].ci_low > 1.0
