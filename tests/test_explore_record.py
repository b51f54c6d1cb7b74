"""The explorer's bookkeeping pinned by tests: its settings, the stages it times, the table and summary it writes,
which screened runs it confirms at full size, the joint design it draws and the sizing of the default.

Tiny registers and exact measures (no Monte Carlo draw unless a test needs one): each exploration takes well
under a second.
"""

import math
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest

from tvtrack import explore as explore_module
from tvtrack.conditions import Run
from tvtrack.explore import explore, joint_sample, replicate_seeds, replicates_needed
from tvtrack.montecarlo import Estimate, mean_ci, zero_events_bound
from tvtrack.register import Entry, Register, UndeclaredEntry
from tvtrack.verdicts import AllOf, InBand, Judgement

BAND = InBand("mean", -0.5, 0.5, "px")
REG2 = Register([Entry("a", "regime", 0, (0, 1), "a world"), Entry("c", "reading", "x", ("x", "y|z"), "a reading")])
REG3 = Register(
    [
        Entry("a", "regime", 0, (0, 1, 2), "test regime a"),
        Entry("b", "operating point", 0, (0, 1, 2), "test operating point b"),
        Entry("c", "reading", "x", ("x", "y"), "test reading c"),
    ]
)
X = Estimate.exact


def _two(config, seed):
    """Y's p1 flips when a = 1, p2 when c = "y|z"; X never."""
    return {"Y": {"p1": X(3.0 * (config["a"] == 1)), "p2": X(3.0 * (config["c"] == "y|z"))}, "X": X(0.0)}


RULES2 = {"Y": AllOf({"p1": BAND, "p2": BAND}), "X": BAND}


def _ab(config, seed, claims=None):
    """X flips only when a = 2 and b = 2 (an interaction); Z never."""
    return {"X": X(3.0 if (config["a"], config["b"]) == (2, 2) else 0.0), "Z": X(0.0)}


# --------------------------------------------------------------------------- settings, stages, table, summary


def test_the_settings_record_the_design_as_run():
    ex = explore(_two, REG2, RULES2, seed=7)
    s = {k: v for k, v in ex.settings.items() if k not in ("stopping", "timing")}
    assert s == {
        "replicates": 3,
        "min_replicates": 3,
        "max_replicates": 3,
        "joint": 0,
        "joint_configurations": 0,
        "joint_exhaustive": False,
        "screened": False,
        "screened_singles": False,
        "confirmed_at_full_size": 0,
        "confirmed_claims": 0,
        "measures_claims_asked": False,
        "combinations": 0,
        "max_subset": 3,
        "subset_round": 4,
        "condition_runs": 0,
        "sizing_budget": None,
        "sizing_budget_used": 0,
        "left_by_budget": 0,
        "replicates_needed": {"Y": 1, "X": 1},
        "guarded": True,
        "one_at_a_time": True,
        "seed": 7,
    }
    assert {k: v["configurations"] for k, v in ex.settings["timing"].items()} == {"replicates": 3, "one at a time": 2}
    assert ex.record("X")["design"] == ex.settings


def test_the_table_lists_each_replicate_and_condition_with_its_verdict_per_part():
    ex = explore(_two, REG2, RULES2, seed=7)
    assert ex.table("Y") == "\n".join(
        [
            "| run | p1 | p2 |",
            "| --- | --- | --- |",
            *(f"| replicate {i} | reproduced | reproduced |" for i in (1, 2, 3)),  # not a 19-digit seed
            "| single (1 replicate): a = 1 | not reproduced | reproduced |",
            "| single (1 replicate): c = y/z | reproduced | not reproduced |",  # a "|" in a value would split the row
        ]
    )
    assert ex.table("X").splitlines()[:3] == [
        "| run | claim |",
        "| --- | --- |",
        "| replicate 1 | reproduced |",
    ]


def test_the_summary_gives_each_claim_its_coverage_and_what_differs():
    ex = explore(_two, REG2, RULES2, seed=7)
    cover = (
        "over 2 distinct configurations (2 one at a time over 2 register entries, 0 joint samples); x 3 independent "
        "replicates; provisional: 2 distinct configurations are too few for a share"
    )
    assert ex.summary() == (
        f"- **Y**: depends (weakest part: p2) {cover}; differs: (p1) not reproduced when a = 1; (p2) not reproduced "
        f"when c = y|z\n- **X**: unexplored {cover}"
    )


def test_a_record_describes_a_condition_by_the_entries_the_claim_reads():
    ex = explore(_two, REG2, RULES2, seed=7, depends={"Y": ["a", "c"], "X": ["c"]})
    (row,) = ex.record("X")["conditions"]
    assert (row["changed"], row["config"]) == ({"c": "y|z"}, {"c": "y|z"})
    assert [r["changed"] for r in ex.record("Y")["conditions"]] == [{"a": 1}, {"c": "y|z"}]


