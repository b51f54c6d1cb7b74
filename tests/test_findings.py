"""The one claims table, Markdown escaping of generated text, and every claim's sentence: complete, in plain
words, every number with its unit."""

import json
import re
from pathlib import Path

import pytest

import tvtrack.numbers
import tvtrack.paragraphs
import tvtrack.run_words
import tvtrack.value_words
import tvtrack.wording
from tvtrack.montecarlo import Estimate
from tvtrack.results import Results, claim_summary, claims_table, format_measured, main_part, md_escape
from tvtrack.labels import Robustness, label_parts
from tvtrack.register import Entry
from tvtrack.verdicts import AllOf, InBand


def test_generated_text_is_escaped_for_markdown():
    assert md_escape("sigma*2 and a_b | c") == r"sigma\*2 and a\_b \| c"
    assert "\n" not in md_escape("two\nlines")


def test_claims_table_one_line_per_claim(tmp_path):
    res = Results("999_t", "c", {"seed": 1, "output_dir": str(tmp_path)})
    rob = Robustness(note="fixture", seeds={1: 1.5, 2: 1.5, 3: 1.5})
    res.claim(
        "C999-1",
        "The error is sigma*2 at most.",
        "<= 2",
        InBand("error", high=2.0),
        Estimate(1.5, 0.1, 1.3, 1.7, 50, method="t"),
        robustness=rob,
    )
    table = claims_table(res.claims)
    lines = table.splitlines()
    assert len(lines) == 3 and lines[0].startswith("| claim | the paper says")
    assert r"sigma\*2" in lines[2] and r"1.5 \[1.3, 1.7\]" in lines[2] and "**reproduced**" in lines[2]
    # a hand-built record explores no configuration: its label is provisional, never robust, and the sentence says so
    assert "| provisional |" in lines[2] and "(too few configurations to label)" in lines[2]
    assert claims_table([c.__dict__ for c in res.claims]) == table  # results.json dicts render the same
    assert format_measured({"a": Estimate(1, 0, 1, 1, 1, method="exact")}) == "a: 1"


# --- every claim's sentence: complete, in plain words, every number with its unit ------------------------------


REPO = Path(__file__).resolve().parents[1]
_WRITER = "".join(
    Path(m.__file__).read_text()
    for m in (tvtrack.wording, tvtrack.value_words, tvtrack.paragraphs, tvtrack.numbers, tvtrack.run_words)
)
_WORDS = re.compile(r"[A-Za-z]+")
_COUNTS = (
    r"times|% of\b|of \d|explored configurations|independent replicates|replicates?,|parts? hold|other changes?|points?|"
    r"runs|this run allows|agree|flips?\b|stay undecided|fails?\b|undecided\b|of (?:its|their) \d|steps?\b|fall\b|rises?\b"
)


#: units a sentence may quote a quantity in beside the claim's own (C004-6's caveat: the filters' RMS errors in px
#: beside a ratio), each accepted only where the record's own words use it (:func:`_other_units`)
_KNOWN_UNITS = ("px", "pixels?", "s", "ms", "el", "elements?", "Hz", "°", "deg", "km", "m/s", "rev/s", "dB", "%")
#: the end of a unit: a space, a separator, a closing bracket, a sentence's full stop or the end
_UNIT_END = r"(?=[\s,;:)]|\.(?!\w)|$)"
#: what a number glued to letters may be without owing anything: an ordinal ("2nd", "95th"), an exponent or a
#: dimension ("3D")
_GLUED_FREE = re.compile(r"(?:st|nd|rd|th|D)\b|e[+-]?\d")
#: a product of sizes ("128x128"): read as one number, which owes its unit after its last factor
_PRODUCT = r"(?:[x×]\d+(?:\.\d+)?)+"


def _other_units(record: dict) -> str:
    """The alternation of :data:`_KNOWN_UNITS` that the record's own words (its rules, statement, value and
    register; :func:`_sources`, without the caveat the sentence copies) use as a unit after a number or as a word:
    a sentence may quote a number in one of those, never in a unit the record has nowhere (an "el" claim's value
    said in "px" is a wrong unit)."""
    words = json.dumps({k: v for k, v in _sources(record).items() if k != "caveat"}, ensure_ascii=False)
    words = re.sub(r"\b95 % (?:interval|confidence)", "", words)  # every rule's interval: no "%" quantity
    found = [u for u in _KNOWN_UNITS if re.search(rf"(?<![\w/'’])(?:{u})(?![\w/])|\d\s*(?:{u})(?![A-Za-z])", words)]
    return rf"(?:{'|'.join(found)}){_UNIT_END}" if found else r"(?!)"


def _strings(x) -> list[str]:
    if isinstance(x, str):
        return [x]
    if isinstance(x, dict):
        return [s for k, v in x.items() for s in _strings(k) + _strings(v)]
    if isinstance(x, (list, tuple)):
        return [s for v in x for s in _strings(v)]
    return []


def _plain_texts(record: dict) -> list[str]:
    """What a sentence may copy from its record: the paper's words (its statement and value), the rules' quantities, the parts' names and
    the register's titles and phrases (never its names)."""
    rob = record.get("robustness") or {}
    texts = [record.get("statement", ""), record.get("note", ""), record.get("paper_value", "")]
    texts += [
        s
        for r in _rules(record.get("rule") or {})
        for k in ("quantity", "a", "b", "over", "direction", "unit", "reason")
        for s in _strings(r.get(k))
    ]
    texts += [s for e in rob.get("register") or [] for s in [e.get("title", "")] + _strings(e.get("phrases"))]
    texts += list(rob.get("parts") or {})  # a part's name, as its rule names it
    return sorted((t for t in texts if t), key=len, reverse=True)


def _rules(rule: dict) -> list[dict]:
    out = [rule]
    for sub in list((rule.get("parts") or {}).values()) + list((rule.get("rules") or {}).values()):
        out += _rules(sub)
    if isinstance(rule.get("default"), dict):
        out += _rules(rule["default"])
    return out


def _sources(record: dict) -> dict:
    """The record without the text generated from it (flip texts, where, coverage): the words a sentence may use."""
    import copy

    out = copy.deepcopy(record)
    rob = out.get("robustness") or {}
    for k in ("where", "coverage"):
        rob.pop(k, None)
    for p in (rob.get("parts") or {}).values():
        for f in (p or {}).get("flips") or [] if isinstance(p, dict) else []:
            f.pop("text", None)
    return out


def _shown_rule(record: dict) -> dict:
    rule, measured = tvtrack.value_words.rule_in_force(record.get("rule") or {}, record.get("measured"))
    if rule.get("kind") == "all_of":
        rule = (rule.get("parts") or {}).get(main_part(record)) or {}
    return rule


#: words of the project's machinery a reader of the paper does not know (a reader's test found each in a sentence)
PROJECT_TAGS = (
    "register",
    "earlier world",
    "default reading",
    "the reading's",
    "at the default statistic",
    "as the reading defines",
    "unless a reading sets",
    "20-times sentence",
)


def sentence_faults(record: dict, keys: set[str]) -> list[str]:
    """What is wrong with a claim's sentence: a cut word or an ellipsis, a "+N more", an unfinished sentence, the
    project's own terms, a register key, a number without its unit."""
    text = claim_summary(record)
    faults = []
    if "…" in text or "..." in text or re.search(r"\+\s*\d+ more", text):
        faults.append("cut or '+N more'")
    if not text.endswith(".") or not text[:1].isupper():
        faults.append("not a complete sentence")
    tags = [t for t in PROJECT_TAGS if t in text]
    if tags:
        faults.append(f"the project's own terms: {tags}")
    vocabulary = set(_WORDS.findall(json.dumps(_sources(record), ensure_ascii=False) + _WRITER))
    cut = [w for w in _WORDS.findall(text) if w not in vocabulary]
    if cut:
        faults.append(f"words found nowhere in the record or the writer (cut?): {cut}")
    plain = _plain_texts(record)
    for key in keys:
        hit = re.search(rf"(?<![\w-]){re.escape(key)}(?![\w-])", text)
        if hit and not any(re.search(rf"(?<![\w-]){re.escape(key)}(?![\w-])", t) for t in plain):
            faults.append(f"register key {key!r}")
    unit = _owed_unit(record)
    if unit:
        faults += [f"number without its unit {unit!r}: {n}" for n in _bare_numbers(text, plain, record, unit)]
    return faults


def _owed_unit(record: dict) -> str:
    """The unit every number of the sentence owes: the main part's rule's, or "%" for a dimensionless fraction the
    paper gives in per cent (C000-2's "2 %" of the micro-raster: the sentence says 2.3 %, never a bare 0.023)."""
    rule = _shown_rule(record)
    unit = tvtrack.value_words.real_unit(rule)
    ends = [rule.get(k) for k in ("low", "high") if tvtrack.numbers.finite(rule.get(k))]
    if not unit and "%" in str(record.get("paper_value") or "") and ends and all(abs(e) <= 1 for e in ends):
        return "%"
    return unit


