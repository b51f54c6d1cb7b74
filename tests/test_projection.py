"""Each claim measured in the world it declares (``tvtrack.projection``), on hand-built ``DEPENDS``, defaults and
configurations whose right grouping is known by construction: two claims that declare different entries share a
world unless the configuration changes an entry only one of them declares, and a claim never sees an entry it does
not declare."""

import pytest

from tvtrack.projection import as_declared, claim_groups
from tvtrack.register import Undeclared, UndeclaredEntry

DEPENDS = {"A": ["x"], "B": ["x", "y"], "C": ["x"], "D": ["z"]}
DEFAULT = {"x": 0, "y": 0, "z": 0}


def test_an_entry_only_one_claim_declares_splits_the_claims_into_two_worlds():
    depends = {"A": ["x"], "B": ["x", "y"]}
    assert claim_groups({"x": 1, "y": 2}, None, depends, {"x": 0, "y": 0}) == [
        ({"x": 1, "y": 0}, frozenset({"A"})),
        ({"x": 1, "y": 2}, frozenset({"B"})),
    ]


def test_an_entry_every_claim_declares_keeps_one_world_and_the_claims_as_they_were_asked():
    abc = {k: DEPENDS[k] for k in "ABC"}  # every claim here declares x
    assert claim_groups({"x": 1}, None, abc, DEFAULT) == [({"x": 1, "y": 0, "z": 0}, None)]
    assert claim_groups({"x": 1}, ["A", "B", "C"], DEPENDS, DEFAULT) == [
        ({"x": 1, "y": 0, "z": 0}, frozenset({"A", "B", "C"}))
    ]
    # a change of y alone, which only B declares, asked of A and C only: one world, the default
    assert claim_groups({"y": 5}, iter(["A", "C"]), DEPENDS, DEFAULT) == [
        ({"x": 0, "y": 0, "z": 0}, frozenset({"A", "C"}))
    ]


def test_at_the_default_every_projection_is_the_default_and_the_measurement_runs_once():
    assert claim_groups(DEFAULT, None, DEPENDS, DEFAULT) == [(DEFAULT, None)]
    assert claim_groups({}, None, DEPENDS, DEFAULT) == [(DEFAULT, None)]


def test_claims_sharing_a_projection_share_a_world_in_the_order_they_were_asked():
    config = {"x": 1, "y": 2, "z": 3}
    assert claim_groups(config, None, DEPENDS, DEFAULT) == [
        ({"x": 1, "y": 0, "z": 0}, frozenset({"A", "C"})),
        ({"x": 1, "y": 2, "z": 0}, frozenset({"B"})),
        ({"x": 0, "y": 0, "z": 3}, frozenset({"D"})),
    ]
    assert claim_groups(config, ["D", "C", "B", "A"], DEPENDS, DEFAULT) == [
        ({"x": 0, "y": 0, "z": 3}, frozenset({"D"})),
        ({"x": 1, "y": 0, "z": 0}, frozenset({"A", "C"})),
        ({"x": 1, "y": 2, "z": 0}, frozenset({"B"})),
    ]


def test_a_claim_depends_lacks_declares_nothing_and_is_measured_at_the_default():
    assert claim_groups({"x": 1}, ["A", "unknown"], DEPENDS, DEFAULT) == [
        ({"x": 1, "y": 0, "z": 0}, frozenset({"A"})),
        ({"x": 0, "y": 0, "z": 0}, frozenset({"unknown"})),
    ]


def test_no_claim_asked_is_one_world_at_the_default_with_no_claim():
    assert claim_groups({"x": 1}, [], DEPENDS, DEFAULT) == [({"x": 0, "y": 0, "z": 0}, frozenset())]