def test_the_defaults_are_three_replicates_no_joint_design_and_unscreened_singles():
    def screen(config, seed):
        seen.append(dict(config))
        return _ab(config, seed)

    seen: list = []
    ex = explore(_ab, REG3, {"X": BAND}, seed=1, screen=screen)
    assert ex.settings["replicates"] == 3 and len(ex.replicates()) == 3
    assert ex.settings["joint_configurations"] == 0 and not [r for r in ex.runs if r.stage == "joint"]
    assert seen == [] and ex.settings["screened_singles"] is False and ex.settings["screened"] is False


def test_bad_designs_are_refused_in_words():
    with pytest.raises(ValueError, match=r"^explore: max_replicates 3 < replicates 4$"):
        explore(_ab, REG3, {"X": BAND}, seed=1, replicates=4, max_replicates=3)
    with pytest.raises(ValueError, match="^explore: no claims to measure$"):
        explore(_ab, REG3, {}, seed=1)


def test_the_stages_are_timed_under_their_names():
    ex = explore(_ab, REG3, {"X": BAND}, seed=1, joint=12)
    assert {k: v["configurations"] for k, v in ex.settings["timing"].items()} == {
        "replicates": 3,
        "one at a time": 5,
        "joint": 12,
    }
    ex = explore(_ab, REG3.with_pinned({"a": 2, "b": 2, "c": "y"}), {"X": BAND}, seed=1)
    assert {k: v["configurations"] for k, v in ex.settings["timing"].items()} == {
        "replicates": 3,
        "one at a time": 5,
        "pinned": 1,
        "combinations": 3,
    }


def test_an_exhaustive_joint_design_is_said_so_a_sample_is_not():
    full = explore(_ab, REG3, {"X": BAND}, seed=1, joint=12)  # 3 x 3 x 2 entries: 12 joint combinations
    assert full.settings["joint_configurations"] == 12 and full.settings["joint_exhaustive"] is True
    assert full.settings["confirmed_at_full_size"] == 12 and full.settings["confirmed_claims"] == 0  # unscreened
    sample = explore(_ab, REG3, {"X": BAND}, seed=1, joint=5)
    assert sample.settings["joint_exhaustive"] is False and 0 < sample.settings["joint_configurations"] <= 5
    assert explore_module._n_joint_combinations(REG3, ["a", "b", "c"]) == 12
    assert explore_module._n_joint_combinations(REG3, ["a", "b"]) == 4


def test_one_at_a_time_off_runs_no_single_and_entries_go_in_register_order():
    assert not [r for r in explore(_ab, REG3, {"X": BAND}, seed=1, one_at_a_time=False).runs if r.stage == "single"]
    reg = Register([Entry("z", "regime", 0, (0, 1), "w"), Entry("b", "regime", 0, (0, 1), "w")])
    ex = explore(lambda c, s: {"X": X(0.0)}, reg, {"X": BAND}, seed=1)
    assert [list(r.changed(ex.default)) for r in ex.runs if r.stage == "single"] == [["z"], ["b"]]


def test_the_joint_design_is_the_latin_hypercube_drawn_from_the_seed_after_the_runs():
    reg = Register([Entry(k, "regime", 0, (0, 1, 2), f"w {k}") for k in "abcde"])  # 243 cells: a sample
    ex = explore(lambda c, s: {"X": X(0.0)}, reg, {"X": BAND}, seed=11, joint=10, one_at_a_time=False)
    got = [r.config for r in ex.runs if r.stage == "joint"]
    assert got == joint_sample(reg, list("abcde"), 10, 12) and got != joint_sample(reg, list("abcde"), 10, 10)


def test_replicates_and_sizing_replicates_see_the_whole_configuration_unguarded():
    reg = Register([Entry("a", "regime", 0, (0, 1), "w"), Entry("b", "regime", 0, (0, 1), "w")])

    def measure(config, seed):
        assert config["b"] == 0  # an entry no claim declares: only the default's replicates may read it
        return {"X": mean_ci(np.random.default_rng(seed).normal(0.56, 1.0, 100))}

    ex = explore(measure, reg, {"X": BAND}, seed=2, max_replicates=30, depends={"X": ["a"]}, one_at_a_time=False)
    assert (
        ex.settings["replicates"] > 3
        and ex.settings["timing"]["sizing"]["configurations"] == ex.settings["replicates"] - 3
    )
    with pytest.raises(UndeclaredEntry):
        explore(measure, reg, {"X": BAND}, seed=2, depends={"X": ["a"]})  # a condition's run is guarded
    assert explore(measure, reg, {"X": BAND}, seed=2, depends={"X": ["a"]}, guard=False).settings["guarded"] is False


