"""Paper 003: the words that leave the notebook for the report's tables (claim statements, the paper's values, the
rules' quantities and reasons, the notes, the register's phrases, the figure captions) define every symbol of the
model they use, and name nothing by the code's names: a tracking researcher reads them without the code."""

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import pytest  # noqa: E402

from tvtrack.papers.p003_rotating_marker_tracker import claims, plots  # noqa: E402
from tvtrack.papers.p003_rotating_marker_tracker.register import REGISTER  # noqa: E402
from tvtrack.papers.p003_rotating_marker_tracker.scene import Scenario  # noqa: E402
from tvtrack.verdicts import AllOf  # noqa: E402

# symbols and code names the report once printed undefined ("SIR_0 = kappa SIR", "B_xy = 5 and 20 Hz",
# "max(q, 1/q)", "the register's decoy_brightness", "its 'static_gate' comparator", "runs of 2T = 10 s", "d/20")
UNDEFINED = ("SIR_0", "kappa", "B_xy", "max(q", "x_r", "y_r", "decoy_brightness", "static_gate", "2T", "d/")


def _leaf_texts(rule) -> list[str]:
    """Each part's own text (an all-of's text also names its parts by their keys, the labels the report shows)."""
    if isinstance(rule, AllOf):
        return [t for r in rule.parts.values() for t in _leaf_texts(r)]
    return [rule.text()]


def _reader_texts() -> dict[str, str]:
    out = {f"{cid} statement": c["statement"] for cid, c in claims.CLAIMS.items()}
    out |= {f"{cid} paper value": c["paper_value"] for cid, c in claims.CLAIMS.items()}
    out |= {f"{cid} note": n for cid, n in claims.NOTES.items()}
    for cid, rule in claims.claim_rules().items():
        out |= {f"{cid} rule {i}": t for i, t in enumerate(_leaf_texts(rule))}
    for e in REGISTER:
        out[f"{e.name} title"] = e.title
        out |= {f"{e.name}={v}": e.phrase(v) for v in e.values}
    return out


@pytest.mark.parametrize("where, text", sorted(_reader_texts().items()), ids=sorted(_reader_texts()))
def test_no_undefined_symbol_or_code_name_reaches_the_reader(where, text):
    assert not [s for s in UNDEFINED if s in text], f"{where}: {text!r}"


def test_the_quadrant_slope_defines_2dD_where_it_is_named():
    # C003-9's parts are read alone in the report's table: each says what d and D are (eq. (9): brightness d,
    # a spot of width D; the quadrant slope 2dD of the paper card, Sect. 4.3)
    quads = [t for t in _leaf_texts(claims.claim_rules()["C003-9"]) if "2dD" in t]
    assert len(quads) == 2
    for t in quads:
        assert "d the spot's brightness" in t and "D its width" in t
    fig, caption = plots.s_curves(Scenario())
    plt.close(fig)
    assert "2dD (d the spot's brightness)" in caption and "spot width D = 8 px" in caption


def test_the_compensation_model_is_said_in_words_where_c003_8_and_c003_10_rest_on_it():
    # l. 198: "compensation ... equivalent to reducing the background by an order of magnitude"
    rules = claims.claim_rules()
    for text in (rules["C003-8"].text(), rules["C003-10"].parts["compensation"].text(), claims.NOTES["C003-10"]):
        assert "leaving a tenth of the whole static scene, interferers included" in text
        assert "before compensation" in text


def _record(part_verdict: str, first_replicate: str, conditions: list, flips: list) -> dict:
    """A robustness record as :func:`tvtrack.verdicts.label_parts` leaves it, one part ("no_loss") and the register's
    motion entries."""
    return {
        "register": [REGISTER["motion"].to_dict(), REGISTER["motion_scale"].to_dict()],
        "replicates": [{"parts": {"no_loss": first_replicate}}],
        "conditions": conditions,
        "parts": {"no_loss": {"verdict": part_verdict, "flips": flips}},
    }


