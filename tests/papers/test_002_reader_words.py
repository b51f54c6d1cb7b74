"""Paper 002: the words the notebook prints say only what this run measures, in words a reader needs no code for.

No register rationale quotes a result of an earlier run; C002-11's direction is said for every comparison the run
made, each from its own interval; the claims that read points where an EM stopped at its cap are counted from the
run's simulations; the notebook words the pinned conditions, the cap, the recording's unit and the replicate its
gain figure draws. All on hand-made inputs."""

from __future__ import annotations

import json
import re
from pathlib import Path

import numpy as np
import pytest

from tvtrack.estimate import Estimate
from tvtrack.papers.p002_unified_location_em import extras, flip_caps, study
from tvtrack.papers.p002_unified_location_em.register import REGISTER

NOTEBOOK = Path(__file__).resolve().parents[2] / "notebooks" / "002_unified_location_em.ipynb"

# a result quoted in a rationale: a "Measured ..." sentence, "300 trials: ...", a count of an earlier run's trials,
# a 95 % interval "[1.14, 1.76]", a gain "rho 1.22" / "rho falls from 1.24", "no flip at ..."
MEASURED = re.compile(
    r"\bmeasured\b|\btrials?\s*:|\b\d+\s+trials\b|\[\s*[-+]?\d[^\][]*,\s*[-+]?\d[^\][]*\]"
    r"|\brho\s*(?:=|of|is|falls|rises)?\s*(?:from\s*)?[-+]?\d|\bno flip at\b",
    re.IGNORECASE,
)


def _e(value, lo, hi, n=80):
    return Estimate(value, float("nan"), lo, hi, n)


def _source(start: str) -> str:
    cells = json.loads(NOTEBOOK.read_text())["cells"]
    hits = ["".join(c["source"]) for c in cells if "".join(c["source"]).lstrip().startswith(start)]
    assert len(hits) == 1, start
    return hits[0]


def test_no_why_text_quotes_a_measured_result():
    quoting = {e.name: MEASURED.findall(e.why) for e in REGISTER.entries if MEASURED.search(e.why)}
    assert quoting == {}


@pytest.mark.parametrize(
    "text",
    [
        "Measured on 100 trials, it adds 0.34",
        "adversarial review, 300 trials: at 0.5 sigma the ULA's variance is 0.31 of the CRB",
        "one replicate of 80 trials: rho 1.22 at 3 sigma",
        "the variance gain rho falls from 1.24 to 1.11",
        "rho = 1.42 [1.14, 1.76]",
        "alone, no flip at 1500 trials",
    ],
)
def test_the_pattern_catches_the_quoted_results_it_was_written_for(text):
    assert MEASURED.search(text)


def test_the_reasons_stay():
    assert "not the same added error" in REGISTER["EM stopping"].why
    assert "van Trees" in REGISTER["very close separation of C002-15 (sigma)"].why
    assert "pixel" in REGISTER["distance unit of C002-11"].why


# -- C002-11: the direction of every comparison, from its own interval ------------------------------------------

D1, D3 = "d = 1 sigma (paper x4.5)", "d = 3 sigma (paper x4)"
ML = {D1: _e(0.7403, 0.5791, 0.9464), D3: _e(1.234, 1.146, 1.33)}
KNOWN = {D1: _e(1.396, 0.9698, 2.059), D3: _e(1.184, 1.074, 1.307)}
MAP = {D1: _e(1.421, 1.141, 1.759), D3: _e(1.266, 1.103, 1.472)}


def _fmt(e):
    return f"{e.value:.3g} [{e.ci_low:.3g}, {e.ci_high:.3g}]"


def test_each_comparison_gets_the_direction_its_interval_gives():
    rows = {
        "the ULA as published": ML,
        "the designated velocity to both": KNOWN,
        "the designation as a prior": MAP,
        "not run": None,
    }
    text = extras.headline_comparisons(rows, D1, (3.0, 6.0), _fmt)
    assert "the ULA as published: 0.74 [0.579, 0.946], below 1: the two-stage more accurate, wholly below" in text
    assert "the designated velocity to both: 1.4 [0.97, 2.06], not distinguishable from 1, wholly below" in text
    assert "the designation as a prior: 1.42 [1.14, 1.76], above 1: the ULA more accurate, wholly below" in text
    assert "the paper's band [3, 6]" in text and "not run" not in text
    assert "the claim's sentence reads the first comparison only" in text
    assert "so which algorithm is more accurate here depends on what the ULA is given" in text
    same = extras.headline_comparisons(rows, D3, (3.0, 6.0), _fmt)
    assert "below 1" not in same and "the same direction in every comparison" in same
    assert "depends on what the ULA is given" not in same


