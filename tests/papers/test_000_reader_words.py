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
