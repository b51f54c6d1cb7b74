"""The explorer: replicates are independent, joint-only flips are caught, adaptive stopping stops
early on a clear claim and late on a borderline one, labels are per part."""

import math
import time
import warnings

import numpy as np
import pytest
from load import wall_budget

from tvtrack.explore import explore, joint_sample, pool, replicate_seeds
from tvtrack.montecarlo import Estimate, mean_ci
from tvtrack.register import Entry, Register
from tvtrack.results import Results
from tvtrack.verdicts import AllOf, InBand, Ordering

REG = Register(
    [
        Entry("a", "regime", 0, (0, 1, 2), "test regime a"),
        Entry("b", "operating point", 0, (0, 1, 2), "test operating point b"),
        Entry("c", "reading", "x", ("x", "y"), "test reading c"),
    ]
)


def _mean(seed, shift, n=400, sd=1.0):
    return mean_ci(np.random.default_rng(seed).normal(shift, sd, n))


def measure_joint_only(config, seed):
    """The claim 'mean in [-0.5, 0.5]' flips only when a and b are both 2 (an interaction); elsewhere a and b move
    it a little (each world reaches it), well inside the band."""
    shift = 3.0 if (config["a"] == 2 and config["b"] == 2) else 0.01 * (config["a"] + config["b"])
    y = {"p1": _mean(seed, 0.01 * config["a"]), "p2": _mean(seed, 3.0 * (config["c"] == "y"))}
    return {"X": _mean(seed, shift), "Y": y}


def measure_renamed(config, seed):
    return {"C000-1": measure_joint_only(config, seed)["Y"]}


RULES = {"X": InBand("mean", -0.5, 0.5), "Y": AllOf({"p1": InBand("m1", -0.5, 0.5), "p2": InBand("m2", -0.5, 0.5)})}


def test_a_flip_under_a_joint_combination_only_is_caught():
    ex = explore(measure_joint_only, REG, {"X": RULES["X"]}, seed=7, replicates=3, joint=40)
    single = [r for r in ex.runs if r.stage == "single"]
    assert all(r.outputs["X"].ci_high < 0.5 for r in single)  # no single-axis value flips it
    rec = ex.record("X")
    assert rec["label"] == "limited"  # a and b are worlds (regime, operating point), not readings of the paper
    assert any("a = 2" in w and "b = 2" in w for w in rec["where"])
    assert not rec["provisional"]  # every joint combination of the small register was run
    # without joint samples the same claim would look robust: the test guards the joint stage itself; such a
    # small design cannot estimate a share, so it is provisional and never robust
    rec0 = explore(measure_joint_only, REG, {"X": RULES["X"]}, seed=7, replicates=3, joint=0).record("X")
    assert rec0["label"] == "unexplored" and rec0["provisional"] and rec0["parts"]["claim"]["flips"] == []


def kept_unless_a_and_b_are_both_2(config):
    """The exploration's ``operating_point``: the joint a = b = 2 cannot be kept at the paper's operating point."""
    return "no re-calibration reaches it" if config["a"] == 2 and config["b"] == 2 else None


def test_a_joint_flip_the_exploration_cannot_keep_at_the_operating_point_is_counted_beside_the_label():
    seen = []

    def hook(config):
        seen.append(dict(config))
        return kept_unless_a_and_b_are_both_2(config)

    ex = explore(measure_joint_only, REG, {"X": RULES["X"]}, seed=7, replicates=3, joint=40, operating_point=hook)
    part = ex.record("X")["parts"]["claim"]
    assert part["flips"] == [] and part["label"] == "robust"  # the only flip is the joint the hook marks
    assert part["off_operating_point"]["flip"] >= 1 and part["share"]["flip"] == 0
    assert all("no re-calibration reaches it" in w for w in part["where"] if "a = 2" in w and "b = 2" in w)
    assert seen and all(set(c) == {"a", "b", "c"} for c in seen)  # every entry, the others at their defaults
    rows = ex.record("X")["conditions"]
    assert {bool(c.get("operating_point_lost")) for c in rows} == {True, False}
    assert all(("operating_point_lost" in c) == (c["changed"].get("a") == c["changed"].get("b") == 2) for c in rows)
    seen.clear()  # a claim that reads only a sees every configuration at b's default: nothing it reads leaves
    design = {"seed": 7, "replicates": 3, "joint": 40, "depends": {"X": ["a"]}, "operating_point": hook}
    ex_a = explore(lambda config, seed: {"X": _mean(seed, 0.0)}, REG, {"X": RULES["X"]}, **design)
    assert "off_operating_point" not in ex_a.record("X")["parts"]["claim"]
    assert seen and all(c["b"] == 0 and c["c"] == "x" for c in seen)


FIVE = Register([Entry(k, "regime", 0, (0, 1), "w") for k in "abcde"], pinned=[dict.fromkeys("abcde", 1)])


def measure_ab(config, seed):
    return {"X": _mean(seed, 3.0 if config["a"] == 1 and config["b"] == 1 else 0.0)}


def pair_ab_alone_is_lost(config):
    return "the pair alone leaves it" if [k for k in "abcde" if config[k]] == ["a", "b"] else None


def test_a_flip_off_the_operating_point_explains_no_larger_flip_in_the_subset_search():
    # a = b = 1 flips the claim; the pair alone leaves the paper's operating point, the pinned five-entry joint does
    # not: the search must go on to a triple at the operating point, not stop at the pair and call the joint
    # unattributed
    plain = explore(measure_ab, FIVE, {"X": RULES["X"]}, seed=3, replicates=3, max_subset=3).record("X")
    assert plain["label"] == "limited" and [f["changed"] for f in plain["parts"]["claim"]["flips"]] == [
        {"a": 1, "b": 1}
    ]
    ex = explore(
        measure_ab, FIVE, {"X": RULES["X"]}, seed=3, replicates=3, max_subset=3, operating_point=pair_ab_alone_is_lost
    )
    part = ex.record("X")["parts"]["claim"]
    named = [f["changed"] for f in part["flips"]]
    assert named and all(len(ch) == 3 and {"a", "b"} <= set(ch) for ch in named), named
    assert part["label"] == "limited" and not any(f.get("note") for f in part["flips"])
    assert part["off_operating_point"]["flip"] == 1 and "the pair alone leaves it" in " ".join(part["where"])
    assert [r.off_point for r in ex.runs if r.changed(FIVE.default()) == {"a": 1, "b": 1}] == [
        "the pair alone leaves it"
    ]


