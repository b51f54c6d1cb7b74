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