def _bare_numbers(text: str, plain: list[str], record: dict, unit: str) -> list[str]:
    """The numbers of ``text`` that are neither inside a copied phrase or quantity (which carry their own) nor
    followed by ``unit`` (after an interval or a bound in parentheses) or by a count's noun."""
    units = {r.get("unit") for r in _rules(record.get("rule") or {})}
    skip = [m.span() for t in plain if len(t) > 3 and t not in units
            for m in re.finditer(rf"(?<![\w-]){re.escape(t)}(?![\w-])", text)]  # fmt: skip
    skip += [m.span(1) for m in re.finditer(r"\d\s*(\[[^\]]*\])", text)]  # an interval after its value
    skip += [m.span() for m in re.finditer(r"\((?:at most|at least) [^)]*\)", text)]
    skip += [m.span(1) for m in re.finditer(r"between (-?[\d.e+-]+) and ", text)]  # a range: its end has the unit
    # the size of the claim's own unit, in the unit it is measured in ("Its unit, the smallest ... RMS, is 7.62 elements")
    skip += [m.span(1) for m in re.finditer(r"[Ii]ts unit, [^.]*?, is (-?\d+(?:\.\d+)?) [a-z]+", text)]
    if "ratio" in unit:  # a ratio's parity, the pure number it is compared with ("not distinguishable from 1")
        skip += [m.span(1) for m in re.finditer(r"(?:distinguishable from|above|below) (1)(?!\w|\.\d)(?!\s*\[)", text)]
    said = re.escape(unit) + (f"|{re.escape(unit).replace('el', 'elements?', 1)}" if unit.startswith("el") else "")
    said = rf"(?:{said})(?![\w/])"  # the claim's unit as a whole word ("0.77 pxl" or "px/frame" owe it still)
    after = rf"\s*(?:\[[^\]]*\]\s*)?(?:\((?:at most|at least) [^)]*\)\s*)?(?:\(?(?:{said}|{_COUNTS})|{_other_units(record)})"
    tokens = (  # a sentence's full stop ends a number; a number glued to letters ("1.4x", "2.4el/s") is read with
        # them, and one after a multiplication sign ("x1.4") with the sign
        r"\[[^\]]*\]|(?<![\w.\[,^-])(?:[x×](?=\d))?-?\d+(?:\.\d+)?(?:e[+-]?\d+)?"
        rf"(?:{_PRODUCT}(?!\w|\.\d)|(?P<glued>[^\W\d_][\w/]*))?(?!\w|\.\d)"
    )
    bare = []
    for m in re.finditer(tokens, text):
        if any(a <= m.start() < b for a, b in skip):
            continue
        glued = m.group("glued")
        if glued:  # the letters glued on are its unit: the claim's own, or one the record uses, or an ordinal
            if not (_GLUED_FREE.match(glued) or re.fullmatch(rf"(?:{said}|{_other_units(record)})", glued)):
                bare.append(f"{m.group()!r} (a number glued to {glued!r}) before {text[m.end() : m.end() + 30]!r}")
            continue
        if not re.match(after, text[m.end() :]):
            bare.append(f"{m.group()!r} before {text[m.end() : m.end() + 30]!r}")
    return bare


@pytest.fixture(scope="module")
def keys():
    from paper_records import register_keys

    return register_keys()


def test_every_claim_of_every_paper_reads_as_complete_sentences_in_plain_words_with_units(keys):
    from paper_records import paper_records

    records = paper_records()
    assert len({r["id"] for r in records}) == 58  # every claim of the five papers
    faults = {f"{r['id']} ({r['verdict']})": sentence_faults(r, keys) for r in records}
    assert not {k: v for k, v in faults.items() if v}


def test_the_claims_of_real_paper_runs_read_as_complete_sentences_when_there_are_runs(keys):
    found = sorted((REPO / "papermill_runs" / "reproduce").glob("*/results.json"))
    if not found:
        pytest.skip("no paper-profile runs here (make reproduce makes them)")
    records = [c for f in found for c in json.loads(f.read_text())["claims"]]
    faults = {r["id"]: sentence_faults(r, keys) for r in records}
    assert not {k: v for k, v in faults.items() if v}


def test_the_checker_catches_a_cut_word_a_register_key_and_a_missing_unit(keys, monkeypatch):
    """The faults the sentence test looks for, planted one at a time: each is caught."""
    import copy

    from record_fixtures import DEPENDS

    assert sentence_faults(DEPENDS, keys) == []
    cut = copy.deepcopy(DEPENDS)
    flip = cut["robustness"]["parts"]["claim"]["flips"][0]
    flip["text"] = "sigma read as the SD of the raw velocity incr"  # the record's phrase, cut mid-word
    cut["robustness"]["parts"]["claim"]["flips"] = [flip]
    cut["robustness"]["register"][0]["phrases"]["raw_increments"] = "sigma read as the SD of the raw increments"
    assert any("cut" in f for f in sentence_faults(cut, keys)), sentence_faults(cut, keys)
    leak = copy.deepcopy(DEPENDS)
    leak["robustness"]["parts"]["claim"]["flips"][0]["text"] = "target_motion = weave"
    assert any("target_motion" in f for f in sentence_faults(leak, keys | {"target_motion"}))
    tag = copy.deepcopy(DEPENDS)
    tag["robustness"]["parts"]["claim"]["flips"][0]["text"] = "slow wander, the earlier world"
    assert any("the project's own terms" in f for f in sentence_faults(tag, keys)), sentence_faults(tag, keys)
    defined = copy.deepcopy(DEPENDS)  # the size of the claim's unit may be given in its own unit, no other number
    assert tvtrack.value_words.real_unit(_shown_rule(defined))  # the fixture's numbers owe a unit
    defined["caveat"] = "Its unit, the smallest error of the sweep, is 7.62 elements; 3.5 elsewhere."
    found = " ".join(sentence_faults(defined, keys))
    assert "'7.62'" not in found and "'3.5'" in found, found
    parity = copy.deepcopy(DEPENDS)  # a ratio compared with 1 (equal sizes) owes no unit there; any other number does
    parity["rule"]["unit"] = "variance ratio"
    parity["caveat"] = "Given the velocity: 1.4 [0.97, 2.1] variance ratio, not distinguishable from 1."
    assert not any("'1'" in f for f in sentence_faults(parity, keys)), sentence_faults(parity, keys)
    parity["caveat"] = "Given the velocity: 1.4 [0.97, 2.1] variance ratio, not distinguishable from 2."
    assert any("'2'" in f for f in sentence_faults(parity, keys)), sentence_faults(parity, keys)
    quoted = copy.deepcopy(DEPENDS)  # a number in a unit the record uses carries it; a bare one beside it does not
    quoted["caveat"] = (
        "The error stays at one level (4.44 px over the first half of the frames, 4.97 px over the second)."
    )
    found = sentence_faults(quoted, keys)  # the record's own words have no "px": a unit it never uses is a slip
    assert any("'4.44'" in f for f in found) and any("'4.97'" in f for f in found), found
    quoted["note"] = "the two windows overlap; the tracking error is a few px"
    assert not any("4.4" in f or "4.97" in f for f in sentence_faults(quoted, keys)), sentence_faults(quoted, keys)
    quoted["caveat"] = "The error stays at one level (4.44 px over the first half of the frames, 4.97 over the second)."
    assert any("'4.97'" in f for f in sentence_faults(quoted, keys)), sentence_faults(quoted, keys)
    for slip in (
        "The ratio is 1.4 (s.e. 0.2).",
        "It is 1.4 s-shaped.",
        "It is 1.4 pixel-wise.",
        "It is below 1 [0.6, 0.9].",
        "The ratio is 1.4x the default's.",  # a number glued to letters is read with them
        "The ratio is 1.4pxl.",
        "The ratio is 1.4px/s.",  # glued to a unit the record uses, then more: not that unit
        "The ratio rises x1.4 over the default.",  # after a multiplication sign
        "The ratio is 1.4 s.",  # "s" only in the record's possessives ("the paper's"), never as a unit
    ):
        quoted["caveat"] = slip  # a unit's letters inside another word, or a measured 1 with its interval, owe the unit
        assert any("1.4'" in f or "'1'" in f or "1.4px" in f or "1.4x" in f for f in sentence_faults(quoted, keys)), (
            slip,
            sentence_faults(quoted, keys),
        )
    quoted["caveat"] = "The 2nd-order filter's error is 4.44px over the first half."  # glued: a unit or an ordinal
    assert sentence_faults(quoted, keys) == [], sentence_faults(quoted, keys)
    own = copy.deepcopy(DEPENDS)  # the claim's own unit counts only as a whole word
    own["rule"]["unit"] = "px"
    for slip in ("It is 0.77 pxl wide.", "It is 0.77 px/frame."):
        own["caveat"] = slip
        assert any("'0.77'" in f for f in sentence_faults(own, keys)), (slip, sentence_faults(own, keys))
    own["caveat"] = "It is 0.77 px wide (0.8 px, 0.9px)."
    assert sentence_faults(own, keys) == [], sentence_faults(own, keys)
    # a dimension, a product of sizes with its unit after the last factor, a share of something named: no unit owed
    own["caveat"] = "On the 3D scene's 128x128 px frames, 4 % of the runs drift."
    assert sentence_faults(own, keys) == [], sentence_faults(own, keys)
    for slip, token in (
        ("On the 128x128 frames it drifts.", "'128x128'"),  # a product owes its unit too
        ("It drifts by 2.7 % a frame.", "'2.7'"),  # "%" is a unit the record never uses, not a share of anything
        ("It drifts by 2.7% a frame.", "'2.7'"),
    ):
        own["caveat"] = slip
        assert any(token in f for f in sentence_faults(own, keys)), (slip, sentence_faults(own, keys))
    own["note"] = "the drift is about 3 % of the frame"  # ... unless the record quotes a quantity in per cent
    own["caveat"] = "It drifts by 2.7 % a frame."
    assert sentence_faults(own, keys) == [], sentence_faults(own, keys)
    share = copy.deepcopy(DEPENDS)  # a fraction the paper gives in per cent owes "%" after each number ...
    share["rule"].update(low=0.01, high=0.03, unit="")
    share["measured"] = {"value": 0.0233, "ci_low": 0.0178, "ci_high": 0.0358}
    share["paper_value"] = "2 %"
    assert sentence_faults(share, keys) == []
    said = tvtrack.value_words._percent  # ... and a writer that scales the value but drops the "%" is caught
    monkeypatch.setattr(tvtrack.value_words, "_percent", lambda *a: (lambda r: r and (*r[:2], ""))(said(*a)))
    assert any("number without its unit '%'" in f for f in sentence_faults(share, keys)), sentence_faults(share, keys)
    monkeypatch.undo()
    bare = copy.deepcopy(DEPENDS)
    bare["rule"]["unit"] = "px"  # the sentence now owes "px" after each number: the writer gives it ...
    assert sentence_faults(bare, keys) == []
    unitless = tvtrack.wording.claim_summary(bare).replace(" px", "")  # ... and a sentence without it is caught
    original = tvtrack.wording.claim_summary
    try:
        tvtrack.wording.claim_summary = lambda c, chars=250: unitless
        globals()["claim_summary"] = tvtrack.wording.claim_summary
        assert any("without its unit" in f for f in sentence_faults(bare, keys))
    finally:
        tvtrack.wording.claim_summary = original
        globals()["claim_summary"] = original


