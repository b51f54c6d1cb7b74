"""``REPRODUCTION.md`` and the README's first screen from the runs of ``make reproduce`` (:mod:`.reproduce`).

Inputs: ``papermill_runs/reproduce/<notebook>/`` (a run directory, see :mod:`tvtrack.pipeline.runner`; another
profile's runs live in ``papermill_runs/reproduce-<profile>/``, :func:`.paths.reproduce_dir`). Outputs:
``REPRODUCTION.md`` at the repository root (or in the profile's folder), rebuilt by :func:`write_report`
(``python -m tvtrack report``), with two pictures saved beside the runs (``figures/forest.png``: every claim's
measured interval against the paper's band; ``figures/robustness.png``: claims by register entries, coloured by
verdict); and the README's results block between :data:`README_BEGIN` and :data:`README_END`, regenerated once
every notebook has a paper-profile run. The README block carries no date (the date is in ``REPRODUCTION.md``
and on the site), so a ``make reproduce`` whose numbers reproduce leaves ``git status`` clean.

Both open with the same first screen: a paragraph in plain words (:func:`tvtrack.results.results_summary`), the
glossary of the verdict and label words, one row per paper, and the claims that do not hold or were not decided,
each in one sentence (:func:`tvtrack.results.claim_summary`). Claim text is generated (statements, rule text,
register phrases such as ``sigma*2``): everything written to Markdown goes through :func:`md_escape`.
"""

from __future__ import annotations

import os
import re
import time
from collections import Counter
from pathlib import Path
from typing import Any

from ..results import (
    FLIP_WORDS,
    LABEL_WORDS,
    VERDICT_WORDS,
    at_profile,
    claim_flips,
    claim_summary,
    claims_table,
    coverage_words,
    flip_with_kind,
    format_measured,
    hold_note,
    label_basis,
    label_verdict,
    label_words,
    md_escape,
    paper_paragraph,
    parts_held,
    results_summary,
)
from .audit import audit_markdown, audit_runs
from .outputs import replace_text
from .figures import ALL_LABELS, ALL_VERDICTS, NO_LABEL, coverage_text, forest_items, forest_plot, part_labels
from .figures import robustness_label, robustness_picture, robustness_where
from .paths import PAPER_PROFILE, REPO_ROOT, reproduce_dir as _reproduce_dir
from .preflight import UsageError
from .runfiles import load_results, load_run
from .runner import list_notebooks

__all__ = [
    "REPRODUCE_DIR",
    "REPORT_PATH",
    "README_PATH",
    "README_BEGIN",
    "README_END",
    "ALL_VERDICTS",
    "ALL_LABELS",
    "NO_LABEL",
    "write_report",
    "md_escape",
    "format_measured",
    "robustness_label",
    "robustness_where",
    "coverage_text",
    "plain_coverage",
    "part_labels",
    "verdict_summary",
    "glossary_markdown",
    "papers_table",
    "results_paragraph",
    "update_readme",
    "check_readme",
    "collect_runs",
    "first_screen",
    "first_screen_list",
    "forest_items",
    "forest_plot",
    "robustness_picture",
    "profiles_shown",
]

REPRODUCE_DIR = _reproduce_dir()
REPORT_PATH = REPO_ROOT / "REPRODUCTION.md"
README_PATH = REPO_ROOT / "README.md"
README_BEGIN = "<!-- begin generated results -->"
README_END = "<!-- end generated results -->"


def _cell(text: Any) -> str:
    return md_escape(text)


