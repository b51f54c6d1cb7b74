"""Notebook 000: lock loss told apart from accuracy (the share of runs that lost lock, and each claim scored over the
runs in lock beside the mean over all runs)."""

import numpy as np
import pytest

from tvtrack.papers.p000_dissector_ekf import lock_loss, study
from tvtrack.papers.p000_dissector_ekf.claims import claim_rules
from tvtrack.papers.p000_dissector_ekf.register import REGISTER

SIZES = study.Sizes(n_trials=300)
JOINT = {"C000-6 filter": "ignoring the signal noise", "contrast convention": "fixed background"}  # pinned


def test_runs_that_lost_lock_are_dropped_only_inside_the_context():
    a = np.full(40, 0.01)
    a[[3, 17]] = 1.0  # two runs 100x the median mean square: lost lock
    b = np.full(40, 0.02)
    b[5] = 0.6  # the reference filter lost lock in another run
    assert lock_loss.lost(a, 5.0).sum() == 2 and not lock_loss.lost(np.full(40, 0.01), 5.0).any()
    assert lock_loss.keep_pair(a, b)[0] is a and lock_loss.keep(a) is a  # outside: untouched, the same objects
    with lock_loss.in_lock(5.0) as counts:
        ka, kb = lock_loss.keep_pair(a, b)
        assert lock_loss.keep(a).size == 38
    assert ka.size == kb.size == 37 and ka.max() == 0.01 and kb.max() == 0.02
    assert counts == [(3, 40), (2, 40)]


def test_c000_6_flip_under_its_joint_condition_is_carried_by_the_runs_that_lost_lock():
    """The pinned joint condition (a filter ignoring the signal noise, the background held fixed) reads 'exceeds 20
    times' reproduced over all runs (ratio about 98 on these draws) because about 3 % of the runs lost lock; over the
    runs in lock the ratio is about 2.2, as at the default: the flip is the lost runs'."""
    d = REGISTER.default()
    rule = claim_rules(SIZES)["C000-6"]
    before = study.measure({**d, **JOINT}, 7, SIZES, frozenset({"C000-6"}))["C000-6"]
    m = lock_loss.measure_in_lock(study.measure, {**d, **JOINT}, 7, SIZES, "C000-6")
    assert m["all"] == before  # measuring in lock leaves the measurement over all runs as it was
    assert 5 <= m["lost_runs"] <= 20 and m["runs"] == 300
    assert m["lost"].ci_low < m["lost_runs"] / 300 < m["lost"].ci_high  # Clopper-Pearson around the count
    assert m["all"].value > 20 and rule.decide(m["all"]) == "reproduced"
    assert m["in lock"].value == pytest.approx(2.2, rel=0.1) and rule.decide(m["in lock"]) == "not reproduced"
    rep = lock_loss.lock_report(study.measure, rule, d, [JOINT], 7, SIZES, "C000-6", REGISTER.describe)
    assert "over the default's one replicate (every one the claim pools)" in rep["note"]
    assert "they read not reproduced over all runs and the same over the runs in lock" in rep["note"]
    assert all(row["replicates"] == 1 for row in rep["rows"])  # one replicate's draws, said in the sentence
    assert "the flip is carried by the runs that lost lock" in rep["note"]
    assert "The mean over all runs decides" in rep["note"]
    row = rep["metric"][REGISTER.describe(JOINT)]
    assert (row["verdict_all_runs"], row["verdict_in_lock"]) == ("reproduced", "not reproduced")
    assert rep["metric"]["default"]["lost_runs"] == 0
    flip = next(r for r in rep["rows"] if r["changed"] == JOINT)  # what Results.claim(lost_runs=...) marks
    assert (flip["verdict"], flip["in_lock_verdict"], flip["runs"]) == ("reproduced", "not reproduced", 300)
    assert flip["lost"] == m["lost_runs"] and rep["rows"][0]["changed"] == {}


def test_flip_changes_reads_every_part_once():
    rec = {
        "parts": {
            "a": {"flips": [{"changed": {"x": 1}}, {"changed": {"y": 2}}]},
            "b": {"flips": [{"changed": {"x": 1}}]},
        }
    }
    assert lock_loss.flip_changes(rec) == [{"x": 1}, {"y": 2}]


