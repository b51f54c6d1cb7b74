"""Tests of 002's check of the flips that read capped points (:mod:`.flip_caps_check`): the larger cap is the run's
cap times the factor (a reading's own cap kept), a simulation with no capped trial is reused bit for bit, a factor of
1 gives back the condition's own pooled verdicts, and the words follow the verdicts."""

from dataclasses import replace

import numpy as np
import pytest

from tvtrack.conditions import Run
from tvtrack.labels import part_judgements
from tvtrack.pooling import pool
from tvtrack.papers.p002_unified_location_em import flip_caps, study
from tvtrack.papers.p002_unified_location_em import flip_caps_check as fcc
from tvtrack.papers.p002_unified_location_em.claims import RULES
from tvtrack.papers.p002_unified_location_em.register import DEPENDS, REGISTER

DEFAULT = REGISTER.default()
#: The smoke profile's cap of 100 EM steps at 6 trials a point: under Fig 6b's coarse pixels the marks reach it in
#: most trials (as in test_002_cap_check).
SCALE = study.Scale(n_trials=6, n_iter_trials=4, separations=(1.0, 2.0, 3.0, 4.0, 6.0, 8.0), crb_phases=2, max_iter=100)
COARSE = {"Delta of Figs 4, 5, 7 (sigma)": 5.0, "distance unit of C002-11": "pixel"}
SEEDS = [5, 6]


def test_the_larger_cap_multiplies_the_runs_cap_and_keeps_a_readings_own():
    paper = study.Scale()
    assert study.settings_of(DEFAULT, 1, paper).max_iter == 5000
    assert study.settings_of(DEFAULT, 1, replace(paper, cap_factor=200)).max_iter == 1_000_000
    assert study.settings_of(DEFAULT, 1, replace(SCALE, cap_factor=200)).max_iter == 20_000  # the smoke cap x 200
    practical = {**DEFAULT, "EM stopping": study.PRACTICAL_STOP}
    assert study.settings_of(practical, 1, replace(paper, cap_factor=3)).max_iter == 15_000
    own = {**DEFAULT, "EM stopping": "plain EM, cap 100"}
    assert study.settings_of(own, 1, replace(paper, cap_factor=200)).max_iter == 100
    # the plain-EM iteration counts (Fig 7) run at the run's cap whatever the reading: raised too
    s = study.settings_of(own, 1, replace(paper, cap_factor=4))
    assert study._job_settings(s, "p", replace(paper, cap_factor=4)).max_iter == 20_000
    assert study._job_settings(s, "q", paper).max_iter == 5000
    two = replace(paper, cap_factor=2)
    assert study._job_settings(study.settings_of(DEFAULT, 1, two), "p", two).max_iter == 10_000
    # the ULA's and the marks' cap is raised once, by settings_of, not again per job
    big = replace(paper, cap_factor=200)
    for letter in "ue":
        assert study._job_settings(study.settings_of(DEFAULT, 1, big), letter, big).max_iter == 1_000_000


@pytest.fixture(scope="module")
def coarse():
    """C002-11 measured at the coarse-pixel condition on two seeds at the run's cap (the cache then holds its points)."""
    study.clear_cache()
    config = {**DEFAULT, **COARSE}
    ms = study.measure_batch([config] * 2, SEEDS, SCALE, [{"C002-11"}] * 2)
    return [m["C002-11"] for m in ms]


def _jobs(scale):
    return [j for s in SEEDS for j in fcc._jobs(COARSE, s, scale, "C002-11")]


def test_uncapped_simulations_are_reused_and_capped_ones_rerun(coarse):
    big = replace(SCALE, cap_factor=200)
    capped = []
    for job in _jobs(SCALE):
        letter = job[1].algs
        r = study.cached(job)
        capped.append(letter in flip_caps.CAPPED and bool(flip_caps.capped_flags(r, flip_caps.CAPPED[letter][1]).any()))
    assert any(capped) and not all(capped)  # the marks reach the smoke cap at 5 sigma pixels, other points do not
    left = fcc._reuse_uncapped(COARSE, SEEDS, SCALE, big, "C002-11")
    assert len(left) == sum(capped)  # every point of the claim ran at the run's cap: only the capped ones are left
    for job, jb, hit in zip(_jobs(SCALE), _jobs(big), capped):
        if hit:
            assert study.cached(jb) is None  # left to run at the larger cap
        elif jb != job:
            assert study.cached(jb) is study.cached(job)  # the same result: no capped trial, same estimates


