"""The README is for users: short, the two commands and the findings on its first screen, contributor
material in docs/, every link resolving."""

from __future__ import annotations

import copy
import re

from conftest import REPO
from tvtrack.pipeline.report import README_BEGIN, README_END, results_paragraph, update_readme

README = REPO / "README.md"
DOCS = ("docs/contributing.md", "docs/benchmarks.md")


def _first_screen_ok(text: str) -> None:
    lines = text.splitlines()
    assert len(lines) <= 160, len(lines)
    head = "\n".join(lines[:40])
    assert "make reproduce" in head and "make test" in head
    block = head[head.index(README_BEGIN) + len(README_BEGIN) :].strip()
    assert re.match(r"(Of )?\d+ claims", block), block[:200]  # the summary opens the block, inside the 40 lines


def test_readme_is_short_with_the_commands_and_the_summary_first():
    text = README.read_text()
    _first_screen_ok(text)
    for contributor in ("## Writing a notebook", "## The library", "## Tests and benchmarks", "Choices made"):
        assert contributor not in text, contributor
    for doc in DOCS:
        assert f"]({doc})" in text and (REPO / doc).is_file()


def test_links_in_the_readme_and_the_moved_docs_resolve():
    for page in ("README.md", *DOCS):
        text = (REPO / page).read_text()
        for target in re.findall(r"\]\(([^)#:]+)(?:#[^)]*)?\)", text):
            assert ((REPO / page).parent / target).exists(), (page, target)


def test_the_regenerated_block_still_fits_the_first_screen(tmp_path):
    """Five papers of twelve claims, three of each not holding: the generated block keeps the README under 160
    lines with the summary on its first screen."""
    from record_fixtures import DEPENDS, UNDECIDED, VECTOR

    runs = {}
    for k in range(5):
        claims = []
        for j in range(12):
            c = copy.deepcopy((DEPENDS, UNDECIDED, VECTOR, VECTOR)[j % 4])
            c["id"] = f"C00{k}-{j + 1}"
            claims.append(c)
        runs[f"00{k}_paper"] = ({"profile": "paper", "status": "ok"}, {"claims": claims})
    readme = tmp_path / "README.md"
    readme.write_text(README.read_text())
    update_readme(readme, results_paragraph(runs))
    text = readme.read_text()
    assert text.count(README_BEGIN) == 1 and text.count(README_END) == 1
    assert "Of 60 claims checked" in text and "**limited**: holds under every reading" in text
    _first_screen_ok(text)