def test_an_executor_is_used_when_given():
    class Counting(ThreadPoolExecutor):
        calls = 0

        def submit(self, *a, **kw):
            Counting.calls += 1
            return super().submit(*a, **kw)

    with Counting(max_workers=2) as pool:
        explore(_ab, REG3, {"X": BAND}, seed=1, executor=pool)
    assert Counting.calls == 3 + 5  # three replicates and five one-at-a-time runs


def test_executor_for_waits_ten_seconds_by_default(monkeypatch):
    import tvtrack.executors

    got = []
    monkeypatch.setattr(tvtrack.executors, "connect_dask", lambda *a: got.append(a) or "client")
    assert explore_module.executor_for("host:8786") == "client" and got == [("host:8786", 10.0)]
    assert explore_module.executor_for("") is None


# --------------------------------------------------------------------------- screening and confirmation


def test_screened_stages_confirm_only_what_may_flip_and_count_it():
    screened: list = []

    def screen(config, seed, claims=None):
        screened.append((config["a"], config["b"], config["c"]))
        return _ab(config, seed)

    ex = explore(_ab, REG3, {"X": BAND, "Z": BAND}, seed=1, joint=12, screen=screen)
    joints = [r for r in ex.runs if r.stage == "joint"]
    assert len(screened) == len(joints) == 12  # only the joint stage screened
    redo = [r for r in joints if r.claims]
    assert [(r.config["a"], r.config["b"]) for r in redo] == [(2, 2)] * 2 and all(r.claims == {"X"} for r in redo)
    assert (ex.settings["confirmed_at_full_size"], ex.settings["confirmed_claims"]) == (2, 2)
    assert ex.settings["screened"] is True and ex.settings["screened_singles"] is False
    # a measure taking claims re-measured X alone: Z keeps the screen's value there; elsewhere both do
    assert all(r.screened == {"Z"} for r in redo)
    assert all(r.screened == {"X", "Z"} for r in joints if not r.claims)
    assert set(ex.settings["timing"]) >= {"joint, screened", "joint, confirmed at full size", "one at a time"}

    both = explore(_ab, REG3, {"X": BAND, "Z": BAND}, seed=1, joint=12, screen=screen, screen_singles=True)
    singles = [r for r in both.runs if r.stage == "single"]
    assert [(r.config["a"], r.config["b"]) for r in singles if r.claims] == []  # no single entry flips X
    assert both.settings["screened_singles"] is True and "one at a time, screened" in both.settings["timing"]


def test_a_confirmation_by_a_measure_without_claims_re_measures_every_claim():
    def screen(config, seed):
        return _ab(config, seed)

    def measure(config, seed):
        return _ab(config, seed)

    ex = explore(measure, REG3, {"X": BAND, "Z": BAND}, seed=1, joint=12, screen=screen, screen_singles=True)
    joints = [r for r in ex.runs if r.stage == "joint"]
    assert all(r.screened == frozenset() for r in joints if r.claims)
    assert all(r.screened == {"X", "Z"} for r in joints if not r.claims)
    # only the joint stage confirmed anything: the screened singles add no runs and no claims
    assert (ex.settings["confirmed_at_full_size"], ex.settings["confirmed_claims"]) == (2, 2)


def test_confirmed_runs_and_claims_add_up_over_the_screened_stages():
    def flip_a(config, seed, claims=None):
        return {"X": X(3.0 if config["a"] == 2 else 0.0), "Z": X(3.0 if config["b"] == 1 else 0.0)}

    ex = explore(flip_a, REG3, {"X": BAND, "Z": BAND}, seed=1, joint=12, screen=flip_a, screen_singles=True)
    redo = [r for r in ex.runs if r.stage in ("single", "joint") and r.claims]
    singles = [r for r in redo if r.stage == "single"]
    assert len(singles) == 2 and len(redo) > len(singles)
    assert ex.settings["confirmed_at_full_size"] == len(redo)
    assert ex.settings["confirmed_claims"] == sum(len(r.claims) for r in redo) > len(redo)


def _run(changed, outputs, scope=None):
    r = Run({"a": 0, "b": 0, **changed}, 1, "joint", scope=scope)
    r.outputs = outputs
    return r