def test_the_pcrlb_refers_to_the_time_the_errors_are_scored_at():
    """The filtering error is scored at the end of an integrated sample's interval (the register's default): the
    bound there is the interval-centre bound propagated half a step by the message (f^2 B + q), 10 % above it at
    psi_A = 20, P = 0.9 in the steady window; a point sample, or errors scored at the centre, keep the sample-time
    bound."""
    from tvtrack.papers.p000_dissector_ekf.model import scan_at_snr
    from tvtrack.papers.p000_dissector_ekf.reference import pcrlb_variance

    scan, n = scan_at_snr(20.0, 0.9, 0.05), 600
    centre, end = pcrlb_variance(scan, study.MESSAGE, n), pcrlb_variance(scan, study.MESSAGE, n, "interval_end")
    f, q = study.MESSAGE.exact(0.025)
    np.testing.assert_allclose(end, f**2 * centre + q, rtol=1e-12)
    assert 1.05 < end[400:].mean() / centre[400:].mean() < 1.3  # 1.10 here; 1.01 at psi_A = 2, 1.67 at 100
    d = REGISTER.default()
    assert study.bound_time(d) == "interval_end"
    assert study.bound_time({**d, "scoring time": "interval centre"}) == "sample"
    assert study.bound_time({**d, "sample model": "point"}) == "sample"
    with pytest.raises(ValueError, match="score_at"):
        pcrlb_variance(scan, study.MESSAGE, 10, "end")


def test_the_lock_report_gives_each_part_its_own_verdicts_so_a_flip_is_carried_only_where_its_part_is():
    """Two parts flip at one condition: part a over every run and over the runs in lock alike, part b only over
    every run (10 runs of 40 lost lock). The whole claim's verdicts differ (not reproduced, partly); the rows say
    per part which flip the lost runs carry."""
    from types import SimpleNamespace

    from tvtrack.lost_labels import mark_lost_runs
    from tvtrack.montecarlo import mean_ci
    from tvtrack.verdicts import AllOf, InBand

    def measure(config, seed, sizes, claims):
        rng = np.random.default_rng(seed)
        a = (3.0 if config["x"] else 0.2) + rng.uniform(0.0, 0.01, 40)
        b = 0.01 + rng.uniform(0.0, 0.01, 40)
        if config["x"]:
            b[:10] = 5.0  # lost lock: 10 runs about 300 times the median run's mean square
        return {"C": {"a": mean_ci(lock_loss.keep(a)), "b": mean_ci(lock_loss.keep(b))}}

    band = InBand("mean", -0.5, 0.5, "px")
    rule = AllOf({"a": band, "b": band})
    at = {"x": 1}
    rep = lock_loss.lock_report(measure, rule, {"x": 0}, [at], 7, SimpleNamespace(lock_factor=5.0), "C", str)
    row = rep["rows"][1]
    assert (row["verdict"], row["in_lock_verdict"]) == ("not reproduced", "partly")
    assert row["parts"] == {"a": "not reproduced", "b": "not reproduced"}
    assert row["in_lock_parts"] == {"a": "not reproduced", "b": "reproduced"}
    carried = "of its parts, part b reads not reproduced over all runs and reproduced over the runs in lock: that flip"
    assert carried + " is carried by the runs that lost lock" in rep["note"], rep["note"]
    assert (
        "part a reads" not in rep["note"]
    )  # its flip stands over the runs in lock too: the whole claim's words say so
    flips = {p: {"verdict": "reproduced", "flips": [{"changed": dict(at), "verdict": "not reproduced"}]} for p in "ab"}
    record = mark_lost_runs({"parts": flips}, rep["rows"], "reproduced")
    assert {p: v["flips"][0]["lost_runs"]["carried"] for p, v in record["parts"].items()} == {"a": False, "b": True}


