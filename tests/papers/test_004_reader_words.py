"""Paper 004: the Conclusions' list of the entries added by the adversarial passes names each entry by its title and
each value by its phrase, the register's plain words, as every other sentence of the report does (it once listed
`roll-off` ... "at f^-2" and `vibration` ... "at 1.0")."""

from types import SimpleNamespace

from tvtrack.papers.p004_laser_spot_prediction import findings as fd
from tvtrack.papers.p004_laser_spot_prediction.register import build


def _exploration(register, changed: dict, parts_at: dict):
    """An exploration of one claim (C004-3) whose one-at-a-time condition ``changed`` gives ``parts_at`` where the
    first replicate gave every part ``reproduced``."""
    conditions = [{"kind": "single", "changed": changed, "parts": parts_at}]
    record = {"parts": {p: {"replicate_verdicts": ["reproduced"]} for p in parts_at}, "conditions": conditions}
    return SimpleNamespace(
        register=register,
        depends={"C004-3": [e.name for e in register]},
        record=lambda cid, rule: record,
    )


def test_adversarial_entries_are_named_by_title_and_values_by_phrase():
    register = build()
    vibration, saturation = register["vibration"], register["saturation"]
    assert vibration.origin == saturation.origin == "adversarial"
    ex = _exploration(register, {"vibration": 1.0}, {"cubic spline": "not reproduced"})
    text = fd.adversarial_summary(ex, {"C004-3": None})
    line = next(ln for ln in text.splitlines() if "cubic spline" in ln)
    assert line == (
        f"- {vibration.title[:1].upper() + vibration.title[1:]}: C004-3 (cubic spline) reproduced -> not reproduced "
        f"with {vibration.phrase(1.0)}."
    )
    assert "1 px mount vibration at 8 Hz" in line
    assert f"- {saturation.title[:1].upper() + saturation.title[1:]}: no verdict changed." in text
    adversarial = [e for e in register if e.origin == "adversarial"]
    assert len(text.splitlines()) == len(adversarial)
    for e in adversarial:  # no code name in backticks, no raw value
        assert f"`{e.name}`" not in text
    assert " at 1.0" not in text


# --- the words of the executed notebook a reader review found wanting ---


def _est(v, lo, hi):
    from tvtrack.montecarlo import Estimate

    return Estimate(v, 0.01, lo, hi, 15)


def test_a_setting_at_its_methods_own_minimum_is_said_so_not_called_inside_its_grid(monkeypatch):
    """'Every tuned setting lies inside its grid' while regression of degree 1 sat at 2 samples and the variant floor
    at 3: the smallest each search allows, which the edge shares rightly do not count."""
    import numpy as np

    from tvtrack.papers.p004_laser_spot_prediction import side_studies as side
    from tvtrack.papers.p004_laser_spot_prediction.prediction_study import PAPER, VARIANT

    monkeypatch.setattr(side, "comparison_setup", lambda config, size: SimpleNamespace(floor_grid=(3, 4, 5, 7)))
    chosen = {
        PAPER: np.array([4, 4, 5]),
        VARIANT: np.array([3, 3, 3]),
        "linear regression deg 1": np.array([2, 2, 2]),
        "linear regression deg 2": np.array([4, 4, 4]),  # its search starts at 3: inside
        "cubic spline": np.array([4, 4, 6]),
    }
    run = SimpleNamespace(comparison=SimpleNamespace(chosen=chosen), config={}, size=None)
    low = side.own_minimum_report(run)
    assert set(low) == {VARIANT, "linear regression deg 1", "cubic spline"}
    text = fd.edge_sentence({PAPER: 0.0}, low)
    assert "Every tuned setting lies inside its grid" not in text
    assert "No tuned setting sits on an edge its grid imposes." in text
    assert "At the smallest value its own search allows" in text
    assert "linear regression deg 1 at window L 2 (100%)" in text and "cubic spline at window L 4 (67%)" in text
    assert f"{VARIANT} at floor N_f 3 (100%)" in text


def test_the_amplitude_worlds_are_said_to_be_recalibrated_so_inside_the_band_by_construction():
    text = fd.amplitude_sentence({0.5: _est(1.32, 1.16, 1.54), 2.0: _est(1.34, 1.18, 1.56)}, lambda a: 3.0 / a)
    assert "amplitude x0.5 (bandwidth factor 6): 1.32 [1.16, 1.54] px (inside 1-2 px)" in text
    assert "re-calibrated to the paper's operating point" in text and "holds by construction" in text


def test_the_singer_time_constant_is_a_property_of_this_synthetic_wander():
    summary = {
        "ratio_2_over_1": _est(1.44, 1.43, 1.45),
        "singer_tau_frames": 0.032,
        "tau_over_horizon": 0.032,
        "tau_grid_min": 0.01,
        "rms": {"a": 1.1, "b": 1.3},
        "best_order1": "a",
        "best_order2": "b",
        "frame_ms": 40.0,
    }
    text = fd.model_order_sentence(summary)
    assert "In this synthetic wander the acceleration's correlation time" in text
    assert "the paper's laser paths are not available" in text