def test_a_value_that_reverses_the_papers_direction_says_so_in_words():
    """C002-11: the paper has the ULA 3-6 times better than two-stage processing (rho = two-stage / ULA variance);
    0.74 means the two-stage beats the ULA. An ordering measured the other way round says which is larger."""
    from tvtrack.papers.p002_unified_location_em.claims import RULES

    rule = RULES["C002-11"].to_dict()["parts"]["d = 1 sigma (paper x4.5)"]
    measured = {"value": 0.7403, "ci_low": 0.6042, "ci_high": 0.9071}
    assert tvtrack.value_words.value_clause(rule, measured) == (
        "gain rho = two-stage / ULA variance at d = 1 sigma, T = 50 is 0.7403 [0.6042, 0.9071] variance ratio, "
        "where the paper has [3, 6] variance ratio: the two-stage beats the ULA, the reverse of the paper's direction"
    )
    inside = {"value": 4.2, "ci_low": 3.9, "ci_high": 4.6}
    assert "reverse" not in tvtrack.value_words.value_clause(rule, inside)
    better = RULES["C002-8"].to_dict()["parts"]["better than the marks"]  # ULA's variance < two-stage's
    assert tvtrack.value_words.value_clause(better, {"value": 1.3, "ci_low": 1.1, "ci_high": 1.5}) == (
        "ULA variance of x_o, coarse pixels is 1.3 [1.1, 1.5] times two-stage's: larger, where the paper has it smaller"
    )


def test_a_flip_of_one_part_says_the_whole_claims_verdict_there():
    """A reading that flips one part of a claim of several does not make the claim that verdict: the sentence
    says what the whole claim is under that reading, and the part's verdict beside it."""
    reading = Entry("sigma", "reading", "raw", ("raw", "smoothed"), "the text reads either way")
    rule = AllOf({"early": InBand("mean", -0.5, 0.5, "px"), "late": InBand("mean", -0.5, 0.5, "px")})
    held = {"early": Estimate.exact(0.0), "late": Estimate.exact(0.0)}
    reps = [{"seed": s, "measured": held} for s in (1, 2, 3)]
    half = {"early": Estimate.exact(3.0), "late": Estimate.exact(0.0)}  # the reading fails one part only
    conds = [{"changed": {"sigma": "smoothed"}, "kind": "single", "measured": half, "runs": 3}]
    rob = label_parts(rule, held, reps, conds, [reading])
    claim = {"id": "C9-1", "verdict": "reproduced", "rule": rule.to_dict(), "measured": held, "robustness": rob}
    assert (
        "Under another reading of the paper's text the claim is partly reproduced (its part early: not "
        "reproduced): sigma = smoothed." in claim_summary(claim)
    )
    whole = {"early": Estimate.exact(3.0), "late": Estimate.exact(3.0)}  # both parts fail: the claim's verdict
    rob = label_parts(rule, held, reps, [{**conds[0], "measured": whole}], [reading])
    assert "the paper's text it is not reproduced: sigma = smoothed." in claim_summary({**claim, "robustness": rob})


def test_the_flip_named_is_the_strongest_of_every_part_not_only_the_main_parts():
    """A claim that holds is said through its first part; where that part is flipped only by a mix no subset
    isolates and another part by a single reading, the sentence names the reading (the label rests on it), with
    the whole claim's verdict there and the part it moves."""
    reading = Entry("sigma", "reading", "raw", ("raw", "smoothed"), "the text reads either way")
    world = Entry("motion", "model", "still", ("still", "weave"), "beyond the paper")
    rule = AllOf({"early": InBand("mean", -0.5, 0.5, "px"), "late": InBand("mean", -0.5, 0.5, "px")})
    held = {"early": Estimate.exact(0.0), "late": Estimate.exact(0.0)}
    reps = [{"seed": s, "measured": held} for s in (1, 2, 3)]
    fails = (
        {"early": Estimate.exact(3.0), "late": Estimate.exact(0.0)},
        {"early": Estimate.exact(0.0), "late": Estimate.exact(3.0)},
    )
    conds = [
        {"changed": {"sigma": "smoothed", "motion": "weave"}, "kind": "joint", "measured": fails[0], "runs": 3},
        {"changed": {"sigma": "smoothed"}, "kind": "single", "measured": fails[1], "runs": 3},
        {"changed": {"motion": "weave"}, "kind": "single", "measured": held, "runs": 3},
    ]
    rob = label_parts(rule, held, reps, conds, [reading, world])
    claim = {"id": "C9-1", "verdict": "reproduced", "rule": rule.to_dict(), "measured": held, "robustness": rob}
    assert rob["parts"]["early"]["flips"][0]["side"] == "unattributed"
    text = claim_summary(claim)
    assert (
        "Under another reading of the paper's text the claim is partly reproduced (its part late: not reproduced): "
        "sigma = smoothed." in text
    ), text
    assert "changes together" not in text


def test_the_flip_named_changes_the_whole_verdict_before_one_that_moves_only_a_part():
    """A claim partly reproduced (early and mid hold, late fails): a reading that makes early fail leaves it partly
    (only a part moves); an unreported setting that makes late hold changes the whole verdict to reproduced. Both
    make ``depends``; the sentence names the setting, and the first screen counts the claim under settings only."""
    from tvtrack.paragraphs import part_only, turns_on

    reading = Entry("sigma", "reading", "raw", ("raw", "smoothed"), "the text reads either way")
    setting = Entry("rate", "unreported setting", 25, (25, 50), "the paper never printed it")
    band = InBand("mean", -0.5, 0.5, "px")
    rule = AllOf({"early": band, "mid": band, "late": band})
    ok, bad = Estimate.exact(0.0), Estimate.exact(3.0)
    partly = {"early": ok, "mid": ok, "late": bad}
    reps = [{"seed": s, "measured": partly} for s in (1, 2, 3)]
    conds = [
        {"changed": {"sigma": "smoothed"}, "kind": "single", "runs": 3, "measured": {**partly, "early": bad}},
        {"changed": {"rate": 50}, "kind": "single", "runs": 3, "measured": {**partly, "late": ok}},
    ]
    rob = label_parts(rule, partly, reps, conds, [reading, setting])
    claim = {"id": "C9-2", "verdict": "partly", "rule": rule.to_dict(), "measured": partly, "robustness": rob}
    assert rob["label"] == "depends" and rob["parts"]["early"]["flips"][0]["side"] == "reading"
    text = claim_summary(claim)
    assert text.endswith(
        "Under another setting of the paper's own experiment, one the paper never printed, it is reproduced: rate = 50."
    )
    assert "sigma" not in text  # the reading that moves only the part early is not the one named
    assert set(turns_on([claim])) == {"setting"} and part_only([claim]) == 0
    only_part = {
        **claim,
        "robustness": {**rob, "parts": {"early": rob["parts"]["early"]}, "conditions": rob["conditions"][:1]},
    }
    assert part_only([only_part]) == 1 and turns_on([only_part]) == {}
    from tvtrack.flip_words import label_basis  # the first screen's "(depends: ...)" beside each claim that holds

    assert label_basis(claim) == "an unprinted setting" and label_basis(only_part) == "a reading, in a part only"


def test_a_flip_that_leaves_the_papers_operating_point_is_counted_beside_the_label_not_in_it():
    """Two unreported settings flip the claim alone; the first in the record leaves the operating point the paper
    states (the register marks it ``off_operating_point``): it is no flip of the label, it is counted beside it
    with its own where-line, and the sentence names the one that keeps the operating point."""
    wander = Entry(
        "bandwidth", "unreported setting", 2.0, (1.0, 2.0), "speed of the wander", off_operating_point=(1.0,)
    )
    band = Entry("error in the band", "unreported setting", 1.5, (1.0, 1.5), "where the world is calibrated")
    rule = InBand("95th percentile", None, 2.0, "px")
    fails, holds = Estimate.exact(2.7), Estimate.exact(1.0)
    reps = [{"seed": s, "measured": fails} for s in (1, 2, 3)]
    conds = [
        {"changed": {"bandwidth": 1.0}, "kind": "single", "runs": 3, "measured": holds},
        {"changed": {"error in the band": 1.0}, "kind": "single", "runs": 3, "measured": holds},
    ]
    rob = label_parts(rule, fails, reps, conds, [wander, band])
    rob["register"] = [wander.to_dict(), band.to_dict()]
    claim = {"id": "C9-3", "verdict": "not reproduced", "rule": rule.to_dict(), "measured": fails, "robustness": rob}
    part = rob["parts"]["claim"]
    assert [f["changed"] for f in part["flips"]] == [{"error in the band": 1.0}]
    assert part["off_operating_point"] == {
        "agree": 0,
        "flip": 1,
        "undecided": 0,
        "flips": [{"changed": {"bandwidth": 1.0}, "verdict": "reproduced", "text": "bandwidth = 1"}],
    }
    assert part["where"][-1] == "reproduced when bandwidth = 1 (outside the paper's operating point)"
    assert part["share"]["design"] == 1  # the share is over the configurations at the operating point
    assert [c.get("off_operating_point", False) for c in rob["conditions"]] == [True, False]
    assert claim_summary(claim).split("it is reproduced: ")[1].startswith("error in the band = 1")
    # alone, the flip outside the operating point leaves the part without a flip: robust where the world was varied
    alone = label_parts(rule, fails, reps, conds[:1], [wander, band], design={"min_share_design": 1})
    assert alone["parts"]["claim"]["flips"] == [] and alone["parts"]["claim"]["off_operating_point"]["flip"] == 1


def test_a_caveat_the_record_carries_is_said_in_the_claims_sentence():
    """A default calibrated to the claim's own value is a consistency check: the record's caveat is a sentence the
    summary must carry, right after the value; a claim without one reads as before."""
    import copy

    from record_fixtures import DEPENDS

    claim = copy.deepcopy(DEPENDS) | {"caveat": "The window was chosen to give the delay, so it is a consistency check"}
    text = claim_summary(claim)
    plain = claim_summary(DEPENDS)
    assert text.startswith(
        plain.split(". ")[0] + ". The window was chosen to give the delay, so it is a consistency check."
    )
    assert "consistency" not in plain