def verdict_summary(claims: list[dict]) -> str:
    """``"3 reproduced (2 robust, 1 depends) · 1 partly (1 unstable) · ..."``: each verdict's
    count with its robustness labels (a claim whose record decides no part counts as "no part decided", one
    without a record as "no record")."""
    parts = []
    for verdict in ALL_VERDICTS:
        these = [c for c in claims if c["verdict"] == verdict]
        if verdict == "undecided" and not these:
            continue
        labels = Counter((robustness_label(c), label_verdict(c)) for c in these)  # a part undecided: its scope
        keys = sorted(
            (k for k in labels if k[0] in ALL_LABELS), key=lambda k: (ALL_LABELS.index(k[0]), k[1] == "undecided")
        )
        detail = [
            _counted_label(labels[k], k[1], k[0]) for k in keys
        ]  # the label over every part before its scoped one
        if verdict != "not checkable":
            bare = _unlabelled(these)
            detail += [f"{n} {what}" for n, what in zip(bare, ("no part decided", "no record")) if n]
        parts.append(f"{len(these)} {verdict}" + (f" ({', '.join(detail)})" if detail else ""))
    return " · ".join(parts)


def _counted_label(n: int, verdict: str, label: str) -> str:
    """``"2 robust in their decided parts only"``: ``n`` claims of ``verdict`` with ``label``, the label as each
    claim's line says it (:func:`tvtrack.paragraphs.label_words`: an undecided claim's label is its decided parts')."""
    words = label_words(verdict, label)
    return f"{n} {words.replace(' its decided parts', ' their decided parts') if n > 1 else words}"


def _unlabelled(claims: list[dict]) -> tuple[int, int]:
    """How many of ``claims`` carry no label though their record explored them (no part decided at the default:
    nothing to flip), and how many have no robustness record at all."""
    bare = [c for c in claims if robustness_label(c) == NO_LABEL]
    explored = sum(bool(c.get("robustness")) for c in bare)
    return explored, len(bare) - explored


def label_counts(claims: list[dict]) -> str:
    """`` · 1 without a decided part · 2 without a robustness record``: the checkable claims the label counts leave
    out, by why (``""`` where none is)."""
    explored, bare = _unlabelled([c for c in claims if c["verdict"] != "not checkable"])
    return (f" · {explored} without a decided part" if explored else "") + (
        f" · {bare} without a robustness record" if bare else ""
    )


def collect_runs(reproduce_dir: Path, notebooks: list[str]) -> dict[str, tuple[dict | None, dict | None]]:
    """``{name: (run.json, results.json)}`` for each notebook; ``None`` where missing (not run, or failed).

    Both files are checked (:mod:`.runfiles`): a damaged one is a :class:`.runfiles.DamagedRun` naming it."""
    runs = {}
    for name in notebooks:
        run_dir = Path(reproduce_dir) / name
        record = load_run(run_dir)
        data = load_results(run_dir) if record is not None and record["status"] == "ok" else None
        runs[name] = (record, data)
    return runs


def profiles_shown(runs: dict[str, tuple[dict | None, dict | None]]) -> str:
    """ "paper", or the profiles of the runs shown when they are not all paper-scale ("smoke", "paper and smoke")."""
    names = sorted({(record or {}).get("profile") or PAPER_PROFILE for record, data in runs.values() if data})
    return " and ".join(names) if names else PAPER_PROFILE


# --- the first screen ------------------------------------------------------------------------------------------

_FIRST_ORDER = {"not reproduced": 0, "undecided": 1}
NOT_HOLDING = ("not reproduced", "undecided")
"""The verdicts listed claim by claim on the README's first screen (the rest are counted)."""