def test_ratios_print_enough_digits_to_show_their_interval_and_the_calibration_names_the_slow_world():
    assert fd.fmt_shown(_est(0.8912, 0.8897, 0.8928)) == "0.891 [0.890, 0.893]"
    assert fd.fmt_shown(_est(0.6168, 0.6145, 0.6192)) == "0.617 [0.615, 0.619]"
    assert fd.fmt_shown(_est(1.25, 1.23, 1.28)) == "1.25 [1.23, 1.28]"
    cal = SimpleNamespace(evaluations=[(1.0, 0.33), (3.09, 1.5)], scale=3.09, rms_px=1.5, target_px=1.5)
    text = fd.calibration_sentence(cal, 3.0)
    assert "earlier world" not in text
    assert "in the uncalibrated world (bandwidth factor 1, the wander's corners at 0.02, 0.1, 0.5 Hz)" in text


def test_the_register_why_texts_name_no_code():
    register = build()
    whys = " ".join(e.why for e in register)
    for code in ("operating.bandwidth_for", "calibration.calibrate_bandwidth", "lag_grid", "docs/validity", "V_perp"):
        assert code not in whys, code


def test_the_floor_caption_says_what_the_curves_show():
    from tvtrack.papers.p004_laser_spot_prediction import plots

    level = plots.floor_caption({"no floor": [4.9, 5.0], "floor (cross-validated)": [1.5, 1.45]}, 1, [3, 4, 5])
    assert "stays at about one level over the frames, above the floored filter's" in level
    assert "$N_f$ = 4" in level and "4.90 px over the first half" in level and "degrade" not in level
    grows = plots.floor_caption({"no floor": [2.0, 5.0], "floor (cross-validated)": [1.5, 1.45]}, 0, [3, 4, 5])
    assert "grows over the frames" in grows


def test_the_ranking_figure_names_conditions_by_phrase_and_centres_its_markers_on_the_rows():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    from tvtrack.papers.p004_laser_spot_prediction import plots
    from tvtrack.papers.p004_laser_spot_prediction.register import DEFAULT

    register = build()
    ranks = {"C004-3": {"finite differences, 2 points": _est(0.6, 0.5, 0.7), "cubic spline": _est(3.5, 3.4, 3.6)}}
    run = SimpleNamespace(stage="single", outputs=ranks, changed=lambda d: {"bandwidth": 8})
    ex = SimpleNamespace(runs=[run], default=dict(DEFAULT), measured=lambda c: ranks.get(c, {}), register=register)
    fig = plots.ranking_figure(ex, ("C004-3",))
    ax = fig.axes[0]
    labels = [t.get_text().replace("\n", " ") for t in ax.get_yticklabels()]
    ys = [np.ravel(c[0].get_ydata()) for c in ax.containers]
    plt.close(fig)
    assert register.describe({"bandwidth": 8}) in labels and not [x for x in labels if " = " in x]
    assert np.allclose(np.mean(ys, axis=0), [0, 1])  # the markers of a row spread about its tick


def test_the_findings_lines_show_the_label_a_reader_sees():
    """A record too small to label reads ``provisional`` in the findings, as in the core's table, never its raw
    ``unexplored`` (nor ``robust``); a record of its own size keeps its label."""
    from types import SimpleNamespace

    from tvtrack.estimate import Estimate
    from tvtrack.papers.p004_laser_spot_prediction.findings import findings
    from tvtrack.verdicts import InBand

    rule = InBand("error", 0.0, 2.0, "px")
    m = Estimate(1.0, 0.1, 0.8, 1.2, 50)

    def text(**record):
        rec = {"label": "unexplored", "parts": {"claim": {"verdict": "reproduced", "label": "unexplored"}}} | record
        ex = SimpleNamespace(rules={"C004-1": rule}, measured=lambda cid: m, record=lambda cid, r: rec)
        return findings({"C004-1": rule}, ex, {"C004-1": "at most 2 px"})

    assert "**reproduced**, provisional." in text(provisional=True)
    assert "**reproduced**, unexplored." in text(provisional=False)


def test_c004_6_caveat_says_how_degrades_is_read_and_whether_the_error_worsens_over_the_run():
    """The rule judges "degrades" as erring more than with the floor; the caveat says so and, from the two halves
    of the scored frames, whether the no-floor error also worsens over the run (the record: 4.44 -> 4.97 px)."""
    from tvtrack.papers.p004_laser_spot_prediction import plots

    flat = plots.c004_6_caveat({"no floor": [4.44, 4.97], "floor (cross-validated)": [1.5, 1.45]})
    assert "judged as erring more than the filter with the floor" in flat
    assert (
        "stays at about one level" in flat
        and "4.44 px over the first half of the scored frames, 4.97 px over the second" in flat
        and "does not worsen over the run" in flat
    )
    grows = plots.c004_6_caveat({"no floor": [2.0, 5.0], "floor (cross-validated)": [1.5, 1.45]})
    assert "grows over the frames" in grows and "it also worsens over the run" in grows