def test_a_change_every_flip_shares_is_named_with_its_kind():
    """Flips that are all combinations sharing one change (a world): the sentence names the shared change, which a
    list of combinations hides; flips sharing nothing add no such sentence."""
    import copy

    from record_fixtures import DEPENDS

    claim = copy.deepcopy(DEPENDS)
    mixes = [
        {"paper_sigma": "raw_increments", "target_motion": "weave"},
        {"k_bound2": 100, "target_motion": "weave"},
    ]
    claim["robustness"]["parts"]["claim"]["flips"] = [
        {"changed": c, "side": "unattributed", "kind": "combination", "verdict": "reproduced", "text": f"mix {i}"}
        for i, c in enumerate(mixes)
    ]
    assert "Every change that flips it includes a target weaving at 0.1 T (a world beyond the paper)." in claim_summary(
        claim
    )
    claim["robustness"]["parts"]["claim"]["flips"][1]["changed"] = {"k_bound2": 100, "paper_sigma": "raw"}
    assert "Every change" not in claim_summary(claim)


def test_part_flips_that_together_change_the_whole_verdict_count_in_the_first_screen():
    """A claim partly reproduced (early and mid hold, late fails): one reading makes early fail, another mid, each
    leaving it partly; both together make it not reproduced. The joint configuration is not named (each part's flip
    is explained by its single reading), but the first screen counts the claim under readings and never says that
    its whole verdict stays under every change explored."""
    from tvtrack.paragraphs import depends_also_on_a_world, part_only, results_summary, turns_on

    sigma = Entry("sigma", "reading", "raw", ("raw", "smoothed"), "the text reads either way")
    gate = Entry("gate", "reading", "wide", ("wide", "narrow"), "the text reads either way")
    band = InBand("mean", -0.5, 0.5, "px")
    rule = AllOf({"early": band, "mid": band, "late": band})
    ok, bad = Estimate.exact(0.0), Estimate.exact(3.0)
    partly = {"early": ok, "mid": ok, "late": bad}
    reps = [{"seed": s, "measured": partly} for s in (1, 2, 3)]
    both = {"sigma": "smoothed", "gate": "narrow"}
    conds = [
        {"changed": {"sigma": "smoothed"}, "kind": "single", "runs": 3, "measured": {**partly, "early": bad}},
        {"changed": {"gate": "narrow"}, "kind": "single", "runs": 3, "measured": {**partly, "mid": bad}},
        {"changed": both, "kind": "joint", "runs": 3, "measured": {"early": bad, "mid": bad, "late": bad}},
    ]
    rob = label_parts(rule, partly, reps, conds, [sigma, gate])
    claim = {"id": "C9-5", "verdict": "partly", "rule": rule.to_dict(), "measured": partly, "robustness": rob}
    assert [c["verdict"] for c in rob["conditions"]] == ["partly", "partly", "not reproduced"]
    assert all(f["changed"] != both for p in rob["parts"].values() for f in p["flips"])  # the joint is not named
    assert turns_on([claim]) == {"reading": (1, [("sigma", "9", 1), ("gate", "9", 1)])} and part_only([claim]) == 0
    assert "only in a part" not in results_summary([claim])
    undersized = {**claim, "robustness": {**rob, "conditions": [*rob["conditions"][:2], {**rob["conditions"][2]}]}}
    undersized["robustness"]["conditions"][2]["undersized"] = {}  # too small to count: the screen does not lean on it
    assert part_only([undersized]) == 1 and turns_on([undersized]) == {}
    world = Entry("gate", "regime", "wide", ("wide", "narrow"), "a world beyond the paper")
    mixed = label_parts(rule, partly, reps, conds, [sigma, world])  # a reading and a world only together
    claim = {**claim, "robustness": mixed}
    assert mixed["label"] == "depends" and depends_also_on_a_world([claim]) == 0  # the world alone moves a part
    assert turns_on([claim]) == {} and part_only([claim]) == 0  # counted under neither side, never "stays"


def test_a_part_flip_of_an_undecided_claim_counts_in_the_first_screen():
    """An undecided claim (early holds, late straddles the band) whose early part a reading makes fail: the whole
    verdict reads undecided there too, but whatever late turns out to be, the claim's verdict differs under the
    reading (reproduced or partly at the default, partly or not reproduced there). The first screen counts it under
    readings, as its label ``depends`` does, never as a claim whose whole verdict stays."""
    from tvtrack.paragraphs import part_only, results_summary, turns_on
    from tvtrack.wording import moves_verdict

    reading = Entry("sigma", "reading", "raw", ("raw", "smoothed"), "the text reads either way")
    band = InBand("mean", -0.5, 0.5, "px")
    rule = AllOf({"early": band, "late": band})
    open_late = {"early": Estimate.exact(0.0), "late": Estimate(0.45, 0.05, 0.3, 0.6, 50, method="t")}
    reps = [{"seed": s, "measured": open_late} for s in (1, 2, 3)]
    fails = {**open_late, "early": Estimate.exact(3.0)}
    conds = [{"changed": {"sigma": "smoothed"}, "kind": "single", "runs": 3, "measured": fails}]
    rob = label_parts(rule, open_late, reps, conds, [reading])
    claim = {"id": "C9-4", "verdict": "undecided", "rule": rule.to_dict(), "measured": open_late, "robustness": rob}
    assert rob["label"] == "depends" and rob["conditions"][0]["verdict"] == "undecided"
    (flip,) = rob["parts"]["early"]["flips"]
    assert moves_verdict(claim, flip)
    assert turns_on([claim]) == {"reading": (1, [("sigma", "9", 1)])} and part_only([claim]) == 0
    assert (
        "What the verdicts turn on: a reading of the paper's text (alone or with other readings) flips 1 claim."
        in results_summary([claim])
    )


def test_a_flip_that_takes_several_changes_says_how_many():
    from tvtrack.wording import _flip_sentence

    two = {"changed": {"a": 1, "b": 2}, "verdict": "reproduced", "text": "x and y"}
    assert _flip_sentence({**two, "side": "reading"}) == (
        "Under two other readings of the paper's text together it is reproduced: x and y."
    )
    assert _flip_sentence({**two, "side": "setting"}) == "Under two changes together it is reproduced: x and y."
    three = {**two, "changed": {"a": 1, "b": 2, "c": 3}, "side": "unattributed"}
    assert (
        _flip_sentence(three) == "Under three changes together (none of them flips it alone) it is reproduced: x and y."
    )
    assert _flip_sentence({**two, "changed": {"a": 1}, "side": "setting"}) == (
        "Under another setting of the paper's own experiment, one the paper never printed, it is reproduced: x and y."
    )


def test_the_first_screen_says_what_verdicts_turn_on_by_kind():
    """A reading of the text, an unreported setting of the paper's experiment, a world beyond it: each in plain
    words, with the register title that flips the most claims (the sides the core's records may carry)."""
    import copy

    from record_fixtures import DEPENDS
    from tvtrack.results import results_summary

    setting = copy.deepcopy(DEPENDS) | {"id": "C001-8"}
    setting["robustness"]["register"][1]["kind"] = "unreported setting"
    setting["robustness"]["register"][1]["side"] = "setting"
    setting["robustness"]["parts"]["claim"]["flips"] = [
        {"changed": {"k_bound2": 100}, "side": "setting", "kind": "single", "verdict": "reproduced", "text": "x"}
    ]
    text = results_summary([DEPENDS, setting])
    assert text.endswith(
        "What the verdicts turn on: a reading of the paper's text (alone or with other readings) flips 1 claim; "
        "a setting of the paper's own experiment that the paper never printed (alone or with readings or other settings) flips 1 claim; "
        "a world beyond the paper (alone or with other worlds) flips 1 claim."
    ), text
    assert (
        "2 turn on a reading of an ambiguous passage or a setting the paper never printed, and 0 differ" in text
        and "Of the 2 that turn on a reading or setting, for 1 of them worlds beyond the paper (one or several), with "
        "no reading or setting changed, also flip the verdict."
        in text
    )  # DEPENDS is flipped by a world too: the label names the reading, the count says what it hides
    sentence = claim_summary(setting)
    assert "Under another setting of the paper's own experiment, one the paper never printed, it is reproduced: x." in (
        sentence
    )


def test_the_sentence_on_how_sure_the_verdicts_are_accounts_for_every_checkable_verdict():
    """Its counts add up to the checkable verdicts: one that decides no part (or has no record) carries no label,
    and is said so rather than left out of the sum."""
    from tvtrack.results import results_summary

    def claim(cid, verdict, label):
        return {"id": cid, "verdict": verdict, "robustness": {"label": label}}

    claims = [claim("C001-1", "reproduced", "robust"), claim("C001-2", "undecided", "-")]
    claims += [claim("C001-3", "not reproduced", "unexplored"), claim("C001-4", "not checkable", "-")]
    text = results_summary(claims)
    assert (
        "Of the 3 checkable verdicts, 1 survives every reading of the paper, 0 turn on a reading of an ambiguous "
        "passage or a setting the paper never printed, 1 has nothing explored to show how far it extends "
        "(unexplored), 1 has no label (no part of it decided, or no record of what was explored), and 0 differ "
        "between independent replicates. The one that survives every reading: it holds; 1 robust, 0 limited "
        "(holding only within the paper's world)." in text
    ), text
    two = claims + [{"id": "C001-5", "verdict": "reproduced"}]
    assert "2 have no label (no part of them decided, or no record of what was explored), and 0 differ" in (
        results_summary(two)
    )
    assert "no label" not in results_summary(claims[:1] + claims[2:])


def test_a_papers_limitations_come_from_its_records():
    """Worlds calibrated to the paper's own operating point, what is not checkable and why, runs that lost lock
    (the fields the core's records may carry), the undecided claims and the notebook's own limitations."""
    import copy

    from record_fixtures import DEPENDS, NOT_CHECKABLE, UNDECIDED
    from tvtrack.results import paper_paragraph

    lost = copy.deepcopy(DEPENDS)
    lost["robustness"]["parts"]["claim"].update(lost_share=0.3, in_lock_verdict="reproduced", decided_by_lost_runs=True)
    some = copy.deepcopy(UNDECIDED) | {"id": "C004-5"}
    some["robustness"]["parts"]["claim"]["lost_share"] = 0.04
    register = copy.deepcopy(DEPENDS["robustness"]["register"])
    register[2]["why"] = "calibrated so that the paper's filter errs 1.5 px"
    data = {"claims": [lost, some, NOT_CHECKABLE], "register": register, "limitations": ["No figure survives"]}
    paragraph, limits = paper_paragraph(data)
    assert paragraph.startswith("The paper makes 3 claims checked here; 2 can be measured. It does not hold that ")
    assert not any("Nothing explored shows" in x for x in limits)  # C004-5 is undecided: its runs are the limit
    assert limits == [
        "No figure survives.",
        "The simulated world is calibrated to the paper's own operating point (how the target moves): agreement at "
        "that point is partly by construction.",
        "C001-6 is not checkable: the recording of the real aircraft is not published.",
        "More runs than these would be needed to decide C004-5.",
        "Runs that lost lock carry the verdict of C001-3: over the runs in lock alone it differs.",
        "Some runs lost lock in C004-5 (at most 4 % of them).",
    ]
    assert "Runs that lost lock carry this verdict: over the runs in lock alone it is reproduced." in claim_summary(
        lost
    )