def test_a_factor_of_one_gives_back_the_conditions_pooled_verdicts(coarse):
    out = fcc.at_larger_cap(COARSE, SEEDS, SCALE, "C002-11", RULES["C002-11"], factor=1)
    assert out["rerun"] == 0
    expected = pool(coarse)
    for part, e in expected.items():
        assert out["pooled"][part].value == e.value and out["pooled"][part].ci_low == e.ci_low
    assert out["verdicts"] == {p: j.verdict for p, j in part_judgements(RULES["C002-11"], expected).items()}


def test_the_larger_cap_changes_only_capped_trials_and_counts_its_own_hits(coarse):
    out = fcc.at_larger_cap(COARSE, SEEDS, SCALE, "C002-11", RULES["C002-11"], factor=200)
    assert out["rerun"] > 0
    marks = "the two-stage's per-frame marks"
    before = flip_caps.cap_counts(COARSE, SEEDS, SCALE, "C002-11")
    assert out["counts"][marks][1] == before[marks][1]  # the same trials
    assert out["counts"][marks][0] < before[marks][0]  # fewer reach a cap 200 times larger
    big = replace(SCALE, cap_factor=200)
    assert out["counts"] == fcc.raised_counts(COARSE, SEEDS, SCALE, big, "C002-11", larger=True)
    assert fcc.raised_counts(COARSE, SEEDS, SCALE, big, "C002-11") == {k: v for k, v in before.items() if k != "caps"}
    for job, jb in zip(_jobs(SCALE), _jobs(big)):
        if job[1].algs == "e":
            r0, r1 = study.cached(job), study.cached(jb)
            free = ~r0["em_flags"][:, 2]
            assert np.array_equal(r0["em"][free], r1["em"][free])  # an uncapped trial: the same estimates


class _Exploration:
    """The attributes :func:`.flip_caps_check.flips_at_larger_cap` reads of an exploration."""

    def __init__(self, replicates, runs):
        self.default, self.depends = DEFAULT, DEPENDS
        self._reps, self.runs = replicates, [*replicates, *runs]

    def replicates(self):
        return self._reps

    def measured(self, claim):  # as tvtrack.explore.Exploration.measured: the replicates pooled, None skipped
        return pool([r.outputs.get(claim) for r in self._reps])


CAP100 = {"EM stopping": "plain EM, cap 100"}


def _c11(config, seed):
    return study.measure(config, seed, SCALE, {"C002-11"})["C002-11"]


