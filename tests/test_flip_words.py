"""How a named flip's kind is said (``tvtrack.flip_words``), on hand-built flips and records whose right words are
known by construction: each kind alone, several of one kind, mixes of kinds (each change with its own kind), more
changes than the count words name, an unknown side, and the bracket of a claim whose verdict is already undecided."""

from tvtrack.flip_words import flip_kinds, flip_with_kind, label_basis, mixed_kinds, under_words

_KINDS = {"r": "reading", "r2": "reading", "s": "unreported setting", "s2": "unreported setting", "w": "regime"}
REGISTER = [{"name": k, "title": k, "kind": v, "phrases": {}} for k, v in _KINDS.items()]
# six readings and one unreported setting, each value with a phrase of its own: a mix of seven changes
SEVEN = {f"a{i}": "reading" for i in range(1, 7)} | {"u": "unreported setting"}
REGISTER_7 = [{"name": k, "title": k, "kind": v, "phrases": {"1": f"{k} moved"}} for k, v in SEVEN.items()]
READING_TAG, SETTING_TAG = "(a reading of the paper's text)", "(a setting the paper never printed)"


def _claim(*flips: tuple, register=REGISTER, verdict="reproduced", parts=1, conditions=()) -> dict:
    """A claim whose first part has the named ``(text, side, changed)`` flips (``parts`` parts in all)."""
    named = [{"text": t, "side": side, "changed": ch, "verdict": "not reproduced"} for t, side, ch in flips]
    all_parts = {"claim": {"verdict": verdict, "flips": named}}
    all_parts |= {f"p{i}": {"verdict": verdict, "flips": []} for i in range(1, parts)}
    rob = {"register": register, "label": "depends", "parts": all_parts, "conditions": list(conditions)}
    return {"id": "C9-1", "verdict": verdict, "robustness": rob}


def test_an_entry_the_register_does_not_know_is_a_reading_and_a_known_one_keeps_its_kind():
    record = {"register": REGISTER}
    assert flip_kinds({"changed": {"nowhere": 1}}, record) == {"reading"}
    assert flip_kinds({"changed": {"nowhere": 1, "s": 2, "w": 3}}, record) == {"reading", "setting", "world"}
    assert flip_kinds({"changed": {}}, record) == set() and flip_kinds({}, record) == set()


def test_a_claim_no_change_flips_has_no_bracket():
    assert label_basis(_claim()) == ""


def test_more_changes_than_the_count_words_name_are_counted_in_digits():
    """Two to five are words; six or more are digits, never "None"."""
    six = {f"a{i}": 1 for i in range(1, 7)}
    assert label_basis(_claim(("six", "reading", six))) == "6 readings together"
    assert label_basis(_claim(("six", "world", six))) == "6 worlds together"
    settings = {f"x{i}": 1 for i in range(6)}
    setting_register = [{"name": k, "title": k, "kind": "unreported setting", "phrases": {}} for k in settings]
    assert label_basis(_claim(("six", "setting", settings), register=setting_register)) == (
        "6 unprinted settings together"
    )
    seven = dict.fromkeys(SEVEN, 1)
    assert label_basis(_claim(("seven", "setting", seven), register=REGISTER_7)) == (
        "an unprinted setting with 6 other changes"
    )
    five = {k: 1 for k in ("a1", "a2", "a3", "a4", "u")}
    assert label_basis(_claim(("five", "setting", five), register=REGISTER_7)) == (
        "an unprinted setting with four other changes"
    )
    # a combination no smaller subset isolates, of entries the register does not know: all readings
    assert label_basis(_claim(("six", "unattributed", six), register=[])) == "a combination of 6 changes, all readings"


def test_a_side_the_words_do_not_know_is_said_as_a_world():
    """A flip whose side is none of reading, setting, world or combination is never said as a reading: the bracket
    and the record's list say a world, the paragraph says "another change"."""
    assert label_basis(_claim(("t", "elsewhere", {"w": 1}))) == "a world"
    assert label_basis(_claim(("t", "elsewhere", {"w": 1, "r": 1}))) == "two worlds together"
    flip = {"text": "t", "side": "elsewhere", "changed": {"w": 1}}
    assert flip_with_kind(flip, {"register": REGISTER}) == "t (a world beyond the paper)"
    assert under_words(flip, {"register": REGISTER}) == "another change: t"


