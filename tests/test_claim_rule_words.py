"""Every claim rule's words and numbers as the report prints them, pinned against a reviewed copy.

The rule pins (``tests/papers/test_NNN_rule_pins.py``) check that each rule decides values either side of the
paper's statement as the paper says; this file pins what the rule *says*: the quantity it compares, its reference,
its unit and band as they appear in every claim's sentence, record and page (``Rule.text`` and ``Rule.to_dict``).
A changed word or unit (a quantity renamed by mistake, a unit dropped, "ratio" for "difference") fails here with
the claim named. A deliberate change is reviewed and written into ``tests/data/claim_rules.json`` with
``TVTRACK_UPDATE_CLAIM_RULES=1 pytest tests/test_claim_rule_words.py``.
"""

from __future__ import annotations

import importlib
import json
import os
from pathlib import Path

import pytest

PACKAGES = [
    "p000_dissector_ekf",
    "p001_maneuver_occlusion_kf",
    "p002_unified_location_em",
    "p003_rotating_marker_tracker",
    "p004_laser_spot_prediction",
]
STORED = Path(__file__).parent / "data" / "claim_rules.json"
UPDATE = bool(os.environ.get("TVTRACK_UPDATE_CLAIM_RULES"))


def rule_words(package: str) -> dict:
    """``{claim: the rule's record}`` (its words at every level, numbers and units) of the package's rules, built
    afresh (not the import-time ``RULES``)."""
    claims = importlib.import_module(f"tvtrack.papers.{package}.claims")
    rules = claims.claim_rules()
    return {cid: json.loads(json.dumps(r.to_dict())) for cid, r in rules.items()}


@pytest.mark.parametrize("package", PACKAGES)
def test_every_rules_words_units_and_band_are_the_reviewed_ones(package):
    now = rule_words(package)
    stored = json.loads(STORED.read_text()) if STORED.is_file() else {}
    if UPDATE:
        stored[package] = now
        STORED.write_text(json.dumps(stored, indent=1, sort_keys=True, ensure_ascii=False) + "\n")
    mine = stored.get(package, {})
    assert sorted(now) == sorted(mine), f"claims with a rule: {sorted(now)} against the reviewed {sorted(mine)}"
    changed = [cid for cid in now if now[cid] != mine[cid]]
    assert not changed, "; ".join(f"{cid}: {now[cid]['text']!r} was {mine[cid]['text']!r}" for cid in changed)


def test_the_reviewed_copy_names_units_and_references():
    # the copy itself is checked for what a reader needs: every rule says what it compares, in words
    stored = json.loads(STORED.read_text())
    assert sorted(stored) == PACKAGES
    for package, claims in stored.items():
        for cid, entry in claims.items():
            assert entry["kind"] and len(entry["text"].strip()) > 12, (package, cid)
