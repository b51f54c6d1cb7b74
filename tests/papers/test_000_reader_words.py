"""Paper 000: the words the notebook prints from the package say only what this run measures: no register entry's
rationale quotes a result of an earlier run, and the conclusions carry the runs that lost lock behind a flip."""

import re

from tvtrack.papers.p000_dissector_ekf.register import REGISTER

# a result quoted in a rationale: "Measured (200 runs, ...)", a 95 % interval "[8.5, 10.2]"
MEASURED = re.compile(r"Measured \(|\[\s*[-+]?\d[\d.]*\s*,\s*[-+]?\d[\d.]*\s*\]")


def test_no_why_text_quotes_a_measured_result():
    quoting = {e.name: MEASURED.findall(e.why) for e in REGISTER if MEASURED.search(e.why)}
    assert quoting == {}


def _claim(lost_runs: dict | None, **record):
    """A hand-made claim of one part whose one named flip (two changes together) turns it reproduced."""
    from types import SimpleNamespace

    flip = {
        "changed": {"C000-6 filter": "ignoring the signal noise", "contrast convention": "fixed background"},
        "side": "setting",
        "verdict": "reproduced",
        "text": "a filter ignoring the signal noise and background current held fixed",
    }
    flip |= {"lost_runs": lost_runs} if lost_runs else {}
    where = [f"reproduced when {flip['text']} (the smallest found: a filter ignoring the signal noise stays undecided)"]
    robustness = {
        "label": "depends",
        "where": where,
        "parts": {"claim": {"verdict": "not reproduced", "flips": [flip]}},
    }
    return SimpleNamespace(
        id="C000-6",
        statement="",
        verdict="not reproduced",
        rule={"kind": "at_least"},
        measured=1.5,
        robustness=robustness | record,
    )


def _conclusions(claim) -> str:
    from types import SimpleNamespace

    from tvtrack.papers.p000_dissector_ekf.findings import conclusions

    return conclusions([claim], SimpleNamespace(settings={"replicates": 3}, runs=[], register=REGISTER))


def test_conclusions_say_when_only_runs_that_lost_lock_carry_a_flip():
    lost = {"lost": 54, "runs": 1200, "verdict": "reproduced", "in_lock_verdict": "not reproduced", "replicates": 2}
    text = _conclusions(_claim(lost | {"carried": True}))
    assert (
        "stays undecided), but in 2 replicates, the 54 of their 1200 runs that lost lock there carry that flip: over "
        "those replicates' runs in lock alone the claim is not reproduced." in text
    )
    assert "lost lock" not in _conclusions(_claim(lost | {"in_lock_verdict": "reproduced", "carried": False}))
    assert "lost lock" not in _conclusions(_claim(None))


def test_conclusions_say_when_runs_that_lost_lock_carry_the_default_verdict():
    share = {"lost": 6, "runs": 3000, "replicates": 5}
    text = _conclusions(_claim(None, lost_share=share, in_lock_verdict="reproduced", decided_by_lost_runs=True))
    assert (
        "In 5 replicates, 6 of their 3000 runs lost lock and carry this verdict: over those replicates' runs in "
        in text
    )


def _est(value, low=None, high=None):
    from tvtrack.estimate import Estimate

    return Estimate(value, 0.1, value if low is None else low, value if high is None else high, 100)


def test_pull_in_range_is_said_to_the_grid_and_with_both_sides_shares():
    from tvtrack.papers.p000_dissector_ekf.findings import pull_in_words
    from tvtrack.papers.p000_dissector_ekf.studies import pull_in_range

    offsets = [-0.6, -0.4, 0.0, 0.4, 0.6]
    late = [_est(0.66, 0.6, 0.7), _est(0.28, 0.25, 0.32), _est(0.0, 0.0, 0.01), _est(0.033, 0.02, 0.05), _est(0.12)]
    acq = {"v1": {"late": late}}
    text = pull_in_words(offsets, acq, pull_in_range(offsets, acq), 5.0)
    assert "from 0 T" not in text  # the old wording hid that no offset between -0.4 T and 0 was tried
    assert "-0.6, -0.4, 0, +0.4, +0.6 T: each edge is known only to the grid's spacing" in text
    assert "negative side short of -0.4 T, the nearest offset tried (28.0 % not in lock there)" in text
    assert "positive side to +0.4 T (3.3 % not in lock there, 12.0 % at +0.6 T)" in text
    assert "-0.4 T and +0.4 T, the runs not in lock for good by 5 T are 28.0 % and 3.3 % (variant 1)" in text


class _Ex:
    """A hand-made exploration of C000-6: the default, two entries changed alone, a pinned pair that flips it and
    two joint samples, one of which flips it."""

    register = REGISTER

    def __init__(self):
        def row(kind, changed, value):
            return {
                "kind": kind,
                "changed": changed,
                "measured": _est(value, value / 2, value * 1.5),
                "verdict": "reproduced" if value / 2 > 20 else "not reproduced",
            }

        self.conditions = [
            row("single", {"G22": "euler"}, 2.0),
            row("single", {"psi_A": 50.0}, 2.1),
            row(
                "pinned",
                {"C000-6 filter": "ignoring the signal noise", "contrast convention": "fixed background"},
                190.0,
            ),
            row("joint", {"sigma_sh": "unit bandwidth", "psi_A": 100.0}, 1.5),
            row("joint", {"G22": "matched", "psi_A": 5.0}, 60.0),
        ]

    def record(self, claim_id):
        return {"conditions": self.conditions}

    def measured(self, claim_id):
        return _est(1.5, 0.6, 2.2)