def test_a_setting_with_a_reading_also_flipping_a_claim_a_reading_flips_is_a_setting_with_other_changes():
    """Beside the reading named first, a setting that moves the whole verdict only with another change is "a
    setting with other changes too", not "worlds together"."""
    reading, joint = ("r", "reading", {"r": 1}), ("r2 and s", "setting", {"r2": 1, "s": 1})
    assert label_basis(_claim(reading, joint)) == "a reading; a setting with other changes too"
    worlds = ("w and r2", "world", {"w": 1, "r2": 1})
    assert label_basis(_claim(reading, joint, worlds)) == (
        "a reading; a setting with other changes too; worlds together too"
    )


def test_an_undecided_claim_a_world_leaves_undecided_is_not_said_to_be_left_undecided():
    """Where the claim reads undecided already, a world that leaves it undecided is not said to leave it so: the
    bracket names the world by the part it flips. The same world beside a decided claim whose parts it opens is
    named as leaving it undecided."""
    reading, world = ("r", "reading", {"r": 1}), ("w", "world", {"w": 1})
    open_there = [{"changed": {"w": 1}, "verdict": "undecided"}]
    claim = _claim(reading, world, verdict="undecided", parts=2, conditions=open_there)
    assert label_basis(claim) == "a reading; a world, in a part only"
    # decided at the default, undecided under the world whatever its open part turns out: "leaves it undecided"
    row = {"changed": {"w": 1}, "verdict": "undecided", "parts": {"claim": "undecided", "p1": "reproduced"}}
    decided = _claim(reading, world, verdict="reproduced", parts=2, conditions=[row])
    assert label_basis(decided) == "a reading; a world leaves it undecided"


def test_a_mix_of_kinds_names_each_change_and_a_combination_says_none_flips_it_alone():
    record = {"register": REGISTER_7}
    tags = f"a1 moved {READING_TAG} and u moved {SETTING_TAG}"
    mixed = {"text": "a1 and u", "side": "setting", "changed": {"a1": 1, "u": 1}}
    assert mixed_kinds(mixed, record) == tags
    assert flip_with_kind(mixed, record) == f"{tags}, together"
    unattributed = {**mixed, "side": "unattributed"}
    assert flip_with_kind(unattributed, record) == f"{tags}, together (none of them flips the claim alone)"
    assert under_words(unattributed, record) == f"two changes together: {tags}"
    # one kind only: no mix, one bracket
    readings = {"text": "a1 and a2", "side": "reading", "changed": {"a1": 1, "a2": 1}}
    assert mixed_kinds(readings, record) == ""
    assert flip_with_kind(readings, record) == "a1 and a2 (a reading of the paper's text)"


def test_a_paragraph_counts_six_or_more_changes_in_digits():
    record = {"register": REGISTER_7}
    six_mixed = {"text": "t", "side": "setting", "changed": {k: 1 for k in ("a1", "a2", "a3", "a4", "a5", "u")}}
    each = ", ".join(f"a{i} moved {READING_TAG}" for i in range(1, 6))
    assert under_words(six_mixed, record) == f"6 changes together: {each} and u moved {SETTING_TAG}"
    six_readings = {"text": "six readings", "side": "reading", "changed": {f"a{i}": 1 for i in range(1, 7)}}
    assert under_words(six_readings, record) == "6 other readings of the paper's text together: six readings"


def test_the_bracket_names_the_flip_of_fewest_changes_whichever_search_found_it():
    """A joint configuration of two worlds that is its own smallest flipping subset is named before a combination of
    three worlds found inside another joint configuration: the fewest changes first, not the search that found it
    (a label said "three worlds together" where two worlds together flip it)."""
    register = REGISTER + [{"name": k, "title": k, "kind": "regime", "phrases": {}} for k in ("w2", "w3")]
    claim = _claim(
        ("w, w2 and w3", "world", {"w": 1, "w2": 1, "w3": 1}),
        ("w2 and w3", "world", {"w2": 2, "w3": 2}),
        register=register,
    )
    named = claim["robustness"]["parts"]["claim"]["flips"]
    named[0]["kind"], named[1]["kind"] = "combination", "joint"
    assert label_basis(claim) == "two worlds together"


def test_several_changes_of_one_kind_are_counted_in_the_words_that_introduce_them():
    """Two worlds together are never introduced as "a world beyond the paper", nor two settings as one."""
    register = REGISTER + [{"name": "w2", "title": "w2", "kind": "regime", "phrases": {}}]
    worlds = {"text": "w and w2", "side": "world", "changed": {"w": 1, "w2": 1}}
    assert under_words(worlds, {"register": register}) == "two worlds beyond the paper together: w and w2"
    settings = {"text": "s and s2", "side": "setting", "changed": {"s": 1, "s2": 1}}
    assert under_words(settings, {"register": REGISTER}) == ("two settings the paper never printed, together: s and s2")
    one = {"text": "w", "side": "world", "changed": {"w": 1}}
    assert under_words(one, {"register": REGISTER}) == "a world beyond the paper: w"


