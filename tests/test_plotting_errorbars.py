"""``tvtrack.plotting.errorbars``: the one error-bar helper (it replaces the copies in papers 000 and 004)."""

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from tvtrack.montecarlo import Estimate  # noqa: E402
from tvtrack.plotting import errorbars  # noqa: E402


def _bars(container):
    """(lower, upper) ends of each bar, from the drawn segments."""
    segments = container.lines[2][0].get_segments()
    return np.array([[s[0], s[1]] for s in segments])


def test_bars_span_each_interval_and_the_points_sit_on_the_values():
    fig, ax = plt.subplots()
    ests = [Estimate(1.0, 0.1, 0.8, 1.3, 10), Estimate(2.0, 0.2, 1.5, 2.1, 10), 3.0]
    c = errorbars(ax, [10, 20, 30], ests, fmt="o")
    assert np.allclose(c.lines[0].get_ydata(), [1.0, 2.0, 3.0]) and np.allclose(c.lines[0].get_xdata(), [10, 20, 30])
    ends = _bars(c)  # vertical bars: (x, y_low) -> (x, y_high)
    assert np.allclose(ends[:, 0, 1], [0.8, 1.5, 3.0]) and np.allclose(ends[:, 1, 1], [1.3, 2.1, 3.0])
    h = errorbars(ax, [0, 1], ests[:2], horizontal=True, fmt="s")
    assert np.allclose(h.lines[0].get_xdata(), [1.0, 2.0]) and np.allclose(_bars(h)[:, 1, 0], [1.3, 2.1])
    plt.close(fig)