def test_to_confirm_takes_the_touched_in_scope_claims_whose_screen_may_flip():
    rules = {"Z": BAND, "X": BAND, "U": BAND}
    depends = {"Z": ["b"], "X": ["a"], "U": ["a"]}
    ok = Judgement("reproduced", "")
    default_j = {("Z", "claim"): ok, ("X", "claim"): ok, ("U", "claim"): Judgement("undecided", "", False, 4.0)}
    tc = lambda r: explore_module._to_confirm(rules, depends, default_j, r, {"a": 0, "b": 0})  # noqa: E731
    flip = {"Z": X(3.0), "X": X(3.0), "U": X(3.0)}
    assert tc(_run({"a": 1}, flip)) == {"X"}  # Z untouched, U undecided at the default: nothing to flip
    assert tc(_run({"a": 1}, flip, scope=frozenset({"Z"}))) == frozenset()  # X out of this run's scope
    assert tc(_run({"a": 1}, {"X": X(0.1)})) == frozenset()  # decisively the default's
    near = Estimate(0.6, 0.1, 0.4, 0.8, 10, method="Student t")  # straddles 0.5, its point outside: may flip
    assert tc(_run({"a": 1}, {"X": near})) == {"X"}
    inside = Estimate(0.45, 0.1, 0.3, 0.6, 10, method="Student t")  # straddles 0.5, its point inside: stays
    assert tc(_run({"a": 1}, {"X": inside})) == frozenset()
    assert tc(_run({"a": 1}, {"X": Estimate(0.45, math.nan, math.nan, math.nan, 10)})) == frozenset()


# --------------------------------------------------------------------------- the joint design


def test_a_joint_sample_covers_every_value_differs_in_two_entries_and_repeats_none():
    reg = Register([Entry(k, "regime", 0, (0, 1, 2), f"w {k}") for k in "abc"])  # 27 cells, 20 joint
    for seed in range(6):
        got = joint_sample(reg, list("abc"), 6, seed)
        keys = [tuple(c[k] for k in "abc") for c in got]
        assert len(set(keys)) == len(keys) > 1  # seed 4 draws one cell twice
        assert all(sum(v != 0 for v in k) >= 2 for k in keys)
    pooled = [c for seed in range(6) for c in joint_sample(reg, list("abc"), 6, seed)]
    assert all({c[k] for c in pooled} == {0, 1, 2} for k in "abc")  # every stratum of every entry is drawn
    assert any(sum(c[k] != 0 for k in "abc") == 2 for c in pooled)  # two entries off is joint enough


def test_a_register_with_as_many_joint_cells_as_asked_gets_every_one():
    cells = joint_sample(REG3, ["a", "b", "c"], 12, seed=1)
    assert len(cells) == 12 and len({tuple(c.values()) for c in cells}) == 12
    two = Register([Entry("a", "regime", 0, (0, 1), "w"), Entry("b", "regime", 0, (0, 1), "w")])
    assert all(joint_sample(two, ["a", "b"], 1, seed) == [{"a": 1, "b": 1}] for seed in range(5))


def test_a_one_valued_entry_adds_no_dimension_and_no_sample_is_drawn_for_none():
    reg = Register([*(Entry(k, "regime", 0, (0, 1, 2), f"w {k}") for k in "abcde"), Entry("f", "regime", 0, (0,), "w")])
    assert joint_sample(reg, list("abcdef"), 8, 3) == joint_sample(reg, list("abcde"), 8, 3)
    assert joint_sample(reg, list("abcde"), 0, 3) == [] == joint_sample(reg, list("abcde"), -1, 3)
    assert joint_sample(reg, ["a", "f"], 8, 3) == []
    assert len(joint_sample(reg, list("abcde"), 1, 3)) <= 1
    assert any(len(joint_sample(reg, list("abcde"), 1, s)) == 1 for s in range(5))


# --------------------------------------------------------------------------- the default's size


def test_the_default_needs_one_replicate_per_claim_where_one_decides():
    reps = [Run({}, s, "replicate") for s in (1, 2, 3)]
    for r in reps:
        r.outputs = {"X": X(0.0), "Z": X(3.0), "U": Estimate(0.5, math.nan, math.nan, math.nan, 5)}
    rules = {"X": BAND, "Z": BAND, "U": BAND}
    default_j = explore_module._pooled(rules, reps)
    assert replicates_needed(rules, reps, default_j) == {"X": 1, "Z": 1, "U": 1}


def _reps(*outputs):
    reps = [Run({}, s, "replicate") for s in range(1, len(outputs) + 1)]
    for r, out in zip(reps, outputs):
        r.outputs = {"X": out}
    return reps


def _ci(value, half):
    return Estimate(value, half / 1.959964, value - half, value + half, 100, 0.95, "mean t")


def test_one_replicate_is_not_enough_where_only_the_first_replicates_draw_decides():
    # the first replicate decides inside the band alone, the second and third straddle its edge: the pooled default
    # decides from the first two on, so a condition must hold two replicates, not the one the lucky draw allowed
    reps = _reps(_ci(0.0, 0.2), _ci(0.0, 0.7), _ci(0.0, 0.7))
    default_j = explore_module._pooled({"X": BAND}, reps)
    assert default_j[("X", "claim")].verdict == "reproduced"
    assert [BAND.judge(r.outputs["X"]).verdict for r in reps] == ["reproduced", "undecided", "undecided"]
    assert replicates_needed({"X": BAND}, reps, default_j) == {"X": 2}
    # each replicate deciding alone: one is enough
    reps = _reps(_ci(0.0, 0.2), _ci(0.1, 0.2), _ci(-0.1, 0.2))
    assert replicates_needed({"X": BAND}, reps, explore_module._pooled({"X": BAND}, reps)) == {"X": 1}