def _labelled(cid: str, measured: dict, conds: list, entries: list, single: bool = False) -> dict:
    """A claim the label machinery records: an AllOf of the band per part (``single``: the band alone on part a)."""
    from tvtrack.labels import label_parts
    from tvtrack.verdicts import AllOf, InBand

    band = InBand("mean", -0.5, 0.5, "px")
    rule = band if single else AllOf({n: band for n in measured})
    m = measured["a"] if single else measured
    conds = [{**c, "measured": c["measured"]["a"]} for c in conds] if single else conds
    rob = label_parts(rule, m, [{"seed": s, "measured": m} for s in (1, 2, 3)], conds, entries)
    rob["register"] = [e.to_dict() for e in entries]  # as the explorer's record carries it
    verdict = rule.judge(m).verdict
    return {"id": cid, "verdict": verdict, "rule": rule.to_dict(), "measured": m, "robustness": rob, "paper_value": "0"}


def _entries(*names: str) -> list:
    from tvtrack.register import Entry

    return [
        Entry(n, "reading" if n.startswith("r") else "regime", 0, (0, 1), "e", phrases={1: f"{n} moved"}) for n in names
    ]


def test_why_a_claim_fails_reads_its_main_parts_value_and_the_flip_its_summary_names():
    """Whole sentences: the value of the part that fails worst-labelled (3 px, not the other part's 2 px), the whole
    claim's verdict under the flip ("in part"), a claim of one rule, and a whole verdict left open ("reads")."""
    from tvtrack.flip_words import why_not_clause
    from tvtrack.montecarlo import Estimate

    hold, fail, two, open_ = Estimate.exact(0.0), Estimate.exact(3.0), Estimate.exact(2.0), None
    conds = [
        {"changed": {"r1": 1}, "kind": "single", "measured": {"a": two, "b": hold}},
        {"changed": {"w1": 1}, "kind": "single", "measured": {"a": hold, "b": hold}},
    ]
    claim = _labelled("C9-1", {"a": two, "b": fail}, conds, _entries("r1", "w1"))
    assert why_not_clause(claim) == (
        "mean is 3 px, against [-0.5, 0.5] px (the paper: 0); it holds in part under a reading of the paper's text: "
        "r1 moved"
    )
    one = _labelled("C9-2", {"a": fail}, conds[1:], _entries("w1"), single=True)
    assert why_not_clause(one) == (
        "mean is 3 px, against [-0.5, 0.5] px (the paper: 0); it holds under a world beyond the paper: w1 moved"
    )
    open_ = Estimate(0.45, 0.05, 0.3, 0.6, 50, method="t")  # straddles the band's edge: part a undecided there
    left = [{"changed": {"r1": 1}, "kind": "single", "measured": {"a": open_, "b": hold}}]
    assert why_not_clause(_labelled("C9-3", {"a": fail, "b": fail}, left, _entries("r1"))).endswith(
        "; it reads undecided under a reading of the paper's text: r1 moved"
    )


def test_what_would_turn_a_claim_falls_back_to_the_strongest_change_that_turns_the_whole_claim():
    """Part b (the one that fails) is moved only by a reading that leaves the claim partly holding; a world alone and
    two worlds together break parts a and c, so the whole claim fails: the sentence names the single world and counts the
    pair, never the reading."""
    from tvtrack.flip_words import turns_on_sentence
    from tvtrack.montecarlo import Estimate

    h, f = Estimate.exact(0.0), Estimate.exact(3.0)
    conds = [
        {"changed": {"r2": 1}, "kind": "single", "measured": {"a": h, "b": h, "c": f}},
        {"changed": {"w1": 1}, "kind": "single", "measured": {"a": f, "b": f, "c": f}},
        {"changed": {"w2": 1}, "kind": "single", "measured": {"a": h, "b": f, "c": h}},
        {"changed": {"w3": 1}, "kind": "single", "measured": {"a": h, "b": f, "c": h}},
        {"changed": {"w2": 1, "w3": 1}, "kind": "joint", "measured": {"a": f, "b": f, "c": f}},
    ]
    claim = _labelled("C9-4", {"a": h, "b": f, "c": h}, conds, _entries("r2", "w1", "w2", "w3"))
    assert claim["verdict"] == "partly"
    assert turns_on_sentence(claim) == (
        "C9-4 does not hold under a world beyond the paper: w1 moved (1 other smallest change flips it too; its verdict "
        "changes in 2 of 5 explored configurations)."
    )