def test_a_joint_reading_flip_counts_where_the_verdicts_turn():
    """A joint configuration is named only where no subset flips alone: a flip of two readings together counts as a
    reading on the first screen, as it does for the claim's label (``depends``)."""
    from tvtrack.paragraphs import turns_on

    flip = {"changed": {"cost": "CPU time", "noise at": "updated"}, "side": "reading", "kind": "joint"}
    claim = {
        "id": "C9-4",
        "verdict": "reproduced",
        "robustness": {"parts": {"claim": {"flips": [{**flip, "verdict": "not reproduced", "text": "both"}]}}},
    }
    assert turns_on([claim]) == {"reading": (1, [("cost", "9", 1), ("noise at", "9", 1)])}


def test_an_undecided_claim_says_the_runs_its_slowest_part_needs():
    """The claim is decided only when every part is: the sentence gives the largest need, not the shown part's."""
    rule = AllOf({"a": InBand("mean", -0.5, 0.5, "px"), "b": InBand("mean", -0.5, 0.5, "px")})
    straddles = {"value": 0.45, "ci_low": 0.3, "ci_high": 0.6}
    parts = {
        "a": {"verdict": "undecided", "label": "-", "runs_to_decide": {"replicates": 14, "now": 3}},
        "b": {"verdict": "undecided", "label": "-", "runs_to_decide": {"replicates": 95, "now": 3}},
    }
    claim = {
        "id": "C9-5",
        "verdict": "undecided",
        "rule": rule.to_dict(),
        "measured": {"a": straddles, "b": straddles},
        "robustness": {"parts": parts},
    }
    assert "About 95 independent replicates are projected to decide its part b." in claim_summary(
        claim
    )  # a's value is shown
    parts["b"]["runs_to_decide"] = {"replicates": None, "now": 3}  # no practical number of runs decides b
    assert "No practical number of runs is projected to decide its part b." in claim_summary(claim)
    parts["a"]["runs_to_decide"] = {"replicates": 140, "now": 3}  # the shown part is the slowest: "it"
    parts["b"]["runs_to_decide"] = {"replicates": 95, "now": 3}
    assert "About 140 independent replicates are projected to decide it." in claim_summary(claim)


def test_a_flip_carried_by_runs_that_lost_lock_says_so_in_the_sentence_and_the_limitations():
    """A paper's own count of the runs that lost lock (Results.claim(lost_runs=...)): a named flip whose verdict
    over the runs in lock is the default's is carried by those runs, and the claim's sentence and the paper's
    limitations say so; a flip that holds over the runs in lock too is said as before."""
    import copy

    from record_fixtures import DEPENDS
    from tvtrack.lost_labels import mark_lost_runs
    from tvtrack.flip_words import why_not_clause as _why_not
    from tvtrack.results import paper_paragraph

    def mark_lost_runs_copy(claim: dict, row: dict) -> dict:
        out = copy.deepcopy(claim)
        mark_lost_runs(out["robustness"], [row], out["verdict"])
        return out

    plain = claim_summary(DEPENDS)
    claim = copy.deepcopy(DEPENDS)
    reading = {"paper_sigma": "raw_increments"}
    row = {"changed": reading, "lost": 27, "runs": 600, "verdict": "reproduced", "in_lock_verdict": "not reproduced"}
    mark_lost_runs(claim["robustness"], [row], claim["verdict"])
    text = claim_summary(claim)
    assert (
        "it is reproduced: sigma read as the SD of the raw velocity increments. The 27 of 600 runs that lost lock "
        "there carry that flip: over the runs in lock alone the claim is not reproduced, but the verdict counts every "
        "run, so the flip stands." in text
    ), text
    _, limits = paper_paragraph({"claims": [claim], "register": claim["robustness"]["register"]})
    assert any(x.startswith("Runs that lost lock carry flips of C001-3") for x in limits), limits
    one = copy.deepcopy(DEPENDS)  # a count over one replicate's draws says so: the pooled verdict rests on more
    mark_lost_runs(one["robustness"], [{**row, "replicates": 1}], one["verdict"])
    assert (
        "In one replicate, the 27 of its 600 runs that lost lock there carry that flip: over that replicate's runs in "
        "lock alone the claim is not reproduced, but the verdict counts every run, so the flip stands."
    ) in claim_summary(one)
    assert _why_not(one).endswith(
        "but in one replicate only through the 27 of its 600 runs that lost lock there"
    )  # the list of claims that do not reproduce says whose runs it counts, as the sentence does
    _, limits = paper_paragraph({"claims": [one], "register": one["robustness"]["register"]})
    assert (
        "Runs that lost lock carry flips of C001-3: over the runs in lock alone those changes do not flip the verdict "
        "(counted over one replicate's draws)." in limits
    ), limits
    few = copy.deepcopy(DEPENDS)
    mark_lost_runs(few["robustness"], [{**row, "lost": 1, "replicates": 3}], few["verdict"])
    assert "In 3 replicates, the 1 of their 600 runs that lost lock there carries that flip: over" in claim_summary(few)
    assert _why_not(few).endswith("but in 3 replicates only through the 1 of their 600 runs that lost lock there")
    assert "The 1 of 600 runs that lost lock there carries that flip" in claim_summary(
        mark_lost_runs_copy(DEPENDS, {**row, "lost": 1})
    )
    held = copy.deepcopy(DEPENDS)
    mark_lost_runs(held["robustness"], [{**row, "in_lock_verdict": "reproduced"}], held["verdict"])
    assert claim_summary(held) == plain  # the flip holds over the runs in lock: nothing to add
    _, limits = paper_paragraph({"claims": [held], "register": held["robustness"]["register"]})
    assert not any("carry" in x for x in limits)


def test_runs_that_lost_lock_deciding_the_default_are_said_and_counted():
    import copy

    from record_fixtures import DEPENDS
    from tvtrack.lost_labels import mark_lost_runs
    from tvtrack.paragraphs import _lost_share
    from tvtrack.results import paper_paragraph

    claim = copy.deepcopy(DEPENDS)
    row = {"changed": {}, "lost": 6, "runs": 200, "verdict": "not reproduced", "in_lock_verdict": "reproduced"}
    mark_lost_runs(claim["robustness"], [row], claim["verdict"])
    assert claim["robustness"]["decided_by_lost_runs"] is True
    assert _lost_share(claim) == pytest.approx(0.03)
    # how many, and never "decide" (an undecided claim's sentence says what would decide it)
    assert "6 of 200 runs lost lock and carry this verdict: over the runs in lock alone it is reproduced." in (
        claim_summary(claim)
    )
    one = copy.deepcopy(DEPENDS)
    mark_lost_runs(one["robustness"], [{**row, "lost": 1, "runs": 600}], one["verdict"])
    assert "1 of 600 runs lost lock and carries this verdict: over the runs in lock alone" in claim_summary(one)
    rep = copy.deepcopy(DEPENDS)
    mark_lost_runs(rep["robustness"], [{**row, "lost": 1, "runs": 600, "replicates": 1}], rep["verdict"])
    assert rep["robustness"]["lost_share"]["replicates"] == 1
    _, limits = paper_paragraph({"claims": [rep], "register": rep["robustness"]["register"]})
    assert (
        "Runs that lost lock carry the verdict of C001-3: over the runs in lock alone it differs (counted over one "
        "replicate's draws)." in limits
    ), limits
    said = claim_summary(rep)
    lock = (
        "In one replicate, 1 of its 600 runs lost lock and carries this verdict: over that replicate's runs in "
        "lock alone it is reproduced."
    )
    assert lock in said and " there" not in said.split(lock)[0][-10:]
    first_flip = min(said.find(w) for w in ("Under ", "It does not extend") if w in said)
    assert said.index(lock) < first_flip  # the default's lost runs come before any flip: "this verdict" is its
    with pytest.raises(ValueError, match="lost 7 of runs 6"):
        mark_lost_runs(claim["robustness"], [{**row, "lost": 7, "runs": 6}], claim["verdict"])


def test_the_band_is_said_as_what_the_paper_says_or_as_set_here_where_the_paper_gives_no_number():
    from tvtrack.value_words import against_paper, value_clause

    band = "at most 10 % of the runs"
    assert against_paper(band, "fairly quickly (no number)") == (
        ', where the paper says "fairly quickly" (read here as at most 10 % of the runs)'
    )
    assert (
        against_paper(band, "qualitative (Fig. 3)")
        == ", against at most 10 % of the runs, set here (the paper gives no number)"
    )
    assert against_paper("[5.25, 5.75] s", "5.5 s (one run)") == ", against [5.25, 5.75] s (the paper: 5.5 s)"
    assert against_paper("[3, 6]", "x4 (d = 3 sigma), x4.5 (d = 1 sigma)").endswith(
        "(the paper: x4 (d = 3 sigma), x4.5 (d = 1 sigma))"
    )
    assert against_paper("[0, 2]", None) == ", where the paper has [0, 2]"  # a bare rule: its band is all there is
    # a share of runs in per cent, its band too
    rule = {"kind": "in_band", "quantity": "share of runs not in lock", "low": None, "high": 0.1, "unit": "of the runs"}
    measured = Estimate(0.0078, float("nan"), 0.0043, 0.013, 900, 0.95, "count")
    assert value_clause(rule, measured, "fairly quickly (no number)") == (
        'share of runs not in lock is 0.78 [0.43, 1.3] % of the runs, where the paper says "fairly quickly" (read '
        "here as at most 10 % of the runs)"
    )