def test_the_design_counts_only_values_at_the_operating_point():
    from tvtrack.explore import _n_joint_combinations

    reg = Register(
        [Entry("a", "regime", 0, (0, 1, 9), "w", off_operating_point=(9,)), Entry("b", "regime", 0, (0, 1, 2), "w")]
    )
    assert _n_joint_combinations(reg, ["a", "b"]) == 2  # (1, 1), (1, 2): a = 9 is tried one at a time only
    ex = explore(lambda c, s: {"X": _mean(s, 0.0)}, reg, {"X": RULES["X"]}, seed=1, joint=2)
    assert ex.settings["joint_exhaustive"] and ex.settings["joint_configurations"] == 2


def test_replicates_are_independent_full_size_runs():
    seen = []

    def measure(config, seed):
        seen.append(seed)
        return {"X": _mean(seed, 0.0)}

    ex = explore(measure, REG, {"X": RULES["X"]}, seed=3, replicates=4, one_at_a_time=False)
    reps = ex.replicates()
    assert len({r.seed for r in reps}) == 4
    assert replicate_seeds(3, 4) == [r.seed for r in reps]
    values = [r.outputs["X"].value for r in reps]
    assert len(set(values)) == 4  # distinct draws, not copies
    assert all(r.outputs["X"].n == 400 for r in reps)  # each a full-size run
    # other seeds give other replicates
    assert set(replicate_seeds(4, 4)).isdisjoint(replicate_seeds(3, 4))


def test_adaptive_stopping_clear_early_borderline_late():
    clear = explore(
        lambda c, s: {"X": _mean(s, 0.0)},
        REG,
        {"X": RULES["X"]},
        seed=1,
        replicates=3,
        max_replicates=12,
        one_at_a_time=False,
    )
    assert clear.settings["replicates"] == 3
    # the true mean sits on the band's edge: intervals straddle it, more replicates are run (to the cap)
    border = explore(
        lambda c, s: {"X": _mean(s, 0.5, n=100)},
        REG,
        {"X": RULES["X"]},
        seed=1,
        replicates=3,
        max_replicates=12,
        one_at_a_time=False,
    )
    # projected far beyond the cap: no replicate is spent, and the record says how many would decide it
    assert border.settings["replicates"] == 3
    runs = border.record("X")["parts"]["claim"]["runs_to_decide"]
    assert border.record("X")["parts"]["claim"]["verdict"] == "undecided" and border.record("X")["label"] == "-"
    assert runs["now"] == 3 and (runs["replicates"] is None or runs["replicates"] > 12)
    assert "beyond the cap of 12" in runs["text"] or "no number of runs" in runs["text"]
    # a borderline claim that the extra replicates decide stops before the cap
    near = explore(
        lambda c, s: {"X": _mean(s, 0.56, n=100)},
        REG,
        {"X": RULES["X"]},
        seed=2,
        replicates=3,
        max_replicates=30,
        one_at_a_time=False,
    )
    assert 3 < near.settings["replicates"] < 30
    assert near.record("X")["parts"]["claim"]["verdict"] == "not reproduced"


def test_labels_are_per_part_and_say_what_they_cover():
    ex = explore(measure_joint_only, REG, {"Y": RULES["Y"]}, seed=5, replicates=3, joint=40)
    rec = ex.record("Y")
    assert rec["parts"]["p1"]["label"] == "robust"
    assert rec["parts"]["p2"]["label"] == "depends"  # c is a reading of the paper
    assert rec["label"] == "depends"
    assert any(w.startswith("(p2) not reproduced when c = y") for w in rec["where"])
    assert "5 one at a time over 3 register entries" in rec["coverage"]
    assert "3 independent replicates" in rec["coverage"]
    p1, p2 = rec["parts"]["p1"]["share"], rec["parts"]["p2"]["share"]
    assert p1["value"] == 1.0 and p1["decided"] == 17  # every distinct configuration of a, b and c
    assert p2["agree"] == 8 and p2["ci_low"] < 8 / 17 < p2["ci_high"]  # c = y in 9 of the 17


def test_no_world_entry_varied_cannot_be_robust():
    reg = Register([Entry("stat", "statistic", "mean", ("mean", "median"), "either summary")])
    ex = explore(lambda c, s: {"X": _mean(s, 0.0)}, reg, {"X": RULES["X"]}, seed=1)
    assert ex.record("X")["label"] == "unexplored"


def test_unstable_when_replicates_disagree_and_conditions_still_reported():
    def measure(config, seed):
        rng = np.random.default_rng(seed)
        shift = 0.0 if rng.random() < 0.5 else 3.0  # the whole run is a lucky or unlucky draw
        return {"X": _mean(seed, shift + 3.0 * (config["a"] == 1))}

    ex = explore(measure, REG, {"X": RULES["X"]}, seed=12, replicates=6)  # seed 12: the first replicate is lucky
    rec = ex.record("X")
    assert rec["label"] == "unstable"  # decisive disagreement: some replicates reproduce it, some decisively not
    assert rec["where"] == ["independent replicates disagree: reproduced in 3, not reproduced in 3 of 6"]
    assert rec["parts"]["claim"]["replicate_verdicts"].count("not reproduced") == 3
    assert any(c["changed"] == {"a": 1} for c in rec["conditions"])  # the conditions are still in the record


def test_pool_intervals_and_undecided():
    es = [Estimate(1.0, 0.1, 0.8, 1.2, 100, method="t"), Estimate(1.2, 0.1, 1.0, 1.4, 100, method="t")]
    p = pool(es)
    assert 1.0 < p.value < 1.2 and p.ci_high - p.ci_low < 0.4  # narrower than either
    nan = pool([es[0], Estimate(1.0, np.nan, np.nan, np.nan, 100, method="bootstrap")])
    assert InBand("q", 0.5, 2.0).decide(nan) == "undecided"
    assert pool([{"a": es[0]}, {"a": es[1]}])["a"].n == 200
    assert pool([2.0, 2.0, 2.0]).value == 2.0


def test_pool_of_replicates_with_no_value_is_undefined_without_a_warning():
    # every run of every replicate lost lock: the "in lock" value is NaN in each, and so is the pooled one (the
    # verdict undecided) -- quietly, since a warning on stderr is a fault in a notebook's output
    none = Estimate(math.nan, math.nan, math.nan, math.nan, 0, method="bootstrap")
    some = Estimate(2.0, 0.5, 1.0, 3.0, 10, method="bootstrap")
    lost = [{"value": some, "in lock": none, "lost": 10, "runs": 10}] * 3
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        p = pool(lost)
        assert math.isnan(p["in lock"].value) and math.isnan(p["in lock"].ci_low)
        assert p["value"].value == pytest.approx(2.0) and (p["lost"], p["runs"]) == (30, 30)
        assert pool([none, some]).value == 2.0  # the replicates that have a value: their mean, the interval undefined
        assert math.isnan(pool([none, some]).ci_high)


