"""A part is robust only where a world reached the part itself (tvtrack.reach): a configuration that left the part's
value as the default gives it on the same random numbers, bit for bit, explored nothing of it."""

from __future__ import annotations

from tvtrack.counts import zero_events_bound
from tvtrack.labels import label_parts
from tvtrack.montecarlo import Estimate
from tvtrack.reach import reached, unchanged, world_reached
from tvtrack.register import Entry
from tvtrack.verdicts import AllOf, InBand

BAND = InBand("mean", -0.5, 0.5, "px")
SLOPE = Entry("slope", "reading", "half", ("half", "full"), "the slope read over half or all of the range")
WORLD = Entry("compensation", "regime", "mean", ("mean", "median"), "a world beyond the paper")


def _noisy(v: float) -> Estimate:
    return Estimate(v, 0.05, v - 0.1, v + 0.1, 100, method="mean t")


def _two_parts(slope: str, compensation: str, seed: int) -> dict:
    """Part ``tracking`` reads the world (and its seed), part ``linear`` only the reading: an exact number."""
    shift = 0.01 * seed + (0.05 if compensation == "median" else 0.0)
    return {"tracking": _noisy(shift), "linear": Estimate.exact(0.2 if slope == "half" else 0.3)}


def _record(configs):
    reps = [{"seed": s, "measured": _two_parts("half", "mean", s)} for s in (1, 2, 3)]
    conds = [
        {"changed": ch, "kind": "single" if len(ch) == 1 else "joint", "runs": 1, "measured": _two_parts(**cfg, seed=1)}
        for ch, cfg in configs
    ]
    rule = AllOf({"tracking": BAND, "linear": BAND})
    default = {"tracking": _noisy(0.02), "linear": Estimate.exact(0.2)}
    return label_parts(rule, default, reps, conds, [SLOPE, WORLD], design={"min_share_design": 2}, needed=1)


def test_a_part_no_world_reached_is_unexplored_though_the_claim_varied_one():
    rec = _record(
        [
            ({"compensation": "median"}, {"slope": "half", "compensation": "median"}),
            ({"slope": "full"}, {"slope": "full", "compensation": "mean"}),
            ({"slope": "full", "compensation": "median"}, {"slope": "full", "compensation": "median"}),
        ]
    )
    tracking, linear = rec["parts"]["tracking"], rec["parts"]["linear"]
    assert tracking["label"] == "robust" and tracking["share"]["unchanged"] == 1  # the reading alone: unmoved
    # the world configuration left the exact part's number as it was: it agreed without exploring it; the joint
    # one moved it only through the reading (its number is the reading's alone)
    assert linear["share"]["agree"] == 3 and linear["share"]["unchanged"] == 1
    assert linear["label"] == "unexplored"


def test_a_joint_configuration_whose_rest_was_never_measured_shows_no_world_reaching_the_part():
    # the joint moved the exact part, but its reading alone was never measured: nothing shows the world did it, and
    # the one world measured alone left it as it was
    rec = _record(
        [
            ({"compensation": "median"}, {"slope": "half", "compensation": "median"}),
            ({"slope": "full", "compensation": "median"}, {"slope": "full", "compensation": "median"}),
        ]
    )
    assert rec["parts"]["tracking"]["label"] == "robust"
    assert rec["parts"]["linear"]["label"] == "unexplored"


def test_an_equal_count_is_no_sign_the_world_missed_the_part():
    # zero events under the default and under the world: the count coincides, the world still ran
    zero = Estimate(0.0, float("nan"), 0.0, zero_events_bound(30), 30, 0.95, "count: zero events")
    assert not unchanged(zero, [zero, zero, zero], 3)
    rows = [{"changed": {"w": 1}, "runs": 3, "part_measured": {"loss": zero}}]
    reps = [{"part_measured": {"loss": zero}}] * 3
    assert reached(rows, "loss", reps) == rows