def test_a_fraction_the_paper_gives_in_per_cent_is_said_in_per_cent():
    """C000-2: the paper's "2 %" of the micro-raster against a measured fraction 0.0233 reads as 2.33 %; a ratio
    the paper gives as a plain number, or a band beyond one, stays as it is."""
    from tvtrack.value_words import value_clause

    rule = {"kind": "in_band", "quantity": "RMS error / raster size", "low": 0.01, "high": 0.03, "unit": ""}
    measured = Estimate(0.02327, float("nan"), 0.01784, 0.03578, 600, 0.95, "bootstrap")
    assert value_clause(rule, measured, "2 %") == (
        "RMS error / raster size is 2.327 [1.784, 3.578] %, against [1, 3] % (the paper: 2 %)"
    )
    assert value_clause(rule, measured, "0.02").startswith("RMS error / raster size is 0.02327 [0.01784, 0.03578],")
    wide = {**rule, "low": 0.5, "high": 2.0}
    assert "%" not in value_clause(wide, measured, "2 %").split(", against")[0]
    # of a paper value in pieces, the per cent is the other piece's: the correlation stays a plain number
    rho = {"kind": "in_band", "quantity": "lag-1 correlation rho", "low": 0.4, "high": 0.6, "unit": ""}
    assert value_clause(rho, Estimate.exact(0.5), "rho <= 0.5; false alarms within 5 %") == (
        "lag-1 correlation rho is 0.5, against [0.4, 0.6] (the paper: rho <= 0.5)"
    )
    assert value_clause({**rho, "high": None}, Estimate.exact(0.5), "rho >= 40 %").startswith(
        "lag-1 correlation rho is 50 %, against at least 40 %"
    )


def test_a_paper_bound_on_a_symbol_the_quantity_never_names_is_said_as_read_from_not_as_the_band():
    """C001-3: the paper bounds the correlation (rho <= 0.5) while the rule measures a false-alarm rate in
    multiples of alpha whose band happens to start at 0.5; "(the paper: rho <= 0.5)" would say the band is the
    paper's number. Where the quantity names the symbol, the paper's number is the band's."""
    from tvtrack.value_words import against_paper

    rate = "per-test false-alarm rate of the threshold set as if neighbouring velocity samples were independent"
    assert against_paper("[0.5, 2] × alpha", "rho <= 0.5", 0.5, 2.0, rate) == (
        ', against [0.5, 2] × alpha (set here to check the paper\'s "rho <= 0.5")'
    )
    assert against_paper("at most 0.5", "rho <= 0.5", None, 0.5, "lag-1 correlation rho of the samples") == (
        ", against at most 0.5 (the paper: rho <= 0.5)"
    )
    assert against_paper("at most 0.5", "rho <= 0.5", None, 0.5) == ", against at most 0.5 (the paper: rho <= 0.5)"
    assert against_paper("[0.5, 2] × alpha", "ρ ≤ 0.5", 0.5, 2.0, rate).endswith(
        '(set here to check the paper\'s "ρ ≤ 0.5")'
    )
    # a paper value in pieces, one per part: the band's own piece
    assert against_paper("[9.091, 11] el", "1 element; 10 elements/frame", 9.091, 11.0) == (
        ", against [9.091, 11] el (the paper: 10 elements/frame)"
    )
    assert against_paper("[0.5, 1.5] el", "1 element; 10 elements/frame", 0.5, 1.5).endswith("(the paper: 1 element)")


def _lost_row(changed, verdict, in_lock, **more):
    return {"changed": changed, "lost": 27, "runs": 600, "verdict": verdict, "in_lock_verdict": in_lock, **more}


def test_a_flip_the_same_draws_do_not_show_over_every_run_is_never_said_carried_by_lost_runs():
    """The lock report runs on the first replicate's draws while a flip pools every replicate: where those draws
    over every run read the default's verdict and only the runs in lock read the flip's, the lost runs carry
    nothing (they hide the flip on that draw); the sentence must not say they carry it."""
    import copy

    from record_fixtures import DEPENDS
    from tvtrack.lost_labels import mark_lost_runs

    claim = copy.deepcopy(DEPENDS)  # not reproduced; the reading flips it to reproduced
    row = _lost_row({"paper_sigma": "raw_increments"}, "not reproduced", "reproduced")
    mark_lost_runs(claim["robustness"], [row], claim["verdict"])
    flip = claim["robustness"]["parts"]["claim"]["flips"][0]
    assert flip["lost_runs"]["carried"] is False
    assert "carry that flip" not in claim_summary(claim)


def test_runs_that_lost_lock_are_not_said_to_decide_a_verdict_the_same_draws_over_every_run_do_not_give():
    """At the default the claim pools its replicates; the lock report's draws (the first replicate) may read
    otherwise over every run. Runs that lost lock decide the verdict only where those draws give it over every
    run and another over the runs in lock."""
    import copy

    from record_fixtures import DEPENDS
    from tvtrack.lost_labels import mark_lost_runs

    claim = copy.deepcopy(DEPENDS)  # not reproduced
    mark_lost_runs(claim["robustness"], [_lost_row({}, "reproduced", "not reproduced")], claim["verdict"])
    assert claim["robustness"]["decided_by_lost_runs"] is False
    assert "lost lock and carr" not in claim_summary(claim)


def test_a_flip_of_one_part_is_said_carried_by_lost_runs_only_by_that_part_s_own_verdicts():
    """A claim of several parts: the whole claim's verdicts over every run and over the runs in lock may differ
    through another part. Each flip is judged by its own part's verdicts where the row gives them, and is never
    said carried where only the whole claim's are given."""
    from tvtrack.lost_labels import mark_lost_runs

    at = {"sigma_1": 0.2}
    record = {
        "parts": {
            "p1": {"verdict": "reproduced", "flips": [{"changed": dict(at), "verdict": "not reproduced"}]},
            "p2": {"verdict": "reproduced", "flips": [{"changed": dict(at), "verdict": "not reproduced"}]},
        }
    }
    parts = {"parts": {"p1": "not reproduced", "p2": "not reproduced"}}
    in_lock = {"in_lock_parts": {"p1": "not reproduced", "p2": "reproduced"}}
    mark_lost_runs(record, [_lost_row(at, "not reproduced", "partly", **parts, **in_lock)], "reproduced")
    carried = {p: v["flips"][0]["lost_runs"]["carried"] for p, v in record["parts"].items()}
    assert carried == {"p1": False, "p2": True}  # p1 flips over the runs in lock too
    mark_lost_runs(record, [_lost_row(at, "not reproduced", "partly")], "reproduced")  # whole-claim verdicts only
    assert [v["flips"][0]["lost_runs"]["carried"] for v in record["parts"].values()] == [False, False]


def test_a_paper_number_the_band_does_not_hold_is_said_as_what_the_band_is_read_from_not_as_the_paper_s_value():
    """A claim's paper value may be of another quantity than the part its sentence shows (a threshold SIR beside a
    probability of losing lock, a contrast beside a variance ratio): "(the paper: 2)" after "at least 0.1" would
    say the paper has 2 for the probability. A paper number inside a two-sided band (or on a one-sided band's edge;
    a per cent as a share) is the paper's value; else the band is said as read from the paper's words."""
    from tvtrack.value_words import against_paper

    assert (
        against_paper("at least 0.1", "2", 0.1, None) == ', against at least 0.1 (set here to check the paper\'s "2")'
    )
    assert against_paper("at most 1.3", "threshold near P = 0.5", None, 1.3) == (
        ', against at most 1.3 (set here to check the paper\'s "threshold near P = 0.5")'
    )
    assert against_paper("at least 20", "> 20", 20, None) == ", against at least 20 (the paper: > 20)"
    assert against_paper("[0.01, 0.03]", "2 %", 0.01, 0.03) == ", against [0.01, 0.03] (the paper: 2 %)"
    assert (
        against_paper("[5.25, 5.75] s", "5.5 s (one run)", 5.25, 5.75) == ", against [5.25, 5.75] s (the paper: 5.5 s)"
    )
    assert against_paper("[0, 0.625]", "filter 1-2 px; MLP 2-3 px", 0, 0.625).endswith(
        'check the paper\'s "filter 1-2 px; MLP 2-3 px")'
    )


def test_the_paper_s_words_in_their_own_quotes_are_quoted_once():
    from tvtrack.value_words import against_paper

    assert against_paper("[0.8, 1.5]", "'practically potential'") == (
        ', where the paper says "practically potential" (read here as [0.8, 1.5])'
    )


def test_a_claims_parts_are_tallied_by_verdict_never_as_held_of_all():
    from tvtrack.wording import parts_tally

    assert parts_tally(["reproduced"] * 3) == "all 3 parts hold"
    assert (
        parts_tally(["reproduced"] * 5 + ["not reproduced"] + ["undecided"] * 4) == "5 parts hold, 1 fails, 4 undecided"
    )
    assert parts_tally(["reproduced", "undecided", "undecided"]) == "1 part holds, 2 undecided"
    assert parts_tally(["not reproduced"] * 3) == "no part holds, 3 fail"


def test_a_change_that_moves_one_part_but_not_the_claim_is_said_as_such():
    from tvtrack.wording import _flip_to

    claim = {
        "verdict": "partly",
        "robustness": {"conditions": [{"changed": {"g": "euler"}, "verdict": "partly"}]},
    }
    flip = {"verdict": "reproduced", "part": "variant 1", "changed": {"g": "euler"}}
    assert _flip_to(flip, claim, 3) == "the claim stays partly reproduced, but its part variant 1 is reproduced"
    claim["robustness"]["conditions"][0]["verdict"] = "reproduced"
    assert _flip_to(flip, claim, 3) == "it is reproduced"
    claim["robustness"]["conditions"][0]["verdict"] = "not reproduced"
    assert _flip_to(flip, claim, 3) == "the claim is not reproduced (its part variant 1: reproduced)"


