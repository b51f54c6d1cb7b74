"""The report's label words against the record: a count, a kind or a label word says no more about a flip than
the claim's record holds (its parts' verdicts, the whole claim's verdict under each condition)."""

from tvtrack.labels import label_parts
from tvtrack.montecarlo import Estimate
from tvtrack.register import Entry
from tvtrack.verdicts import AllOf, InBand

BAND = InBand("mean", -0.5, 0.5, "px")
HOLDS, FAILS = Estimate.exact(0.0), Estimate.exact(3.0)
OPEN = Estimate(0.45, 0.05, 0.3, 0.6, 50, method="t")  # straddles the band's upper edge


def _claim(cid: str, measured: dict, conds: list, entries: list) -> dict:
    rule = AllOf({n: BAND for n in measured})
    reps = [{"seed": s, "measured": measured} for s in (1, 2, 3)]
    rob = label_parts(rule, measured, reps, conds, entries)
    verdict = rule.judge(measured).verdict
    return {"id": cid, "verdict": verdict, "rule": rule.to_dict(), "measured": measured, "robustness": rob}


def test_a_part_flip_an_undecided_claim_may_read_at_the_default_too_is_not_counted_as_moving_it():
    """An undecided claim (a and c hold, b straddles) under a reading that makes a fail and b hold: the whole claim
    reads ``partly`` there, which it also reads at the default should b fail. The reading moves a part, not surely
    the whole verdict: the first screen counts the claim as moving only in a part, not as one a reading flips."""
    from tvtrack.flip_words import label_basis
    from tvtrack.paragraphs import part_only, results_summary, turns_on
    from tvtrack.wording import claim_verdict_at, moves_verdict

    reading = Entry("sigma", "reading", "raw", ("raw", "smoothed"), "the text reads either way")
    default = {"a": HOLDS, "b": OPEN, "c": HOLDS}
    there = {"a": FAILS, "b": HOLDS, "c": HOLDS}
    claim = _claim(
        "C9-7", default, [{"changed": {"sigma": "smoothed"}, "kind": "single", "measured": there}], [reading]
    )
    assert claim["verdict"] == "undecided" and claim["robustness"]["label"] == "depends"
    (flip,) = claim["robustness"]["parts"]["a"]["flips"]
    assert claim_verdict_at(claim, flip["changed"]) == "partly"
    assert not moves_verdict(claim, flip)
    assert turns_on([claim]) == {} and part_only([claim]) == 1
    assert label_basis(claim) == "a reading, in a part only"
    assert (
        "1 claim (C9-7) moves only in a part under every change explored (its whole verdict is not shown to move: "
        "it is undecided, or undecided there)" in results_summary([claim])
    )
    # a and c fail at the default and hold there, b open on both sides: for either outcome of b the two whole
    # verdicts differ (partly against reproduced, not reproduced against partly), so the reading moves it
    both_open = {"a": FAILS, "b": OPEN, "c": FAILS}
    claim = _claim(
        "C9-8", both_open, [{"changed": {"sigma": "smoothed"}, "kind": "single", "measured": default}], [reading]
    )
    assert claim["verdict"] == "undecided"
    (flip,) = [f for p in claim["robustness"]["parts"].values() for f in p["flips"]][:1]
    assert claim_verdict_at(claim, flip["changed"]) == "undecided" and moves_verdict(claim, flip)


def test_a_part_flip_that_moves_an_undecided_claim_whatever_its_open_part_counts():
    """The same reading making a and c fail: the whole claim reads partly or not reproduced there (b open there
    too), reproduced or partly at the default, never the same for one outcome of b: it moves the whole verdict."""
    from tvtrack.paragraphs import part_only, turns_on
    from tvtrack.wording import moves_verdict

    reading = Entry("sigma", "reading", "raw", ("raw", "smoothed"), "the text reads either way")
    default = {"a": HOLDS, "b": OPEN, "c": HOLDS}
    there = {"a": FAILS, "b": OPEN, "c": FAILS}
    claim = _claim(
        "C9-9", default, [{"changed": {"sigma": "smoothed"}, "kind": "single", "measured": there}], [reading]
    )
    flip = claim["robustness"]["parts"]["a"]["flips"][0]
    assert moves_verdict(claim, flip)
    assert turns_on([claim]) == {"reading": (1, [("sigma", "9", 1)])} and part_only([claim]) == 0


