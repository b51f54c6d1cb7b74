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
    parts |= {"failed": _part("not reproduced", label="robust")}  # holds in part, one part still open
    claim.__dict__.update(claim_fields(_claim("C002-7", "partly", parts) | {"robustness": record["robustness"]}))
    claim.robustness["parts"] = parts
    assert claim._repr_markdown_().startswith("**C002-7: partly, robust in its decided parts only**.")


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


OFF = {"agree": 1, "flip": 2, "undecided": 0}
OFF_FLIPS = [{"changed": {"rate": 5}, "verdict": "not reproduced", "text": "a camera at 5 frames/s"}]


def test_a_part_flipped_only_outside_the_operating_point_names_those_flips_and_is_not_said_unflipped():
    from tvtrack.part_lines import part_line, unflipped_words

    share = SHARE | {"agree": 42, "flip": 0, "off_operating_point": OFF}
    part = _part("reproduced", label="robust", share=share, off_operating_point=OFF | {"flips": OFF_FLIPS})
    line = part_line("C001-1", part)
    assert "no explored configuration flips it" not in line  # 2 of them flip, outside the operating point
    assert "no configuration at the paper's operating point flips it" in line
    assert (
        "outside the paper's operating point (counted beside the label) flipped by: not reproduced when a camera at 5"
        in line
    )
    words = unflipped_words(_claim("C001-1", "reproduced", {"claim": part}))
    assert words.startswith("no configuration at the paper's operating point flips it (")
    assert (
        "while outside the paper's operating point, counted beside the label, it reads not reproduced when a" in words
    )


def test_a_part_whose_counted_flips_have_no_name_is_not_said_unflipped():
    from tvtrack.part_lines import part_line, unflipped_words

    line = part_line("C001-1", _part("reproduced", share=SHARE))  # 2 flip in the share, none named
    assert "no explored configuration flips it" not in line
    assert "its 2 flips are not named in the record" in line
    words = unflipped_words(_claim("C001-1", "reproduced", {"claim": _part("reproduced", share=SHARE)}))
    assert words.startswith("no named configuration flips it (") and ", 2 flips but are not named" in words


def test_unflipped_words_say_nothing_to_flip_for_a_claim_not_checkable_or_never_explored():
    from tvtrack.part_lines import unflipped_words

    nc = _claim("C002-1", "not checkable", {"claim": _part("not checkable", label="-")})
    assert unflipped_words(nc) == "nothing to flip: not checkable at the default"
    mixed = {"a": _part("not checkable", label="-"), "b": _part("undecided", label="-")}
    assert unflipped_words(_claim("C002-2", "undecided", mixed)) == "nothing to flip: no part decided at the default"
    empty = {"agree": 0, "flip": 0, "undecided": 0, "design": 0, "decided": 0}
    bare = _claim("C002-3", "reproduced", {"claim": _part("reproduced", label="unexplored", share=empty)})
    assert unflipped_words(bare) == "no configuration was explored for it"
    norecord = _claim("C002-4", "reproduced", {})
    norecord.pop("robustness")
    assert unflipped_words(norecord) == "no configuration was explored for it"


def test_an_older_share_without_flips_says_its_count_is_of_the_decided_configurations_only():
    from tvtrack.part_lines import part_line

    line = part_line("C001-1", _part("reproduced", share={"agree": 5, "decided": 8}))
    assert "5 of the 8 decided configurations agree (this older record does not count the undecided ones)" in line
    assert "its 3 flips are not named in the record" in line  # 8 decided, 5 agree
    assert "of None" not in part_line("C001-1", _part("reproduced", share={"agree": 5, "design": 8}))


def test_a_part_that_holds_in_part_is_named_among_the_parts_held():
    from tvtrack.part_lines import parts_held

    parts = {"a": _part("reproduced"), "b": _part("partly"), "c": _part("not reproduced")}
    assert parts_held(_claim("C001-5", "partly", parts)) == "holds for “a”; holds in part for “b”; fails for “c”"


def test_a_held_claim_with_several_flips_does_not_call_the_carried_one_its_flip():
    from tvtrack.part_lines import hold_note

    lost = {"lost": 5, "runs": 600, "in_lock_verdict": "reproduced", "carried": True}
    world = FLIP | {"side": "world", "text": "a weaving target", "lost_runs": lost}
    c = _claim("C001-6", "reproduced", {"claim": _part("reproduced", label="limited", flips=[FLIP, world])})
    assert hold_note(c).startswith("one of its 2 flips, under a weaving target, rests on the 5 of the 600 runs")


def test_a_flip_whose_smaller_subsets_stayed_undecided_is_not_shown_as_isolated():
    from tvtrack.part_lines import part_line

    joint = FLIP | {"text": "a detection counts within 0.25 s and a weaving target", "kind": "joint"}
    joint |= {"side": "unattributed", "undecided_subsets": ["a weaving target"]}
    line = part_line("C001-1", _part("reproduced", flips=[joint], share=SHARE))
    assert (
        "and a weaving target (a combination of changes that no smaller set of them was found to flip; the smallest "
        in line
    )
    assert "found: a weaving target stays undecided)" in line


