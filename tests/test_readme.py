"""The README is for users: short, the two commands and the findings on its first screen, contributor
material in docs/, every link resolving."""

from __future__ import annotations

import copy
import re

from conftest import REPO
from tvtrack.pipeline.report import README_BEGIN, README_END, results_paragraph, update_readme

README = REPO / "README.md"
DOCS = ("docs/contributing.md", "docs/benchmarks.md", "docs/terms.md")
#: The hand-written definitions of the block's symbols, linked right after the block and its paragraph.
TERMS = REPO / "docs" / "terms.md"
#: Symbols of the generated block, as the block escapes them, that the terms section must define.
KEY_SYMBOLS = (
    "psi\\_A",
    "micro-raster",
    "potentially achievable",
    "variant 1",
    "alpha",
    "rho",
    "raster element",
    "el/frame",
    "3rd-order filter",
    "ULA",
    "two-stage processing",
    "iterative marks",
    "centre-of-region",
    "1-sigma pixels",
    "pixels 5 sigma wide",
    "Delta",
    "x\\_o",
    "r\\_m",
    "\\|ln r\\_T\\|",
    "van Trees bound",
    "designation",
    "rev/s",
    "marker's law",
    "imitator",
    "decoy",
    "wander",
    "per-axis \\|prediction error\\|",
    "MLP back-prop",
    "RBF network",
)


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


def _plain(markdown: str) -> str:
    """Markdown text without its backslash escapes, in lower case, its whitespace runs made single spaces."""
    return " ".join(re.sub(r"\\(.)", r"\1", markdown).lower().split())


def _terms_check(text: str, terms: str) -> tuple[list[str], list[str]]:
    """``(stale, undefined)``: the bold names of the terms page ``terms`` that the README ``text``'s generated block
    does not contain, and the :data:`KEY_SYMBOLS` that no bold name of the page holds."""
    block = text[text.index(README_BEGIN) + len(README_BEGIN) : text.index(README_END)]
    names = [_plain(n) for n in re.findall(r"\*\*(.+?)\*\*", terms, flags=re.S)]
    names = [n for n in names if not re.fullmatch(r"\d{3}", n)]  # the papers' numbers that head the bullets
    stale = [n for n in names if n not in _plain(block)]
    undefined = [s for s in KEY_SYMBOLS if not any(_plain(s) in n for n in names)]
    return stale, undefined


def test_the_terms_page_is_linked_after_the_block_and_defines_its_symbols():
    """Every term docs/terms.md defines is in the generated block (a definition left behind by a rewording fails),
    every key symbol of the block has a definition there, and the README links the page right after the block."""
    text, terms = README.read_text(), TERMS.read_text()
    end = text.index(README_END) + len(README_END)
    after = text[end : text.index("## Where to look next")].strip()
    assert after.startswith("The block carries no date") and "\n\n" not in after and "](docs/terms.md)" in after, after
    block = text[text.index(README_BEGIN) : end]
    assert all(s in block for s in KEY_SYMBOLS), [s for s in KEY_SYMBOLS if s not in block]
    assert _terms_check(text, terms) == ([], [])
    for line in terms.splitlines():
        assert len(line) <= 118, line


def test_the_terms_check_catches_a_stale_and_a_missing_definition():
    """A symbol renamed in the block leaves its definition stale; a definition dropped leaves its symbol undefined."""
    text, terms = README.read_text(), TERMS.read_text()
    end = text.index(README_END)
    renamed = text[:end].replace("psi\\_A", "psi\\_B") + text[end:]
    assert _terms_check(renamed, terms) == (["psi_a"], [])
    dropped = terms.replace("**van Trees bound**", "van Trees bound")
    assert _terms_check(text, dropped) == ([], ["van Trees bound"])