def test_unchanged_compares_with_the_default_pooled_over_the_conditions_own_replicates():
    reps = [_noisy(0.0), _noisy(0.1), _noisy(0.2)]
    assert unchanged(reps[0], reps, 1)  # one run on the first seed: the first replicate's value
    assert not unchanged(reps[0], reps, 2)  # two runs: the pool of the first two, not the first
    from tvtrack.pooling import pool

    assert unchanged(pool(reps[:2]), reps, 2)
    assert not unchanged(_noisy(0.0 + 1e-12), reps, 1)  # any change of any number is a move
    assert not unchanged(reps[0], reps, 4)  # more runs than the default has: cannot say
    assert unchanged(Estimate.exact(0.2), [Estimate.exact(0.2)] * 3, None)


def test_every_kind_filed_as_a_world_counts_as_varying_the_world():
    from tvtrack.register import ENTRY_KINDS, WORLD_KINDS, side_of

    assert {k for k in ENTRY_KINDS if side_of(k) == "world"} == set(WORLD_KINDS)
    scale = Entry("statistic", "scale", "mean", ("mean", "median"), "a summary beyond the paper's")
    reps = [{"seed": s, "measured": _noisy(0.01 * s)} for s in (1, 2, 3)]
    conds = [{"changed": {"statistic": "median"}, "kind": "single", "runs": 1, "measured": _noisy(0.05)}]
    rec = label_parts(BAND, _noisy(0.02), reps, conds, [scale], design={"min_share_design": 1}, needed=1)
    assert rec["label"] == "robust"


# --------------------------------------------------------------------------- what counts as the same value

NAN = float("nan")


def test_a_reading_tag_is_the_same_only_with_the_same_reading_and_value():
    e = _noisy(0.1)
    assert unchanged({"reading": "a", "measured": e}, [{"reading": "a", "measured": e}], 1)
    assert not unchanged({"reading": "b", "measured": e}, [{"reading": "a", "measured": e}], 1)
    assert not unchanged({"reading": "a", "measured": _noisy(0.2)}, [{"reading": "a", "measured": e}], 1)


def test_curves_and_parts_are_the_same_only_point_by_point():
    pts = [_noisy(0.0), _noisy(0.1), _noisy(0.2)]
    assert unchanged(list(pts), [list(pts)], 1)
    assert not unchanged([pts[0], pts[1], _noisy(0.3)], [list(pts)], 1)  # the last point moved
    assert not unchanged(pts[:2], [list(pts)], 1)  # a shorter curve
    parts = {"a": _noisy(0.0), "b": _noisy(0.1)}
    assert unchanged({"b": parts["b"], "a": parts["a"]}, [parts], 1)  # the parts' order is no change
    assert not unchanged({"a": parts["a"], "b": _noisy(0.5)}, [parts], 1)
    assert not unchanged({"a": parts["a"], "b": parts["a"]}, [parts], 1)


def test_counts_and_values_with_lost_runs_are_never_taken_as_unmoved():
    from tvtrack.measured import with_lost_runs

    cp = Estimate(0.1, NAN, 0.05, 0.2, 50, 0.95, "Clopper-Pearson")
    counted = Estimate(0.1, NAN, 0.05, 0.2, 50, 0.95, "count: 5 of 50")
    for m in (cp, counted, [_noisy(0.0), cp], {"a": _noisy(0.0), "b": counted}):
        assert not unchanged(m, [m], 1), m
    lost = with_lost_runs(_noisy(0.9), _noisy(0.8), lost=3, runs=60)
    assert not unchanged(lost, [lost], 1)
    assert unchanged(_noisy(0.1), [_noisy(0.1)], 1)  # the same estimate with a method of its own is compared


def test_an_undefined_interval_equals_itself_and_nothing_is_said_without_the_defaults_runs():
    undefined = Estimate(0.5, NAN, NAN, NAN, 5)
    assert unchanged(undefined, [undefined, undefined], 1)
    assert not unchanged(Estimate(0.6, NAN, NAN, NAN, 5), [undefined], 1)
    assert not unchanged(_noisy(0.0), [_noisy(0.0)], 0)  # no run: nothing to compare
    assert not unchanged(_noisy(0.0), [None, _noisy(0.0)], 1)  # the default's replicate was not measured
    assert not unchanged(None, [_noisy(0.0)], 1)