def test_a_claim_holding_in_part_with_an_undecided_part_is_robust_in_its_decided_parts_only():
    from tvtrack.pipeline.report import holding_lines

    parts = {"fine": _part("reproduced", label="robust"), "coarse": _part("not reproduced", label="robust")}
    parts["rise"] = _part("undecided", label="-")
    c = _claim("C001-8", "partly", parts)
    c["robustness"]["label"] = "robust"
    line = holding_lines({"001_maneuver": (None, {"claims": [c]})})[0]
    assert (
        "C001-8 (robust in its decided parts only — holds for “fine”; fails for “coarse”; undecided for “rise”)" in line
    )


def test_an_older_record_with_a_list_of_parts_says_which_parts_hold():
    from tvtrack.part_lines import parts_held

    c = _claim("C001-9", "partly", [{"name": "a", "verdict": "reproduced"}, {"name": "b", "verdict": "not reproduced"}])
    assert parts_held(c) == "holds for “a”; fails for “b”"


def test_a_provisional_record_never_reads_robust_in_its_coverage_line():
    """A design too small to label (C000-8 at the paper profile) is shown provisional: its coverage line must not
    go on to call it robust ("provisional: robust over 8 ...")."""
    from tvtrack.part_lines import record_lines

    record = {
        "label": "robust",
        "provisional": True,
        "coverage": "robust over 8 distinct configurations (6 one at a time over 3 register entries, 2 joint "
        "samples); x 6 independent replicates; provisional: 8 distinct configurations are too few for a share",
        "parts": {"claim": _part("reproduced", label="robust", share=SHARE | {"flip": 0, "agree": 42})},
    }
    head, line = record_lines("C000-8", record)
    assert head.startswith("- **C000-8**: provisional over 8 distinct configurations (")
    assert "robust" not in head and "robust" not in line and "provisional" in line


def test_an_older_record_with_a_list_of_parts_lists_its_flips():
    """``claim_flips`` read ``parts`` as a mapping only: an older record's list of parts raised AttributeError."""
    from tvtrack.wording import claim_flips

    c = _claim("C001-9", "partly", [{"name": "a", "verdict": "reproduced", "flips": [FLIP]}, {"name": "b"}])
    assert [(f["text"], f["part"]) for f in claim_flips(c)] == [(FLIP["text"], "a")]
    assert [f["part"] for f in claim_flips(c, "a")] == ["a"] and claim_flips(c, "b") == []


def test_a_flip_through_two_parts_keeps_the_lost_runs_that_only_one_copy_carries():
    """The same flip through two parts is said once; the lost-runs note on the second part's copy was dropped with
    the copy, so the flip read as resting on runs in lock."""
    from tvtrack.wording import claim_flips

    lost = {"lost": 5, "runs": 600, "in_lock_verdict": "reproduced", "carried": True}
    parts = {
        "first": _part("reproduced", flips=[FLIP]),
        "second": _part("reproduced", flips=[FLIP | {"lost_runs": lost}]),
    }
    flips = claim_flips(_claim("C001-6", "reproduced", parts))
    assert len(flips) == 1 and flips[0]["lost_runs"] == lost and flips[0]["part"] == "first"


def test_a_part_some_explored_configurations_do_not_measure_says_how_many():
    """C000-3's psi_A parts do not exist under a contrast of 0 (its reading there reads other parts): their shares
    are over the configurations that measure them, and the line says how many of the claim's do not."""
    from tvtrack.part_lines import part_line, record_lines

    fewer = {**SHARE, "agree": 34, "design": 42, "decided": 36}
    record = {
        "label": "depends",
        "parts": {"a": _part("reproduced", share=SHARE), "b": _part("reproduced", share=fewer)},
    }
    a, b = record_lines("C9-1", record)[1:]
    assert "6 of 48 explored configurations do not measure this part" in b and "do not measure" not in a
    assert "do not measure" not in part_line("C9-1", _part("reproduced", share=SHARE))  # no claim to compare with


def test_every_part_some_configurations_do_not_measure_is_counted_against_the_claims_explored_configurations():
    """Six configurations explored at the operating point (a pinned flip, a searched combination and one outside
    the point are not among them): a part four of them measure misses two, one five measure misses one, however
    many the widest part's share counts."""
    from tvtrack.part_lines import record_lines

    rows = [{"changed": {f"e{i}": 1}, "kind": "single"} for i in range(5)] + [
        {"changed": {"e0": 1, "e1": 1}, "kind": "joint"}
    ]
    rows += [{"changed": {"e9": 1}, "kind": "pinned"}, {"changed": {"e0": 2}, "kind": "combination"}]
    rows += [{"changed": {"e8": 1}, "kind": "single", "off_operating_point": True}]
    four, five = (
        {"agree": n, "flip": 0, "undecided": 0, "design": n, "decided": n, "ci_low": 0.4, "ci_high": 1.0}
        for n in (4, 5)
    )
    record = {
        "label": "robust",
        "conditions": rows,
        "parts": {"a": _part("reproduced", share=four), "b": _part("reproduced", share=five)},
    }
    a, b = record_lines("C9-1", record)[1:]
    assert "(2 of 6 explored configurations do not measure this part)" in a
    assert "(1 of 6 explored configurations does not measure this part)" in b