def test_results_claim_from_an_exploration(tmp_path):
    res = Results("000_x", "c", {"seed": 1, "output_dir": str(tmp_path)})
    ex = explore(measure_renamed, REG, {"C000-1": RULES["Y"]}, seed=5, replicates=3, joint=10)
    c = res.claim("C000-1", "s", "p", RULES["Y"], exploration=ex)
    assert c.robustness["label"] == "depends" and c.robustness["register"][0]["name"] == "a"
    assert c.verdict == "reproduced"  # both parts hold at the default; p2 flips only when c = y
    assert c.measured["p1"].n == 1200  # the three replicates pooled
    assert res.to_dict()["register"][0]["kind"] == "regime"


def test_joint_sample_is_space_filling_and_skips_single_axis_configs():
    cfgs = joint_sample(REG, ["a", "b", "c"], 30, seed=0)
    assert all(sum(cfg[k] != REG.default()[k] for k in "abc") >= 2 for cfg in cfgs)
    assert {cfg["a"] for cfg in cfgs} >= {1, 2} and {cfg["b"] for cfg in cfgs} >= {1, 2}


def test_the_joint_design_combines_only_values_at_the_papers_operating_point():
    # a value marked off the operating point is counted beside the label: a joint sample spent there would leave the
    # label resting on fewer joints (004's design spent about two thirds of its joints on its marked bandwidths)
    reg = Register(
        [
            Entry("a", "regime", 0, (0, 1, 2, 3), "w", off_operating_point=(2, 3)),
            Entry("b", "regime", 0, (0, 1, 2), "w"),
            Entry("c", "reading", "x", ("x", "y"), "w"),
            Entry("d", "regime", 0, (0, 9), "w", off_operating_point=(9,)),
        ]
    )
    assert reg["a"].operating_values == (0, 1) and reg["d"].operating_values == (0,)
    cfgs = joint_sample(reg, ["a", "b", "c", "d"], 40, seed=3)
    assert cfgs and all(c["a"] in (0, 1) and c["d"] == 0 for c in cfgs)
    assert {c["a"] for c in cfgs} == {0, 1} and {c["b"] for c in cfgs} == {0, 1, 2}
    ex = explore(lambda cfg, seed: {"X": _mean(seed, 0.0)}, reg, {"X": InBand(-0.5, 0.5)}, seed=1, joint=12)
    tried = [r.changed(reg.default()) for r in ex.runs if r.stage == "single"]
    assert {"a": 2} in tried and {"a": 3} in tried and {"d": 9} in tried  # still tried one at a time


def test_bad_designs_are_refused():
    with pytest.raises(ValueError, match="at least 3"):
        explore(measure_joint_only, REG, RULES, seed=1, replicates=2)
    with pytest.raises(KeyError, match="unknown register"):
        explore(measure_joint_only, REG, RULES, seed=1, depends={"X": ["zz"]})


def test_ordering_undecided_on_extrapolated_estimate():
    e = Estimate(1e-13, 0.0, 1e-14, 1e-12, 50, method="logistic fit", extrapolated=True)
    assert Ordering("a", "b", "<", measure="difference").decide(e) == "undecided"


def _measure_module_level(config, seed):
    return {"X": _mean(seed, 3.0 * (config["a"] == 2))}


def test_an_executor_gives_the_same_exploration_as_in_process():
    from concurrent.futures import ThreadPoolExecutor

    here = explore(_measure_module_level, REG, {"X": RULES["X"]}, seed=9, replicates=3, joint=6)
    with ThreadPoolExecutor(2) as pool_:
        there = explore(_measure_module_level, REG, {"X": RULES["X"]}, seed=9, replicates=3, joint=6, executor=pool_)
    assert [r.outputs["X"].value for r in here.runs] == [r.outputs["X"].value for r in there.runs]
    assert here.record("X")["where"] == there.record("X")["where"]
    assert here.record("X")["where"][0] == "not reproduced when a = 2"


def test_a_batched_measurement_sees_every_configuration_of_a_stage_at_once():
    calls = []

    def batched(configs, seeds):
        calls.append(len(configs))
        return [_measure_module_level(c, s) for c, s in zip(configs, seeds)]

    ex = explore(batched, REG, {"X": RULES["X"]}, seed=9, replicates=3, batched=True)
    # the three replicates in one call, the five one-at-a-time values in one; the default decided on its first
    # replicate, so a condition of one replicate is sized like it: no sizing call
    assert ex.settings["replicates_needed"] == {"X": 1}
    assert calls == [3, 5]
    assert ex.record("X")["label"] == "limited"  # a = 2 is a regime of the world


def test_executor_for_refuses_an_address_without_port_in_one_line():
    from tvtrack.explore import executor_for

    assert executor_for("") is None
    with pytest.raises(ValueError, match="has no port"):
        executor_for("localhost")


def test_shares_from_counts_pool_as_counts():
    from tvtrack.explore import pool
    from tvtrack.montecarlo import Estimate, proportion_ci, zero_events_bound

    zero = Estimate(0.0, float("nan"), 0.0, zero_events_bound(8), 8, 0.95, "count: zero events")
    p = pool([zero, zero, zero])
    assert (p.value, p.ci_low, p.n) == (0.0, 0.0, 24)
    assert p.ci_high == pytest.approx(zero_events_bound(24))  # averaging the intervals would give ~0.10
    mixed = pool([proportion_ci(2, 10), proportion_ci(0, 10), proportion_ci(1, 10)])
    ref = proportion_ci(3, 30)
    assert (mixed.value, mixed.ci_low, mixed.ci_high) == pytest.approx((ref.value, ref.ci_low, ref.ci_high))


def test_a_joint_condition_is_described_by_the_entries_the_claim_reads():
    ex = explore(
        measure_joint_only, REG, RULES, seed=7, replicates=3, joint=40, depends={"X": ["a", "b"], "Y": ["a", "c"]}
    )
    joint = [c for c in ex.record("X")["conditions"] if c["kind"] == "joint"]
    assert joint and all(set(c["changed"]) <= {"a", "b"} for c in joint)
    assert any(r.changed(ex.default).get("c") == "y" for r in ex.runs if r.stage == "joint")  # c did vary


