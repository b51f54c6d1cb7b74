"""tvtrack.plotting.specification_curve: every explored configuration of a claim, sorted, over a dot matrix of the
register values it changed (Simonsohn, Simmons & Nelson 2020)."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from record_fixtures import DEPENDS, REGISTER_KEYS, VECTOR  # noqa: E402
from tvtrack.plotting import specification_curve, specification_rows  # noqa: E402


def test_rows_hold_the_default_and_every_condition():
    rows = specification_rows(DEPENDS)
    assert [r["kind"] for r in rows] == ["default", "single", "single", "single", "joint", "joint", "combination"]
    assert rows[0]["point"] == (351.6, 350.0, 353.1) and rows[0]["verdict"] == "not reproduced"
    assert rows[2] == {"kind": "single", "changed": {"k_bound2": 100}, "verdict": "not reproduced",
                       "point": (340.0, 338.0, 342.0)}  # fmt: skip
    # an all-of claim: the weakest-labelled part by default, any part on request
    assert specification_rows(VECTOR)[0]["point"] == (13.14, 13.14, 13.14)
    assert specification_rows(VECTOR, "decreasing")[0]["point"] is None  # a vector has no single value


def test_the_curve_is_sorted_with_the_band_the_default_and_the_dot_matrix():
    fig, caption = specification_curve(DEPENDS)
    top, bottom = fig.axes
    values = top.collections[1].get_offsets()[:, 1]  # [0]: the interval lines, [1]: the points
    assert np.all(np.diff(values) >= 0) and values[-1] == 351.6 and len(values) == 7
    default = top.collections[2].get_offsets()  # the diamond: the default, replicates pooled
    assert tuple(default[0]) == (6, 351.6)
    band = [p for p in top.patches if p.get_label() == "the rule's band"]
    assert len(band) == 1 and band[0].get_extents().height > 0
    assert top.get_yscale() == "log"  # 0.9 to 353 spans more than two decades
    labels = [t.get_text() for t in bottom.get_yticklabels()]
    assert "a target weaving at 0.1 T" in labels and "gain bound set at frame 100" in labels
    assert not any(key in " ".join(labels) for key in REGISTER_KEYS)  # phrases, not register keys
    # the sorted configuration that set sigma's other reading has a dark dot in that row
    row = next(i for i, t in enumerate(labels) if t.startswith("sigma read as the SD of the raw"))
    dark = [c for c in bottom.collections if tuple(np.round(c.get_facecolor()[0][:3], 2)) == (0.2, 0.2, 0.2)]
    on = {int(x) for c in dark for x, y in c.get_offsets() if y == row}
    assert on == {0, 1, 2}  # 0.9 (sigma + weave), 1.1 (sigma + gain bound), 1.2 (sigma alone): sorted first
    assert "under each of 7 configurations" in caption and "3 of 7 give the default's verdict" in caption
    plt.close(fig)


def test_a_vector_part_shows_each_configurations_verdict():
    fig, caption = specification_curve(VECTOR, part="decreasing")
    top = fig.axes[0]
    assert [t.get_text() for t in top.get_yticklabels()][:2] == ["reproduced", "undecided"]
    assert "by verdict" in caption and "7 of 7 give the default's verdict" in caption
    plt.close(fig)
