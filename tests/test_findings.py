"""The one claims table, and Markdown escaping of generated text."""

from tvtrack.montecarlo import Estimate
from tvtrack.results import Results, claims_table, format_measured, md_escape
from tvtrack.labels import Robustness
from tvtrack.verdicts import InBand


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
    assert r"sigma\*2" in lines[2] and "1.5 [1.3, 1.7]" in lines[2] and "**reproduced**" in lines[2]
    # a hand-built record explores no configuration: its label is provisional, never robust, and the sentence says so
    assert "| provisional |" in lines[2] and "(too few configurations to label)" in lines[2]
    assert claims_table([c.__dict__ for c in res.claims]) == table  # results.json dicts render the same
    assert format_measured({"a": Estimate(1, 0, 1, 1, 1, method="exact")}) == "a: 1"