def test_executor_for_a_port_where_nothing_or_no_scheduler_listens_is_one_line_within_the_limit():
    import socket
    import threading
    import time

    from tvtrack.explore import executor_for

    s = socket.socket()
    s.bind(("127.0.0.1", 0))
    port = s.getsockname()[1]
    s.close()
    with pytest.raises(ValueError, match="cannot reach"):
        executor_for(f"127.0.0.1:{port}", timeout_s=2)
    silent = socket.socket()
    silent.bind(("127.0.0.1", 0))
    silent.listen(1)
    held = []
    threading.Thread(target=lambda: held.append(silent.accept()), daemon=True).start()
    t0 = time.perf_counter()
    with pytest.raises(ValueError, match="no Dask scheduler answers"):
        executor_for(f"127.0.0.1:{silent.getsockname()[1]}", timeout_s=2)
    assert time.perf_counter() - t0 < wall_budget(10)
    silent.close()


def test_results_keep_the_union_of_the_registers_of_several_explorations(tmp_path):
    res = Results("000_x", "c", {"seed": 1, "output_dir": str(tmp_path)})
    other = Register([Entry("d", "regime", 0, (0, 1), "another study's regime")])
    ex1 = explore(measure_renamed, REG, {"C000-1": RULES["Y"]}, seed=5, replicates=3)
    ex2 = explore(lambda c, s: {"C000-2": _mean(s, 0.0)}, other, {"C000-2": RULES["X"]}, seed=5, replicates=3)
    res.claim("C000-1", "s", "p", RULES["Y"], exploration=ex1)
    res.claim("C000-2", "s", "p", RULES["X"], exploration=ex2)
    assert [e["name"] for e in res.register] == ["a", "b", "c", "d"]


def test_a_small_register_gets_every_joint_combination():
    # C000-4 flips only when both of its two entries are off their defaults: a sample could miss that one cell
    from tvtrack.explore import joint_sample

    small = Register([Entry("a", "reading", 0, (0, 1), "w"), Entry("b", "scale", "x", ("x", "y", "z"), "w")])
    got = joint_sample(small, ["a", "b"], 4, seed=1)
    assert sorted((c["a"], c["b"]) for c in got) == [(1, "y"), (1, "z")]
    assert joint_sample(small, ["a", "b"], 1, seed=1) != got  # fewer samples than cells: a Latin-hypercube sample


def test_a_pinned_joint_condition_is_measured_every_run():
    # a flip found once by a joint sample (a = 2 and b = 2) stays in the record when the joint stage misses it
    plain = explore(measure_joint_only, REG, {"X": RULES["X"]}, seed=7, replicates=3, joint=0)
    assert plain.record("X")["parts"]["claim"]["flips"] == []
    pinned = REG.with_pinned({"a": 2, "b": 2})
    ex = explore(measure_joint_only, pinned, {"X": RULES["X"]}, seed=7, replicates=3, joint=0)
    rec = ex.record("X")
    assert rec["label"] == "limited" and any("a = 2 and b = 2" in w for w in rec["where"])
    assert "1 pinned known flip" in rec["coverage"] and "1 pinned known flips" not in rec["coverage"]
    assert pinned.subset(["a", "c"]).pinned == [] and pinned.subset(["a", "b"]).pinned == [{"a": 2, "b": 2}]
    with pytest.raises(ValueError, match="not among"):
        REG.with_pinned({"a": 5, "b": 2})
    with pytest.raises(ValueError, match="at least two"):
        REG.with_pinned({"a": 2})


def test_certified_bounds_pool_to_their_envelope_never_below_zero():
    bound = [Estimate(0.0, 0.003, 0.0, b, 6, 0.95, "bound from the grid's top") for b in (0.004, 0.0066, 0.005)]
    p = pool(bound)
    assert (p.value, p.ci_low, p.ci_high) == (0.0, 0.0, 0.0066)  # a linear pool gave [-0.006, 0.006]
    mixed = pool([bound[0], Estimate(0.03, 0.01, 0.01, 0.09, 6, 0.95, "ratio")])
    assert mixed.ci_low == 0.0 and mixed.ci_high == 0.09
    upper = [Estimate(0.58, 0.1, 0.0, 0.71, 2, 0.95, "upper bound"), Estimate(0.87, 0.5, 0.11, 6.6, 2, 0.95, "ratio")]
    assert (pool(upper).ci_low, pool(upper).ci_high) == (0.0, 6.6)  # a ratio's pooled interval never below zero
    lower = pool([Estimate(2.0, 0.5, 1.5, math.inf, 6, 0.95, "fold"), Estimate(3.0, 0.5, 2.5, math.inf, 6, 0.95, "f")])
    assert lower.ci_low == 1.5 and lower.ci_high == math.inf


def test_a_linear_pool_stays_within_the_replicates_intervals():
    # paired share differences near their edge: each replicate's interval ends at 1, the pool must too
    reps = [Estimate(0.97, 0.04, 0.85, 1.0, 6, 0.95, "paired t"), Estimate(0.97, 0.03, 0.9, 1.0, 6, 0.95, "paired t")]
    reps.append(Estimate(0.96, 0.05, -0.2, 1.0, 6, 0.95, "paired t"))
    p = pool(reps)
    assert p.ci_high <= 1.0 and p.ci_low < p.value < p.ci_high  # a linear pool gave 1.2
    # replicates that disagree are widened to Student's t over their values, which the hull stops at 1
    apart = pool([*reps[:2], Estimate(0.2, 0.03, 0.15, 0.25, 6, 0.95, "paired t")])
    assert (apart.ci_low, apart.ci_high) == (0.15, 1.0) and "disagree" in apart.method


def test_a_log_scale_pool_stays_within_the_replicates_intervals():
    # positive share differences pool on the log scale; their pooled interval must not pass 1 either (C003-4)
    reps = [Estimate(0.97, 0.05, 0.8, 1.0, 6, 0.95, "paired t"), Estimate(0.97, 0.04, 0.85, 1.0, 6, 0.95, "paired t")]
    reps.append(Estimate(0.97, 0.03, 0.9, 1.0, 6, 0.95, "paired t"))
    p = pool(reps)
    assert p.ci_high <= 1.0 and p.ci_low < p.value < p.ci_high and "log scale" in p.method  # was 1.019
    apart = pool([*reps[:2], Estimate(0.3, 0.03, 0.25, 0.35, 6, 0.95, "paired t")])
    assert apart.ci_high == 1.0 and "log scale" in apart.method and "disagree" in apart.method