def test_the_band_side_follows_the_interval():
    assert extras._band_side(_e(4.0, 3.2, 5.1), 3.0, 6.0) == "inside"
    assert extras._band_side(_e(2.9, 2.2, 3.6), 3.0, 6.0) == "reaching into"
    assert extras._band_side(_e(8.0, 6.5, 9.0), 3.0, 6.0) == "wholly above"
    assert extras.who_wins(_e(1.0, float("nan"), float("nan"))) == "undetermined against 1"


def test_the_notebook_says_every_comparison_under_the_headline_and_in_the_conclusions():
    c11 = _source('MAP, KNOWN = {"ULA"')
    assert "extras.headline_comparisons(rows" in c11 and 'claim("C002-11"' in c11
    assert "ML ULA" not in c11  # the comparisons in words
    conclusions = _source("verdicts = {c.id: c.verdict")
    assert "extras.who_wins(h[d1])" in conclusions and "extras.who_wins(map_free[d1])" in conclusions


# -- which claims read points where an EM reached its cap ---------------------------------------------------------


def _scale():
    return study.Scale(n_trials=4, n_iter_trials=4, n_bootstrap=10, crb_phases=1)


def _fake_cache(config, seed, scale, claim, hit_every=2):
    """Hand-made results for the jobs ``claim`` reads at ``config``: every ``hit_every``-th trial at the cap."""
    cache = {}
    for job in study.jobs_of(config, seed, scale, claims={claim}):
        n = job[1].n
        hits = (np.arange(n) % hit_every) == 0
        flags = np.zeros((n, 5), bool)
        flags[:, 2] = hits
        cache[job] = {"ula_flags": flags, "em_flags": flags[:, :4], "plain_cap": hits, "em_plain_cap": hits}
    return cache


def test_cap_counts_reads_the_flags_of_the_points_a_claim_reads():
    scale, default = _scale(), REGISTER.default()
    cache = _fake_cache(default, 7, scale, "C002-10")
    counts = flip_caps.cap_counts({}, [7], scale, "C002-10", cache)
    k, n = counts["the two-stage's per-frame marks"]
    assert n > 0 and k == n // 2
    assert counts["caps"] == {5000}
    assert flip_caps.cap_counts({}, [8], scale, "C002-10", cache) is None  # another seed: nothing cached


def test_the_sentence_names_the_claims_and_the_shares_from_the_counts():
    marks = "the two-stage's per-frame marks"
    caps = {
        "C002-10": {
            "default": {marks: (30, 80), "the ULA": (0, 80), "caps": {5000}},
            "flips": [
                {"changed": {}, "parts": ["closer"], "counts": {marks: (10, 100), "caps": {5000}}},
                {"changed": {}, "parts": ["closer"], "counts": {marks: (40, 100), "caps": {100}}},
            ],
        },
        "C002-11": {
            "default": {marks: (0, 80), "caps": set()},
            "flips": [{"changed": {}, "parts": ["d"], "counts": {marks: (45, 100), "caps": {5000}}}],
        },
        "C002-1": {
            "default": {"the ULA": (0, 80), "caps": set()},
            "flips": [{"changed": {}, "parts": ["claim"], "counts": {"the ULA": (0, 80), "caps": set()}}],
        },
        "C002-12": {"default": {"caps": set()}, "flips": [{"changed": {}, "parts": ["claim"], "counts": None}]},
    }
    text = flip_caps.flip_caps_sentence(caps, 5000)
    assert "C002-10 at the default (first replicate: the two-stage's per-frame marks in 38% of its trials)" in text
    assert "in 2 of its 2 flipping conditions (the two-stage's per-frame marks in 10% to 40% of the trials" in text
    assert "at a cap of 100 iterations set by the condition in 1 of them" in text
    assert "C002-11 in 1 of its 1 flipping conditions (the two-stage's per-frame marks in 45% of the trials" in text
    assert "The flipping conditions of C002-1, C002-12 read no point where an EM reached the cap" in text
    assert "Some flipping conditions of C002-12 ran outside this process" in text
    assert "the ULA in 0%" not in text  # an algorithm that never reached the cap is not named