def test_a_papers_paragraph_says_the_whole_claims_verdict_under_the_flip_and_the_lost_runs_that_carry_it():
    import copy

    from record_fixtures import DEPENDS
    from tvtrack.flip_words import why_not_clause as _why_not

    claim = copy.deepcopy(DEPENDS)
    reading = {"paper_sigma": "raw_increments"}
    others = [c for c in claim["robustness"]["conditions"] if c.get("changed") != reading]
    claim["robustness"]["conditions"] = [*others, {"changed": reading, "verdict": "partly"}]  # the whole claim there
    text = _why_not(claim)
    assert "; it holds in part under a reading of the paper's text: sigma read as the SD" in text, text
    claim["robustness"]["parts"]["claim"]["flips"][0]["lost_runs"] = {"lost": 27, "runs": 600, "carried": True}
    assert _why_not(claim).endswith(", but only through the 27 of 600 runs that lost lock there"), _why_not(claim)


def test_what_the_verdicts_turn_on_names_each_entry_with_its_paper_and_keeps_ties():
    from tvtrack.paragraphs import _turns_sentence

    def claim(cid, title):
        flip = {"changed": {title: 1}, "side": "world", "kind": "single", "verdict": "not reproduced", "text": "x"}
        return {"id": cid, "verdict": "reproduced", "robustness": {"parts": {"claim": {"flips": [flip]}}}}

    claims = [claim("C000-1", "drift"), claim("C000-2", "drift"), claim("C001-1", "drift"), claim("C001-2", "rate")]
    claims.append(claim("C001-3", "rate"))
    assert _turns_sentence(claims) == (
        "What the verdicts turn on: a world beyond the paper (alone or with other worlds) flips 5 claims (2 of 000 and 3 of 001), most often "
        "“drift” (2 claims of 000) and “rate” (2 claims of 001)."
    )


def test_the_sentence_names_the_flip_the_label_rests_on_a_reading_before_a_world():
    """A claim labelled ``depends`` by a pair of readings and also flipped by one world: its sentence names the
    pair (the label's reason), not the world."""
    import copy

    from record_fixtures import DEPENDS

    claim = copy.deepcopy(DEPENDS)
    world, reading = (
        claim["robustness"]["parts"]["claim"]["flips"][1],
        claim["robustness"]["parts"]["claim"]["flips"][0],
    )
    pair = {**reading, "kind": "combination", "changed": {**reading["changed"], "gain_bound": 100}}
    claim["robustness"]["parts"]["claim"]["flips"] = [world, pair]
    text = claim_summary(claim)
    assert "Under two other readings of the paper's text together it is reproduced" in text
    assert "does not extend" not in text
    assert share_words(0, 1, 1) == "0 agree, 1 flips and 1 stays undecided of 2 explored configurations"


def share_words(agree, flip, undecided):
    from tvtrack.wording import share_counts

    return share_counts({"agree": agree, "flip": flip, "undecided": undecided, "design": agree + flip + undecided})


def test_a_depends_label_resting_on_an_unattributed_mix_is_named_before_a_world():
    import copy

    from record_fixtures import DEPENDS

    claim = copy.deepcopy(DEPENDS)
    world = claim["robustness"]["parts"]["claim"]["flips"][1]
    mix = {**world, "side": "unattributed", "kind": "combination", "text": "a target weaving and sigma as raw"}
    mix["changed"] = {**world["changed"], "paper_sigma": "raw_increments"}
    claim["robustness"]["parts"]["claim"]["flips"] = [world, mix]
    assert (
        "Under two changes together (none of them flips it alone) it is reproduced: a target weaving at 0.1 T (a world "
        "beyond the paper) and sigma read as the SD of the raw velocity increments (a reading of the paper's text)."
        in claim_summary(claim)
    )


def test_an_unexplored_claim_says_why_and_a_depends_resting_on_a_world_mix_is_counted_so():
    """A reader took "unexplored" to mean no world was varied where one was and left the part undecided, and a
    "depends" resting only on a mix of settings with a world for one a reading or setting flips alone: the
    sentence says which, and the first screen counts the second kind."""
    import copy

    from record_fixtures import DEPENDS
    from tvtrack.paragraphs import depends_only_with_a_world, results_summary

    claim = copy.deepcopy(DEPENDS)
    part = claim["robustness"]["parts"]["claim"]
    claim["robustness"]["label"] = part["label"] = "unexplored"
    part["flips"] = []
    part["share"] = {"agree": 0, "flip": 0, "undecided": 1, "design": 1}
    assert claim_summary(claim).endswith(
        "Beyond the paper's default, the one change explored for it left it undecided, so nothing shows how far it "
        "extends."
    )
    part["share"] = {"agree": 0, "flip": 0, "undecided": 0, "design": 0}
    assert claim_summary(claim).endswith("Nothing was varied for it, so nothing shows how far it extends.")
    part["share"] = {"agree": 6, "flip": 0, "undecided": 0, "design": 6}
    assert claim_summary(claim).endswith(
        "No world beyond the paper was varied for it, so nothing shows how far it extends."
    )

    mixed = copy.deepcopy(DEPENDS) | {"id": "C001-4"}
    world = mixed["robustness"]["parts"]["claim"]["flips"][1]
    mix = {**world, "side": "unattributed", "kind": "combination"}
    mix["changed"] = {**world["changed"], "paper_sigma": "raw_increments"}
    mixed["robustness"]["parts"]["claim"]["flips"] = [world, mix]
    assert depends_only_with_a_world([DEPENDS, mixed]) == 1
    assert (
        "Of the 2 that turn on a reading or setting, for 1 of them worlds beyond the paper (one or several), with "
        "no reading or setting changed, also flip the verdict, and 1 (C001-4) only together with a world beyond it."
        in results_summary([DEPENDS, mixed])
    )


def test_a_flip_of_a_reading_and_a_setting_together_names_each_kind_not_the_setting_alone():
    """A joint flip mixing a reading of the text and an unprinted setting is filed under neither: the paper's
    paragraph and the record's list of flips name each change's own kind; one kind keeps the one bracket."""
    from tvtrack.flip_words import flip_with_kind, under_words as _under

    record = {
        "register": [
            {"name": "pixel", "title": "pixel size", "kind": "unreported setting", "phrases": {"5": "pixels 5 wide"}},
            {"name": "dist", "title": "distances", "kind": "reading", "phrases": {"px": "distances in pixels"}},
            {"name": "stop", "title": "EM stop", "kind": "reading", "phrases": {"loose": "a loose stop"}},
        ]
    }
    mixed = {"text": "pixels 5 wide and distances in pixels", "side": "setting", "changed": {"pixel": 5, "dist": "px"}}
    kinds = "pixels 5 wide (a setting the paper never printed) and distances in pixels (a reading of the paper's text)"
    assert flip_with_kind(mixed, record) == f"{kinds}, together"
    assert _under(mixed, record) == f"two changes together: {kinds}"
    both = {
        "text": "distances in pixels and a loose stop",
        "side": "reading",
        "changed": {"dist": "px", "stop": "loose"},
    }
    assert flip_with_kind(both, record) == "distances in pixels and a loose stop (a reading of the paper's text)"
    assert (
        _under(both, record) == "two other readings of the paper's text together: distances in pixels and a loose stop"
    )
    one = {"text": "pixels 5 wide", "side": "setting", "changed": {"pixel": 5}}
    assert _under(one, record) == "a setting of the paper's own experiment that the paper never printed: pixels 5 wide"
    assert flip_with_kind(one, record) == (
        "pixels 5 wide (a setting of the paper's own experiment that the paper never printed)"
    )
    from tvtrack.flip_words import label_basis

    def claim_with(flip: dict) -> dict:
        part = {"verdict": "reproduced", "label": "depends", "flips": [{**flip, "verdict": "not reproduced"}]}
        rob = {**record, "label": "depends", "parts": {"claim": part}, "conditions": []}
        return {"id": "C9-1", "verdict": "reproduced", "robustness": rob}

    settings = {"text": "pixels 5 wide and 20 frames", "side": "setting", "changed": {"pixel": 5, "frames": 20}}
    record["register"].append({"name": "frames", "title": "frames", "kind": "unreported setting", "phrases": {}})
    assert label_basis(claim_with(mixed)) == "an unprinted setting with a reading"
    assert label_basis(claim_with(settings)) == "two unprinted settings together"
    assert label_basis(claim_with(both)) == "two readings together"
    from tvtrack.pipeline.site import _flips  # the site's claim page and ledger show the same kinds

    shown = _flips(claim_with(mixed)) + _flips(claim_with(both))
    assert [f["kinds"] for f in shown] == [kinds, ""]


def test_a_combination_beyond_the_subsets_searched_is_named_a_combination_with_its_entries_kinds():
    """A joint flip larger than the subset search (side ``unattributed``, with the search's note) holds a world only
    where one of its entries is one: the first screen's bracket and its count of claims that depend only together
    with a world read the entries, not the side."""
    from tvtrack.flip_words import label_basis
    from tvtrack.paragraphs import _only_with_a_world_ids

    kinds = {"a": "reading", "b": "reading", "c": "unreported setting", "w": "regime"}
    register = [{"name": k, "title": k, "kind": v, "phrases": {}} for k, v in kinds.items()]

    def claim_with(changed: dict) -> dict:
        flip = {"text": "t", "side": "unattributed", "changed": changed, "verdict": "not reproduced"}
        flip["note"] = "no subset of up to 1 entry flips it alone: unattributed"
        part = {"verdict": "reproduced", "label": "depends", "flips": [flip]}
        rob = {"register": register, "label": "depends", "parts": {"claim": part}, "conditions": []}
        return {"id": "C9-1", "verdict": "reproduced", "robustness": rob}

    no_world = claim_with({"a": 1, "b": 1, "c": 1})
    with_world = claim_with({"a": 1, "w": 1, "c": 1})
    assert label_basis(no_world) == "a combination of three changes, an unprinted setting among them"
    assert label_basis(claim_with({"a": 1, "b": 1})) == "a combination of two changes, all readings"
    assert label_basis(with_world) == "a combination with a world"
    assert _only_with_a_world_ids([no_world, with_world]) == ["C9-1"] and _only_with_a_world_ids([no_world]) == []


