"""Labels and sentences that say more than the exploration checked (each test states the defect in its docstring)."""

from __future__ import annotations

import pytest

from tvtrack.estimate import Estimate
from tvtrack.labels import Condition, Robustness, label_parts
from tvtrack.pooling import pool
from tvtrack.register import Entry
from tvtrack.verdicts import InBand

RULE = InBand("x", low=0.0, high=1.0)


def _est(v: float) -> Estimate:
    return Estimate(v, 0.01, v - 0.02, v + 0.02, 100, 0.95, "normal")


def test_a_deterministic_record_over_one_configuration_is_not_robust():
    """A deterministic claim skips the share's design-size rule: explored over one configuration of the 109 its
    register admits, with one world value that moves it, it is labelled robust (share 1 of 1, interval 0.025-1).
    Determinism removes replicate noise, not the sampling of configurations: robust needs 32 decided
    configurations (or every combination), else the label is unexplored or provisional."""
    world = Entry("w", "regime", 1, tuple(range(1, 11)), "a world")
    reading = Entry("r", "reading", 0, tuple(range(10)), "a reading")
    rec = Robustness(
        choices=[world, reading], conditions=[Condition({"w": 2}, 0.6)], note="arithmetic", deterministic=True
    )
    out = rec.record(RULE, 0.5)
    assert out["parts"]["claim"]["share"]["design"] == 1
    assert out["label"] != "robust"


def test_configurations_that_left_the_part_unchanged_do_not_make_it_robust():
    """tvtrack.reach says a configuration that leaves the part's value as the default's, bit for bit, explores
    nothing of it and does not count among the decided configurations a robust label needs; the label counts it
    anyway (decided = agree + flip, unchanged included): 33 agree, 6 of them unchanged, so only 27 reached the part,
    fewer than the 32 a share needs, and the part is still robust."""
    reps = [_est(0.5), _est(0.51), _est(0.49)]
    world = Entry("w", "regime", 0, (0, 1), "a world")
    reading = Entry("r", "reading", 0, tuple(range(40)), "a reading")
    conds = [{"changed": {"w": 1}, "kind": "single", "measured": _est(0.6), "runs": 3}]
    conds += [
        {"changed": {"r": i}, "kind": "single", "measured": _est(0.3 + 0.01 * i), "runs": 3} for i in range(1, 27)
    ]
    conds += [{"changed": {"r": i}, "kind": "single", "measured": pool(reps), "runs": 3} for i in range(27, 33)]
    out = label_parts(
        RULE, pool(reps), [{"seed": s, "measured": m} for s, m in enumerate(reps)], conds, [world, reading], needed=3
    )
    share = out["parts"]["claim"]["share"]
    assert share["agree"] == 33 and share["unchanged"] == 6
    assert out["parts"]["claim"]["label"] != "robust"


REGISTER = [
    {"name": "r", "kind": "reading", "side": "reading", "title": "a reading", "phrases": {"1": "the other reading"}},
    {
        "name": "s",
        "kind": "unreported setting",
        "side": "setting",
        "title": "a setting",
        "phrases": {"1": "the other setting"},
    },
    {"name": "w", "kind": "regime", "side": "world", "title": "a world", "phrases": {"1": "the other world"}},
]


def _flip(changed: dict, side: str, **more) -> dict:
    """A named flip to ``not reproduced`` of the entries ``changed`` on ``side``, in the register above's words."""
    words = {"r": "the other reading", "s": "the other setting", "w": "the other world"}
    text = " and ".join(words[k] for k in changed)
    return {"changed": changed, "side": side, "kind": "joint", "verdict": "not reproduced", "text": text, **more}


def test_a_part_line_names_each_kind_of_a_reading_and_a_setting_flipping_together():
    """A notebook's exploration lines (part_lines.record_lines) name each change's own kind where a flip mixes a
    reading and an unreported setting, never the setting's alone for both (docs/verdicts.md; 003's C003-1 x_r: "8
    rev/s varied by 15 % at 1 Hz and the noise-equivalent bandwidth (...)" is a setting and a reading)."""
    from tvtrack.part_lines import record_lines

    flip = _flip({"r": 1, "s": 1}, "setting", kind="combination", runs=3)
    share = {"agree": 40, "flip": 1, "undecided": 0, "design": 41, "decided": 41, "ci_low": 0.8, "ci_high": 1.0}
    record = {
        "label": "depends",
        "coverage": "depends over 41 distinct configurations",
        "register": REGISTER,
        "parts": {"claim": {"verdict": "reproduced", "label": "depends", "flips": [flip], "share": share}},
        "conditions": [],
    }
    line = "\n".join(record_lines("C9-1", record))
    assert "a reading of the paper's text" in line