def test_the_dependence_sentence_names_only_the_records_flips_not_a_condition_beside_one_replicate():
    """A one-at-a-time condition that decides like the pooled default, beside a first replicate that is undecided
    (0 losses in 6 runs), is no flip; only the record's named flips (decisive the other way at the default's size)
    are named, each with the default's verdict."""
    from tvtrack.papers.p003_rotating_marker_tracker import prose

    same = {"kind": "single", "changed": {"motion": "sinusoids"}, "parts": {"no_loss": "reproduced"}}
    flip = {"kind": "single", "changed": {"motion_scale": 0.25}, "parts": {"no_loss": "not reproduced"}}
    joint = {"changed": {"motion": "random", "motion_scale": 2.0}, "kind": "joint", "verdict": "not reproduced"}
    named = [{"changed": {"motion_scale": 0.25}, "kind": "single", "verdict": "not reproduced"}, joint]
    text = prose.dependence({"C003-5": _record("reproduced", "undecided", [same, flip], named)})
    assert REGISTER.describe({"motion_scale": 0.25}) in text and "reproduced by default" in text
    assert REGISTER.describe({"motion": "sinusoids"}) not in text  # agrees with the pooled default
    assert REGISTER.describe({"motion": "random"}) not in text  # a joint flip is not one entry alone
    quiet = prose.dependence({"C003-5": _record("reproduced", "undecided", [same], [])})
    assert quiet.startswith("no part of these claims flips")


# --- the typical breaking SIR, the register table, the figures' words (a reader review of the executed notebook) ---

_GRID = [0.5, 0.75, 1.0, 4 / 3, 2.0, 3.0, 4.5, 6.75, 10.125]


def _lost(thresholds):
    import numpy as np

    return np.asarray(_GRID)[:, None] < np.asarray(thresholds)[None, :]


def _censored_above(config, seed):
    """Every run loses lock at every SIR of the grid when the object hovers; a typical run otherwise."""
    from tvtrack.papers.p003_rotating_marker_tracker import estimators

    thr = [20.0] * 6 if config["interference_motion"] == "hovering" else [0.6, 0.7, 0.65, 0.8, 0.6, 0.7]
    lost = _lost(thr)
    e = estimators.threshold(lost, _GRID)
    b = estimators.threshold_bound(lost, _GRID)
    return {"C": e, "_map": {"rotating 1": e, "rotating 5": e}, "_map_bound": {"rotating 1": b, "rotating 5": b}}


def _explored():
    from tvtrack.explore import explore
    from tvtrack.register import Register
    from tvtrack.verdicts import InBand

    reg = Register([REGISTER["interference_motion"]])
    return explore(_censored_above, reg, {"C": InBand("t", high=100.0)}, seed=1, replicates=3, joint=0)


def test_the_threshold_is_called_a_typical_breaking_sir_against_the_papers_loss_free_value():
    """The geometric mean of the runs' breaking SIRs lies below a loss-free threshold even where the paper holds: the
    sentences name it a typical breaking SIR and the paper's 2 and 3 loss-free, and say the claims read the loss
    shares."""
    from tvtrack.papers.p003_rotating_marker_tracker import prose

    text = prose.threshold_conditions(_explored(), "rotating 1", 2.0)
    assert "typical (geometric-mean) SIR at which lock breaks with 1 interferer" in text
    assert "the paper's loss-free 2" in text and "marker's threshold" not in text
    assert "loss-free thresholds" in prose.LOSS_FREE and "shares of runs that lost lock" in prose.LOSS_FREE
    first = _censored_above({"interference_motion": "moving"}, 0)["_map_bound"]
    summary = prose.typical_against_paper(first)
    assert "typical (geometric-mean) SIR at which lock breaks is below the paper's loss-free 3" in summary
    assert "even where the paper holds" in summary and "The threshold with five" not in summary


def test_an_extrapolated_typical_value_leads_with_what_the_runs_show():
    """'8.27 [6.75, 10.1] (extrapolated)' read as a measured interval; every run lost lock up to the grid's top, so
    only a lower bound is known and the placed estimate is said to be extrapolated."""
    from tvtrack.papers.p003_rotating_marker_tracker import prose

    text = prose.threshold_conditions(_explored(), "rotating 1", 2.0)
    assert "at least 8.27 (some runs lost lock even at the highest SIR run" in text
    assert "placed half a grid step above it: 8.27 [6.75, 10.1], extrapolated)" in text
    assert "] (extrapolated)" not in text
    out = _censored_above({"interference_motion": "hovering"}, 0)
    assert prose.show(out["_map"]["rotating 1"]).endswith("placed half a grid step beyond its edge)")