# --------------------------------------------------------------------------- measuring only the claims asked


def _depends_xy():
    return {"X": ["a", "b"], "Y": ["c"]}


def test_a_measure_taking_claims_gives_the_same_exploration_and_skips_what_no_claim_needs():
    asked = []

    from tvtrack.register import Undeclared

    def subset(config, seed, claims=None):  # reads only what the asked claims declare (the guard checks it)
        asked.append(({k: v for k, v in config.items() if not isinstance(v, Undeclared)}, claims))
        out = {}
        if claims is None or "X" in claims:
            a, b = config["a"], config["b"]
            out["X"] = _mean(seed, 3.0 if (a == 2 and b == 2) else 0.01 * (a + b))  # as measure_joint_only
        if claims is None or "Y" in claims:
            out["Y"] = {"p1": _mean(seed, 0.0), "p2": _mean(seed, 3.0 * (config["c"] == "y"))}
        return out

    design = dict(seed=3, replicates=3, joint=8, depends=_depends_xy())
    plain = explore(measure_joint_only, REG, RULES, **design)
    lean = explore(subset, REG, RULES, **design)
    assert lean.settings["measures_claims_asked"] and not plain.settings["measures_claims_asked"]
    for cid in RULES:  # every verdict, label and flip is the same
        a, b = plain.record(cid), lean.record(cid)
        for part in a["parts"]:
            for key in ("verdict", "label", "flips", "share"):
                assert a["parts"][part][key] == b["parts"][part][key], (cid, part, key)
    # a condition measures only the claims that read what it changes; replicates measure all
    default = REG.default()
    for config, claims in asked:
        changed = {k for k in config if config[k] != default[k]}  # only the declared entries (the others guarded)
        if not changed:
            assert claims is None
        else:
            assert claims == {c for c, names in _depends_xy().items() if changed & set(names)}
    assert any(c == {"Y"} for _, c in asked) and any(c == {"X"} for _, c in asked)


def test_sizing_adds_replicates_only_to_the_claims_still_undecided():
    reg = Register([Entry("a", "regime", 0, (0, 1), "w")])
    rules = {"clear": InBand("m", -0.5, 0.5), "edge": InBand("m", -0.5, 0.5)}
    asked = []

    def measure(config, seed, claims=None):
        asked.append(claims)
        out = {"clear": _mean(seed, 0.0), "edge": _mean(seed + 12, 0.45, n=100)}
        return out if claims is None else {k: out[k] for k in claims}

    ex = explore(measure, reg, rules, seed=2, replicates=3, max_replicates=12, one_at_a_time=False)
    assert ex.settings["replicates"] > 3
    sized = asked[3 : ex.settings["replicates"]]
    assert sized and all(c == {"edge"} for c in sized)  # the clear claim spends nothing more
    reps = [r for r in ex.runs if r.stage == "replicate"]
    assert sum("clear" in r.outputs for r in reps) == 3 and sum("edge" in r.outputs for r in reps) == len(reps)
    assert len(ex.record("clear")["replicates"]) == 3


def test_a_confirmation_re_measures_only_the_claims_that_may_flip():
    def full(config, seed, claims=None, n=400):
        out = {
            "X": _mean(seed, 3.0 * (config["a"] == 1) * (config["b"] == 1), n=n),
            "Y": {"p1": _mean(seed, 0.0, n=n), "p2": _mean(seed, 3.0 * (config["c"] == "y"), n=n)},
        }
        return out if claims is None else {k: out[k] for k in claims}

    def small(config, seed, claims=None):
        return full(config, seed, claims, n=40)

    ex = explore(full, REG, RULES, seed=5, replicates=3, joint=8, screen=small, screen_singles=True)
    for r in ex.runs:
        if r.stage in ("single", "joint"):
            flips_x = r.config["a"] == 1 and r.config["b"] == 1
            flips_y = r.config["c"] == "y"
            assert ("X" in r.claims) >= flips_x and ("Y" in r.claims) >= flips_y  # every flip confirmed
            n_x = r.outputs["X"].n
            assert n_x == (400 if "X" in r.claims else 40)  # confirmed claims at full size, the others screened
    assert 0 < ex.settings["confirmed_claims"] < 2 * ex.settings["confirmed_at_full_size"]  # not every claim


def test_sizing_measures_every_undecided_claim_not_only_those_projected_to_decide():
    """A claim whose projection from few replicates exceeds the cap still gets the replicates that another claim's
    sizing adds (its projection is noisy; left out, it would stay pooled over fewer replicates than the run has)."""
    reg = Register([Entry("a", "regime", 0, (0, 1), "w")])
    rules = {"edge": InBand("m", -0.5, 0.5), "far": InBand("m", -0.5, 0.5)}
    asked = []

    def measure(config, seed, claims=None):
        asked.append(claims)
        out = {"edge": _mean(seed + 12, 0.45, n=100), "far": _mean(seed + 11, 0.5, n=100)}
        return out if claims is None else {k: out[k] for k in claims}

    ex = explore(measure, reg, rules, seed=2, replicates=3, max_replicates=12, one_at_a_time=False)
    n = ex.settings["replicates"]
    undecided_far = [i for i in range(3, n) if "far" in (asked[i] or ())]
    reps = [r for r in ex.runs if r.stage == "replicate"]
    assert n > 3 and sum("far" in r.outputs for r in reps) == 3 + len(undecided_far)
    assert len(undecided_far) == n - 3  # undecided at n = 3 and every step: measured in every sizing replicate


def _edge_and_near(config, seed, claims=None):
    out = {"edge": _mean(seed + 7, 0.42, n=100), "near": _mean(seed + 11, 0.35, n=60)}
    return out if claims is None else {k: out[k] for k in claims}