def test_the_notebook_counts_the_flips_beside_the_cap_paragraph():
    cell = _source("capc = cap_check.cap_check(")
    assert "fcap = flip_caps.flip_caps(ex, RULES, scale)" in cell
    assert 'flip_caps.flip_caps_sentence(fcap, capc["cap"])' in cell
    # and the flips that read capped points are measured again at a larger cap, in words and metrics
    assert 'flip_caps_check.flips_at_larger_cap(ex, fcap, RULES, scale, capc["cap"])' in cell
    assert "flip_caps_check.larger_cap_sentence(fcheck)" in cell and "larger_cap_metrics(fcheck)" in cell
    md = _source("## Failures and an unknown number of objects")
    assert "The EM iteration cap is the parameter `em_iteration_cap`" not in md
    assert "It is a parameter of this\nnotebook (named `em_iteration_cap` in the parameters cell" in md


# -- words of the notebook ------------------------------------------------------------------------------------------


def test_the_pinned_conditions_are_worded_as_the_register_table_words_them():
    cell = _source("esc = lambda t")
    assert 'f"{k} = {v}"' not in cell and "REGISTER[k].title)}: {esc(REGISTER[k].phrase(v))}" in cell
    velocity = REGISTER["velocity (sigma/frame)"]
    assert velocity.phrase(REGISTER.pinned[0]["velocity (sigma/frame)"]) == "objects moving 0.56 sigma per frame"
    assert "0.5, 0.25" in REGISTER["velocity (sigma/frame)"].values  # the pinned value is one of the entry's


def test_the_rules_words_are_defined():
    md = _source("## The rules, fixed before the run")
    for words in ("frame-iterations", "max($q$, 1/$q$)", '"unpaired" means', "are\nnot units"):
        assert words in md


def test_the_recording_reports_its_errors_in_sigma_with_the_pixel_size():
    cell = _source("pix_rec = 1.0")
    assert " px" not in cell.split("print(", 1)[1]
    assert "pixels {pix_rec:g} sigma wide" in cell and "* pix_rec:.3f} sigma" in cell


def test_the_gain_figure_says_it_draws_the_first_replicate():
    cell = _source('n_rep = len(ex.record("C002-11")["replicates"])')
    assert "Drawn from the first replicate at the register default" in cell
    assert "Pooled over the {n_rep} replicates (the figure draws the first alone)" in cell


def test_the_headline_caveat_gives_the_other_comparisons_where_they_point_the_other_way():
    part = "d = 1 sigma (paper x4.5)"
    rows = {
        "published, velocity free (replicates pooled)": {part: _e(0.74, 0.58, 0.95)},
        "with the designation as a prior (one replicate)": {part: _e(1.42, 1.14, 1.76)},
        "the designated velocity given to both (one replicate)": {part: _e(1.4, 0.97, 2.06)},
        "not run": None,
    }
    text = extras.headline_caveat(rows, [part])
    assert text == (
        "At d = 1 sigma (paper x4.5) which algorithm is more accurate depends on what the ULA is given: with the "
        "designation as a prior (one replicate): 1.42 [1.14, 1.76] variance ratio, above 1: the ULA more accurate; "
        "the designated velocity given to both (one replicate): 1.4 [0.97, 2.06] variance ratio, not distinguishable "
        "from 1"
    )
    same = {k: {part: _e(0.7, 0.6, 0.9)} for k in ("a", "b")}
    assert extras.headline_caveat(same, [part]) == ""  # one direction: nothing to add to the claim's sentence


def test_the_notebook_words_its_counts_labels_and_comparisons_from_the_record():
    assert "(*{esc(e.name)}*)" not in _source("esc = lambda t")  # the register table: titles, no code names
    c11 = _source('MAP, KNOWN = {"ULA"')
    assert "extras.headline_caveat(rows" in c11  # the caveat travels with the claim into every summary
    conclusions = _source("verdicts = {c.id: c.verdict")
    assert "no explored condition flips it" not in conclusions and "unflipped_words(c)" in conclusions
    assert "label_words(label_verdict(c), shown_label(c))" in conclusions  # "robust in its decided parts only"
    assert "on the same scenes" not in conclusions and "in one replicate of that condition" in conclusions
    assert "{REGISTER[a].title}: alone" in _source("display(Markdown(ex.summary()))")
    assert _source("display(Markdown(exploration_lines(ex)))")  # each part's agree / flip / undecided