def test_c6_figure_draws_each_entry_alone_and_every_flip_in_plain_words():
    from tvtrack.papers.p000_dissector_ekf.findings import drawn_conditions
    from tvtrack.verdicts import InBand

    rows, left = drawn_conditions(_Ex(), "C000-6", InBand("ratio", 20.0, None))
    labels = [r[0] for r in rows]
    assert not any(" = euler" in t or "sigma_sh" in t for t in labels)  # register keys are not a reader's words
    assert labels[0] == "the default (replicates pooled)"
    assert REGISTER.describe({"G22": "euler"}) in labels
    assert REGISTER.describe({"G22": "matched", "psi_A": 5.0}) in labels  # the flipping joint sample
    assert REGISTER.describe({"sigma_sh": "unit bandwidth", "psi_A": 100.0}) not in labels
    assert left == "Not drawn: 1 joint sample of the register agreeing with the default's verdict."


def test_c6_caption_counts_the_undecided_conditions_as_undecided_not_as_agreeing():
    """The record counts a condition left with fewer replicates than the default needed (by the sizing budget) as
    undecided, whatever its own pooled value reads: the paper-profile caption said "none of them changing the
    verdict: 27 joint samples ..., 197 combinations", while the record's share of the claim had all 197 combinations
    undecided (195 of them short by the sizing budget) and 10 of the 27 joint samples undecided. The caption says how
    many agree and how many are undecided, and of those how many the budget left short."""
    from tvtrack.papers.p000_dissector_ekf.findings import drawn_conditions
    from tvtrack.verdicts import InBand

    ex = _Ex()
    short = {"undersized": {"claim": "not reproduced"}, "left_by_budget": 2}
    ex.conditions += [
        {**ex.conditions[3], "changed": {"psi_A": 5.0, "G22": "euler"}, "kind": "combination", **short},
        {**ex.conditions[3], "changed": {"psi_A": 5.0, "G22": "matched"}, "kind": "combination", **short},
        {**ex.conditions[3], "changed": {"psi_A": 2.0, "G22": "euler"}, "kind": "joint", **short},
        {**ex.conditions[3], "changed": {"psi_A": 2.0, "G22": "paper"}, "kind": "joint", "verdict": "undecided"},
    ]
    rows, left = drawn_conditions(ex, "C000-6", InBand("ratio", 20.0, None))
    assert len(rows) == 5  # the default, two entries alone, the pinned pair, the flipping joint sample
    assert left == (
        "Not drawn: 1 joint sample of the register agreeing with the default's verdict; undecided (neither agreeing "
        "nor flipping): 2 combinations searched inside flipping joint samples (2 of them left smaller than the "
        "default needed by the sizing budget), 2 joint samples of the register (1 of them left smaller than the "
        "default needed by the sizing budget)."
    )


def test_conclusions_count_configurations_as_configurations_and_runs_as_runs():
    """A joint sample of the register is one configuration, measured once per group of claims that read what it
    changes: the paper-profile conclusions said "35 one-at-a-time and 227 joint configurations" where the record
    held 32 joint configurations measured in 227 runs."""
    from types import SimpleNamespace

    from tvtrack.papers.p000_dissector_ekf.findings import conclusions

    def run(stage, changed):
        return SimpleNamespace(stage=stage, changed=lambda default, c=changed: dict(c))

    runs = [run("single", {"G22": "euler"}), run("single", {"psi_A": 50.0})]
    runs += [run("joint", {"G22": "euler", "psi_A": 5.0})] * 3 + [run("joint", {"G22": "matched", "psi_A": 2.0})] * 4
    ex = SimpleNamespace(settings={"replicates": 3, "joint_configurations": 2}, runs=runs, register=REGISTER)
    text = conclusions([_claim(None)], ex)
    assert "2 one-at-a-time configurations and 2 joint configurations (measured in 7 runs" in text
    assert "7 joint configurations" not in text


def test_c6_list_of_flips_says_what_it_counts():
    from tvtrack.papers.p000_dissector_ekf.findings import conditions_above
    from tvtrack.verdicts import InBand

    text = conditions_above(_Ex(), "C000-6", InBand("ratio", 20.0, None), "put the whole 95 % interval above 20")
    assert "(of " not in text
    assert text.startswith(
        "Of the 5 explored conditions (2 register entries changed one at a time, 1 pinned joint condition, 2 joint "
        "samples of the register), 2 put the whole 95 % interval above 20:\n\n- "
    )
    assert f"\n- {REGISTER.describe({'G22': 'matched', 'psi_A': 5.0})}" in text


def test_conclusions_show_the_labels_a_reader_sees_and_every_named_flip():
    """A record too small to label (``provisional``) reads ``provisional`` in the conclusions, as in the findings
    table, never the record's raw ``unexplored``; its parts likewise in the claim's details; and every line of
    ``where`` is named, not the first two."""
    from types import SimpleNamespace

    from tvtrack.papers.p000_dissector_ekf.findings import claim_details

    claim = _claim(None)
    extra = [f"not reproduced when change {i}" for i in range(3)]
    rec = claim.robustness | {"label": "unexplored", "provisional": True, "where": claim.robustness["where"] + extra}
    rec["parts"] = {"claim": rec["parts"]["claim"] | {"label": "unexplored", "replicate_verdicts": ["undecided"]}}
    rec["coverage"] = "unexplored; provisional"
    claim = SimpleNamespace(**{**vars(claim), "robustness": rec, "statement": "s", "acceptance": "a"})
    text = _conclusions(claim)
    assert ", provisional:" in text and "unexplored" not in text and "labels 1 provisional" in text
    assert all(w in text for w in extra) and "first conditions" not in text
    details = claim_details(SimpleNamespace(claims=[claim]), None, claim.id)
    assert "| claim | not reproduced | provisional | undecided |" in details