def test_a_condition_whose_draws_read_the_default_s_verdict_over_every_run_is_never_said_carried_by_lost_runs():
    """Where the lock report's draws read the default's verdict over every run and the flip's only over the runs in
    lock, the lost runs hide the flip on those draws: the note must not say they carry it, and the row is not marked
    carried."""
    from types import SimpleNamespace

    from tvtrack.lost_labels import mark_lost_runs
    from tvtrack.montecarlo import Estimate
    from tvtrack.verdicts import InBand

    def measure(config, seed, sizes, claims):
        b = 0.01 + np.random.default_rng(seed).uniform(0.0, 0.01, 40)
        if config["x"]:
            b[:10] = 5.0  # lost lock: 10 runs about 300 times the median run's mean square
            return {"C": Estimate.exact(1.2 - float(np.mean(lock_loss.keep(b))))}  # 1.2 - 1.26 over every run
        return {"C": Estimate.exact(0.0)}

    rule, at = InBand("mean", -0.5, 0.5, "px"), {"x": 1}
    rep = lock_loss.lock_report(measure, rule, {"x": 0}, [at], 7, SimpleNamespace(lock_factor=5.0), "C", str)
    row = rep["rows"][1]
    assert (rep["rows"][0]["verdict"], row["verdict"], row["in_lock_verdict"]) == (
        "reproduced",
        "reproduced",
        "not reproduced",
    )
    assert "carried by the runs that lost lock" not in rep["note"], rep["note"]
    assert "the runs that lost lock carry no flip" in rep["note"]
    part = {"verdict": "reproduced", "flips": [{"changed": dict(at), "verdict": "not reproduced"}]}
    record = mark_lost_runs({"parts": {"claim": part}}, rep["rows"], "reproduced")
    assert record["parts"]["claim"]["flips"][0]["lost_runs"]["carried"] is False


def _two_seed_measure(config, seed, sizes, claims):
    """40 runs per seed; at the condition (x = 1) seed 11 loses no run and seed 12 loses 3 (about 300 times the
    median run's mean square); a dict seed lookup, so that a list of seeds is never taken for one seed."""
    from tvtrack.montecarlo import mean_ci

    b = 0.01 + np.random.default_rng(seed).uniform(0.0, 0.01, 40)
    b[: {11: 0, 12: 3}[seed] if config["x"] else 0] = 3.0
    return {"C": mean_ci(lock_loss.keep(b))}


def test_the_lock_report_counts_the_lost_runs_of_every_replicate_seed_and_pools_the_runs_in_lock():
    """The claim pools two replicates; only the second lost runs. A report on the first replicate alone said none
    lost lock; over both seeds it counts the second's 3 of their 80 runs, says so with both replicates, and its
    values are the two replicates pooled as the claim's are (:func:`tvtrack.pooling.pool`)."""
    from types import SimpleNamespace

    from tvtrack.pooling import pool
    from tvtrack.verdicts import InBand

    sizes, at = SimpleNamespace(lock_factor=5.0), {"x": 1}
    one = [lock_loss.measure_in_lock(_two_seed_measure, at, s, sizes, "C") for s in (11, 12)]
    m = lock_loss.measure_in_lock(_two_seed_measure, at, [11, 12], sizes, "C")
    assert [o["lost_runs"] for o in one] == [0, 3]
    assert (m["lost_runs"], m["runs"], m["replicates"]) == (3, 80, 2)
    assert m["lost"].ci_low < 3 / 80 < m["lost"].ci_high
    assert m["all"] == pool([o["all"] for o in one]) and m["in lock"] == pool([o["in lock"] for o in one])
    assert m["in lock"].value < 0.02 < m["all"].value  # the second replicate's lost runs carry the mean
    rule = InBand("mean", -0.5, 0.5, "px")
    rep = lock_loss.lock_report(_two_seed_measure, rule, {"x": 0}, [at], [11, 12], sizes, "C", str)
    flip = rep["rows"][1]
    assert (flip["lost"], flip["runs"], flip["replicates"]) == (3, 80, 2)
    assert (rep["rows"][0]["lost"], rep["rows"][0]["runs"], rep["rows"][0]["replicates"]) == (0, 80, 2)
    assert "over its 2 replicates 3 of 80 runs lost lock" in rep["note"], rep["note"]
    assert "over the default's 2 replicates (every one the claim pools) 0 of 80 runs" in rep["note"]
    assert rep["metric"][str(at)]["replicates"] == 2