def test_flips_are_rerun_only_where_the_runs_cap_was_reached(coarse):
    reps = [Run(DEFAULT, s, "replicate", {"C002-11": _c11(DEFAULT, s)}) for s in SEEDS]
    # a replicate the explorer's sizing added for other claims: it holds no C002-11 and is not pooled for it
    reps.append(Run(DEFAULT, 9, "replicate", {"C002-1": object()}, claims=frozenset({"C002-1"})))
    cond = Run({**DEFAULT, **COARSE}, SEEDS[0], "joint", {"C002-11": coarse[0]})
    cond.sized.append(Run({**DEFAULT, **COARSE}, SEEDS[1], "condition sizing", {"C002-11": coarse[1]}))
    # at the smoke profile the condition's own cap of 100 equals the run's: it is not raised, so not rerun
    own = Run({**DEFAULT, **CAP100}, SEEDS[0], "single", {"C002-11": _c11({**DEFAULT, **CAP100}, SEEDS[0])})
    ex = _Exploration(reps, [cond, own])
    part = ["d = 1 sigma (paper x4.5)"]
    # the condition with its own cap first: it is passed over, and the next one still checked
    flips = [{"changed": CAP100, "parts": part, "counts": {}}, {"changed": COARSE, "parts": part, "counts": {}}]
    out = fcc.flips_at_larger_cap(ex, {"C002-11": {"default": {}, "flips": flips}}, RULES, SCALE, 100, factor=200)
    e = out["claims"]["C002-11"]
    assert [f["changed"] for f in e["flips"]] == [COARSE]
    big = replace(SCALE, cap_factor=200)
    assert fcc.raised_counts(CAP100, [SEEDS[0]], SCALE, big, "C002-11") == {}  # its marks hit its own cap only
    # the default's own points reach the smoke cap: it is rerun on the replicates that hold the claim, and the flips
    # are judged against its verdicts at the larger cap
    assert e["default"]["seeds"] == SEEDS and e["reference"] == e["default"]["verdicts"]
    assert e["default"]["before"] == {
        p: j.verdict for p, j in part_judgements(RULES["C002-11"], ex.measured("C002-11")).items()
    }
    f = e["flips"][0]
    assert f["seeds"] == SEEDS
    assert f["before"] == {p: j.verdict for p, j in part_judgements(RULES["C002-11"], pool(coarse)).items()}
    assert out["larger cap"] == 20_000 and out["rerun"] > 0
    for m in (e["default"], f):  # each verdict at the larger cap is the rule's on the value measured there
        assert m["verdicts"] == {p: j.verdict for p, j in part_judgements(RULES["C002-11"], m["pooled"]).items()}
        assert set(m["verdicts"]) == {"d = 1 sigma (paper x4.5)", "d = 3 sigma (paper x4)"}
    metrics = fcc.larger_cap_metrics(out)
    assert metrics["flip_caps/rerun"] == out["rerun"]
    assert metrics["flip_caps/C002-11/default/measured"] is e["default"]["pooled"]
    assert metrics["flip_caps/C002-11/flip 1/measured"] is f["pooled"]
    d1 = "d = 1 sigma (paper x4.5)"
    assert metrics[f"flip_caps/C002-11/default/{d1}/verdicts"] == [
        e["default"]["before"][d1],
        e["default"]["verdicts"][d1],
    ]
    assert len(metrics[f"flip_caps/C002-11/flip 1/{d1}/verdicts"]) == 3  # a flip's outcome beside its verdicts


def test_a_readings_own_cap_is_raised_only_up_to_itself():
    own = {**DEFAULT, **CAP100}
    low = study.Scale(max_iter=50)  # the run's cap below the reading's: the run's binds
    assert study.settings_of(own, 1, low).max_iter == 50
    assert study.settings_of(own, 1, replace(low, cap_factor=200)).max_iter == 100
    assert study.settings_of(DEFAULT, 1, replace(low, cap_factor=200)).max_iter == 10_000


def _out(after: str, reference: str = "not reproduced", n: int = 1):
    marks = "the two-stage's per-frame marks"
    flip = {
        "changed": {"Delta of Figs 4, 5, 7 (sigma)": 5.0},
        "parts": ["d = 3 sigma (paper x4)"],
        "before": {"d = 3 sigma (paper x4)": "reproduced"},
        "verdicts": {"d = 3 sigma (paper x4)": after},
        "counts": {marks: (3, 240), "the ULA": (0, 240)},
        "pooled": {},
    }
    entry = {"default": None, "flips": [flip] * n, "reference": {"d = 3 sigma (paper x4)": reference}}
    return {"claims": {"C002-11": entry}, "cap": 5000, "larger cap": 1_000_000, "cpu_s": 1.0}