def first_screen(runs: dict[str, tuple[dict | None, dict | None]]) -> list[dict]:
    """The claims a researcher asks about first, one row each: every claim that does not reproduce or is
    undecided, then every other checkable claim whose verdict depends on a reading or is unstable.

    Rows: ``{paper, id, statement, paper_value, measured, verdict, label, where, summary, basis}`` (measured with
    its unit and interval; ``summary``: :func:`tvtrack.results.claim_summary`; ``basis``: what flips a
    ``depends`` or ``limited`` claim, every kind that does, :func:`tvtrack.flip_words.label_basis`)."""
    rows = []
    for name, (_, data) in runs.items():
        for c in (data or {}).get("claims", []):
            label = robustness_label(c)
            if c["verdict"] in _FIRST_ORDER or (c["verdict"] != "not checkable" and label in ("depends", "unstable")):
                rows.append(
                    {
                        "paper": name,
                        "id": c["id"],
                        "statement": c["statement"],
                        "paper_value": c.get("paper_value", ""),
                        "measured": format_measured(c["measured"], c.get("rule")),
                        "verdict": c["verdict"],
                        "label": label,
                        "label_verdict": label_verdict(c),
                        "where": robustness_where(c),
                        "summary": claim_summary(c),
                        "basis": label_basis(c) if label in ("depends", "limited") else "",
                    }
                )
    return sorted(rows, key=lambda r: (_FIRST_ORDER.get(r["verdict"], 2), r["paper"], _claim_order(r["id"])))


def _claim_order(cid: str):
    return [int(t) if t.isdigit() else t for t in re.split(r"(\d+)", cid)]


def first_screen_list(rows: list[dict], verdicts: tuple[str, ...] | None = None) -> str:
    """Rows of :func:`first_screen` (those with ``verdicts``, default all) as a Markdown list, one claim a line:
    its id, statement, verdict and label with every kind of change that flips it, then its sentence; a sentence
    when there are none."""
    rows = [r for r in rows if verdicts is None or r["verdict"] in verdicts]
    if not rows:
        return "Every checkable claim reproduces or holds in part."
    return "\n".join(
        f"- **{r['paper'][:3]} {r['id']}** ({r['verdict']}, {label_words(r.get('label_verdict', r['verdict']), r['label'])}"
        f"{': ' + r['basis'] if r.get('basis') else ''}) "
        f"*{md_escape(_whole(r['statement']))}* "
        f"{md_escape(r['summary'])}"
        for r in rows
    )


def _whole(text: str) -> str:
    """A statement on one line, whole (never cut)."""
    return " ".join(str(text).split())


def as_shown(runs: dict[str, tuple[dict | None, dict | None]]) -> dict[str, tuple[dict | None, dict | None]]:
    """The runs with their claims as a reader sees them: a run at another profile than the paper's has every
    record marked provisional (:func:`tvtrack.results.at_profile`: never robust), whatever its design."""
    out = {}
    for name, (record, data) in runs.items():
        if data is not None:
            data = {**data, "claims": at_profile(data.get("claims") or [], (record or {}).get("profile"))}
        out[name] = (record, data)
    return out


def paper_markdown(data: dict, profile: str = PAPER_PROFILE) -> list[str]:
    """One paper in plain words (:func:`tvtrack.results.paper_paragraph`): the paragraph, then its limitations."""
    paragraph, limits = paper_paragraph(data, profile)
    lines = [md_escape(paragraph), ""]
    if limits:
        lines += ["**Limitations.** " + md_escape(" ".join(limits)), ""]
    return lines


def glossary_markdown() -> str:
    """The verdict and label words with their meanings, and what counts as a flip: three paragraphs, for the
    first screen."""
    verdicts = "; ".join(f"**{w}**: {m}" for w, m in VERDICT_WORDS.items())
    labels = "; ".join(f"**{md_escape(w)}**: {m}" for w, m in LABEL_WORDS.items())
    return (
        f"Verdicts (what the runs say): {verdicts}.\n\nLabels (how sure, and why): {labels}.\n\n"
        f"What counts as a flip: {FLIP_WORDS}."
    )


