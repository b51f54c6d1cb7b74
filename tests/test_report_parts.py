"""The first screen says which parts of a claim hold, carries a held claim's caveat and the flips that runs which
lost lock carry; every notebook's exploration section shows each part's agree / flip / undecided, its flips and
the entries that move it most (:mod:`tvtrack.part_lines`)."""

from __future__ import annotations

import copy

from record_fixtures import DEPENDS


def _part(verdict, label="depends", flips=(), share=None, **more):
    return {"verdict": verdict, "label": label, "flips": list(flips), "share": share, **more}


def _claim(cid, verdict, parts, **more):
    c = copy.deepcopy(DEPENDS) | {"id": cid, "verdict": verdict, **more}
    c["robustness"]["parts"] = parts
    return c


SHARE = {"agree": 40, "flip": 2, "undecided": 6, "design": 48, "decided": 42, "ci_low": 0.7, "ci_high": 0.9}
FLIP = {"text": "a detection counts within 0.25 s", "side": "reading", "kind": "single", "verdict": "not reproduced"}
FLIP["changed"] = {"delay": 0.25}


def test_a_claim_that_holds_in_part_says_which_parts_hold_and_which_do_not():
    from tvtrack.pipeline.report import holding_lines

    parts = {
        "faster compensation": _part("reproduced", flips=[FLIP]),
        "min RMS vs IMM": _part("not reproduced", flips=[FLIP]),
        "finite differences, 2 points": _part("not reproduced", flips=[FLIP]),
        "rise_time": _part("undecided", label="-"),
    }
    line = holding_lines({"001_maneuver": (None, {"claims": [_claim("C001-4", "partly", parts)]})})[0]
    assert line.startswith("- **Hold in part** (label in brackets, the kind of change that flips it, and which parts")
    assert (
        "(depends: a reading — holds for “faster compensation”; fails for “min RMS vs IMM” and “finite differences, 2 points”; "
        "undecided for “rise time”)."
    ) in line


def test_a_claim_that_holds_carries_its_caveat_and_a_flip_that_lost_runs_carry():
    from tvtrack.pipeline.report import holding_lines

    lost = {"lost": 127, "runs": 1200, "in_lock_verdict": "reproduced", "replicates": 2, "carried": True}
    world = FLIP | {"side": "world", "text": "sigma_1 = 0.2 T drift spread", "lost_runs": lost}
    caveat = "The detector's settings were chosen to give the 0.5 s delay, so the default's delay is a check."
    held = _claim("C001-1", "reproduced", {"claim": _part("reproduced", flips=[])}, caveat=caveat)
    carried = _claim("C000-9", "reproduced", {"claim": _part("reproduced", label="limited", flips=[world])})
    line = holding_lines({"000_x": (None, {"claims": [carried]}), "001_y": (None, {"claims": [held]})})[0]
    assert (
        "(depends — the detector's settings were chosen to give the 0.5 s delay, so the default's delay is a check)"
        in line
    )  # the whole caveat, a clause of the brackets
    assert (
        "(depends: a world — its only flip, under sigma\\_1 = 0.2 T drift spread, rests on the 127 of the 1200 runs of 2 replicates that "
        "lost lock there: over those replicates' runs in lock alone it is reproduced)"
    ) in line


def test_the_unexplored_sentence_quotes_the_part_with_the_fewest_decided_configurations():
    from tvtrack.wording import claim_summary

    def share(agree, undecided):
        return {"agree": agree, "flip": 0, "undecided": undecided, "design": 49, "decided": agree, "decided_needed": 32}

    parts = {
        "worse than fine pixels": _part("reproduced", label="unexplored", share=share(14, 35)),
        "better than the marks": _part("reproduced", label="unexplored", share=share(5, 44)),
    }
    c = _claim("C002-8", "reproduced", parts)
    c["robustness"]["label"] = "unexplored"
    text = claim_summary(c)
    assert "only 5 of the 49 changes explored for it (its part better than the marks) decided it and 44" in text
    assert "only 14 of" not in text