def test_a_condition_runs_on_the_seeds_of_its_own_replicates():
    """``lock_draws`` reads a claim's record: the default on every replicate seed the claim pools, each flipping
    condition on the seeds its own replicates ran on (the default's first ones, past the claim's own up to the
    exploration's max_replicates); ``lock_report`` measures each on those seeds."""
    from types import SimpleNamespace

    from tvtrack.explore import replicate_seeds
    from tvtrack.verdicts import InBand

    spawned = replicate_seeds(1995, 6)
    record = {
        "replicates": [{"seed": s} for s in spawned[:3]],
        "design": {"seed": 1995, "max_replicates": 6},
        "parts": {
            "a": {"flips": [{"changed": {"x": 1}, "runs": 1}, {"changed": {"y": 2}, "runs": 5}]},
            "b": {"flips": [{"changed": {"x": 1}, "runs": 1}]},
        },
    }
    conditions, seeds = lock_loss.lock_draws(record)
    assert seeds == spawned[:3]
    assert conditions == [({"x": 1}, spawned[:1]), ({"y": 2}, spawned[:5])]
    asked = []

    def measure(config, seed, sizes, claims):
        asked.append((config["x"], config["y"], seed))
        return {"C": _two_seed_measure({"x": 0}, 11, sizes, claims)["C"]}

    rule = InBand("mean", -0.5, 0.5, "px")
    rep = lock_loss.lock_report(
        measure, rule, {"x": 0, "y": 0}, conditions, seeds, SimpleNamespace(lock_factor=5.0), "C", str
    )
    assert [r["replicates"] for r in rep["rows"]] == [3, 1, 5]
    assert sorted({s for x, y, s in asked if (x, y) == (0, 2)}) == sorted(spawned[:5])
    assert {s for x, y, s in asked if (x, y) == (0, 0)} == set(spawned[:3])


def test_a_condition_left_undecided_over_every_run_is_never_said_a_flip():
    """Over every run the condition's interval straddles the band's end (undecided), over the runs in lock it lies
    inside (reproduced): the draws show no flip, so the note must not say the lost runs carry one."""
    from types import SimpleNamespace

    from tvtrack.montecarlo import Estimate
    from tvtrack.verdicts import InBand

    def measure(config, seed, sizes, claims):
        b = np.full(40, 0.01)
        if config["x"]:
            b[:10] = 2.0  # lost lock: the mean over every run about 0.51
        m = float(np.mean(lock_loss.keep(b)))
        return {"C": Estimate(m, 0.1, m - 0.2, m + 0.2, 40)}

    rule, at = InBand("mean", -0.5, 0.5, "px"), {"x": 1}
    rep = lock_loss.lock_report(measure, rule, {"x": 0}, [at], 7, SimpleNamespace(lock_factor=5.0), "C", str)
    row = rep["rows"][1]
    assert (rep["rows"][0]["verdict"], row["verdict"], row["in_lock_verdict"]) == (
        "reproduced",
        "undecided",
        "reproduced",
    )
    assert "flip is carried" not in rep["note"] and "the flip is not made" not in rep["note"], rep["note"]
    assert "over all runs these draws leave the claim as a whole undecided, so they show no flip" in rep["note"]


def test_c000_2_lock_report_counts_every_replicate_s_lost_runs():
    """C000-2 on two replicate seeds of the study: the runs lost at switch-on are counted over both, each
    replicate's count the same as alone, the values pooled as the claim's replicates are."""
    from tvtrack.pooling import pool

    sizes = study.Sizes(n_trials=100, duration_T=8.0, window_T=3.0, substeps=2, psi_grid=(5.0, 20.0))
    d = REGISTER.default()
    one = [lock_loss.measure_in_lock(study.measure, d, s, sizes, "C000-2") for s in (1, 2)]
    both = lock_loss.measure_in_lock(study.measure, d, [1, 2], sizes, "C000-2")
    assert one[0]["lost_runs"] == 3 and both["runs"] == 200 and both["replicates"] == 2
    assert both["lost_runs"] >= max(o["lost_runs"] for o in one)
    assert both["lost_runs"] <= sum(o["lost_runs"] for o in one)
    assert both["all"] == pool([o["all"] for o in one])
    assert both["in lock"] == pool([o["in lock"] for o in one])