def test_values_are_told_apart_by_their_repr_so_unhashable_and_equal_looking_values_group_right():
    depends = {"A": ["x"], "B": ["x"], "C": ["y"]}
    # lists cannot be hashed: grouped by repr, A and B declaring the same list share a world, C its own
    assert claim_groups({"x": [1, 2], "y": [3]}, None, depends, {"x": [], "y": []}) == [
        ({"x": [1, 2], "y": []}, frozenset({"A", "B"})),
        ({"x": [], "y": [3]}, frozenset({"C"})),
    ]
    # 1 and 1.0 compare equal but are different settings as written: two worlds
    one = {"A": ["x"], "B": ["y"]}
    assert claim_groups({"x": 1.0, "y": 1}, None, one, {"x": 1, "y": 1.0}) == [
        ({"x": 1.0, "y": 1.0}, frozenset({"A"})),
        ({"x": 1, "y": 1}, frozenset({"B"})),
    ]


def test_a_guarded_entry_no_claim_asked_declares_is_never_read():
    guarded = {"x": 1, "y": Undeclared("y"), "z": Undeclared("z")}
    assert claim_groups(guarded, ["A", "C"], DEPENDS, DEFAULT) == [({"x": 1, "y": 0, "z": 0}, frozenset({"A", "C"}))]
    with pytest.raises(UndeclaredEntry):
        bool(guarded["y"])  # the sentinel does raise where it is read


def _measurement(calls: list, loads: list):
    """A measurement of claims A and B over ``DEPENDS``: each claim's value is the configuration it saw."""

    def load(args, kwargs):
        loads.append((args, dict(kwargs)))
        return DEPENDS, DEFAULT

    @as_declared(("A", "B"), load)
    def measure(config, seed, *args, claims=None, **kwargs):
        """The hand-built measurement."""
        calls.append((dict(config), seed, args, claims, dict(kwargs)))
        return {cid: (dict(config), seed) for cid in (claims if claims is not None else ("A", "B"))}

    return measure


def test_a_measurement_runs_once_per_world_and_each_claim_sees_only_its_own_entries():
    calls, loads = [], []
    measure = _measurement(calls, loads)
    out = measure({"x": 1, "y": 2, "z": 3}, 7, "extra", size=4)
    assert out == {"A": ({"x": 1, "y": 0, "z": 0}, 7), "B": ({"x": 1, "y": 2, "z": 0}, 7)}
    assert calls == [
        ({"x": 1, "y": 0, "z": 0}, 7, ("extra",), frozenset({"A"}), {"size": 4}),
        ({"x": 1, "y": 2, "z": 0}, 7, ("extra",), frozenset({"B"}), {"size": 4}),
    ]
    assert loads == [(("extra",), {"size": 4})]  # the arguments after the seed, once per measurement


def test_a_change_no_claim_of_the_measurement_declares_runs_it_once_for_all_its_claims():
    """z is declared by D, which this measurement does not measure: A and B share the default world and the
    measurement is asked for all its claims (None), as without the decorator."""
    calls, loads = [], []
    measure = _measurement(calls, loads)
    assert measure({"z": 3}, 1) == {"A": (DEFAULT, 1), "B": (DEFAULT, 1)}
    assert calls == [(DEFAULT, 1, (), None, {})]
    calls.clear()
    assert measure({"x": 2}, 1, claims=["B"]) == {"B": ({"x": 2, "y": 0, "z": 0}, 1)}
    assert calls == [({"x": 2, "y": 0, "z": 0}, 1, (), frozenset({"B"}), {})]
    assert loads == [((), {}), ((), {})]


def test_a_measured_claim_the_register_does_not_know_is_measured_at_the_default():
    calls = []

    @as_declared(("A", "new"), lambda args, kwargs: (DEPENDS, DEFAULT))
    def measure(config, seed, claims=None):
        calls.append((dict(config), claims))
        return {cid: config["x"] for cid in claims}

    assert measure({"x": 5}, 0) == {"A": 5, "new": 0}
    assert calls == [({"x": 5, "y": 0, "z": 0}, frozenset({"A"})), (DEFAULT, frozenset({"new"}))]
    assert measure.__name__ == "measure" and measure.__wrapped__ is not None