def test_an_undecided_claim_card_says_its_label_covers_its_decided_parts_only():
    from tvtrack.results import Claim
    from tvtrack.wording import claim_fields

    parts = {"fine pixels": _part("reproduced", label="robust"), "coarse pixels": _part("undecided", label="-")}
    record = _claim("C002-7", "undecided", parts)
    record["robustness"]["label"] = "robust"
    claim = Claim.__new__(Claim)
    claim.__dict__.update(claim_fields(record))
    assert claim._repr_markdown_().startswith("**C002-7: undecided, robust in its decided parts only**.")


def test_a_claim_not_checkable_has_no_label_because_the_default_has_no_verdict_to_flip():
    from tvtrack.labels import _coverage
    from tvtrack.part_lines import coverage_words

    old = "no label (no part decided at the default: nothing to flip) over 49 distinct configurations"
    assert coverage_words({"coverage": old}, "not checkable").startswith(
        "no label (not checkable at the default: no verdict to flip)"
    )
    assert coverage_words({"coverage": old}, "undecided") == old
    said = "no label (not checkable: nothing measured) over 1 distinct configurations"  # records of an older wording
    assert coverage_words({"coverage": said}, "not checkable").startswith("no label (not checkable at the default:")
    text = _coverage("-", {"claim": {"label": "-", "verdict": "not checkable"}}, [], [1, 2, 3], [], False, 0, False)
    assert text.startswith("no label (not checkable at the default: no verdict to flip) over 0 distinct")


class _Exploration:
    def __init__(self, records):
        self.rules = dict.fromkeys(records)
        self._records = records

    def record(self, cid, rule=None):
        return self._records[cid]


def test_the_exploration_lines_give_every_part_its_counts_flips_and_moving_entries():
    from tvtrack.part_lines import exploration_lines

    sens = [{"title": "camera frame rate", "score": 0.46}, {"title": "half-window", "score": 0.24}]
    sens += [{"title": "noise", "score": 0.01}]
    record = {
        "coverage": "depends over 48 distinct configurations; x 3 independent replicates",
        "label": "depends",
        "parts": {
            "median": _part("reproduced", flips=[FLIP], share=SHARE, sensitivity=sens),
            "missed": _part("undecided", label="-", runs_to_decide={"text": "about 12 replicates decide it"}),
        },
    }
    text = exploration_lines(_Exploration({"C001-1": record}), _Exploration({"C001-2": record}))
    assert text.startswith("Each claim part over every configuration explored for it") and "- **C001-2**:" in text
    lines = text.split("\n")[2:]
    assert lines[0] == "- **C001-1**: depends over 48 distinct configurations; x 3 independent replicates"
    assert lines[1] == (
        "  - **C001-1 (median)**: reproduced, depends; 40 agree, 2 flip and 6 stay undecided of 48 explored "
        "configurations (share agreeing 0.70-0.90, 95 %); flipped by: not reproduced when a detection counts within "
        "0.25 s (a reading of the paper's text); its value moves most with: camera frame rate (46 %); half-window (24 %)."
    )
    assert lines[2] == (
        "  - **C001-1 (missed)**: undecided, no label (undecided at the default: nothing to flip); about 12 "
        "replicates decide it."
    )


def test_a_claim_no_configuration_flips_says_how_many_stayed_undecided():
    from tvtrack.part_lines import unflipped_words

    def share(undecided):
        return {"agree": 49 - undecided, "flip": 0, "undecided": undecided, "design": 49}

    two = _claim(
        "C002-8",
        "reproduced",
        {"worse": _part("reproduced", share=share(35)), "better": _part("reproduced", share=share(44))},
    )
    assert unflipped_words(two) == (
        "no explored configuration flips it (worse: 35 of the 49 explored for it stayed undecided; better: 44 of the "
        "49 explored for it stayed undecided)"
    )
    one = _claim("C002-7", "undecided", {"fine": _part("reproduced", share=share(7)), "coarse": _part("undecided")})
    assert unflipped_words(one) == (
        "no explored configuration flips it (fine: 7 of the 49 explored for it stayed undecided; coarse: undecided at "
        "the default, so nothing to flip)"
    )
    none = _claim("C002-6", "undecided", {"claim": _part("undecided", label="-")})
    assert unflipped_words(none) == "nothing to flip: undecided at the default"