def papers_table(runs: dict[str, tuple[dict | None, dict | None]]) -> str:
    """One row per notebook with a run: its claims counted by verdict and by label (Markdown)."""
    verdicts = list(ALL_VERDICTS)
    labels = [lab for lab in ALL_LABELS if lab not in (NO_LABEL,)]
    lines = [
        "| paper | claims | " + " | ".join(verdicts) + " | labels of the checkable claims |",
        "| --- | ---: | " + " | ".join("---:" for _ in verdicts) + " | --- |",
    ]
    for name, (_, data) in runs.items():
        if not data:
            lines.append(f"| {md_escape(name)} | no run | " + " | ".join("" for _ in verdicts) + " |  |")
            continue
        cs = data["claims"]
        v = Counter(c["verdict"] for c in cs)
        lab = Counter(robustness_label(c) for c in cs if c["verdict"] != "not checkable")
        shown = ", ".join(f"{lab[x]} {x}" for x in labels if lab[x])
        lines.append(f"| {md_escape(name)} | {len(cs)} | " + " | ".join(str(v[x]) for x in verdicts) + f" | {shown} |")
    return "\n".join(lines)


def holding_lines(runs: dict) -> list[str]:
    """Which claims hold, which hold in part and which give nothing to measure, by paper, each with its label where
    it has one and what the label rests on (:func:`tvtrack.flip_words.label_basis`; one bullet per verdict); a
    claim that holds with its caveat and any flip that runs which lost lock carry (:func:`.part_lines.hold_note`),
    one that holds in part with which parts hold and which do not (:func:`.part_lines.parts_held`)."""
    out = []
    for verdict, lead, more in _HOLDING:
        bits = []
        for name, (_, data) in runs.items():
            cs = [c for c in (data or {}).get("claims", []) if c["verdict"] == verdict]
            ids = [c["id"] + _label_brackets(c) for c in cs]
            if ids:
                bits.append(f"{name.split('_')[0]}: {', '.join(ids)}")
        if bits:
            brackets = (
                "" if verdict == "not checkable" else f" (label in brackets, the kind of change that flips it{more})"
            )
            out.append(f"- **{lead}**{brackets}: " + "; ".join(bits) + ".")
    return out


_HOLDING = (
    ("reproduced", "Hold", ", and the claim's caveat where it has one"),
    ("partly", "Hold in part", ", and which parts hold"),
    ("not checkable", "Not checkable", ""),
)


def _label_brackets(claim: dict) -> str:
    """`` (depends: a reading)``: a claim's label and what it rests on, then what a reader of it must also know (a
    held claim's caveat, which parts of a partly held one hold); `` (robust)``; ``""`` without either."""
    label = robustness_label(claim)
    basis = label_basis(claim) if label in ("depends", "limited") else ""
    shown = label_words(label_verdict(claim), label)  # an undecided part: the label not over it
    bits = [] if label == NO_LABEL else [f"{shown}: {basis}" if basis else shown]
    note = {"reproduced": hold_note, "partly": parts_held}.get(claim["verdict"], lambda c: "")(claim)
    bits += [md_escape(note)] if note else []
    return f" ({' — '.join(bits)})" if bits else ""  # the dash: the label's basis ends, the note begins


def _in_short(runs: dict, shown: str) -> list[str]:
    """The first screen: the paragraph, the glossary, the table of papers, the claims that hold and those that do
    not."""
    claims = [c for _, data in runs.values() if data for c in data["claims"]]
    held = holding_lines(runs)
    paragraphs = [md_escape(p) for p in results_summary(claims, shown).split("\n\n")]  # the counts, what they turn on
    return [
        *[line for p in paragraphs for line in (p, "")],
        glossary_markdown(),
        "",
        papers_table(runs),
        "",
        *(["The claims that hold, and those that give nothing to measure:", "", *held, ""] if held else []),
        "The claims that do not reproduce, and those the runs could not decide:",
        "",
        first_screen_list(first_screen(runs), NOT_HOLDING),
        "",
    ]


# --- REPRODUCTION.md -----------------------------------------------------------------------------------------------


