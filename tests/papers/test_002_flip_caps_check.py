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
    assert left == sum(capped)  # every point of the claim ran at the run's cap: only the capped ones are left
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
    assert out["counts"]["caps"] <= {20_000}
    big = replace(SCALE, cap_factor=200)
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


def test_flips_are_rerun_only_where_the_runs_cap_was_reached(coarse):
    reps = [
        Run(DEFAULT, s, "replicate", {"C002-11": study.measure(DEFAULT, s, SCALE, {"C002-11"})["C002-11"]})
        for s in SEEDS
    ]
    cond = Run({**DEFAULT, **COARSE}, SEEDS[0], "joint", {"C002-11": coarse[0]})
    cond.sized.append(Run({**DEFAULT, **COARSE}, SEEDS[1], "condition sizing", {"C002-11": coarse[1]}))
    ex = _Exploration(reps, [cond])
    marks = "the two-stage's per-frame marks"
    caps = {
        "C002-11": {
            "default": {marks: (0, 12), "caps": set()},
            "flips": [
                {"changed": COARSE, "parts": ["d = 1 sigma (paper x4.5)"], "counts": {marks: (9, 12), "caps": {100}}},
                {
                    "changed": {"EM stopping": "plain EM, cap 100"},
                    "parts": ["d = 1 sigma (paper x4.5)"],
                    "counts": {marks: (9, 12), "caps": {50}},
                },  # a cap the condition set: not rerun
            ],
        }
    }
    out = fcc.flips_at_larger_cap(ex, caps, RULES, SCALE, 100, factor=200)
    e = out["claims"]["C002-11"]
    assert len(e["flips"]) == 1
    # the default's own points reach the smoke cap (counted over its replicates, whatever the first one's counts
    # given above): it is rerun too, and the flips are judged against its verdicts at the larger cap
    assert e["default"]["seeds"] == SEEDS and e["reference"] == e["default"]["verdicts"]
    f = e["flips"][0]
    assert f["seeds"] == SEEDS
    assert f["before"] == {p: j.verdict for p, j in part_judgements(RULES["C002-11"], pool(coarse)).items()}
    assert out["larger cap"] == 20_000


def _out(after: str, reference: str = "not reproduced"):
    marks = "the two-stage's per-frame marks"
    flip = {
        "changed": {"Delta of Figs 4, 5, 7 (sigma)": 5.0},
        "parts": ["d = 3 sigma (paper x4)"],
        "before": {"d = 3 sigma (paper x4)": "reproduced"},
        "verdicts": {"d = 3 sigma (paper x4)": after},
        "counts": {marks: (3, 240), "the ULA": (0, 240), "caps": {1_000_000}},
        "pooled": {},
    }
    entry = {"default": None, "flips": [flip], "reference": {"d = 3 sigma (paper x4)": reference}}
    return {"claims": {"C002-11": entry}, "cap": 5000, "larger cap": 1_000_000, "cpu_s": 1.0}


def test_the_words_say_whether_each_flip_stands():
    text = fcc.larger_cap_sentence(_out("reproduced"))
    assert "200 times larger (5,000 -> 1,000,000 iterations" in text
    assert "C002-11 1 of the 1 flipping conditions that read capped points still flip it, 0 do not" in text
    assert 'part "d = 3 sigma (paper x4)": reproduced -> reproduced' in text
    assert "the two-stage's per-frame marks still at the cap in 1% of its trials" in text
    assert "the ULA still" not in text  # an algorithm no longer at the cap is not named
    assert REGISTER.describe({"Delta of Figs 4, 5, 7 (sigma)": 5.0}) in text
    for after in ("undecided", "not reproduced"):  # undecided, or back to the default's verdict: the flip is gone
        assert "0 of the 1 flipping conditions that read capped points still flip it, 1 do not" in (
            fcc.larger_cap_sentence(_out(after))
        )
    assert fcc.larger_cap_sentence({"claims": {}, "cap": 5000, "larger cap": 10**6, "cpu_s": 0.0}) == ""


def test_the_default_rerun_is_worded_by_its_moves_and_flip_words_are_left_out_without_flips():
    out = _out("reproduced")
    default = {"changed": {}, "parts": ["claim"], "seeds": [1, 2, 3], "before": {"claim": "reproduced"}}
    out["claims"]["C002-11"].update(default={**default, "verdicts": {"claim": "undecided"}}, flips=[])
    text = fcc.larger_cap_sentence(out)
    assert "C002-11 at the default (3 replicates pooled) its verdict reproduced -> undecided." in text
    assert "flipping conditions" not in text.split("C002-11", 1)[1]
    out["claims"]["C002-11"]["default"]["verdicts"] = {"claim": "reproduced"}
    assert "every verdict is the same as at the run's cap" in fcc.larger_cap_sentence(out)


def test_the_metrics_carry_both_verdicts_and_the_value():
    m = fcc.larger_cap_metrics(_out("undecided"))
    assert m["flip_caps/C002-11/flip 1/d = 3 sigma (paper x4)/verdicts"] == ["reproduced", "undecided"]
    assert m["flip_caps/larger_cap"] == 1_000_000