def test_more_worlds_or_settings_than_the_count_words_name_are_counted_in_digits():
    six = {f"w{i}": 1 for i in range(6)}
    assert under_words({"text": "six", "side": "world", "changed": six}, {"register": []}) == (
        "6 worlds beyond the paper together: six"
    )
    assert under_words({"text": "six", "side": "setting", "changed": six}, {"register": []}) == (
        "6 settings the paper never printed, together: six"
    )


def test_a_mixed_flip_is_said_with_each_changes_own_kind_in_both_paragraph_sentences():
    """A reading and a world together (no subset flips alone): each change keeps its own kind in the sentence of a
    claim that holds and of one that fails, and two other changes are counted in the plural."""
    from tvtrack.flip_words import turns_on_sentence, why_not_clause
    from tvtrack.montecarlo import Estimate

    h, f = Estimate.exact(0.0), Estimate.exact(3.0)
    entries = _entries("r1", "w1", "w2", "w3")
    held = [
        {"changed": {"r1": 1}, "kind": "single", "measured": {"a": h, "b": h}},
        {"changed": {"w1": 1}, "kind": "single", "measured": {"a": h, "b": h}},
        {"changed": {"r1": 1, "w1": 1}, "kind": "joint", "measured": {"a": f, "b": h}},
        {"changed": {"w2": 1}, "kind": "single", "measured": {"a": f, "b": f}},
        {"changed": {"w3": 1}, "kind": "single", "measured": {"a": f, "b": f}},
    ]
    both = "two changes together: r1 moved (a reading of the paper's text) and w1 moved (a world beyond the paper)"
    assert turns_on_sentence(_labelled("C9-5", {"a": h, "b": h}, held, entries)) == (
        f"C9-5 holds only in part under {both} (2 other smallest changes flip it too; its verdict changes in 3 of 5 "
        "explored configurations)."
    )
    failed = [{**c, "measured": {"a": f if c["measured"]["a"] is h else h, "b": f}} for c in held[:3]]
    failed[2]["measured"] = {"a": h, "b": h}
    claim = _labelled("C9-6", {"a": f, "b": f}, failed, entries)
    assert why_not_clause(claim).endswith(f"; it holds under {both}")


def test_the_configurations_that_change_a_claims_verdict_are_counted_once_over_the_design():
    """Of the design's distinct configurations (a pinned known flip that repeats a joint sample counts once; the
    subset search's sub-combinations are not the design), those whose whole verdict is decided and differs."""
    from tvtrack.flip_words import whole_flips

    rows = [
        {"changed": {"r1": 1}, "kind": "single", "verdict": "not reproduced"},
        {"changed": {"w1": 1}, "kind": "single", "verdict": "reproduced"},
        {"changed": {"w2": 1}, "kind": "single", "verdict": "undecided"},  # not decided: no change counted
        {"changed": {"r1": 1, "w1": 1}, "kind": "joint", "verdict": "partly"},
        {"changed": {"w1": 1, "r1": 1}, "kind": "pinned", "verdict": "partly"},  # the same configuration again
        {"changed": {"w2": 1, "r1": 1}, "kind": "combination", "verdict": "not reproduced"},  # naming a flip only
    ]
    rows.append({"changed": {"r1": 2}, "kind": "single", "verdict": "reproduced"})  # the same entry, another value
    claim = {"verdict": "reproduced", "robustness": {"conditions": rows}}
    assert whole_flips(claim) == (2, 5, 0)
    assert whole_flips({"verdict": "reproduced", "robustness": None}) == (0, 0, 0)


def test_a_kind_that_flips_only_a_part_is_named_in_the_bracket_as_the_label_counts_it():
    """The label counts a part's flip ("changes the verdict, or a part's"): beside a reading that flips the whole
    claim, a world and a setting that each flip only a part are named, each "in a part only"."""
    reading, world, setting = ("r", "reading", {"r": 1}), ("w", "world", {"w": 1}), ("s", "setting", {"s": 1})
    held = [{"changed": {"w": 1}, "verdict": "reproduced"}, {"changed": {"s": 1}, "verdict": "reproduced"}]
    claim = _claim(reading, world, setting, verdict="reproduced", parts=2, conditions=held)
    assert label_basis(claim) == "a reading; a setting, in a part only; a world, in a part only"