def test_one_replicate_is_not_enough_where_the_defaults_replicates_disagree_beyond_their_intervals():
    # each replicate decides alone, but they scatter beyond their own intervals (the agreement test widens the
    # pooled interval to Student's t over their values): one run's interval is narrower than the default supports
    reps = _reps(_ci(0.0, 0.01), _ci(0.0, 0.01), _ci(0.05, 0.01))
    default_j = explore_module._pooled({"X": BAND}, reps)
    assert default_j[("X", "claim")].verdict == "reproduced"
    assert "disagree beyond their own intervals" in explore_module.pool([r.outputs["X"] for r in reps]).method
    assert replicates_needed({"X": BAND}, reps, default_j) == {"X": 2}
    # the same values with intervals that hold their scatter: one is enough
    reps = _reps(_ci(0.0, 0.1), _ci(0.0, 0.1), _ci(0.05, 0.1))
    assert replicates_needed({"X": BAND}, reps, explore_module._pooled({"X": BAND}, reps)) == {"X": 1}


def test_a_later_prefix_that_loses_the_decision_raises_the_size():
    # the first replicate and the first two decide, the first three and four do not, five and six do: five are
    # needed (the smallest size from which every larger prefix decides as the default), not the first one
    reps = _reps(_ci(0.0, 0.2), _ci(0.0, 0.2), _ci(0.0, 2.0), *[_ci(0.0, 0.2)] * 3)
    default_j = explore_module._pooled({"X": BAND}, reps)
    assert default_j[("X", "claim")].verdict == "reproduced"
    pools = [BAND.judge(explore_module.pool([r.outputs["X"] for r in reps[:j]])).verdict for j in range(1, 6)]
    assert pools == ["reproduced", "reproduced", "undecided", "undecided", "reproduced"]
    assert replicates_needed({"X": BAND}, reps, default_j) == {"X": 5}


def _edge(config, seed):
    """Undecided with no projection (the point on the band's edge): no replicate can decide it."""
    return {"X": Estimate(0.5, 0.1, 0.4, 0.6, 10, method="Student t")}


def test_a_part_no_run_decides_gets_no_sizing_replicate():
    ex = explore(_edge, REG3, {"X": BAND}, seed=1, max_replicates=6, one_at_a_time=False)
    assert ex.settings["replicates"] == 3 and "sizing" not in ex.settings["timing"]
    assert math.isinf(explore_module._pooled({"X": BAND}, ex.replicates())[("X", "claim")].runs_factor)


def _near(lo, hi):
    def measure(config, seed):
        return {"X": Estimate(0.6, (hi - lo) / 4, lo, hi, 100, method="Student t")}

    return measure


def test_a_part_projected_to_decide_at_the_cap_gets_its_replicate():
    measure = _near(0.41, 0.79)  # three replicates pooled: undecided, projected at 1.07 times the runs
    j = explore_module._pooled({"X": BAND}, [Run({}, s, "replicate", outputs=measure({}, s)) for s in (1, 2, 3)])
    assert j[("X", "claim")].verdict == "undecided" and 1.0 < j[("X", "claim")].runs_factor <= 4 / 3
    ex = explore(measure, REG3, {"X": BAND}, seed=1, max_replicates=4, one_at_a_time=False)
    assert ex.settings["replicates"] == 4 and ex.settings["timing"]["sizing"]["configurations"] == 1
    assert ex.record("X")["parts"]["claim"]["verdict"] == "not reproduced"


class _Clock:
    """A stand-in for the explorer's stage clock: measures in process and keeps each call's stage and size."""

    def __init__(self, workers):
        self.executor = type("Executor", (), {"_max_workers": workers})() if workers != "none" else None
        self.calls = []

    def run(self, fn, jobs, stage, guarded=True):
        self.calls.append((stage, guarded, len(jobs)))
        for r in jobs:
            r.outputs = fn(r.config, r.seed)


def test_sizing_steps_by_the_executors_workers_unguarded_and_one_at_a_time_in_process():
    measure = _near(0.3613, 0.8387)  # pooled over 3: projected at 6 replicates, decided at 6
    seeds = replicate_seeds(1, 12)

    def steps(workers):
        runs = [Run({"a": 0}, s, "replicate", outputs=measure({}, s)) for s in seeds[:3]]
        clock = _Clock(workers)
        n = explore_module._size(measure, {"X": BAND}, runs, seeds, 12, clock, {"a": 0})
        assert n == len(runs) == 6 and [r.seed for r in runs] == seeds[:6]
        assert all(c[:2] == ("sizing", False) for c in clock.calls)
        return [c[2] for c in clock.calls]

    assert steps("none") == [1, 1, 1]  # in process: re-judged after each replicate
    assert steps(4) == [3]  # four workers: the three projected at once, not four
    assert steps(2) == [2, 1]
    assert steps(None) == [1, 1, 1]  # an executor that does not say its workers: one at a time