def plain_coverage(c: dict) -> str:
    """What a claim's robustness label covers, in plain words.

    Parameters
    ----------
    c : dict
        A claim record of ``results.json``.

    Returns
    -------
    str
        :func:`coverage_text` with every register entry's key replaced by its title (empty when nothing is
        covered).
    """
    text = coverage_words({**(c.get("robustness") or {}), "coverage": coverage_text(c)}, c.get("verdict"))
    for e in (c.get("robustness") or {}).get("register") or []:
        if isinstance(e, dict) and e.get("title") and e.get("name"):
            text = re.sub(rf"\b{re.escape(str(e['name']))}\b", str(e["title"]), text)
    return text


def _details(c: dict) -> str:
    """One claim's rule, decision, what the label covers, its parts, every flip and the note: the record behind
    the compact table (a ``<details>`` block), in phrases, not register keys."""
    bits = [f"rule: {md_escape(c.get('acceptance', ''))}"]
    if c.get("verdict") != "not checkable":
        bits.append(f"measured: {md_escape(format_measured(c.get('measured'), c.get('rule')))}")
    if c.get("decision"):
        bits.append(f"decision: {md_escape(c['decision'])}")
    if plain_coverage(c):
        bits.append(f"covers: {md_escape(plain_coverage(c))}")
    parts = part_labels(c)
    if parts:
        bits.append("parts: " + "; ".join(f"{md_escape(p)} {v}, {lab}" for p, v, lab in parts))
    flips = claim_flips(c)
    if flips:
        record = c.get("robustness") or {}
        bits.append("flipped by: " + "; ".join(md_escape(flip_with_kind(f, record)) for f in flips))
    if c.get("note"):
        bits.append(f"note: {md_escape(c['note'])}")
    return f"- **{c['id']}** " + " · ".join(bits)


def _n_run(runs: dict) -> int:
    """The notebooks with results to show."""
    return sum(1 for _, data in runs.values() if data is not None)


def _report_head(runs: dict, claims: list[dict], notebooks: list[str], reproduce_dir: Path, path: Path) -> list[str]:
    """The report's first screen (profile and date, :func:`_in_short`, the counts) and its two pictures."""
    shown = profiles_shown(runs)
    head = ["# Reproduction report", ""]
    if not notebooks:
        head += ["No notebooks in `notebooks/` yet: nothing to reproduce.", ""]
    else:
        counts = Counter(c["verdict"] for c in claims)
        labels = Counter(robustness_label(c) for c in claims if c["verdict"] != "not checkable")
        folder = os.path.relpath(reproduce_dir, path.parent)
        head += [
            f"**Profile shown: {shown}** (runs in `{folder}/`)"
            + ("" if shown == PAPER_PROFILE else ": **not the paper-scale numbers**; its labels are provisional")
            + ". "
            f"Written {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())} by `make reproduce` "
            "(rebuild with `python -m tvtrack report`).",
            "",
            *_in_short(runs, shown),
            "**Claims: "
            + " · ".join(f"{counts[v]} {v}" for v in ALL_VERDICTS if v != "undecided" or counts[v])
            + f"** ({len(claims)} claims from {_n_run(runs)} of {len(notebooks)} notebooks); of the checkable verdicts **"
            + " · ".join(f"{labels[lab]} {lab}" for lab in ALL_LABELS if lab != "provisional" or labels[lab])
            + "**"
            + label_counts(claims),
            "",
            f"By verdict: {verdict_summary(claims)}.",
            "",
        ]
        figures = Path(reproduce_dir) / "figures"
        forest = forest_plot(forest_items(runs), figures / "forest.png")
        picture = robustness_picture(runs, figures / "robustness.png")
        if forest:
            head += [
                f"![forest plot: every claim's measured interval against the paper's band]"
                f"({os.path.relpath(forest, path.parent)})",
                "",
                "Every claim with an interval and a band: the measured 95 % interval (line) and value (marker: "
                "the robustness label) on the scale of the paper's band (shaded, [0, 1]), coloured by verdict.",
                "",
            ]
        if picture:
            head += [
                f"![robustness: claims by register entries]({os.path.relpath(picture, path.parent)})",
                "",
                "Each notebook's claims by the register entries they were explored over, from the one-at-a-time "
                "design: a cell's colour is the decided verdict when that entry alone takes another value where "
                "one differs from the claim's own, the claim's own verdict where they agree, undecided where none "
                "decided (grey: the entry was not varied alone). A flip that needs two entries changed together "
                "is in the claim's record below, not in a column.",
                "",
            ]
        head += [
            "Each paper below: what it claims, what holds, what does not and why, then its limitations. Each claim: "
            "its verdict at the default reading of what the paper left unstated, its label, and a few sentences: the "
            "measured value against what the paper says in the same unit (in words where it reverses the paper's "
            "direction), the strongest change that flips it (a reading of the text, a setting the paper never "
            "printed, or a world beyond it) and, room permitting, the share of the explored configurations that "
            "agree. The record behind it (rule, decision, coverage, every flip) opens with a click; each notebook's "
            "exploration section draws every claim's specification curve.",
            "",
        ]
    return head


