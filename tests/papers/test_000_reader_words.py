"""Paper 000: the words the notebook prints from the package say only what this run measures: no register entry's
rationale quotes a result of an earlier run, and the conclusions carry the runs that lost lock behind a flip."""

import re

from tvtrack.papers.p000_dissector_ekf.register import REGISTER

# a result quoted in a rationale: "Measured (200 runs, ...)", a 95 % interval "[8.5, 10.2]"
MEASURED = re.compile(r"Measured \(|\[\s*[-+]?\d[\d.]*\s*,\s*[-+]?\d[\d.]*\s*\]")


def test_no_why_text_quotes_a_measured_result():
    quoting = {e.name: MEASURED.findall(e.why) for e in REGISTER if MEASURED.search(e.why)}
    assert quoting == {}
