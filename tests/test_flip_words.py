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
    """Where the claim reads undecided already, a world that leaves it undecided changes nothing a reader needs:
    the bracket names the reading alone. The same world beside a decided claim whose parts it opens is named."""
    reading, world = ("r", "reading", {"r": 1}), ("w", "world", {"w": 1})
    open_there = [{"changed": {"w": 1}, "verdict": "undecided"}]
    claim = _claim(reading, world, verdict="undecided", parts=2, conditions=open_there)
    assert label_basis(claim) == "a reading"
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