def test_an_unattributed_flip_whose_single_change_stayed_undecided_is_not_said_to_flip_nowhere_alone():
    """A flip that mixes a reading with a world, one of whose changes alone stayed undecided (its record's
    undecided_subsets), is not said to be one none of whose changes flips the claim alone: nothing showed that
    (002's C002-5, "a Poisson number of target photons and objects 1 sigma apart", where the reading alone ran 1 of
    the 4 replicates the default needed; 004's C004-3b RBF part)."""
    from tvtrack.flip_words import flip_with_kind

    flip = _flip({"w": 1, "r": 1}, "unattributed", undecided_subsets=["the other reading"])
    text = flip_with_kind(flip, {"register": REGISTER})
    assert "none of them flips the claim alone" not in text


def test_a_claims_sentence_says_a_combination_is_only_not_shown_to_flip_alone_where_a_smaller_set_stayed_open():
    """The claim's sentence for a combination no smaller subset isolates says "none of them flips it alone" only
    where every smaller set measured was decided; with one left undecided it says none is shown to."""
    from tvtrack.wording import _flip_sentence

    flip = _flip({"w": 1, "r": 1}, "unattributed")
    claim = {"verdict": "reproduced", "robustness": {"register": REGISTER}}
    assert "Under two changes together (none of them flips it alone) it is not reproduced" in _flip_sentence(
        flip, claim
    )
    open_ = _flip_sentence({**flip, "undecided_subsets": ["the other reading"]}, claim)
    assert "Under two changes together (none of them is shown to flip it alone) it is not reproduced" in open_


@pytest.mark.parametrize(
    ("k", "words"),
    [
        (0, " (none of them flips the claim alone)"),
        (1, " (none of them is shown to flip the claim alone: one smaller set of them stays undecided)"),
        (2, " (none of them is shown to flip the claim alone: two smaller sets of them stay undecided)"),
        (7, " (none of them is shown to flip the claim alone: 7 smaller sets of them stay undecided)"),
    ],
)
def test_a_combination_says_how_many_of_its_smaller_sets_stayed_undecided(k, words):
    """A flip no smaller subset isolates: "none of them flips the claim alone" only where every smaller set was
    decided, else how many stayed undecided; one kind of change or several, the same words."""
    from tvtrack.flip_words import alone_words, flip_with_kind

    subsets = [f"set {i}" for i in range(k)]
    flip = {"changed": {"r": 1, "s": 1, "w": 1}, "side": "unattributed", "text": "a, b and c"}
    flip |= {"undecided_subsets": subsets} if subsets else {}
    assert alone_words(flip) == words
    one_kind = {**flip, "changed": {"r": 1}, "text": "a and b"}  # a register that holds one kind only
    assert flip_with_kind(one_kind, {"register": REGISTER}) == "a and b, together" + words
    assert alone_words({**flip, "side": "setting"}) == ""


def _one_world(values: int):
    return Entry("w", "regime", 0, tuple(range(values)), "a world")


@pytest.mark.parametrize(
    ("values", "unchanged", "label"), [(2, 0, "robust"), (3, 1, "robust"), (6, 1, "robust"), (6, 2, "unexplored")]
)
def test_a_small_register_needs_every_configuration_that_can_reach_the_part(values, unchanged, label):
    """With fewer reachable configurations than a share's 32, a part is robust when every one that can reach it
    decided it: one world of ``values`` values (``values - 1`` configurations), ``unchanged`` of which leave the
    part's value as the default's; each of the others agrees. One configuration is enough where it is the only one;
    of five with one unchanged, the four that reach it are; with two unchanged, three reach it and one of them is
    undecided here, so it is not."""
    reps = [_est(0.5), _est(0.51), _est(0.49)]
    conds, moved = [], values - 1 - unchanged
    for i in range(1, values):
        if i <= unchanged:
            m = pool(reps)  # the default's value on its own random numbers: never reached the part
        elif unchanged == 2 and i == values - 1:
            m = Estimate(0.99, 0.05, 0.9, 1.08, 100, 0.95, "normal")  # straddles the band's upper edge
        else:
            m = _est(0.3 + 0.01 * i)
        conds.append({"changed": {"w": i}, "kind": "single", "measured": m, "runs": 3})
    out = label_parts(
        RULE,
        pool(reps),
        [{"seed": s, "measured": m} for s, m in enumerate(reps)],
        conds,
        [_one_world(values)],
        needed=3,
    )
    part = out["parts"]["claim"]
    assert part["share"]["unchanged"] == unchanged and moved >= 1
    assert part["label"] == label


def test_a_claim_not_checkable_at_the_default_says_so_in_its_coverage():
    """A claim whose every part is not checkable has no label, and its coverage line says why (no verdict to flip),
    not that no part was decided; a claim with a part undecided says the latter."""
    from tvtrack.verdicts import NotCheckable

    nc = label_parts(NotCheckable("no data"), 1.0, [{"seed": 0, "measured": 1.0}], [], [])
    assert nc["coverage"].startswith("no label (not checkable at the default: no verdict to flip) over 0 distinct")
    wide = Estimate(1.0, 0.5, 0.2, 1.8, 100, 0.95, "normal")  # straddles the band's upper edge: undecided
    open_ = label_parts(RULE, wide, [{"seed": s, "measured": wide} for s in range(3)], [], [], needed=3)
    assert open_["coverage"].startswith("no label (no part decided at the default: nothing to flip) over 0 distinct")