def test_an_undecided_claim_labelled_robust_is_said_to_be_so_in_its_decided_parts_only():
    """C002-7's record: one part holds under every explored configuration (robust), the other straddles the band
    at the default and fails under some configurations (the whole claim reads partly there). Its label speaks for
    its decided part: the first screen does not count its undecided verdict among those that survive every reading
    without saying so, and its table row and first-screen line say the label is of its decided parts."""
    from tvtrack.paragraphs import results_summary
    from tvtrack.pipeline.report import first_screen, first_screen_list
    from tvtrack.results import claims_table

    world = Entry("noise", "regime", "low", ("low", "high"), "a world beyond the paper")
    default = {"fine": HOLDS, "coarse": OPEN}
    moved = Estimate.exact(0.1)  # the world moves the held part, inside the band (it reached it)
    conds = [{"changed": {"noise": "high"}, "kind": "single", "measured": {"fine": moved, "coarse": FAILS}}]
    claim = _claim("C9-1", default, conds, [world])
    claim["statement"] = "One object: the ULA beats two-stage processing only for large pixels."
    claim["robustness"] = {**claim["robustness"], "provisional": False}
    assert claim["verdict"] == "undecided" and claim["robustness"]["label"] == "robust"
    assert claim["robustness"]["conditions"][0]["verdict"] == "partly"  # a world moves its undecided part
    held = {"id": "C9-2", "verdict": "reproduced", "robustness": {"label": "robust"}}
    text = results_summary([claim, held])
    assert (
        "The 2 that survive every reading: 1 holds and 1 is undecided; 2 robust, 0 limited (holding only within the "
        "paper's world); 1 of them (C9-1) undecided, labelled by its decided parts only." in text
    ), text
    assert "| **undecided** | robust in its decided parts only |" in claims_table([claim])
    rows = first_screen({"009_t": (None, {"claims": [claim, held]})})
    assert "**009 C9-1** (undecided, robust in its decided parts only)" in first_screen_list(rows)
    assert (
        "The one that survives every reading: it holds; 1 robust, 0 limited (holding only within the paper's world)."
        in (results_summary([held]))
    )


def test_the_sites_ledger_and_first_screen_say_an_undecided_claims_label_is_of_its_decided_parts():
    """The site's chips: the ledger row and the index's first screen of an undecided claim labelled robust say, beside
    the chip, that the label is of its decided parts only; a reproduced claim's chip stands alone."""
    from types import SimpleNamespace

    from tvtrack.pipeline.site import _environment, _ledger_rows

    claim = {"id": "C9-1", "statement": "s", "paper_value": "v", "verdict": "undecided", "measured": None}
    claim["robustness"] = {"label": "robust", "provisional": False}
    held = {**claim, "id": "C9-2", "verdict": "reproduced"}
    run = SimpleNamespace(name="009_t", results={"claims": [claim, held]}, cells={})
    rows = _ledger_rows([run])
    common = {"root": "", "built": "now", "profile": "paper", "paper_scale": True, "source": "runs"}
    env = _environment()
    page = env.get_template("ledger.html").render(rows=rows, papers=["009_t"], verdicts=[], labels=(), **common)
    assert page.count("in its decided parts only") == 1
    assert page.index(">C9-1<") < page.index("in its decided parts only") < page.index(">C9-2<")
    first = [{**r, "summary": ""} for r in rows]
    index = env.get_template("index.html").render(
        cards=[],
        sweeps=[],
        totals={"verdicts": [], "labels": []},
        n_claims=2,
        first=first,
        summary="",
        papers=[],
        forest=None,
        robustness=None,
        **common,
    )
    assert index.count("in its decided parts only") == 1


def _robust(cid: str, agree: int, undecided: int) -> dict:
    """A reproduced claim labelled robust: no explored configuration flips it, ``agree`` agree, ``undecided`` stay
    undecided (too small, or straddling)."""
    n = agree + undecided
    share = {"agree": agree, "flip": 0, "undecided": undecided, "design": n, "decided": agree, "value": agree / n}
    part = {"verdict": "reproduced", "label": "robust", "share": {**share, "ci_low": 0.0, "ci_high": 1.0}}
    record = {"label": "robust", "provisional": False, "parts": {"claim": part}}
    return {
        "id": cid,
        "statement": "s",
        "verdict": "reproduced",
        "rule": BAND.to_dict(),
        "measured": HOLDS,
        "robustness": record,
    }


