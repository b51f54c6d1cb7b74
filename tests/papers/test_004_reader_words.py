"""Paper 004: the Conclusions' list of the entries added by the adversarial passes names each entry by its title and
each value by its phrase, the register's plain words, as every other sentence of the report does (it once listed
`roll-off` ... "at f^-2" and `vibration` ... "at 1.0")."""

from types import SimpleNamespace

from tvtrack.papers.p004_laser_spot_prediction import findings as fd
from tvtrack.papers.p004_laser_spot_prediction.register import build


def _exploration(register, changed: dict, parts_at: dict):
    """An exploration of one claim (C004-3) whose one-at-a-time condition ``changed`` gives ``parts_at`` where the
    first replicate gave every part ``reproduced``."""
    conditions = [{"kind": "single", "changed": changed, "parts": parts_at}]
    record = {"parts": {p: {"replicate_verdicts": ["reproduced"]} for p in parts_at}, "conditions": conditions}
    return SimpleNamespace(
        register=register,
        depends={"C004-3": [e.name for e in register]},
        record=lambda cid, rule: record,
    )


def test_adversarial_entries_are_named_by_title_and_values_by_phrase():
    register = build()
    vibration, saturation = register["vibration"], register["saturation"]
    assert vibration.origin == saturation.origin == "adversarial"
    ex = _exploration(register, {"vibration": 1.0}, {"cubic spline": "not reproduced"})
    text = fd.adversarial_summary(ex, {"C004-3": None})
    line = next(ln for ln in text.splitlines() if "cubic spline" in ln)
    assert line == (
        f"- {vibration.title[:1].upper() + vibration.title[1:]}: C004-3 (cubic spline) reproduced -> not reproduced "
        f"with {vibration.phrase(1.0)}."
    )
    assert "1 px mount vibration at 8 Hz" in line
    assert f"- {saturation.title[:1].upper() + saturation.title[1:]}: no verdict changed." in text
    adversarial = [e for e in register if e.origin == "adversarial"]
    assert len(text.splitlines()) == len(adversarial)
    for e in adversarial:  # no code name in backticks, no raw value
        assert f"`{e.name}`" not in text
    assert " at 1.0" not in text