def test_the_register_table_and_the_pinned_conditions_speak_in_titles_and_phrases():
    from tvtrack.papers.p003_rotating_marker_tracker import prose

    table = REGISTER.to_markdown()  # the core's table, in the register's titles and phrases
    for name in (
        "motion_scale",
        "interference_motion",
        "sinusoid_hz",
        "fig2_law",
        "bandwidth_reading",
        "slope_range",
        "loss_window_s",
        "static_gate",
        "edge_norm",
        "decoy_brightness",
        "B_n",
        "w_n",
    ):
        assert name not in table, name
    assert REGISTER["motion_scale"].title in table
    assert f"- {REGISTER.describe(REGISTER.pinned[0])}" in table
    assert "x_r and y_r: the object centre's x and y coordinates" in prose.PART_TAGS and "omega" in prose.PART_TAGS


def test_the_threshold_map_labels_rows_by_phrase_and_names_its_axis_in_words():
    fig, caption = plots.threshold_map_figure(_explored(), ("interference_motion",))
    labels = [t.get_text().replace("\n", " ") for t in fig.axes[0].get_yticklabels()]
    xlabel = fig.axes[0].get_xlabel()
    plt.close(fig)
    assert REGISTER.describe({"interference_motion": "hovering"}) in labels
    assert not [x for x in labels if "interference_motion" in x or " = " in x]
    assert xlabel.startswith("typical (geometric-mean) SIR at which lock breaks")
    assert "loss-free 2 (one interferer) and 3 (five)" in caption


def test_the_loss_curve_caption_says_its_bars_are_two_sided_and_the_verdicts_one_sided():
    import numpy as np

    from tvtrack.counts import zero_events_bound
    from tvtrack.papers.p003_rotating_marker_tracker import study

    sirs = np.array(study.SIR_GRID)
    lost = sirs[:, None] < np.full((1, 6), 1.0)
    curves = [{f"{m}/{k}": lost for m in ("rotating", "static") for k in (1, 5)}] * 5
    fig, caption = plots.loss_curves_figure(curves, sirs, 5.0)
    plt.close(fig)
    assert "30 runs per point" in caption and "two-sided 95 % Clopper-Pearson" in caption
    assert f"one-sided 95 % bound ({zero_events_bound(30):.2g} for 0 of 30)" in caption


def test_fig2_caption_names_panels_by_place_and_the_bound_figure_keeps_an_interval_to_zero_on_its_axis():
    import numpy as np

    from tvtrack.montecarlo import Estimate

    t = np.linspace(0, 1, 5)
    f = {"t2": t, "omega_hat": t, "omega": t, "r_hat": t, "r": t}
    fig, caption = plots.fig2_figure(f)
    plt.close(fig)
    assert "(a)" not in caption and "(top)" in caption and "(bottom)" in caption
    est = lambda v, lo: Estimate(v, float("nan"), lo, 1.2 * v, 6, 0.95, "t")  # noqa: E731
    cb = {
        "rms": {"loops 10 Hz": est(0.5, 0.4), "loops 40 Hz": est(5.0, 0.0), "EKF (velocity)": est(0.3, 0.25)},
        "bound": {1: 0.1, 8: 0.09},
        "best_loops": {"bandwidth_hz": 10.0, "edge": False},
    }
    fig, caption = plots.bound_figure(cb)
    left = fig.axes[0].get_xlim()[0]
    plt.close(fig)
    assert left > 0 and "drawn to the axis' left edge" in caption


def test_the_exploration_is_described_as_it_runs():
    """One-at-a-time conditions run on the default's replicate seeds; an unprinted setting makes ``depends`` too;
    the shares are over every explored configuration, listed part by part."""
    import json
    from pathlib import Path

    nb = Path(__file__).resolve().parents[2] / "notebooks" / "003_rotating_marker_tracker.ipynb"
    cells = ["".join(c["source"]) for c in json.loads(nb.read_text())["cells"]]
    register = next(c for c in cells if c.startswith("## 2. What the paper left unstated"))
    assert "first\nreplicate's draws" not in register and "default's\nreplicate seeds" in register
    assert "never\nprinted flips decisively is labelled depends" in register and "`depends`" not in register
    assert "(kind reading, statistic or comparator)" not in register
    verdicts = next(c for c in cells if c.startswith("## 10. Verdicts"))
    assert "share of\njoint configurations" not in verdicts and "all the configurations explored for it" in verdicts
    assert any("exploration_lines(ex_t, ex_i)" in c for c in cells)