def test_a_robust_claim_most_of_whose_configurations_stayed_undecided_is_not_said_to_hold_under_all():
    """C002-3's record: robust over 43 configurations of which 4 agree and 39 stay undecided. No explored change
    flips it, but it is not shown to hold under every one: the paper's paragraph says none flips it, the first
    screen names it among the robust ones most of whose configurations stayed undecided, and its own sentence
    gives the share whatever its length."""
    from tvtrack.paragraphs import paper_paragraph, results_summary
    from tvtrack.wording import claim_summary

    thin, firm = _robust("C9-3", 4, 39), _robust("C9-4", 43, 1)
    paragraph, _ = paper_paragraph({"claims": [thin, firm]})
    assert (
        "2 claims hold (C9-3 and C9-4), 2 of them flipped by no reading or world explored (most explored "
        "configurations stayed undecided for C9-3)." in paragraph
    )
    assert "under every reading and world explored" not in paragraph
    text = results_summary([thin, firm])
    assert (
        "The 2 that survive every reading: all hold; 2 robust, 0 limited (holding only within the paper's world); for 1 "
        "(C9-3) most explored configurations stayed undecided." in text
    ), text
    assert claim_summary(thin, chars=0).endswith(
        " 4 agree, 0 flip and 39 stay undecided of 43 explored configurations."
    )
    assert "explored configurations" not in claim_summary(firm, chars=0)  # a firm share stays optional


def test_a_claim_whose_record_decides_no_part_is_not_said_to_have_no_record():
    """C002-6: undecided at the default in its only part, explored over 43 configurations, so its record carries
    the label ``-`` (nothing to flip). The report's counts by verdict and of the checkable verdicts say it has no
    part decided, and keep "no record" for a claim without one."""
    from tvtrack.pipeline.report import verdict_summary

    explored = {"id": "C9-6", "verdict": "undecided", "robustness": {"label": "-", "parts": {"claim": {}}}}
    bare = {"id": "C9-5", "verdict": "undecided"}
    assert verdict_summary([explored, bare]) == (
        "0 reproduced · 0 partly · 0 not reproduced · 2 undecided (1 no part decided, 1 no record) · 0 not checkable"
    )
    assert verdict_summary([explored]).endswith("1 undecided (1 no part decided) · 0 not checkable")
    from tvtrack.pipeline.report import label_counts

    assert label_counts([explored, bare]) == " · 1 without a decided part · 1 without a robustness record"


def test_every_change_that_flips_a_claim_means_every_part_s():
    """A claim of two parts: readings x and y together, and x and v together, flip part a; z and w together flip
    part b. The sentence names a flip of part a, and does not say that every change that flips the claim includes
    x (z and w flip it without x)."""
    from tvtrack.wording import claim_summary

    entries = [Entry(k, "reading", "0", ("0", "1"), "the text reads either way") for k in "vwxyz"]
    default = {"a": HOLDS, "b": HOLDS}
    conds = [
        {"changed": {"x": "1", "y": "1"}, "kind": "combination", "measured": {"a": FAILS, "b": HOLDS}},
        {"changed": {"x": "1", "v": "1"}, "kind": "combination", "measured": {"a": FAILS, "b": HOLDS}},
        {"changed": {"z": "1", "w": "1"}, "kind": "combination", "measured": {"a": HOLDS, "b": FAILS}},
    ]
    register = [{"name": k, "kind": "reading", "title": k} for k in "vwxyz"]
    claim = _claim("C9-10", default, conds, entries)
    claim["robustness"]["register"] = register
    assert [len(p["flips"]) for p in claim["robustness"]["parts"].values()] == [2, 1]
    text = claim_summary(claim, chars=0)
    assert "Under two other readings of the paper's text together the claim is partly reproduced" in text, text
    assert "Every change that flips it" not in text
    only_a = _claim("C9-11", default, conds[:2], entries)
    only_a["robustness"]["register"] = register
    assert "Every change that flips it includes x = 1 (a reading of the paper's text)." in claim_summary(only_a, 0)