# --------------------------------------------------------------------------- combinations


def test_a_flipping_pair_inside_a_pinned_triple_is_searched_sized_and_asked_only_for_its_claim():
    def measure(config, seed, claims=None):
        loss = (config["a"], config["b"]) == (2, 2)
        bound = Estimate(0.0, math.nan, 0.0, zero_events_bound(6), 6, 0.95, "count: zero events")
        return {
            "L": Estimate(1.0, math.nan, 0.54, 1.0, 6, 0.95, "count: 6 of 6") if loss else bound,
            "Q": X(0.0),
        }

    rules = {"L": InBand("loss rate", None, 0.1), "Q": BAND}
    reg = Register(list(REG3), pinned=[{"a": 2, "b": 2, "c": "y"}])
    ex = explore(measure, reg, rules, seed=5, max_replicates=8)
    combos = [r for r in ex.runs if r.stage == "combination"]
    assert sorted(tuple(sorted(r.changed(ex.default))) for r in combos) == [("a", "b"), ("a", "c"), ("b", "c")]
    assert all(r.claims == {"L"} for r in combos)  # Q has no unexplained flip: not asked
    pair = next(r for r in combos if set(r.changed(ex.default)) == {"a", "b"})
    need = ex.settings["replicates_needed"]["L"]
    assert need > 1 and pair.n_runs("L") == need  # a pair leaning towards a flip is sized
    conds = [r for r in ex.runs if r.stage != "replicate"]
    assert ex.settings["condition_runs"] == sum(len(r.sized) for r in conds) > need - 1
    assert ex.settings["combinations"] == 3 and ex.settings["timing"]["combinations"]["configurations"] == 3
    assert ex.table("L").splitlines()[-4:] == [  # each condition with its own replicates, every changed entry
        f"| pinned ({need} replicates): a = 2 and b = 2 and c = y | not reproduced |",
        f"| combination ({need} replicates): a = 2 and b = 2 | not reproduced |",
        "| combination (1 replicate): a = 2 and c = y | undecided |",
        "| combination (1 replicate): b = 2 and c = y | undecided |",
    ]


def test_the_subset_search_stops_at_triples():
    reg = Register([Entry(k, "regime", 0, (0, 1), f"world {k}") for k in "abcd"], pinned=[dict.fromkeys("abcd", 1)])

    def four(config, seed):
        return {"X": X(3.0 if all(config[k] == 1 for k in "abcd") else 0.0)}

    ex = explore(four, reg, {"X": BAND}, seed=3)
    sizes = sorted(len(r.changed(ex.default)) for r in ex.runs if r.stage == "combination")
    assert sizes == [2] * 6 + [3] * 4


def _six_pinned(lean: bool):
    """Six worlds a..f pinned together; only e = f = 1 flips X. With ``lean``, e or f alone moves the point
    estimate out of the band with an interval that straddles its edge (leans towards a flip, undecided)."""
    reg = Register([Entry(k, "regime", 0, (0, 1), f"world {k}") for k in "abcdef"], pinned=[dict.fromkeys("abcdef", 1)])

    def measure(config, seed):
        if config["e"] == 1 and config["f"] == 1:
            return {"X": X(3.0)}
        if lean and (config["e"] == 1 or config["f"] == 1):
            return {"X": Estimate(0.6, math.nan, 0.3, 0.9, 6, 0.95, "mean")}
        return {"X": X(0.0)}

    return explore(measure, reg, {"X": BAND}, seed=3)


def test_the_subset_search_tries_the_pairs_whose_entries_lean_first_and_stops_at_the_first_that_flips():
    ex = _six_pinned(lean=True)
    pairs = [tuple(sorted(r.changed(ex.default))) for r in ex.runs if r.stage == "combination"]
    # one round: (e, f) both lean, then the pairs with one leaning entry in name order; (e, f) flips: no round 2
    assert pairs == [("e", "f"), ("a", "e"), ("a", "f"), ("b", "e")]
    flips = ex.record("X")["parts"]["claim"]["flips"]
    assert [f["changed"] for f in flips] == [{"e": 1, "f": 1}]


