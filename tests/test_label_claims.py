"""Labels and sentences that say more than the exploration checked (each test states the defect in its docstring)."""

from __future__ import annotations

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


def test_a_part_line_names_each_kind_of_a_reading_and_a_setting_flipping_together():
    """Every notebook's exploration section (part_lines.record_lines / part_line) files a flip of a reading and an
    unreported setting together under "(a setting of the paper's own experiment that the paper never printed)",
    while docs/verdicts.md says the report never names a flip that mixes kinds by one kind for all (003's C003-1
    x_r: "8 rev/s varied by 15 % at 1 Hz and the noise-equivalent bandwidth (...)" is a setting and a reading)."""
    from tvtrack.part_lines import record_lines

    flip = {
        "changed": {"r": 1, "s": 1},
        "side": "setting",
        "kind": "combination",
        "verdict": "not reproduced",
        "text": "the other reading and the other setting",
        "runs": 3,
    }
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
    """A flip that mixes a reading with a world is listed with "(none of them flips the claim alone)" even where
    one of its changes alone stayed undecided (its record's undecided_subsets): 002's C002-5, "a Poisson number
    of target photons (a world) and objects 1 sigma apart (a reading)", while "objects 1 sigma apart" alone ran 1
    of the 4 replicates the default needed; 004's C004-3b RBF part, where "networks fed the centres as measured"
    alone straddles. Nothing showed that the reading does not flip it alone."""
    from tvtrack.flip_words import flip_with_kind

    flip = {
        "changed": {"w": 1, "r": 1},
        "side": "unattributed",
        "kind": "joint",
        "verdict": "not reproduced",
        "text": "the other world and the other reading",
        "undecided_subsets": ["the other reading"],
    }
    text = flip_with_kind(flip, {"register": REGISTER})
    assert "none of them flips the claim alone" not in text


def test_a_claims_sentence_says_a_combination_is_only_not_shown_to_flip_alone_where_a_smaller_set_stayed_open():
    """The claim's sentence for a combination no smaller subset isolates says "none of them flips it alone" only
    where every smaller set measured was decided; with one left undecided it says none is shown to."""
    from tvtrack.wording import _flip_sentence

    flip = {
        "changed": {"w": 1, "r": 1},
        "side": "unattributed",
        "kind": "joint",
        "verdict": "not reproduced",
        "text": "the other world and the other reading",
    }
    claim = {"verdict": "reproduced", "robustness": {"register": REGISTER}}
    assert "Under two changes together (none of them flips it alone) it is not reproduced" in _flip_sentence(
        flip, claim
    )
    open_ = _flip_sentence({**flip, "undecided_subsets": ["the other reading"]}, claim)
    assert "Under two changes together (none of them is shown to flip it alone) it is not reproduced" in open_
