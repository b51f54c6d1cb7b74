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