@pytest.mark.parametrize("seed", [0, 1, 6, 9])
def test_the_sizing_keeps_the_same_replicates_whatever_the_number_of_workers(seed):
    """Three workers measure up to three sizing replicates at once; the explorer keeps exactly the replicates,
    and the claims in each, that one at a time would have given (a replicate after which the sizing would have
    stopped is dropped, one measured for a claim decided meanwhile is measured again without it). These seeds
    kept more replicates, or more claims in them, with three workers before (1 stands in for 4, whose first three
    replicates disagree beyond their intervals, so that the pool is widened and its sizing stops at three)."""
    from concurrent.futures import ThreadPoolExecutor

    reg = Register([Entry("a", "regime", 0, (0, 1), "w")])
    rules = {"edge": InBand("m", -0.5, 0.5), "near": InBand("m", -0.5, 0.5)}
    kw = dict(seed=seed, replicates=3, max_replicates=20, one_at_a_time=False)
    alone = explore(_edge_and_near, reg, rules, **kw)
    with ThreadPoolExecutor(3) as pool_:
        wide = explore(_edge_and_near, reg, rules, executor=pool_, **kw)

    def replicates(ex):
        return [
            (r.seed, r.claims, {c: e.value for c, e in r.outputs.items()}) for r in ex.runs if r.stage == "replicate"
        ]

    assert alone.settings["replicates"] > 3  # the sizing ran
    assert replicates(wide) == replicates(alone)
    assert wide.settings["replicates"] == alone.settings["replicates"]
    for cid in rules:
        assert wide.measured(cid) == alone.measured(cid)
        assert wide.record(cid)["replicates"] == alone.record(cid)["replicates"]
    kept = alone.settings["replicates"] - 3
    assert alone.settings["timing"]["sizing"]["configurations"] == kept  # in process: one at a time, none dropped
    assert wide.settings["timing"]["sizing"]["configurations"] > kept  # some measured at once were dropped


def _burn_cpu(config: dict, seed: int) -> dict:
    """A measurement that spends 0.2 s of CPU in whichever process runs it."""
    t = time.process_time()
    while time.process_time() - t < 0.2:
        pass
    return {"x": float(seed)}


def test_stage_cpu_seconds_count_the_executors_workers():
    """A stage measured in a process pool is charged the workers' CPU (the kernel's own clock saw ~0: 003's
    exploration reported 656 configurations per CPU second in `make bench`)."""
    from concurrent.futures import ProcessPoolExecutor

    from tvtrack.explore import Run
    from tvtrack.jobs import StageClock

    with ProcessPoolExecutor(1) as pool:
        pool.submit(int).result()  # the worker is up before the stage: its start-up is not the stage's
        clock = StageClock(batched=False, executor=pool)
        clock.run(_burn_cpu, [Run({}, s, "replicate") for s in range(3)], "replicates")
    row = clock.table()["replicates"]
    assert row["configurations"] == 3 and 0.5 < row["cpu_s"] < 1.5 * row["wall_s"] + 0.1, row


def _burn_in_a_pool_of_its_own(config: dict, seed: int) -> dict:
    """A measurement that, as 004's does, starts a process pool for its call and shuts it down before returning."""
    from concurrent.futures import ProcessPoolExecutor

    with ProcessPoolExecutor(1) as pool:
        return pool.submit(_burn_cpu, config, seed).result()


def test_stage_cpu_seconds_count_the_pools_a_measurement_starts_and_ends():
    """A worker that ended inside the stage is charged to it: the live-children reading alone lost it (004's
    paper-profile record charged its subset search a fraction of the CPU the run's `time -v` counted)."""
    from tvtrack.explore import Run
    from tvtrack.jobs import StageClock

    clock = StageClock(batched=False, executor=None)
    clock.run(_burn_in_a_pool_of_its_own, [Run({}, s, "replicate") for s in range(3)], "replicates")
    row = clock.table()["replicates"]
    assert row["configurations"] == 3 and 0.55 < row["cpu_s"] < 2 * row["wall_s"] + 0.1, row


def _blas_threads(_=None) -> int:
    from threadpoolctl import threadpool_info

    return max(i["num_threads"] for i in threadpool_info())