def test_without_a_leaning_entry_the_subset_search_tries_every_pair_before_it_finds_the_last():
    ex = _six_pinned(lean=False)
    pairs = [tuple(sorted(r.changed(ex.default))) for r in ex.runs if r.stage == "combination"]
    assert len(pairs) == 15 and pairs[-1] == ("e", "f")  # name order: (e, f) is the last pair; no triple follows
    assert ex.settings["timing"]["combinations"]["configurations"] == 15


def test_the_subset_search_never_measures_one_entry_or_more_than_three_as_a_combination():
    for k in (4, 5):
        names = "abcde"[:k]
        reg = Register([Entry(n, "regime", 0, (0, 1), f"world {n}") for n in names], pinned=[dict.fromkeys(names, 1)])

        def flip(config, seed, names=names):
            return {"X": X(3.0 if all(config[n] == 1 for n in names) else 0.0)}

        ex = explore(flip, reg, {"X": BAND}, seed=3, one_at_a_time=False)  # no single measured before
        sizes = [len(r.changed(ex.default)) for r in ex.runs if r.stage == "combination"]
        assert sorted(sizes) == [2] * math.comb(k, 2) + [3] * math.comb(k, 3)


def test_a_table_marks_a_part_a_run_did_not_measure():
    from tvtrack.verdicts import ByReading

    reg = Register([Entry("c", "reading", "x", ("x", "short"), "a reading")])
    rule = ByReading("c", {"short": AllOf({"p1": BAND})}, default=AllOf({"p1": BAND, "p2": BAND}))
    first = replicate_seeds(7, 3)[0]

    def measure(config, seed):
        reading = "short" if seed == first else config["c"]  # the first replicate measured the short reading
        return {"Y": ByReading.tag(reading, {"p1": X(0.0)} if reading == "short" else {"p1": X(0.0), "p2": X(0.0)})}

    rows = explore(measure, reg, {"Y": rule}, seed=7).table("Y").splitlines()
    assert rows[2] == "| replicate 1 | reproduced | - |"
    assert rows[-1] == "| single (1 replicate): c = short | reproduced | - |"


class _PointDiffers(InBand):
    """A stub rule whose point estimate (an exact value) judges otherwise than its interval, or cannot be judged."""

    def __init__(self, point):
        super().__init__("m", -0.5, 0.5)
        object.__setattr__(self, "point", point)

    def judge(self, measured):
        if measured.method == "exact":
            if self.point == "raise":
                raise ValueError("no point judgement")
            return Judgement(self.point, "")
        return super().judge(measured)


def test_a_decisive_screen_is_judged_as_it_reads_and_a_point_that_cannot_be_judged_is_confirmed():
    ok = Judgement("reproduced", "")
    inside = Estimate(0.1, 0.05, 0.0, 0.2, 10, method="Student t")  # decisively the default's
    rule = _PointDiffers("not reproduced")
    tc = lambda rule, m: explore_module._to_confirm(  # noqa: E731
        {"X": rule}, {"X": ["a"]}, {("X", "claim"): ok}, _run({"a": 1}, {"X": m}), {"a": 0, "b": 0}
    )
    assert tc(rule, inside) == frozenset()  # its point is not asked
    straddles = Estimate(0.45, 0.1, 0.3, 0.6, 10, method="Student t")
    assert tc(_PointDiffers("raise"), straddles) == {"X"}


def test_a_screened_run_keeps_the_screens_value_only_for_the_claims_in_its_scope():
    def flip(config, seed, claims=None):
        out = {"Z": X(0.0)}
        if claims is None or "X" in claims:  # a run for Z alone may not read a or b
            out["X"] = X(3.0 if (config["a"], config["b"]) == (2, 2) else 0.0)
        return out

    depends = {"X": ["a", "b"], "Z": ["c"]}
    ex = explore(flip, REG3, {"X": BAND, "Z": BAND}, seed=1, joint=12, screen=flip, depends=depends)
    joints = [r for r in ex.runs if r.stage == "joint"]
    assert {r.scope for r in joints} == {frozenset({"X"})}  # Z reads c alone: no joint configuration of its own
    assert all(r.screened == r.scope - (r.claims or frozenset()) for r in joints)
    assert [r.screened for r in joints if r.claims] == [frozenset()]


def test_no_sub_combination_leaning_towards_agreement_is_sized_even_when_one_run_would_do():
    def measure(config, seed):  # the default needs two replicates of 15 runs to certify no loss under 0.1
        if (config["a"], config["b"], config["c"]) == (2, 2, "y"):
            return {"L": Estimate(1.0, math.nan, 0.78, 1.0, 15, 0.95, "count: 15 of 15")}
        return {"L": Estimate(0.0, math.nan, 0.0, zero_events_bound(15), 15, 0.95, "count: zero events")}

    reg = Register(list(REG3), pinned=[{"a": 2, "b": 2, "c": "y"}])
    ex = explore(measure, reg, {"L": InBand("loss rate", None, 0.1)}, seed=5, max_replicates=8)
    assert ex.settings["replicates_needed"] == {"L": 2}
    combos = [r for r in ex.runs if r.stage == "combination"]
    assert len(combos) == 3 and all(r.n_runs("L") == 1 and r.left == {"L": 2} for r in combos)