def _claim_with_flips(*flips: tuple) -> dict:
    """A reproduced claim whose one part has the named ``(text, side, changed)`` flips, over a register of readings
    ``r``, ``r2``, an unreported setting ``s`` and worlds ``w``, ``v``."""
    kinds = {"r": "reading", "r2": "reading", "s": "unreported setting", "w": "regime", "v": "model"}
    register = [{"name": k, "title": k, "kind": v, "phrases": {}} for k, v in kinds.items()]
    named = [{"text": t, "side": side, "changed": ch, "verdict": "not reproduced"} for t, side, ch in flips]
    rob = {"register": register, "label": "depends", "parts": {"claim": {"verdict": "reproduced", "flips": named}}}
    return {"id": "C9-1", "verdict": "reproduced", "robustness": {**rob, "conditions": []}}


def test_the_first_screens_bracket_says_a_setting_or_worlds_also_flip_a_claim_a_reading_flips():
    """Beside the reading it names, the bracket says that an unprinted setting alone ("a setting too") or several
    worlds together ("worlds together too", not "a world") also change the whole verdict."""
    from tvtrack.flip_words import label_basis

    claim = _claim_with_flips
    reading, setting = ("r", "reading", {"r": 1}), ("s", "setting", {"s": 1})
    worlds = ("w and v", "world", {"w": 1, "v": 1})
    assert label_basis(claim(reading)) == "a reading"
    assert label_basis(claim(reading, setting)) == "a reading; a setting too"
    assert label_basis(claim(reading, worlds)) == "a reading; worlds together too"
    assert (
        label_basis(claim(reading, setting, worlds, ("w", "world", {"w": 1})))
        == "a reading; a setting too; a world too"
    )
    assert label_basis(claim(setting, ("r and s", "setting", {"r": 1, "s": 1}))) == "an unprinted setting"


def test_the_bracket_names_every_kind_the_first_screens_count_files_the_claim_under():
    """A reader checks the brackets against the count of what the verdicts turn on: a claim counted under "a
    combination" says "a combination too" in its bracket, and a setting flipped with a reading reads as a setting
    (the count files it there), not as "two changes together"."""
    from tvtrack.flip_words import label_basis
    from tvtrack.paragraphs import turns_on

    claim = _claim_with_flips
    reading, joint = ("r", "reading", {"r": 1}), ("r, s and w", "unattributed", {"r": 2, "s": 1, "w": 1})
    both = claim(reading, joint)
    assert sorted(turns_on([both])) == ["reading", "unattributed"]
    assert label_basis(both) == "a reading; a combination too"
    assert label_basis(claim(("r and s", "setting", {"r": 1, "s": 1}))) == "an unprinted setting with a reading"
    assert label_basis(claim(("r, r2 and s", "setting", {"r": 1, "r2": 1, "s": 1}))) == (
        "an unprinted setting with two other changes"
    )


def test_a_part_name_and_a_not_checkable_reason_read_as_words_in_a_sentence():
    """A rule part named for the code (``no_loss``) is said "no loss" where a sentence names it, and a reason after
    "Not checkable:" starts in lower case where its second letter is lower case (not an acronym)."""
    from tvtrack.wording import _flip_to, not_checkable_reason

    claim = {"verdict": "reproduced", "robustness": {"conditions": [{"changed": {"k": 1}, "verdict": "partly"}]}}
    flip = {"verdict": "not reproduced", "part": "no_loss", "changed": {"k": 1}}
    assert _flip_to(flip, claim, 2) == "the claim is partly reproduced (its part no loss: not reproduced)"
    assert not_checkable_reason({"rule": {"reason": "In this model SIR_0 = kappa SIR by construction."}}) == (
        "in this model SIR_0 = kappa SIR by construction"
    )
    assert not_checkable_reason({"rule": {"reason": "SIR_0 is set by construction."}}).startswith("SIR_0")
    from tvtrack.run_words import part_name

    assert part_name("not_lower") == "not lower" and part_name("psi_A=5, P=0.5") == "psi_A=5, P=0.5"
    assert part_name("x_r") == "x_r" and part_name("wide_loops") == "wide loops"  # a subscripted symbol stays


def test_the_first_screen_says_which_surviving_verdicts_hold_and_names_a_claim_counted_in_both_world_groups():
    """ "7 survive every reading" is not "7 hold": the count says how many of them hold, do not hold or are
    undecided. A claim that a reading or setting flips only together with a world, and that worlds alone also flip,
    is in both counts of the ``depends`` ones; the sentence names it as among the others, so the counts are not
    read as disjoint."""
    import copy

    from record_fixtures import DEPENDS
    from tvtrack.results import results_summary

    def claim(cid, verdict, label):
        return {"id": cid, "verdict": verdict, "robustness": {"label": label}}

    robust = [claim("C9-1", "reproduced", "robust"), claim("C9-2", "not reproduced", "robust")]
    robust += [claim("C9-3", "not reproduced", "limited"), claim("C9-4", "partly", "robust")]
    text = results_summary(robust + [claim("C9-5", "reproduced", "unexplored")])
    assert "The 4 that survive every reading: 1 holds, 1 holds in part and 2 do not hold; 3 robust" in text
    assert ": none of them holds; 1 robust, 1 limited (holding only within" in results_summary(robust[1:3])
    assert ": all hold; 2 robust" in results_summary([robust[0], claim("C9-6", "reproduced", "robust")])

    both = copy.deepcopy(DEPENDS) | {"id": "C004-4"}
    world = both["robustness"]["parts"]["claim"]["flips"][1]
    mix = {**world, "side": "unattributed", "kind": "combination", "text": "weave with raw increments"}
    mix["changed"] = {**world["changed"], "paper_sigma": "raw_increments"}
    both["robustness"]["parts"]["claim"]["flips"] = [world, mix]
    text = results_summary([DEPENDS, both])
    assert (
        "for 2 of them worlds beyond the paper (one or several), with no reading or setting changed, also flip the "
        "verdict, and 1 (C004-4) only together with a world beyond it (C004-4 is also among the 2)." in text
    ), text


def test_the_first_screen_bracket_names_a_kind_that_leaves_a_decided_claim_undecided():
    """A claim partly reproduced (early and mid hold, late fails): a reading makes late hold (the whole verdict
    moves to reproduced); a world makes early fail and leaves mid open, so the whole claim reads undecided there,
    partly or not reproduced as mid turns out. That is no flip of the whole verdict, but the bracket says it, so a
    reader can tell what the claim turns on: "a reading; a world leaves it undecided"."""
    from tvtrack.flip_words import label_basis

    reading = Entry("sigma", "reading", "raw", ("raw", "smoothed"), "the text reads either way")
    world = Entry("motion", "regime", "none", ("none", "weave"), "beyond the paper")
    band = InBand("mean", -0.5, 0.5, "px")
    rule = AllOf({"early": band, "mid": band, "late": band})
    ok, bad = Estimate.exact(0.0), Estimate.exact(3.0)
    straddles = Estimate(value=0.5, stderr=0.1, ci_low=0.3, ci_high=0.7, n=30, confidence=0.95, method="t")
    partly = {"early": ok, "mid": ok, "late": bad}
    reps = [{"seed": s, "measured": partly} for s in (1, 2, 3)]
    conds = [
        {"changed": {"sigma": "smoothed"}, "kind": "single", "runs": 3, "measured": {**partly, "late": ok}},
        {
            "changed": {"motion": "weave"},
            "kind": "single",
            "runs": 3,
            "measured": {**partly, "early": bad, "mid": straddles},
        },
    ]
    rob = label_parts(rule, partly, reps, conds, [reading, world])
    claim = {"id": "C9-3", "verdict": "partly", "rule": rule.to_dict(), "measured": partly, "robustness": rob}
    assert [r["verdict"] for r in rob["conditions"]] == ["reproduced", "undecided"]
    assert label_basis(claim) == "a reading; a world leaves it undecided"
    from tvtrack.paragraphs import turns_on

    assert set(turns_on([claim])) == {"reading"}  # the count of what flips verdicts still leaves the world out


def test_a_joint_outside_the_operating_point_explains_no_change_of_the_whole_verdict():
    """Two worlds each flip one part and the whole verdict moves only where both are changed, in a joint that
    leaves the paper's operating point: it is counted beside the label, so the README says the claim moves only in
    a part, not that worlds flip it."""
    from tvtrack.paragraphs import part_only, turns_on

    reg = [{"name": k, "kind": "regime", "values": [0, 1], "default": 0, "title": f"world {k}"} for k in "xy"]

    def flip(k):
        return {"changed": {k: 1}, "side": "world", "kind": "single", "verdict": "not reproduced", "text": f"{k} = 1"}

    def cond(changed, p1, p2, verdict, **kw):
        parts = {"P1": p1, "P2": p2, "P3": "not reproduced"}
        return {
            "changed": changed,
            "kind": "joint" if len(changed) > 1 else "single",
            "parts": parts,
            "verdict": verdict,
            "runs": 3,
            **kw,
        }

    parts = {
        "P1": {"verdict": "reproduced", "label": "limited", "flips": [flip("x")]},
        "P2": {"verdict": "reproduced", "label": "limited", "flips": [flip("y")]},
        "P3": {"verdict": "not reproduced", "label": "robust", "flips": []},
    }
    conds = [
        cond({"x": 1}, "not reproduced", "reproduced", "partly"),
        cond({"y": 1}, "reproduced", "not reproduced", "partly"),
    ]
    lost = cond(
        {"x": 1, "y": 1},
        "not reproduced",
        "not reproduced",
        "not reproduced",
        operating_point_lost="no bandwidth reaches it",
        off_operating_point=True,
    )
    claim = {
        "id": "C9-1",
        "verdict": "partly",
        "robustness": {"label": "limited", "parts": parts, "conditions": [*conds, lost], "register": reg},
    }
    assert turns_on([claim]) == {} and part_only([claim]) == 1
    claim["robustness"]["conditions"][-1] = {k: v for k, v in lost.items() if "operating" not in k}
    assert set(turns_on([claim])) == {"world"} and part_only([claim]) == 0  # at the operating point it would count


def test_a_range_whose_ends_print_alike_is_one_value():
    """A setting the same on every path is one number, never a degenerate range ("0.032..0.032 frames")."""
    from tvtrack.numbers import value_range

    assert value_range(0.0321, 0.0324, ".2g") == "0.032"
    assert value_range(0.031, 0.052, ".2g") == "0.031..0.052"
    assert value_range(4, 4, "d") == "4" and value_range(2, 6, "d") == "2..6"
    assert value_range(0.5, 0.5) == "0.5"