def test_a_flip_the_design_has_no_row_for_turns_the_claim_by_its_own_verdict_and_counts_no_configuration():
    """A named flip whose configuration the record's rows do not hold (an older record) turns the whole claim by the
    flip's own verdict, and the sentence counts no configurations it has none of."""
    from tvtrack.flip_words import turns_on_sentence

    claim = _claim(("r moved", "reading", {"r": 1}))
    claim["robustness"]["register"] = []
    assert turns_on_sentence(claim) == "C9-1 does not hold under a reading of the paper's text: r moved."


def test_two_changes_whose_smaller_part_stays_undecided_are_said_to_be_perhaps_fewer():
    flip = {"text": "r and s", "side": "reading", "changed": {"r": 1, "r2": 1}, "verdict": "not reproduced"}
    claim = _claim()
    claim["robustness"]["parts"]["claim"]["flips"] = [{**flip, "undecided_subsets": [{"r": 1}]}]
    assert label_basis(claim) == "two readings together (or fewer: a smaller part of them stays undecided)"
    claim["robustness"]["parts"]["claim"]["flips"] = [flip]
    assert label_basis(claim) == "two readings together"


def test_the_configurations_counted_as_changing_a_verdict_are_those_the_label_counts_at_the_defaults_size():
    """A configuration given fewer runs than the default needed changes nothing (its parts read undecided, whatever
    its own verdict was); one outside the paper's operating point is counted beside the label, in neither number; a
    pinned known flip is not one of the design's configurations; a configuration whose whole verdict is undecided
    but whose decided part already rules out the default's verdict is counted apart, as one that cannot leave it as
    it is."""
    from tvtrack.flip_words import whole_flips

    parts = {"a": {"verdict": "reproduced"}, "b": {"verdict": "reproduced"}}
    rows = [
        {"changed": {"r1": 1}, "kind": "single", "verdict": "not reproduced", "parts": {"a": "not reproduced", "b": "not reproduced"}},
        {"changed": {"r2": 1}, "kind": "single", "verdict": "not reproduced", "parts": {"a": "undecided", "b": "undecided"},
         "undersized": {"a": "not reproduced", "b": "not reproduced"}},
        {"changed": {"w9": 1}, "kind": "single", "verdict": "not reproduced", "parts": {"a": "not reproduced", "b": "not reproduced"},
         "off_operating_point": True},
        {"changed": {"s1": 1}, "kind": "pinned", "verdict": "not reproduced", "parts": {"a": "not reproduced", "b": "not reproduced"}},
        {"changed": {"w1": 1}, "kind": "single", "verdict": "undecided", "parts": {"a": "not reproduced", "b": "undecided"}},
        {"changed": {"w2": 1}, "kind": "single", "verdict": "undecided", "parts": {"a": "reproduced", "b": "undecided"}},
        {"changed": {"w3": 1}, "kind": "joint", "verdict": "reproduced", "parts": {"a": "reproduced", "b": "reproduced"}},
    ]  # fmt: skip
    claim = {"verdict": "reproduced", "robustness": {"conditions": rows, "parts": parts}}
    assert whole_flips(claim) == (1, 5, 1)  # r1 changes it and w1 cannot leave it as it is, of r1, r2, w1, w2, w3


def test_a_configuration_left_undecided_that_cannot_keep_the_verdict_is_counted_apart_in_the_sentence():
    """A world that fails one part and leaves the other open does not decide the whole claim otherwise (its curve
    shows it undecided) but cannot leave it as it is: the sentence counts it apart, and the bracket names its kind."""
    from tvtrack.flip_words import turns_on_sentence, whole_flips
    from tvtrack.montecarlo import Estimate

    h, f = Estimate.exact(0.0), Estimate.exact(3.0)
    open_ = Estimate(0.45, 0.05, 0.3, 0.6, 50, method="t")
    conds = [
        {"changed": {"r1": 1}, "kind": "single", "measured": {"a": f, "b": f}},
        {"changed": {"w1": 1}, "kind": "single", "measured": {"a": f, "b": open_}},
        {"changed": {"w2": 1}, "kind": "single", "measured": {"a": h, "b": h}},
    ]
    claim = _labelled("C9-7", {"a": h, "b": h}, conds, _entries("r1", "w1", "w2"))
    assert whole_flips(claim) == (1, 3, 1) and label_basis(claim) == "a reading; a world too"
    assert turns_on_sentence(claim).endswith(
        "(its verdict changes in 1 of 3 explored configurations, and in 1 more it is undecided but cannot come out as "
        "at the default)."
    )
