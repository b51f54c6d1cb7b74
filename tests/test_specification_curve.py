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
    kinds = ["default", "single", "single", "single", "combination", "joint", "joint"]
    assert [r["kind"] for r in rows] == kinds  # each configuration once, the smallest first
    assert rows[0]["point"] == (351.6, 350.0, 353.1) and rows[0]["verdict"] == "not reproduced"
    assert rows[2] == {"kind": "single", "changed": {"k_bound2": 100}, "verdict": "not reproduced",
                       "point": (340.0, 338.0, 342.0), "flip": False}  # fmt: skip
    assert [r["flip"] for r in rows] == [False, True, False, True, False, False, False]  # the flips the page names
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
    assert "under each of the 7 configurations the record keeps" in caption
    # one count of configurations on the page: the share the claim's sentence gives, not a count of the drawn points
    assert "29 agree with the default, 3 flip and 0 stay undecided of the 32 explored configurations" in caption
    plt.close(fig)


def test_a_vector_part_shows_each_configurations_verdict():
    fig, caption = specification_curve(VECTOR, part="decreasing")
    top = fig.axes[0]
    assert [t.get_text() for t in top.get_yticklabels()][:2] == ["reproduced", "undecided"]
    assert "by verdict" in caption and "under each of the 7 configurations" in caption
    plt.close(fig)


def _wide_record():
    """DEPENDS with 24 more entries changed one at a time, one interval reaching 8e12 (as C002-11's did), one
    condition without a value, and a named flip whose configuration no condition keeps."""
    import copy

    rec = copy.deepcopy(DEPENDS)
    rob = rec["robustness"]
    for k in range(24):
        rob["register"].append({"name": f"extra_{k}", "kind": "regime", "title": f"extra setting {k}", "side": "world",
                                "default": 0, "values": [0, 1], "phrases": {"1": f"the extra world number {k}, "
                                "described at length so that the label runs over more than one line"}})  # fmt: skip
        rob["conditions"].append({"changed": {f"extra_{k}": 1}, "kind": "single", "verdict": "not reproduced",
                                  "measured": {"value": 300.0 + k, "ci_low": 290.0 + k, "ci_high": 310.0 + k}})  # fmt: skip
    rob["conditions"][1]["measured"] = {"value": 345.0, "ci_low": 1.0, "ci_high": 8e12}
    rob["conditions"][2]["measured"] = [1.0, 2.0]  # no single value kept for this one
    rob["parts"]["claim"]["flips"].append(
        {"changed": {"k_bound2": 100, "target_motion": "weave", "paper_sigma": "raw_increments"}, "side": "world",
         "kind": "joint", "verdict": "reproduced", "text": "three changes together"}
    )  # fmt: skip
    return rec


def test_every_setting_a_configuration_changed_has_a_row_whole():
    rec = _wide_record()
    fig, _ = specification_curve(rec)
    labels = [t.get_text() for t in fig.axes[1].get_yticklabels()]
    changed = {(k, str(v)) for c in rec["robustness"]["conditions"] for k, v in c["changed"].items()}
    assert len(labels) == len(changed) == 27  # every value set, not the 14 most used
    assert not any("…" in t for t in labels)
    assert "the extra world number 3, described at length so that the label runs over more than one line" in [
        " ".join(t.split()) for t in labels
    ]
    plt.close(fig)


def test_the_named_flips_are_on_the_curve_and_estimates_are_shown_wherever_there_is_one():
    from tvtrack.results import claim_flips

    rec = _wide_record()
    rows = specification_rows(rec)
    flipped = {tuple(sorted(f["changed"].items())) for f in claim_flips(rec)}
    ringed = {tuple(sorted(r["changed"].items())) for r in rows if r["flip"]}
    assert flipped == ringed and len(ringed) == 3  # the joint flip no condition kept is drawn too, without a value
    fig, caption = specification_curve(rec)
    top = fig.axes[0]
    points = top.collections[1].get_offsets()
    assert len(points) == sum(r["point"] is not None for r in rows) == len(rows) - 2  # a value for all that have one
    assert "2 without a value, by verdict at the bottom" in caption and "ringed: the 3 flips the page names" in caption
    plt.close(fig)


def test_an_interval_spanning_decades_is_clipped_with_an_arrow_not_flattening_the_curve():
    fig, caption = specification_curve(_wide_record())
    top = fig.axes[0]
    low, high = top.get_ylim()
    assert top.get_yscale() == "log" and high < 1e4  # the values span 0.9-352: log; 8e12 is not on the scale
    arrows = [c for c in top.collections if c.get_label() == "interval runs off the scale"]
    assert len(arrows) == 1 and len(arrows[0].get_offsets()) == 1
    assert "1 interval run off the scale (arrows)" in caption
    plt.close(fig)


def test_an_open_end_a_record_wrote_as_null_is_drawn_off_the_scale_not_closed_at_the_value():
    """A certified bound's open end, written as null with its ``infinite`` marker, is read back as infinite: its
    row's point keeps it and the curve draws it off the scale (an arrow); the forest plot's item reaches the edge."""
    from tvtrack.pipeline.figures import _estimate

    rec = _wide_record()
    rec["robustness"]["conditions"][1]["measured"] = {"value": 345.0, "ci_low": 300.0, "ci_high": None,
                                                      "infinite": {"ci_high": "+inf"}}  # fmt: skip
    points = [
        r["point"] for r in specification_rows(rec) if r["changed"] == rec["robustness"]["conditions"][1]["changed"]
    ]
    assert points == [(345.0, 300.0, float("inf"))]
    fig, caption = specification_curve(rec)
    arrows = [c for c in fig.axes[0].collections if c.get_label() == "interval runs off the scale"]
    assert len(arrows) == 1 and "1 interval run off the scale (arrows)" in caption
    plt.close(fig)
    assert _estimate({"value": 2.0, "ci_low": 1.5, "ci_high": None, "infinite": {"ci_high": "+inf"}}) == (
        2.0,
        1.5,
        float("inf"),
    )
    assert _estimate({"value": 2.0, "ci_low": 1.5, "ci_high": None}) == (2.0, 1.5, 2.0)  # no marker: as before
    assert _estimate({"value": 2.0, "ci_low": None, "ci_high": 3.0, "infinite": {"ci_low": "inf"}}) == (2.0, 2.0, 3.0)