def test_an_undecided_claim_still_undecided_under_a_flip_without_part_verdicts_is_not_shown_to_move():
    """A condition row without its parts' verdicts, where the whole claim reads undecided on both sides: the flip
    moves a part, and the first screen says so ("in a part only") as the claim's sentence ("stays undecided")."""
    from tvtrack.flip_words import label_basis
    from tvtrack.wording import moves_verdict

    flip = {"text": "x", "side": "setting", "changed": {"k": 1}, "verdict": "not reproduced", "part": "one"}
    parts = {"one": {"verdict": "reproduced", "flips": [flip]}, "two": {"verdict": "undecided"}}
    rob = {"register": [{"name": "k", "title": "k", "kind": "unreported setting", "phrases": {}}], "parts": parts}
    rob["conditions"] = [{"changed": {"k": 1}, "verdict": "undecided"}]
    claim = {"id": "C9-1", "verdict": "undecided", "rule": {"kind": "all_of", "parts": {"one": {}, "two": {}}}}
    claim["robustness"] = {**rob, "label": "depends"}
    assert moves_verdict(claim, flip) is False
    assert label_basis(claim) == "an unprinted setting, in a part only"
    claim["robustness"]["conditions"] = [{"changed": {"k": 1}, "verdict": "not reproduced"}]
    assert moves_verdict(claim, flip) is True
    from tvtrack.wording import _flip_to

    row = {"changed": {"k": 1}, "verdict": "undecided", "parts": {"one": "not reproduced", "two": "undecided"}}
    claim["robustness"]["conditions"] = [row]
    said = _flip_to(flip, claim, 2)
    if moves_verdict(claim, flip):  # whatever part two turns out to be, the claim cannot read as at the default
        assert (
            said
            == "the claim stays undecided, but its part one is not reproduced, so it cannot come out as at the default"
        )
    claim["robustness"]["conditions"] = [{"changed": {"k": 1}, "verdict": "undecided"}]
    assert _flip_to(flip, claim, 2) == "the claim stays undecided, but its part one is not reproduced"


def test_the_papers_paragraph_names_the_flip_the_claims_summary_names():
    """A claim that fails in both parts: one reading alone makes part "b" hold (the claim partly holds), two readings
    together make part "a" hold. The summary names the single reading (the stronger flip); the paper's paragraph
    said "it holds in part under two other readings together" (the main part's own flip), so a reader met two
    different flips for one claim. Both now name the single reading."""
    from tvtrack.paragraphs import paper_paragraph
    from tvtrack.wording import claim_summary, named_flips

    r1 = Entry("r1", "reading", 0, (0, 1), "a reading", phrases={1: "r1 read the other way"})
    r2 = Entry("r2", "reading", 0, (0, 1), "a reading", phrases={1: "r2 read the other way"})
    conds = [
        {"changed": {"r1": 1}, "kind": "single", "measured": {"a": FAILS, "b": HOLDS}},
        {"changed": {"r2": 1}, "kind": "single", "measured": {"a": FAILS, "b": FAILS}},
        {"changed": {"r1": 1, "r2": 1}, "kind": "joint", "measured": {"a": HOLDS, "b": FAILS}},
    ]
    claim = _claim("C9-5", {"a": FAILS, "b": FAILS}, conds, [r1, r2])
    claim["statement"] = "Both parts hold."
    assert claim["verdict"] == "not reproduced"
    first = named_flips(claim)[0]
    assert first["changed"] == {"r1": 1} and first["part"] == "b"
    assert "r1 read the other way" in claim_summary(claim, chars=0)
    paragraph, _ = paper_paragraph({"claims": [claim]})
    assert "it holds in part under a reading of the paper's text: r1 read the other way." in paragraph, paragraph
    assert "two other readings" not in paragraph