def write_report(
    reproduce_dir: Path = REPRODUCE_DIR,
    path: Path = REPORT_PATH,
    notebooks: list[str] | None = None,
    readme: Path | None = None,
) -> Path:
    """Rebuild ``REPRODUCTION.md`` from the run directories under ``reproduce_dir``
    (one section per notebook of ``notebooks``, default: all in ``notebooks/``), closed by the label audit of
    every finished run (:mod:`.audit`; its count is also printed).

    The report opens with the profile it shows and its date, the first screen (:func:`first_screen`), the forest
    plot and the robustness picture (saved in ``reproduce_dir/figures/``), then one section per notebook with a
    compact table and each claim's rule and coverage behind a click. With ``readme``, also regenerate that file's
    results block (:func:`update_readme`) when every notebook has a successful paper-profile run; otherwise the
    README is left as it is and the reason is printed.
    """
    if notebooks is None:
        notebooks = [nb.stem for nb in list_notebooks()]
    runs = as_shown(collect_runs(reproduce_dir, notebooks))
    sections, claims = [], []
    for name in notebooks:
        run_dir = Path(reproduce_dir) / name
        rel = os.path.relpath(run_dir, path.parent)
        record, data = runs[name]
        if record is None:
            sections.append(
                f"## {name}\n\nNot run yet: `make reproduce` (or `python -m tvtrack reproduce --only {name}`).\n"
            )
            continue
        if data is None:
            sections.append(
                f"## {name}\n\n**Run failed** after {record.get('runtime_s', 0):.0f} s: "
                f"`{str(record.get('error')).replace('`', chr(39))}` "
                f"(see [{rel}/error.txt]({rel}/error.txt)).\n"
            )
            continue
        claims += data["claims"]
        lines = [
            f"## {name}",
            "",
            f"*{md_escape(data['citation'])}*",
            "",
            *paper_markdown(data, record.get("profile") or PAPER_PROFILE),
            f"Profile `{record.get('profile')}`, seed {data['seed']}, runtime {record['runtime_s']:.0f} s "
            f"(notebook {data['runtime_s']:.0f} s), commit `{data.get('git_commit')}`. "
            f"[Executed notebook]({rel}/notebook.ipynb) · [results.json]({rel}/results.json)",
        ]
        if data.get("recording"):
            lines[-1] += (
                f" · [recording]({rel}/{data['recording']}) (in the browser: "
                f"`python -m tvtrack view {rel}`; desktop: `rerun {rel}/{data['recording']}`)"
            )
        lines += [
            "",
            verdict_summary(data["claims"]),
            "",
            claims_table(data["claims"]),  # the label as the claim's line says it ("... in its decided parts only")
        ]
        lines += ["", "<details><summary>Rules, decisions, coverage, every flip and notes</summary>", ""]
        lines += [_details(c) for c in data["claims"]]
        lines += ["", "</details>"]
        if data.get("figures"):
            lines += ["", "Figures:", ""]
            lines += [f"- [{_cell(f['caption'])}]({rel}/{f['file']})" for f in data["figures"]]
        sections.append("\n".join(lines) + "\n")
    head = _report_head(runs, claims, notebooks, Path(reproduce_dir), path)
    problems = audit_runs(runs)
    path.parent.mkdir(parents=True, exist_ok=True)
    replace_text(path, "\n".join(head + sections + audit_markdown(problems)))
    n_problems = sum(len(v) for v in problems.values())
    print(f"label audit: {n_problems} problem(s) in the records of {len(problems)} notebook(s)")
    if readme is not None:
        incomplete = [
            name for name, (record, data) in runs.items() if data is None or record.get("profile") != PAPER_PROFILE
        ]
        if incomplete:
            print(
                f"{readme.name}: results block left as it is (no successful paper-profile run of "
                f"{', '.join(incomplete)}; `make reproduce` runs them)"
            )
        else:
            update_readme(readme, results_paragraph(runs))
            print(f"{readme.name}: results block regenerated")
    return path