def test_the_words_say_whether_each_flip_stands():
    text = fcc.larger_cap_sentence(_out("reproduced"))
    assert "200 times larger (5,000 -> 1,000,000 iterations" in text
    assert "C002-11: the flipping condition that reads capped points still flips it:" in text
    assert 'part "d = 3 sigma (paper x4)": reproduced -> reproduced' in text
    assert "the two-stage's per-frame marks still at the larger cap in 1% of its trials" in text
    assert "the ULA still" not in text  # an algorithm no longer at the cap is not named
    assert REGISTER.describe({"Delta of Figs 4, 5, 7 (sigma)": 5.0}) in text
    for after in ("undecided", "not reproduced"):  # undecided, or back to the default's verdict: the flip is gone
        assert "the flipping condition that reads capped points no longer does" in fcc.larger_cap_sentence(_out(after))
    # an undecided default at the larger cap: nothing to flip against
    assert "has no decisive default verdict to flip at the larger cap" in fcc.larger_cap_sentence(
        _out("reproduced", "undecided")
    )
    assert "of the 2 flipping conditions that read capped points, 2 no longer do:" in fcc.larger_cap_sentence(
        _out("undecided", n=2)
    )
    assert fcc.larger_cap_sentence({"claims": {}, "cap": 5000, "larger cap": 10**6, "cpu_s": 0.0}) == ""
    mixed = _out("reproduced", n=3)
    e = mixed["claims"]["C002-11"]
    p3 = "d = 3 sigma (paper x4)"
    e["flips"] = [
        {**e["flips"][0], "verdicts": {p3: v}, "parts": [p3]} for v in ("reproduced", "not reproduced", "undecided")
    ]
    assert "of the 3 flipping conditions that read capped points, 1 still flips it, 2 no longer do:" in (
        fcc.larger_cap_sentence(mixed)
    )
    e["reference"] = {p3: "undecided"}
    assert "of the 3 flipping conditions that read capped points, 3 have no decisive default verdict" in (
        fcc.larger_cap_sentence(mixed)
    )


def test_a_flip_stands_only_where_both_verdicts_are_decisive_and_differ():
    f = {"parts": ["a"], "before": {"a": "reproduced"}, "verdicts": {"a": "not reproduced"}}
    assert fcc._outcome(f, {"a": "reproduced"})[0][3] == "stands"
    assert fcc._outcome(f, {"a": "not reproduced"})[0][3] == "gone"
    assert fcc._outcome(f, {"a": "undecided"})[0][3] == "no default"
    assert fcc._outcome({**f, "verdicts": {"a": "undecided"}}, {"a": "reproduced"})[0][3] == "gone"
    assert fcc._outcome({**f, "verdicts": {"a": "not checkable"}}, {"a": "reproduced"})[0][3] == "gone"


def test_the_default_rerun_is_worded_by_its_moves_and_flip_words_are_left_out_without_flips():
    out = _out("reproduced")
    default = {"changed": {}, "parts": ["claim"], "seeds": [1, 2, 3], "before": {"claim": "reproduced"}}
    counts = {"the ULA": (4, 240)}
    out["claims"]["C002-11"].update(default={**default, "verdicts": {"claim": "undecided"}, "counts": counts}, flips=[])
    text = fcc.larger_cap_sentence(out)
    assert (
        "C002-11: at the default (3 replicates pooled, as for the run's verdict) its verdict reproduced -> undecided"
        in text
    )
    assert "the conditions that agreed with the default at the run's cap were not measured again" in text
    assert "the ULA still at the larger cap in 2% of its trials" in text
    assert "flipping condition" not in text.split("C002-11", 1)[1]
    d = out["claims"]["C002-11"]["default"]
    d["verdicts"] = {"claim": "reproduced"}
    assert "every verdict the same as at the run's cap" in fcc.larger_cap_sentence(out)
    d.update(before={"claim": "undecided"}, verdicts={"claim": "undecided"})
    assert "undecided at both caps" in fcc.larger_cap_sentence(out)