def test_the_papers_paragraph_says_what_would_turn_a_claim_that_holds():
    """A claim that holds names its flip in the paper's paragraph as one that fails does (it used to be named for
    the failing claims only), with the whole claim's verdict there and how many other changes flip it."""
    from tvtrack.paragraphs import paper_paragraph

    r1 = Entry("r1", "reading", 0, (0, 1), "a reading", phrases={1: "r1 read the other way"})
    w1 = Entry("w1", "regime", 0, (0, 1), "a world", phrases={1: "a louder world"})
    conds = [
        {"changed": {"r1": 1}, "kind": "single", "measured": {"a": FAILS}},
        {"changed": {"w1": 1}, "kind": "single", "measured": {"a": FAILS}},
    ]
    held = _claim("C9-6", {"a": HOLDS}, conds, [r1, w1])
    quiet = _claim("C9-7", {"a": HOLDS}, [{"changed": {"w1": 1}, "kind": "single", "measured": {"a": HOLDS}}], [w1])
    paragraph, _ = paper_paragraph({"claims": [held, quiet]})
    assert (
        "C9-6 does not hold under a reading of the paper's text: r1 read the other way (1 other smallest change "
        "flips it too; its verdict changes in 2 of 2 explored configurations)." in paragraph
    ), paragraph
    assert "C9-7 does not hold" not in paragraph  # nothing explored flips it


def test_the_papers_paragraph_names_a_change_that_turns_the_whole_claim_and_counts_only_those():
    """A claim holding in part (part "b" fails): one reading makes "b" hold and "a" fail (still partly: a part's flip
    only), one world makes every part hold, one reading makes "c" fail (still partly). The sentence names the world,
    the one change that turns the whole claim, and counts no other: the part-only flips change nothing a reader of
    the claim's verdict sees."""
    from tvtrack.paragraphs import paper_paragraph

    r1 = Entry("r1", "reading", 0, (0, 1), "a reading", phrases={1: "r1 read the other way"})
    r2 = Entry("r2", "reading", 0, (0, 1), "a reading", phrases={1: "r2 read the other way"})
    w1 = Entry("w1", "regime", 0, (0, 1), "a world", phrases={1: "a quieter world"})
    conds = [
        {"changed": {"r1": 1}, "kind": "single", "measured": {"a": FAILS, "b": HOLDS, "c": HOLDS}},
        {"changed": {"r2": 1}, "kind": "single", "measured": {"a": HOLDS, "b": FAILS, "c": FAILS}},
        {"changed": {"w1": 1}, "kind": "single", "measured": {"a": HOLDS, "b": HOLDS, "c": HOLDS}},
    ]
    claim = _claim("C9-9", {"a": HOLDS, "b": FAILS, "c": HOLDS}, conds, [r1, r2, w1])
    assert claim["verdict"] == "partly"
    paragraph, _ = paper_paragraph({"claims": [claim]})
    assert (
        "C9-9 holds under a world beyond the paper: a quieter world (its verdict changes in 1 of 3 explored "
        "configurations)." in paragraph
    ), paragraph


def test_the_papers_paragraph_says_when_only_runs_that_lost_lock_carry_the_flip_of_a_claim_that_holds():
    from tvtrack.paragraphs import paper_paragraph

    lost = {"carried": True, "lost": 5, "runs": 600, "replicates": 1}
    flip = {"text": "r1 moved", "side": "reading", "changed": {"r1": 1}, "verdict": "not reproduced"}
    record = {
        "register": [{"name": "r1", "title": "r1", "kind": "reading", "phrases": {}}],
        "label": "depends",
        "parts": {"claim": {"verdict": "reproduced", "label": "depends", "flips": [{**flip, "lost_runs": lost}]}},
        "conditions": [{"changed": {"r1": 1}, "verdict": "not reproduced"}],
    }
    claim = {"id": "C9-8", "verdict": "reproduced", "rule": BAND.to_dict(), "measured": HOLDS, "robustness": record}
    paragraph, _ = paper_paragraph({"claims": [claim]})
    assert (
        "C9-8 does not hold under a reading of the paper's text: r1 moved, but in one replicate only through the 5 "
        "of its 600 runs that lost lock there (its verdict changes in 1 of 1 explored configurations)."
    ) in paragraph, paragraph


def test_a_claim_unexplored_for_too_few_decided_configurations_says_how_many_and_how_many_are_needed():
    from tvtrack.wording import claim_summary

    claim = _robust("C9-10", 10, 30)
    part = claim["robustness"]["parts"]["claim"]
    part["label"] = claim["robustness"]["label"] = "unexplored"
    part["share"]["decided_needed"] = 32
    assert claim_summary(claim, chars=0).endswith(
        "Beyond the paper's default, only 10 of the 40 changes explored for it decided it and 30 left it undecided; "
        "32 decided ones are needed to say how far it extends, so nothing shows that yet."
    )