def results_paragraph(runs: dict[str, tuple[dict | None, dict | None]]) -> str:
    """The README's results block (Markdown) from :func:`collect_runs`: the paragraph in plain words, the glossary,
    one row per paper and the claims that do not reproduce or were not decided, one sentence each. No date: the
    block changes only when a verdict, a label or a number does, so ``git status`` after ``make reproduce`` is
    itself a reproducibility check."""
    done = {name: (record, data) for name, (record, data) in as_shown(runs).items() if data is not None}
    missing = sorted(set(runs) - set(done))
    if not any(data["claims"] for _, data in done.values()):
        return (
            "No results yet: `make reproduce` runs every notebook at paper scale and `python -m tvtrack report` "
            "writes this block from them."
        )
    lines = _in_short(done, profiles_shown(done))
    if missing:
        lines.insert(0, f"Not included (no successful run): {', '.join(missing)}.\n")
    lines += [
        "Every claim with its sentence, rule and coverage: `REPRODUCTION.md` (written by `make reproduce`); with its "
        "specification curve: the site (`make site`).",
    ]
    return "\n".join(lines)


def check_readme(readme: Path) -> str:
    """The text of ``readme``, checked to hold the results block's markers once each, in order.

    ``reproduce`` and ``report`` call it before any work, so that a README the block cannot go into stops them
    at once, not after an hour of runs.

    Raises
    ------
    UsageError
        One line naming the file: unreadable, not UTF-8 text, or without the two markers (once each, in order).
    """
    fix = "put them back (`git checkout README.md` restores the file)"
    try:
        text = Path(readme).read_text(encoding="utf-8")
    except UnicodeDecodeError:
        raise UsageError(f"{readme}: not UTF-8 text, so its results block cannot be regenerated; {fix}") from None
    except OSError as exc:
        raise UsageError(f"cannot read {readme}: {exc.strerror or exc}") from None
    begin, end = text.count(README_BEGIN), text.count(README_END)
    if begin != 1 or end != 1 or text.index(README_BEGIN) > text.index(README_END):
        raise UsageError(
            f"{readme}: the results block's markers '{README_BEGIN}' and '{README_END}' must each appear once, "
            f"in that order (found {begin} and {end}{', reversed' * (begin == end == 1)}); {fix}"
        )
    return text


def update_readme(readme: Path, paragraph: str) -> None:
    """Replace the text between :data:`README_BEGIN` and :data:`README_END` in ``readme`` (:func:`check_readme`)."""
    text = check_readme(readme)
    pattern = re.compile(re.escape(README_BEGIN) + r".*?" + re.escape(README_END), re.S)
    new = pattern.sub(lambda _: f"{README_BEGIN}\n{paragraph}\n{README_END}", text, count=1)
    if new != text:  # an unchanged block leaves the file (and its timestamp) alone
        replace_text(Path(readme), new)  # whole or not at all: a full disk never truncates the README