def test_the_conclusion_counts_the_flips_that_stand_and_the_defaults_that_move():
    assert fcc.larger_cap_conclusion({"claims": {}, "cap": 5000, "larger cap": 10**6}) == ""
    line = fcc.larger_cap_conclusion(_out("reproduced", n=2))
    assert "200 times larger, 2 of the 2 flips that read points where an EM reached it still stand; no default" in line
    out = _out("undecided", n=2)
    d = {"changed": {}, "parts": ["claim"], "seeds": [1], "before": {"claim": "reproduced"}}
    out["claims"]["C002-14"] = {"default": {**d, "verdicts": {"claim": "undecided"}}, "flips": [], "reference": {}}
    line = fcc.larger_cap_conclusion(out)
    assert (
        "0 of the 2 flips" in line
        and "no longer do (undecided, or no decisive default to flip against): C002-11 (2 of 2)" in line
    )
    assert "the default's verdict moves for C002-14 (its verdict reproduced -> undecided)." in line
    del out["claims"]["C002-11"]
    assert "no flip read such a point); the default's verdict moves for C002-14" in fcc.larger_cap_conclusion(out)


def test_the_metrics_carry_both_verdicts_and_the_value():
    m = fcc.larger_cap_metrics(_out("undecided"))
    assert m["flip_caps/C002-11/flip 1/d = 3 sigma (paper x4)/verdicts"] == ["reproduced", "undecided", "gone"]
    assert m["flip_caps/larger_cap"] == 1_000_000


def test_the_seeds_are_the_replicates_the_explorer_pools_for_the_claim():
    """``_seeds`` against :meth:`tvtrack.conditions.Run.replicates` on hand-built runs: a sized run that did not ask
    for the claim, one that holds no value of it, and a screened first value are all left out."""
    cid = "C002-11"
    run = Run({**DEFAULT, **COARSE}, 1, "joint", {cid: "v1"})
    run.sized += [
        Run({**DEFAULT, **COARSE}, 2, "condition sizing", {cid: "v2"}),
        Run({**DEFAULT, **COARSE}, 3, "condition sizing", {cid: "v3"}, claims=frozenset({"C002-10"})),
        Run({**DEFAULT, **COARSE}, 4, "condition sizing", {"C002-10": "w"}, claims=frozenset({cid})),
        Run({**DEFAULT, **COARSE}, 5, "condition sizing", {cid: "v5"}, claims=frozenset({cid})),
    ]
    seed_of = {"v1": 1, "v2": 2, "v3": 3, "v5": 5}
    assert fcc._seeds(run, cid) == [seed_of[v] for v in run.replicates(cid)] == [1, 2, 5]
    run.screened = frozenset({cid})
    assert fcc._seeds(run, cid) == [seed_of[v] for v in run.replicates(cid)] == [2, 5]


def test_a_flip_is_found_among_the_conditions_never_the_replicates():
    reps = [Run(DEFAULT, 1, "replicate", {"C002-11": "r"})]
    cond = Run({**DEFAULT, **COARSE}, 1, "joint", {"C002-11": "c"})
    ex = _Exploration(reps, [cond])
    assert fcc._run_of(ex, "C002-11", COARSE) is cond
    with pytest.raises(KeyError, match="C002-11: no run of the condition"):
        fcc._run_of(ex, "C002-11", {})  # the default's replicates are not a condition


def test_the_conclusion_names_every_default_that_moves():
    out = {"claims": {}, "cap": 5000, "larger cap": 10**6}
    for cid in ("C002-10", "C002-14"):
        d = {"changed": {}, "parts": ["claim"], "seeds": [1], "before": {"claim": "reproduced"}}
        out["claims"][cid] = {"default": {**d, "verdicts": {"claim": "undecided"}}, "flips": [], "reference": {}}
    d = {"changed": {}, "parts": ["claim"], "seeds": [1], "before": {"claim": "reproduced"}}
    out["claims"]["C002-4"] = {"default": {**d, "verdicts": {"claim": "reproduced"}}, "flips": [], "reference": {}}
    line = fcc.larger_cap_conclusion(out)
    assert (
        "moves for C002-10 (its verdict reproduced -> undecided), C002-14 (its verdict reproduced -> undecided)" in line
    )
    assert "C002-4" not in line  # its verdict is the same at both caps
