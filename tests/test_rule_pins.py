"""Every paper's rules are pinned to the paper (tests/rule_pins.py): each paper package has a pin table, and the
check finds a reversed direction, a moved band end, a missing row and a stale one."""

import dataclasses
import importlib
import re
from pathlib import Path

import pytest
from rule_pins import Band, parts, problems

from tvtrack.contract import paper_packages
from tvtrack.verdicts import AllOf, InBand, NotCheckable

PAPERS = Path(__file__).parent / "papers"


def _pins(package: str) -> dict:
    number = re.match(r"p(\d{3})_", package).group(1)
    return importlib.import_module(f"papers.test_{number}_rule_pins").PINS


@pytest.mark.parametrize("package", paper_packages())
def test_every_paper_package_has_a_pin_table(package):
    number = re.match(r"p(\d{3})_", package).group(1)
    assert (PAPERS / f"test_{number}_rule_pins.py").is_file(), f"{package}: no tests/papers/test_{number}_rule_pins.py"
    assert _pins(package)


@pytest.mark.parametrize("package", paper_packages())
def test_the_exported_rules_are_the_pinned_table(package):
    paper = importlib.import_module(f"tvtrack.papers.{package}")
    assert paper.RULES == importlib.import_module(f"tvtrack.papers.{package}.claims").claim_rules()


def _replace(rule: AllOf, part: str, new) -> AllOf:
    return AllOf({**rule.parts, part: new})


def test_the_check_finds_a_reversed_direction_a_moved_end_and_missing_or_stale_rows(monkeypatch):
    paper = importlib.import_module("tvtrack.papers.p000_dissector_ekf")
    pins = _pins("p000_dissector_ekf")
    assert problems("p000_dissector_ekf", pins) == []
    rules = dict(paper.RULES)
    order = rules["C000-7"].parts["measurement vs estimate"]
    rules["C000-7"] = _replace(rules["C000-7"], "measurement vs estimate", dataclasses.replace(order, relation="<"))
    rules["C000-6"] = InBand("ratio", 19.0, unit="(ratio)")  # the paper's 20 moved by 5 %
    claims = importlib.import_module("tvtrack.papers.p000_dissector_ekf.claims")
    monkeypatch.setattr(claims, "claim_rules", lambda: rules)
    found = problems("p000_dissector_ekf", pins)
    assert any(p.startswith("C000-7 part 'measurement vs estimate': 1.0 -> not reproduced") for p in found), found
    assert any(p.startswith("C000-6 part '': 19.98 -> reproduced") for p in found), found
    fewer = {k: v for k, v in pins.items() if k != "C000-9"} | {"C000-99": {"": pins["C000-6"][""]}}
    found = problems("p000_dissector_ekf", fewer)
    assert "C000-9: no row in the pin table" in found and "C000-99: a pin row but no claim" in found
    stale = pins | {"C000-2": {**pins["C000-2"], "P=1": Band("s", "t", 0.0, 1.0, (0.5,), (2.0,))}}
    assert "C000-2 row 'P=1': matches no part" in problems("p000_dissector_ekf", stale)


def test_parts_names_readings_and_the_default():
    rule = importlib.import_module("tvtrack.papers.p001_maneuver_occlusion_kf").RULES["C001-8"]
    keys = set(parts(rule))
    assert "curve_tolerance=*default* / RMS decreasing" in keys and "curve_tolerance=0.1 / interior minimum" in keys


def test_the_wording_check_finds_a_lost_side_a_lost_quantity_and_a_changed_unit():
    from rule_pins import Order, wording

    from tvtrack.verdicts import Ordering

    row = Band("s", "t", None, 2.0, (1.0,), (3.0,), unit="px")
    assert wording(InBand("95th percentile of |e|", high=2.0, unit="px"), row) == []
    assert wording(InBand("95th percentile of |e|", high=2.0), row) == ["unit '', the paper's quantity is in 'px'"]
    assert wording(InBand(None, high=2.0, unit="px"), row) == ["names None where a phrase belongs"]
    lost_b = Ordering("MSE of the spline", ">", measure="ratio")  # b dropped: the relation took its place
    assert wording(lost_b, Order("s", "t", (2.0,), (0.5,))) == ["names '>' where a phrase belongs"]
    assert wording(Ordering("MSE of None", "the filter's"), None) == ["names 'MSE of None' where a phrase belongs"]
    assert wording(NotCheckable(None), None) == ["names None where a phrase belongs"]
