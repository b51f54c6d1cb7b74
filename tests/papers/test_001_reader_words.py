"""Paper 001: the words the notebook prints from the package say only what this run measures, in a reader's words:
no register entry's rationale quotes a result of an earlier run."""

import re

from tvtrack.papers.p001_maneuver_occlusion_kf.register import build_register

# a result quoted in a rationale: "Measured (300 runs, ...)", a 95 % interval "[1.40, 1.44]", or "the measured
# detection times" / "measured here" (a range an earlier run measured)
MEASURED = re.compile(r"Measured \(|\[\s*[-+]?\d[\d.]*\s*,\s*[-+]?\d[\d.]*\s*\]|\bmeasured (?:here|detection)")


def test_no_why_text_quotes_a_measured_result():
    quoting = {e.name: MEASURED.findall(e.why) for e in build_register() if MEASURED.search(e.why)}
    assert quoting == {}


def test_c4_caveat_names_the_span_its_rms_parts_are_over():
    from tvtrack.papers.p001_maneuver_occlusion_kf.tradeoff import span_caveat

    text = span_caveat(build_register())
    assert "C001-4's RMS span, over which its minimum-RMS parts are taken, is RMS over the tracking from 4 s to" in text
    assert "the loss at 12 s at this run's default" in text
    assert "not the interval its faster-compensation part scores (dynamic error scored from the onset to 8 s)" in text
    other = span_caveat(build_register(rms_span="onset to loss", compensation_end_s=6.0))
    assert "RMS over the manoeuvre only, 5 s to the loss at 12 s" in other and "onset to 6 s" in other


def test_comparators_caption_says_panel_a_includes_the_bias_and_panel_b_uses_the_random_error():
    from tvtrack.papers.p001_maneuver_occlusion_kf.tradeoff import comparators_caption

    text = comparators_caption(build_register())
    assert (
        "(a) position RMS error over time (both channels; the root mean square over runs of the error, dynamic" in text
    )
    assert "dynamic error (bias) and random error together" in text
    assert "RMS read as the random error (spread over runs), the dynamic error judged apart" in text
    assert "the default RMS statistic." not in text  # the old caption named the statistic by no word


def test_c7_and_c8_caveats_give_their_units_in_elements():
    from tvtrack.papers.p001_maneuver_occlusion_kf.curves import C8_UNITS, smallest_rms_words

    assert smallest_rms_words({"rms": [9.0, 7.62, 8.1], "dyn": [1.0, 2.0, 3.0]}).endswith(
        "of the sweep, is 7.62 elements"
    )
    assert C8_UNITS.startswith("Its parts are in raster elements: the RMS prediction error at reappearance")


def test_register_table_names_entries_and_pinned_conditions_in_plain_words():
    register = build_register()
    text = register.to_markdown()  # the core's table, in the register's titles and phrases
    for wrong in ("`test_cadence`", "`k_bound2`", "restart = B", "window_n = 10", "curve_tolerance = 0.001"):
        assert wrong not in text
    assert f"| {register['test_cadence'].title} | unreported setting (a setting of the paper's own experiment" in text
    assert f"- {register.describe({'restart': 'B', 'window_n': 10})}" in text
    assert "curve steps under 0.001 element count as flat" in text