def test_a_measurements_pool_gives_each_worker_its_share_of_the_blas_threads(monkeypatch):
    """Each forked worker keeps to cores // workers BLAS threads (at least 1), and never to more than its parent
    had: two workers with a thread per core each ran a BLAS-bound batch several times slower on two cores."""
    import os

    from tvtrack.jobs import blas_share, fork_pool

    monkeypatch.setattr(os, "sched_getaffinity", lambda pid: set(range(8)))
    assert [blas_share(w) for w in (1, 2, 3, 8, 16)] == [8, 4, 2, 1, 1]
    monkeypatch.undo()
    cores = len(os.sched_getaffinity(0))
    parent = _blas_threads()
    for workers in (1, 2, 2 * cores):
        with fork_pool(workers) as pool:
            seen = set(pool.map(_blas_threads, range(2 * workers)))
        assert seen == {min(parent, max(1, cores // workers))}, (workers, seen, parent)


# --------------------------------------------------------------------------- kinds and entries that cannot leak


def test_three_sides_each_with_plain_words():
    from tvtrack.register import ENTRY_KINDS, SIDE_PHRASES, side_of

    assert "unreported setting" in ENTRY_KINDS
    assert [side_of(k) for k in ("reading", "statistic", "unreported setting", "regime", "scale")] == [
        "reading",
        "reading",
        "setting",
        "world",
        "world",
    ]
    e = Entry("law", "unreported setting", "linear", ("linear", "sine"), "the paper's rate law is not printed")
    assert e.side == "setting" and e.to_dict()["side"] == "setting"
    assert SIDE_PHRASES["setting"] == "a setting of the paper's own experiment that the paper never printed"


def test_a_guarded_configuration_raises_on_every_use_of_an_undeclared_entry_and_copies_freely():
    import copy
    import pickle

    from tvtrack.register import UndeclaredEntry, guard

    cfg = guard({"a": 1, "b": "x"}, ["a"])
    assert dict(cfg)["a"] == 1 and {**cfg}["a"] == 1  # copying does not use the value
    copy.deepcopy(cfg), pickle.loads(pickle.dumps(cfg))
    assert "b" in repr(cfg["b"])  # harmless in an error message
    uses = [
        lambda v: v == "x",
        lambda v: "x" == v,
        lambda v: v != "x",
        lambda v: v in ("x", "y"),
        lambda v: hash(v),
        lambda v: bool(v),
        lambda v: str(v),
        lambda v: f"{v:>3}",
        lambda v: float(v),
        lambda v: int(v),
        lambda v: list(v),
        lambda v: v.lower(),
        lambda v: v < 1,
        lambda v: v + 1,
        lambda v: 2.0 * v,
        lambda v: np.asarray(v, float),
    ]
    for use in uses:
        with pytest.raises(UndeclaredEntry, match="register entry 'b'"):
            use(cfg["b"])
    assert issubclass(UndeclaredEntry, LookupError)


def test_check_declared_names_the_claim_that_reads_an_entry_it_does_not_declare():
    from tvtrack.explore import check_declared

    reg = Register([Entry("a", "regime", 0, (0, 1), "w"), Entry("b", "unreported setting", 0, (0, 1), "w")])

    def leaky(config, seed, claims=None):
        out = {}
        if claims is None or "X" in claims:
            out["X"] = float(config["a"] + config["b"])  # X reads b, which it does not declare
        if claims is None or "Y" in claims:
            out["Y"] = float(config["b"])
        return out

    bad = check_declared(leaky, reg, {"X": ["a"], "Y": ["b"]}, seed=1)
    assert list(bad) == ["X"] and "'b'" in bad["X"]
    assert check_declared(leaky, reg, {"X": ["a", "b"], "Y": ["b"]}, seed=1) == {}

    def asks_all(config, seed):  # no ``claims``: everything is measured, the guard allows every declared entry
        return leaky(config, seed)

    assert check_declared(asks_all, reg, {"X": ["a"], "Y": ["b"]}, seed=1) == {}
    assert list(check_declared(asks_all, reg, {"X": ["a"], "Y": ["a"]}, seed=1)) == ["X", "Y"]


def _leaky(config, seed, claims=None):
    """X declares only a, but its value moves with b (a leak); Y declares b."""
    out = {}
    if claims is None or "X" in claims:
        out["X"] = _mean(seed, 3.0 * (config["b"] == 1))
    if claims is None or "Y" in claims:
        out["Y"] = _mean(seed + 1, 0.0)
    return out


def test_a_condition_runs_each_claim_only_in_the_world_its_depends_declares():
    depends = {"X": ["a"], "Y": ["b"]}
    rules = {"X": RULES["X"], "Y": RULES["X"]}
    ex = explore(_leaky, REG, rules, seed=3, replicates=3, joint=8, depends=depends, guard=False)
    for r in ex.runs:
        if r.stage != "replicate" and r.counts_for("X"):
            assert r.config["b"] == 0 and r.config["c"] == "x"  # projected: only a changes for X
    rec = ex.record("X")
    assert rec["parts"]["claim"]["flips"] == [] and all(set(c["changed"]) == {"a"} for c in rec["conditions"])


def test_a_measurement_that_reads_an_undeclared_entry_raises_naming_it():
    from tvtrack.register import UndeclaredEntry

    with pytest.raises(UndeclaredEntry, match="register entry 'b'"):
        explore(_leaky, REG, {"X": RULES["X"], "Y": RULES["X"]}, seed=3, depends={"X": ["a"], "Y": ["b"]})


def test_a_condition_is_sized_on_the_defaults_seeds_until_it_decides():
    """a = 1 moves the mean to 0.75: one run's interval (n = 25) straddles the band edge 0.5; the replicates the
    default's sizing rule asks for decide that it flips."""

    def measure(config, seed):
        return {"X": _mean(seed, 0.75 * (config["a"] == 1), n=25)}

    ex = explore(measure, REG, {"X": RULES["X"]}, seed=2, replicates=3, max_replicates=16, depends={"X": ["a"]})
    single = next(r for r in ex.runs if r.stage == "single" and r.config["a"] == 1)
    assert RULES["X"].decide(single.outputs["X"]) == "undecided"  # one run cannot tell
    assert [s.seed for s in single.sized] == replicate_seeds(2, 16)[1 : len(single.sized) + 1]  # the default's seeds
    rec = ex.record("X")
    row = next(c for c in rec["conditions"] if c["changed"] == {"a": 1})
    # three replicates (the default's) still straddle; two more decide it
    assert ex.settings["replicates"] == 3 and row["runs"] == 5 and row["parts"]["claim"] == "not reproduced"
    assert rec["label"] == "limited" and rec["parts"]["claim"]["flips"][0]["runs"] == row["runs"]
    assert "condition sizing" in ex.settings["timing"] and "every condition" in ex.settings["stopping"]
    assert ex.settings["condition_runs"] == sum(len(r.sized) for r in ex.runs)


def test_a_condition_counts_only_at_the_size_the_default_needed_to_decide():
    """A zero-loss part: each replicate is 6 runs without a loss, and zero events certify a loss rate below 0.1
    only from 29 runs on, so the default needs 5 replicates (30 runs) to decide it; a clear part decides on its
    first replicate. A condition with no loss counts as agreeing only once it holds the default's 5 replicates:
    one 6-run replicate never certifies it, and the record says how many runs each condition had."""
    from tvtrack.explore import replicates_needed
    from tvtrack.montecarlo import zero_events_bound

    def zero(n):
        return Estimate(0.0, float("nan"), 0.0, zero_events_bound(n), n, 0.95, "count: zero events")

    def measure(config, seed):
        return {"L": zero(6), "X": _mean(seed, 0.0)}

    rules = {"L": InBand("loss rate", None, 0.1), "X": RULES["X"]}
    ex = explore(measure, REG, rules, seed=5, replicates=3, max_replicates=8, depends={"L": ["a"], "X": ["a"]})
    assert ex.settings["replicates"] == 5 and ex.settings["replicates_needed"] == {"L": 5, "X": 1}
    rec = ex.record("L")
    assert all(c["runs"] == 5 for c in rec["conditions"]) and rec["parts"]["claim"]["share"]["agree"] == 2
    assert all(c["runs"] == 1 for c in ex.record("X")["conditions"])  # X decided on one replicate: so do they
    runs = [r for r in ex.runs if r.stage == "replicate"]
    decided_l = {("L", "claim"): type("J", (), {"verdict": "reproduced"})()}
    assert replicates_needed(rules, runs[:3], decided_l)["L"] == 3  # three that never decide it: all of them


def _zero_loss_or_loss(config, seed):
    """A loss-rate part certified below 0.1 only from 29 runs (5 replicates of 6 runs): no loss at the default and
    at a = 1 (leans towards agreement: 0 of 6), every run lost at a = 2 (leans towards a flip: 6 of 6)."""
    from tvtrack.montecarlo import zero_events_bound

    if config["a"] == 2:
        return {"L": Estimate(1.0, float("nan"), 0.54, 1.0, 6, 0.95, "count: 6 of 6")}
    return {"L": Estimate(0.0, float("nan"), 0.0, zero_events_bound(6), 6, 0.95, "count: zero events")}


def test_the_sizing_budget_never_holds_back_a_condition_leaning_towards_a_flip():
    """Budget 0: the condition whose first replicate lies on the other side of the rule (a = 2, every run lost) is
    still sized to the default's 5 replicates and flips; the one leaning towards agreement (a = 1) stays at one
    replicate, undecided, marked as left by the budget with the 5 replicates that would decide it, and the share
    says so. Without a budget both are sized."""
    from tvtrack.conditions import leans_flip
    from tvtrack.wording import share_counts

    rules = {"L": InBand("loss rate", None, 0.1)}
    kw = dict(seed=5, replicates=3, max_replicates=8, depends={"L": ["a"]}, one_at_a_time=True)
    ex = explore(_zero_loss_or_loss, REG, rules, sizing_budget=0, **kw)
    rows = {c["changed"]["a"]: c for c in ex.record("L")["conditions"] if c["kind"] == "single"}
    assert ex.settings["replicates_needed"] == {"L": 5}
    assert rows[2]["runs"] == 5 and rows[2]["parts"]["claim"] == "not reproduced"
    assert rows[1]["runs"] == 1 and rows[1]["parts"]["claim"] == "undecided" and rows[1]["left_by_budget"] == 5
    share = ex.record("L")["parts"]["claim"]["share"]
    assert (share["agree"], share["flip"], share["undecided"], share["left_by_budget"]) == (0, 1, 1, 1)
    assert "1 of them leans towards agreement but was given" in share_counts(share)
    assert ex.settings["left_by_budget"] == 1 and ex.settings["sizing_budget_used"] == 0
    default_j = {("L", "claim"): type("J", (), {"verdict": "reproduced"})()}
    single = {r.config["a"]: r for r in ex.runs if r.stage == "single"}
    assert leans_flip(rules["L"], single[2], "L", default_j) and not leans_flip(rules["L"], single[1], "L", default_j)
    full = explore(_zero_loss_or_loss, REG, rules, **kw)
    rows = {c["changed"]["a"]: c for c in full.record("L")["conditions"] if c["kind"] == "single"}
    assert rows[1]["runs"] == 5 and rows[1]["parts"]["claim"] == "reproduced" and "left_by_budget" not in rows[1]
    assert full.settings["left_by_budget"] == 0 and full.record("L")["parts"]["claim"]["share"]["left_by_budget"] == 0


def test_the_sizing_budget_goes_to_the_conditions_in_order_and_counts_runs():
    """A budget of 4 runs sizes the first condition leaning towards agreement (one replicate to the default's 5:
    4 runs) and leaves the next; the budget spent is stated."""
    from tvtrack.conditions import Run, SizingBudget, size_conditions

    rules = {"L": InBand("loss rate", None, 0.1)}
    default_j = {("L", "claim"): rules["L"].judge(_zero_loss_or_loss({"a": 0}, 0)["L"])}
    assert default_j[("L", "claim")].verdict == "undecided"  # one 6-run replicate cannot certify: pool five
    pooled = pool([_zero_loss_or_loss({"a": 0}, s)["L"] for s in range(5)])
    default_j = {("L", "claim"): rules["L"].judge(pooled)}
    assert default_j[("L", "claim")].verdict == "reproduced"
    conds = []
    for a in (1, 1):
        r = Run({"a": a, "b": 0, "c": "x"}, 0, "single", scope=frozenset({"L"}))
        r.outputs = _zero_loss_or_loss(r.config, 0)
        conds.append(r)
    budget = SizingBudget(4)
    calls = []
    added = size_conditions(
        lambda c, s: _zero_loss_or_loss(c, s),
        rules,
        conds,
        default_j,
        {"L": 5},
        list(range(10)),
        8,
        lambda m, jobs, stage: calls.append(len(jobs)) or [j.outputs.update(m(j.config, j.seed)) for j in jobs],
        budget,
    )
    assert added == 4 and budget.used == 4 and budget.left == 1
    assert conds[0].n_runs("L") == 5 and conds[1].n_runs("L") == 1 and conds[1].left == {"L": 5}


def test_a_sub_combination_leaning_towards_agreement_is_not_sized():
    """Every run lost only when a = 2, b = 2 and c = y together (a pinned joint configuration): its pairs (no loss
    in 6 runs) lean towards agreement and are searched for a flip only, so none is sized to the default's 5
    replicates, while the pinned configuration that flips is; the flip stays a joint one, no smaller subset named."""
    from tvtrack.montecarlo import zero_events_bound

    def measure(config, seed):
        if (config["a"], config["b"], config["c"]) == (2, 2, "y"):
            return {"L": Estimate(1.0, float("nan"), 0.54, 1.0, 6, 0.95, "count: 6 of 6")}
        return {"L": Estimate(0.0, float("nan"), 0.0, zero_events_bound(6), 6, 0.95, "count: zero events")}

    rules = {"L": InBand("loss rate", None, 0.1)}
    reg = Register(list(REG), pinned=[{"a": 2, "b": 2, "c": "y"}])
    ex = explore(measure, reg, rules, seed=5, replicates=3, max_replicates=8)
    combos = [r for r in ex.runs if r.stage == "combination"]
    assert len(combos) == 3 and all(r.n_runs("L") == 1 and r.left == {"L": 5} for r in combos)
    flipped = next(
        r for r in ex.runs if r.stage == "pinned" and (r.config["a"], r.config["b"], r.config["c"]) == (2, 2, "y")
    )
    assert flipped.n_runs("L") == 5
    flips = ex.record("L")["parts"]["claim"]["flips"]
    assert len(flips) == 1 and flips[0]["changed"] == {"a": 2, "b": 2, "c": "y"}


def test_pooling_keeps_a_numeric_reading_tag_and_pools_what_was_measured():
    """A reading named by a number (a contrast of 0) selects a rule: pooled over replicates it stays that number,
    never an Estimate of it, so the rule of that reading judges the pooled value."""
    from tvtrack.montecarlo import Estimate
    from tvtrack.verdicts import AllOf, ByReading, InBand

    tags = [ByReading.tag(0.0, {"a": Estimate(v, 0.1, v - 0.2, v + 0.2, 50, method="t")}) for v in (1.0, 1.2)]
    pooled = pool(tags)
    assert pooled["reading"] == 0.0 and isinstance(pooled["reading"], float)
    assert pooled["measured"]["a"].value == pytest.approx(1.2**0.5)  # pooled on the log scale
    rule = ByReading(
        "contrast",
        {0.0: AllOf({"a": InBand("x", 0.5, 2.0)})},
        AllOf({"a": InBand("x", 0.5, 2.0), "b": InBand("y", 0.5, 2.0)}),
    )
    assert rule.decide(pooled) == "reproduced"  # judged by the zero-contrast rule, whose parts were measured