# --------------------------------------------------------------------------- which worlds reached a part


def _rows(*specs):
    return [{"changed": ch, "runs": runs, "part_measured": {"p": m}} for ch, runs, m in specs]


def test_only_a_row_that_changes_a_world_can_show_a_world_reaching_the_part():
    reps = [{"part_measured": {"p": _noisy(0.0)}}] * 3
    assert not world_reached(_rows(({"r": 1}, 1, _noisy(0.3))), "p", reps, {"w"})  # a reading moved it
    assert world_reached(_rows(({"w": 1}, 1, _noisy(0.3))), "p", reps, {"w"})
    assert not world_reached(_rows(({"w": 1}, 1, _noisy(0.0))), "p", reps, {"w"})
    assert world_reached(_rows(({"w": 1}, 2, _noisy(0.0))), "p", reps, {"w"})  # two runs: the pool of two differs


def test_a_joint_row_is_compared_with_its_rest_measured_alone_on_as_many_runs():
    reps = [{"part_measured": {"p": _noisy(0.0)}}] * 3
    w = {"w"}
    joint = ({"r": 1, "s": 2, "w": 1}, 2, _noisy(0.3))
    same_rest = ({"s": 2, "r": 1}, 2, _noisy(0.3))  # the same readings, listed in another order: the same value
    assert not world_reached(_rows(joint, same_rest), "p", reps, w)
    assert world_reached(_rows(joint, ({"s": 2, "r": 1}, 2, _noisy(0.25))), "p", reps, w)
    assert not world_reached(_rows(joint, ({"s": 2, "r": 1}, 1, _noisy(0.25))), "p", reps, w)  # other runs
    assert not world_reached(_rows(joint, ({"r": 1}, 2, _noisy(0.25))), "p", reps, w)  # another rest
    assert not world_reached(_rows(joint, ({"s": 2, "r": 2}, 2, _noisy(0.25))), "p", reps, w)  # another value
    cp = Estimate(0.1, NAN, 0.05, 0.2, 50, 0.95, "Clopper-Pearson")
    assert world_reached(_rows(({"r": 1, "w": 1}, 2, cp), ({"r": 1}, 2, cp)), "p", reps, w)  # a count: cannot say
    assert world_reached(_rows(({"r": 1, "w": 1}, 2, None), ({"r": 1}, 2, _noisy(0.3))), "p", reps, w)


def test_the_guards_of_the_comparison():
    e, e2 = _noisy(0.0), _noisy(0.1)
    cp = Estimate(0.1, NAN, 0.05, 0.2, 50, 0.95, "Clopper-Pearson")
    assert not unchanged({"reading": "a", "measured": cp}, [{"reading": "a", "measured": cp}], 1)
    pts = [_noisy(0.0), _noisy(0.1)]
    assert not unchanged([_noisy(0.5), pts[1]], [pts], 1)  # the first point moved, the last did not
    assert not unchanged(e, [e], 2)  # more runs than the default's replicates
    assert not unchanged(e, [e, e2], -1)
    reps = [{"part_measured": {"p": e}}] * 3
    w = {"w"}
    # a world row that left the part as it was does not end the search: a later one that moved it counts
    assert world_reached(_rows(({"w": 1}, 1, e), ({"w": 2}, 1, _noisy(0.3))), "p", reps, w)
    # nor does a joint row whose rest was never measured alone
    assert world_reached(_rows(({"r": 1, "w": 1}, 1, e), ({"w": 2}, 1, _noisy(0.3))), "p", reps, w)
    # the rest measured with a count: nothing says the world did not move it
    assert world_reached(_rows(({"r": 1, "w": 1}, 2, _noisy(0.3)), ({"r": 1}, 2, cp)), "p", reps, w)
    # a reading's row, a count in it, says nothing of the worlds
    assert not world_reached(_rows(({"r": 1}, 1, cp)), "p", reps, w)