def test_a_setting_reads_in_four_figures_in_the_table_the_register_and_the_phrases():
    """A register value is said as a reader writes it, through one formatter (``tvtrack.numbers.setting``): the
    explorer's table, the register's table and its pinned conditions, and an entry's phrase show 1.667 and 1e+06,
    never 1.6666666666666667, 1.66667 or 1000000.0."""
    from tvtrack.numbers import setting

    third, big = 5 / 3, 1e6
    reg = Register(
        [Entry("alpha", "regime", 2 / 3, (2 / 3, third), "a world"), Entry("q", "reading", 100.0, (100.0, big), "r")],
        pinned=[{"alpha": third, "q": big}],
    )

    def measure(config, seed):
        return {"Y": X(3.0 * (config["alpha"] == third))}

    rows = explore(measure, reg, {"Y": BAND}, seed=7).table("Y").splitlines()
    assert "| single (1 replicate): alpha = 1.667 | not reproduced |" in rows
    assert "| single (1 replicate): q = 1e+06 | reproduced |" in rows
    md = reg.to_markdown()
    assert "| alpha | regime (a world beyond the paper) | alpha = 0.6667 | alpha = 1.667 | a world | author |" in md
    assert "| q | reading (a reading of the paper's text) | q = 100 | q = 1e+06 | r | author |" in md
    assert "- alpha = 1.667 and q = 1e+06" in md and "`" not in md
    assert reg["q"].phrase(big) == "q = 1e+06" and reg.describe({"alpha": third}) == "alpha = 1.667"
    assert [setting("k", v) for v in (25, 0.1, True, "y/z", 123456.0)] == [
        "k = 25",
        "k = 0.1",
        "k = True",
        "k = y/z",
        "k = 123456",
    ]


def test_the_table_says_a_change_in_the_registers_words():
    """A condition's changes are said by the entry's phrase or title, not its identifier."""
    reg = Register(
        [
            Entry("k_bound2", "unreported setting", 50, (50, 30), "gain bound", title="2nd-order gain bound"),
            Entry("lost", "regime", "coast", ("coast", "skip"), "a world", phrases={"skip": "lost frames, skipped"}),
        ],
        pinned=[{"k_bound2": 30, "lost": "skip"}],
    )

    def measure(config, seed):
        return {"Y": X(3.0 * (config["lost"] == "skip"))}

    ex = explore(measure, reg, {"Y": BAND}, seed=7)
    rows = ex.table("Y").splitlines()
    assert "| single (1 replicate): 2nd-order gain bound = 30 | reproduced |" in rows
    assert "| single (1 replicate): lost frames, skipped | not reproduced |" in rows
    # a configuration reads in the table as in its record and its named flips: changes joined by "and", never by
    # the commas a phrase may hold itself
    joint = next(c for c in ex.record("Y")["conditions"] if len(c["changed"]) == 2)
    assert joint["text"] == "2nd-order gain bound = 30 and lost frames, skipped"
    assert any(r.endswith(f"): {joint['text']} | not reproduced |") for r in rows), rows


def test_a_widened_pooled_value_is_found_at_any_depth_in_any_form():
    """``explore._widened``: the agreement test's mark (:func:`tvtrack.pooling.pool`) on an interval, found on an
    :class:`Estimate`, on an estimate's record form (a mapping with ``ci_low`` and ``method``), and in the parts of
    an ``AllOf`` (a mapping) or a ``Monotone``'s points (a list or tuple)."""
    from tvtrack.pooling import pool

    def reps(*values):
        return [Estimate(v, 0.1, v - 0.2, v + 0.2, 9, method="t") for v in values]

    wide, plain = pool(reps(0.0, 0.1, 5.0)), pool(reps(0.0, 0.1, 0.05))  # the third replicate far off; or not
    mark = wide.method
    w = explore_module._widened
    assert w(wide) and not w(plain)
    as_record = {"value": 1.0, "ci_low": 0.5, "ci_high": 1.5, "method": mark}
    assert w(as_record) and not w({**as_record, "method": "pooled"})
    # a mapping without an interval is a mapping of parts: its own "method" string is no estimate's
    assert not w({"method": mark}) and not w({"ci_low": 0.5, "note": mark})
    assert w({"a": plain, "b": {"c": wide}}) and not w({"a": plain, "b": {"c": plain}})
    assert w([plain, wide]) and w((plain, as_record)) and not w([plain, (plain,)])
    assert not w(mark) and not w(None) and not w([]) and not w(1.0)
