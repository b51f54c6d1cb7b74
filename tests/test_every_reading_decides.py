"""Every register value can decide: under every value of every entry a claim depends on, the rule
in force (:func:`tvtrack.verdicts.for_config`; a :class:`~tvtrack.verdicts.ByReading` rule picks its reading's) can
reach both ``reproduced`` and ``not reproduced`` on a synthetic measurement (:func:`tvtrack.verdicts.synthetic`).
A rule that can never reproduce, or never fail, under some reading decides nothing there."""

import importlib

import pytest

from tvtrack.contract import paper_packages
from tvtrack.verdicts import AllOf, NotCheckable, for_config, synthetic


def _checkable(rule) -> bool:
    if isinstance(rule, NotCheckable):
        return False
    return not (isinstance(rule, AllOf) and all(isinstance(r, NotCheckable) for r in rule.parts.values()))


@pytest.mark.parametrize("package", paper_packages())
def test_every_value_of_every_entry_can_reach_both_verdicts(package):
    paper = importlib.import_module(f"tvtrack.papers.{package}")
    default = paper.REGISTER.default()
    failures = []
    for cid, rule in paper.RULES.items():
        names = [k for k in paper.DEPENDS.get(cid, []) if k in paper.REGISTER] or [None]
        for name in names:
            for value in paper.REGISTER[name].values if name else [None]:
                r = for_config(rule, {**default, **({name: value} if name else {})})
                if not _checkable(r):
                    continue
                for verdict in ("reproduced", "not reproduced"):
                    m = synthetic(r, verdict)
                    if m is None or r.decide(m) != verdict:
                        failures.append(f"{cid} under {name} = {value!r} cannot reach {verdict}")
    assert not failures, "; ".join(failures[:10])


def test_the_check_catches_a_rule_that_cannot_reproduce():
    from tvtrack.verdicts import InBand, Monotone

    never = InBand("q", 1.0, 1.0)  # a band of zero width: no interval fits inside it
    assert synthetic(never, "reproduced") is None or never.decide(synthetic(never, "reproduced")) != "reproduced"
    assert Monotone("g", "x").decide(synthetic(Monotone("g", "x"), "reproduced")) == "reproduced"
