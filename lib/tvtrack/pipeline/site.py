"""``python -m tvtrack site`` (``make site``): a static, offline HTML site built from the runs.

Reads the paper runs under ``papermill_runs/reproduce/<notebook>/`` (what ``make reproduce`` leaves; another
profile's runs, ``--profile smoke``, from ``papermill_runs/reproduce-smoke/`` into ``papermill_runs/site-smoke/``)
and the sweeps under ``papermill_runs/<spec>/`` (directories holding ``summary.csv``), and writes
``papermill_runs/site/``:

- ``index.html``: the profile it shows, then the first screen: a paragraph in plain words
  (:func:`tvtrack.results.results_summary`) beside the glossary of the verdict and label words (every chip on
  every page carries its word's meaning as a tooltip), one row per paper, every claim that does not reproduce or
  is undecided and every verdict that depends or is unstable, one row each with its sentence
  (:func:`tvtrack.results.claim_summary`); the forest plot of every claim and the robustness picture (claims by
  register entries, coloured by verdict); then one card per paper run (citation, run date, commit, runtime,
  claims by verdict and robustness label, the recording's still image and the command that serves it), then
  the sweeps;
- ``ledger.html``: every claim of every ``results.json`` in a compact table (the rule, where the verdict
  differs, what the label covers and the parts behind a click), filterable and sortable by a small inline
  script, each linking to the notebook cell that decided it;
- ``claims/<notebook>/<id>.html``: one page per claim: its sentence, its specification curve
  (:func:`tvtrack.plotting.specification_curve`, ``<id>.png`` beside it) and the record behind it;
- ``notebooks/<name>.html``: the executed notebook through nbconvert with this package's template
  (``site_templates/notebook``), figures inline, math converted to MathML at build time
  (``latex2mathml``), no script or style loaded from anywhere;
- ``sweeps/<name>.html``: the sweep's summary table and plot.

Nothing is fetched at build or view time: the page styles are inline, nbconvert's require.js, MathJax,
Mermaid and widget loaders are left out (the notebooks use none of them), and math is MathML, which
browsers render natively.
"""

from __future__ import annotations

import csv
import html
import re
import shutil
import time
from collections import Counter
from dataclasses import dataclass, field
from pathlib import Path

from . import lean_imports
from .outputs import build_folder, check_replaceable, disk_refused, listed_inside
from .paths import PAPER_PROFILE, RUNS_DIR, profile_name, reproduce_dir
from .preflight import UsageError
from .figures import (
    ALL_LABELS,
    ALL_VERDICTS,
    NO_LABEL,
    forest_items,
    forest_plot,
    part_labels,
    robustness_label,
    robustness_picture,
    robustness_where,
)
from .report import REPRODUCE_DIR, first_screen, plain_coverage, profiles_shown
from .runfiles import DamagedRun, load_results, load_run
from .stills import recording_still
from .webview import DEFAULT_GRPC_PORT, DEFAULT_HOST, DEFAULT_WEB_PORT, viewer_url
from ..results import (
    FLIP_SHORT,
    FLIP_WORDS,
    GLOSSARY,
    LABEL_WORDS,
    VERDICT_WORDS,
    at_profile,
    format_measured,
    claim_flips,
    mixed_kinds,
    claim_summary,
    label_verdict,
    label_words,
    paper_paragraph,
    results_summary,
    share_counts,
    side_words,
)
from ..verdicts import VERDICTS

__all__ = [
    "SITE_DIR",
    "PaperRun",
    "find_paper_runs",
    "find_sweeps",
    "tex_to_html",
    "claim_cells",
    "recording_still",
    "render_notebook",
    "read_notebook",
    "build_site",
]

SITE_DIR = RUNS_DIR / "site"
TEMPLATE_DIR = Path(__file__).with_name("site_templates")
NOTEBOOK_TEMPLATE = "notebook"
NOT_SWEEPS = {"reproduce", "runs", "interactive", "site", "profiles", "sweeps", "edit"}
PAGE_CHARS = 400
"""A claim's own page has room for the optional sentences (the share, the other flips) the ledger leaves out."""


@dataclass
class PaperRun:
    """One notebook's run directory: ``run.json`` and, when it succeeded, ``results.json``."""

    name: str
    run_dir: Path
    record: dict
    results: dict | None = None
    cells: dict = field(default_factory=dict)  # claim id -> notebook cell id
    notebook: object = None  # the executed notebook (an nbformat node) of a finished run, read by :func:`read_notebook`

    @property
    def ok(self) -> bool:
        return self.results is not None


def _flips(claim: dict) -> list[dict]:
    """A claim's named flips for its page and the ledger, a mix of kinds with each change's own kind
    (``kinds``), so a reading and a setting together are not shown under the setting alone."""
    record = claim.get("robustness") or {}
    return [{**f, "kinds": mixed_kinds(f, record)} for f in claim_flips(claim)]


def find_paper_runs(reproduce_dir: Path = REPRODUCE_DIR) -> list[PaperRun]:
    """The run directories under ``reproduce_dir``, in name order (failed runs included)."""
    runs = []
    for run_dir in sorted(p for p in Path(reproduce_dir).glob("*") if p.is_dir() and not p.name.startswith(".")):
        record = load_run(run_dir)  # a damaged run file is one line naming it (:mod:`.runfiles`)
        if record is None:
            continue
        results = load_results(run_dir) if record["status"] == "ok" else None
        runs.append(PaperRun(run_dir.name, run_dir, record, results))
    return runs


def find_sweeps(runs_dir: Path = RUNS_DIR) -> list[Path]:
    """Sweep directories (holding ``summary.csv``) directly under ``runs_dir``."""
    return sorted(
        p
        for p in Path(runs_dir).glob("*/summary.csv")
        if p.parent.name not in NOT_SWEEPS and not p.parent.name.startswith(("reproduce-", "site-"))
    )


# --- math --------------------------------------------------------------------------------------------


def tex_to_html(tex: str, display: bool) -> str:
    """MathML for a TeX formula (``latex2mathml``); a formula it cannot parse stays readable as TeX."""
    from latex2mathml.converter import convert

    try:
        return convert(tex, display="block" if display else "inline")
    except Exception:  # noqa: BLE001 - any parser failure: show the source rather than lose the formula
        delim = "$$" if display else "$"
        return f'<code class="tex">{html.escape(delim + tex + delim)}</code>'


def _markdown_exporter_class():
    """nbconvert's HTMLExporter whose Markdown renderer writes MathML instead of MathJax input."""
    from jinja2 import pass_context
    from nbconvert.exporters import HTMLExporter
    from nbconvert.filters.markdown_mistune import IPythonRenderer, MarkdownWithMath

    class MathMLRenderer(IPythonRenderer):
        def block_math(self, body: str) -> str:
            return tex_to_html(body, display=True)

        def inline_math(self, body: str) -> str:
            return tex_to_html(body, display=False)

        def latex_environment(self, name: str, body: str) -> str:
            return tex_to_html(f"\\begin{{{name}}}{body}\\end{{{name}}}", display=True)

    class SiteExporter(HTMLExporter):
        @pass_context
        def markdown2html(self, context, source):
            cell = context.get("cell", {})
            renderer = MathMLRenderer(
                escape=False, attachments=cell.get("attachments", {}), anchor_link_text=self.anchor_link_text
            )
            return MarkdownWithMath(renderer=renderer).render(source)

    return SiteExporter


# --- notebooks ---------------------------------------------------------------------------------------


def claim_cells(notebook: dict, claim_ids: list[str]) -> dict[str, str]:
    """``{claim id: cell id}``: the code cell that decided each claim (its source names the id in quotes,
    or its output shows the claim's verdict line)."""
    found = {}
    for cell in notebook["cells"]:
        if cell["cell_type"] != "code" or "id" not in cell:
            continue
        source = "".join(cell["source"])
        shown = "".join("".join(o.get("data", {}).get("text/markdown", "")) for o in cell.get("outputs", []))
        for cid in claim_ids:
            if cid in found:
                continue
            if re.search(rf"""["']{re.escape(cid)}["']""", source) or f"**{cid}:" in shown:
                found[cid] = cell["id"]
    return found


def read_notebook(run_dir: Path):
    """The executed notebook of a finished run (an ``nbformat`` node), checked to hold a list of cells.

    Raises
    ------
    DamagedRun
        One line naming ``notebook.ipynb``: missing, unreadable, not a notebook (truncated, of another program).
    """
    nbformat = lean_imports.nbformat()
    path = Path(run_dir) / "notebook.ipynb"
    fix = f"the run folder is damaged: remove {path.parent} and run it again (the same command re-runs a missing run)"
    try:
        nb = nbformat.read(path, as_version=4)
    except OSError as exc:
        raise DamagedRun(f"{path}: cannot be read ({exc.strerror or exc}); {fix}") from None
    except Exception as exc:  # noqa: BLE001 - nbformat's many errors on content that is not a notebook
        raise DamagedRun(f"{path}: not an executed notebook ({type(exc).__name__}); {fix}") from None
    cells = nb.get("cells")
    if not isinstance(cells, list) or not all(isinstance(c, dict) and "cell_type" in c for c in cells):
        raise DamagedRun(f"{path}: not an executed notebook (its 'cells' is not a list of cells); {fix}")
    return nb


def has_inline_images(notebook: dict) -> bool:
    """Whether any output of the notebook is an image (runs from before the verdict standard have none)."""
    return any(
        key.startswith("image/")
        for cell in notebook["cells"]
        for out in cell.get("outputs", [])
        for key in out.get("data", {})
    )


def render_notebook(
    nb, out: Path, title: str, recording: dict | None = None, figures: list[dict] | None = None
) -> None:
    """Write the executed notebook (an ``nbformat`` node) as one offline HTML page.

    ``figures`` (``[{src, caption}]``, ``src`` relative to the page) are shown after the notebook, for
    runs whose notebook does not show its figures inline."""
    exporter = _markdown_exporter_class()(
        template_name=NOTEBOOK_TEMPLATE,
        extra_template_basedirs=[str(TEMPLATE_DIR)],
        extra_template_paths=[str(TEMPLATE_DIR)],
    )
    site = {"title": title, "recording": recording, "figures": figures or []}
    body, _ = exporter.from_notebook_node(nb, resources={"site": site, "metadata": {"name": title}})
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(body)


def _shown(run_dir: Path, runs_dir: Path) -> Path:
    """A run directory as a reader types it: relative to the folder holding ``papermill_runs/``."""
    try:
        return run_dir.resolve().relative_to(runs_dir.resolve().parent)
    except ValueError:
        return run_dir.resolve()


def _recording_info(run: PaperRun, site: Path, runs_dir: Path) -> dict | None:
    """Still image (relative to the site root), the serving command and the URL it serves at."""
    name = (run.results or {}).get("recording")
    rrd = run.run_dir / name if name and listed_inside(run.run_dir, name) else None
    if rrd is None or not rrd.is_file():
        return None
    still = site / "runs" / run.name / "recording.png"
    try:
        has_still = recording_still(rrd, still)
    except (RuntimeError, OSError, ValueError) as exc:
        if disk_refused(exc):  # the still could not be written: the recording is sound
            raise
        raise DamagedRun(
            f"{rrd}: not a readable recording ({str(exc).splitlines()[0] if str(exc) else type(exc).__name__}); "
            f"the run folder is damaged: remove {run.run_dir} and run it again"
        ) from None
    return {
        "still": f"runs/{run.name}/recording.png" if has_still else None,
        "command": f"python -m tvtrack view {_shown(run.run_dir, runs_dir)}",
        "url": viewer_url(DEFAULT_HOST, DEFAULT_WEB_PORT, DEFAULT_GRPC_PORT),
    }


# --- pages -------------------------------------------------------------------------------------------


def _environment():
    from jinja2 import Environment, FileSystemLoader, select_autoescape

    env = Environment(loader=FileSystemLoader(TEMPLATE_DIR), autoescape=select_autoescape(["html"]))
    env.globals.update(
        side_words=side_words(),
        glossary=GLOSSARY,
        glossary_verdicts=list(VERDICT_WORDS.items()),
        glossary_labels=list(LABEL_WORDS.items()),
        flip_words=FLIP_WORDS,
        flip_short=FLIP_SHORT,
        verdict_words=[v for v in ALL_VERDICTS],
        label_scope=lambda verdict, label: label_words(verdict, label)[len(label) :].strip(),
    )
    return env


def claim_page_href(paper: str, claim_id: str) -> str:
    """A claim's page, relative to the site root."""
    return f"claims/{paper}/{claim_id}.html"


def _part_rows(claim: dict) -> list[dict]:
    """The claim's parts for its page: verdict, label, share that agrees, runs to decide, what moves it most."""
    rows = []
    for name, p in ((claim.get("robustness") or {}).get("parts") or {}).items():
        if not isinstance(p, dict):
            continue
        share = p.get("share") or {}
        rows.append(
            {
                "name": name,
                "verdict": p.get("verdict", ""),
                "label": p.get("label", ""),
                "share": (
                    f"{share_counts(share)} (agree: 95 % CI {share['ci_low'] * 100:.0f}-{share['ci_high'] * 100:.0f} %)"
                    if "ci_low" in share
                    else ""
                ),
                "runs": (p.get("runs_to_decide") or {}).get("text", ""),
                "sensitivity": ", ".join(
                    f"{s.get('title') or s.get('entry')} ({float(s.get('score', 0)):.2f})"
                    for s in (p.get("sensitivity") or [])[:3]
                ),
            }
        )
    return rows


def _claim_pages(env, runs: list[PaperRun], site: Path, common: dict) -> None:
    """One page per claim, ``claims/<paper>/<id>.html``: its sentence, its specification curve
    (:func:`tvtrack.plotting.specification_curve`) and the record behind it."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from ..plotting import specification_curve

    template = env.get_template("claim.html")
    for run in runs:
        if not run.ok:
            continue
        folder = site / "claims" / run.name
        folder.mkdir(parents=True, exist_ok=True)
        for c in run.results["claims"]:
            curve, caption = None, ""
            if c["verdict"] != "not checkable" and (c.get("robustness") or {}).get("conditions"):
                fig, caption = specification_curve(c)
                fig.savefig(folder / f"{c['id']}.png", dpi=100)
                plt.close(fig)
                curve = f"{c['id']}.png"
            cell = run.cells.get(c["id"])
            (folder / f"{c['id']}.html").write_text(
                template.render(
                    c=c,
                    paper=run.name,
                    shown=robustness_label(c),
                    scope=label_verdict(c),
                    summary=claim_summary(c, chars=PAGE_CHARS),
                    measured=format_measured(c.get("measured"), c.get("rule")),
                    coverage=plain_coverage(c),
                    flips=_flips(c),
                    parts=_part_rows(c),
                    curve=curve,
                    caption=caption,
                    cell_href=f"notebooks/{run.name}.html" + (f"#cell-id={cell}" if cell else ""),
                    **{**common, "root": "../../"},
                )
            )


def _counts(claims: list[dict]) -> dict:
    verdicts = Counter(c["verdict"] for c in claims)
    labels = Counter(robustness_label(c) for c in claims)
    return {
        "verdicts": [(v, verdicts[v]) for v in ALL_VERDICTS if v in VERDICTS or verdicts[v]],
        "labels": [(lab, labels[lab]) for lab in (*ALL_LABELS, NO_LABEL) if labels[lab]],
    }


def _ledger_rows(runs: list[PaperRun]) -> list[dict]:
    rows = []
    for run in runs:
        for c in (run.results or {}).get("claims", []):
            cell = run.cells.get(c["id"])
            rows.append(
                {
                    "paper": run.name,
                    "id": c["id"],
                    "statement": c["statement"],
                    "paper_value": c["paper_value"],
                    "rule": c.get("acceptance", ""),
                    "measured": format_measured(c["measured"], c.get("rule")),
                    "verdict": c["verdict"],
                    "label": robustness_label(c),
                    "label_verdict": label_verdict(c),
                    "where": robustness_where(c),
                    "summary": claim_summary(c),
                    "flips": _flips(c),
                    "page": claim_page_href(run.name, c["id"]),
                    "note": c.get("note", ""),
                    "coverage": plain_coverage(c),
                    "parts": part_labels(c),
                    "href": f"notebooks/{run.name}.html" + (f"#cell-id={cell}" if cell else ""),
                }
            )
    return rows


def _read_summary(path: Path) -> list[list[str]]:
    """A sweep's ``summary.csv`` as rows, checked: a header with ``status``, every row as long.

    Raises
    ------
    DamagedRun
        One line naming the file and what is wrong (running the sweep again writes it anew)."""
    try:
        with path.open(newline="") as fh:
            rows = list(csv.reader(fh))
    except (OSError, UnicodeDecodeError, csv.Error) as exc:
        raise DamagedRun(f"{path}: cannot be read as CSV ({exc}); the same sweep command writes it again") from None
    if not rows or "status" not in rows[0]:
        raise DamagedRun(f"{path}: no header with a status column; the same sweep command writes it again")
    short = next((k for k, r in enumerate(rows[1:], start=2) if len(r) != len(rows[0])), None)
    if short is not None:
        raise DamagedRun(
            f"{path}: line {short} has {len(rows[short - 1])} fields, the header {len(rows[0])}; "
            "the same sweep command writes it again"
        )
    return rows


def _sweep_page(env, sweep_csv: Path, site: Path) -> dict:
    name = sweep_csv.parent.name
    rows = _read_summary(sweep_csv)
    plot = None
    if (sweep_csv.parent / "summary.png").is_file():
        plot = f"{name}.png"
        shutil.copy2(sweep_csv.parent / "summary.png", site / "sweeps" / plot)
    failed = sum(1 for r in rows[1:] if r[rows[0].index("status")] != "ok")
    info = {"name": name, "header": rows[0] if rows else [], "rows": rows[1:], "plot": plot, "failed": failed}
    (site / "sweeps" / f"{name}.html").write_text(env.get_template("sweep.html").render(sweep=info, root="../"))
    return info


def _figures_not_inline(run: PaperRun, nb, assets: Path) -> list[dict]:
    """The run's saved figures, copied beside the site, when its notebook does not show them inline."""
    if has_inline_images(nb):
        return []
    shown = []
    for fig in run.results.get("figures") or []:
        if listed_inside(run.run_dir, fig["file"]) and (run.run_dir / fig["file"]).is_file():
            (assets / fig["file"]).parent.mkdir(parents=True, exist_ok=True)  # a figure in a folder of the run
            shutil.copy2(run.run_dir / fig["file"], assets / fig["file"])
            shown.append({"src": f"../runs/{run.name}/{fig['file']}", "caption": fig["caption"]})
    return shown


def _first_screen(runs: list[PaperRun], by_name: dict) -> tuple[list[dict], list[dict], list[dict]]:
    """The index's first-screen rows (each with its claim page), one row per paper, and every claim."""
    first = first_screen(by_name)
    for row in first:
        row["page"] = claim_page_href(row["paper"], row["id"])
    papers = [
        {"name": r.name, "n": len(r.results["claims"]), "verdicts": Counter(c["verdict"] for c in r.results["claims"])}
        for r in runs
        if r.ok
    ]
    return first, papers, [c for r in runs if r.ok for c in r.results["claims"]]


def build_site(runs_dir: Path = RUNS_DIR, out: Path | None = None, profile: str | None = None) -> Path:
    """Build the site from ``runs_dir/reproduce`` (``reproduce-<profile>`` for another profile) and the sweeps in
    ``runs_dir``; returns ``index.html``. The default folder is ``runs_dir/site`` (``site-<profile>``).

    The site is built in a temporary folder beside its own and renamed into place (:func:`.outputs.build_folder`):
    a symbolic link, or a folder that is not empty and was not built here, is refused before anything is written;
    of an earlier site only the files it wrote are deleted; a write that fails (a full disk) keeps nothing of the
    new site (:class:`.runner.WriteFailed`)."""
    runs_dir = Path(runs_dir)
    profile = profile_name(profile)
    source = reproduce_dir(profile, runs_dir)
    default = runs_dir / ("site" if profile == PAPER_PROFILE else f"site-{profile}")
    if profile != PAPER_PROFILE and not source.is_dir():
        raise UsageError(
            f"no runs at the {profile} profile ({source} does not exist): `make reproduce PROFILE={profile}` makes them"
            f" (one notebook: `python -m tvtrack reproduce --profile {profile} --only NAME`)"
        )
    final = Path(out) if out is not None else default
    check_replaceable(final, "-o" if out is not None else "site folder", "site")
    runs = find_paper_runs(source)  # every run file checked before anything is written
    for run in runs:
        if run.ok:
            run.notebook = read_notebook(run.run_dir)
    build_folder(final, "site", lambda site: _build_into(site, runs_dir, source, profile, runs))
    return final / "index.html"


def _build_into(site: Path, runs_dir: Path, source: Path, profile: str, runs: list[PaperRun]) -> None:
    """Every page of the site into the (new, empty) folder ``site`` from ``runs`` (:func:`find_paper_runs`, each
    finished one with its notebook read)."""
    (site / "notebooks").mkdir()
    (site / "sweeps").mkdir()
    env = _environment()
    for run in runs:  # at another profile than the paper's, nothing is robust (tvtrack.results.at_profile)
        if run.ok:
            run.results = {**run.results, "claims": at_profile(run.results["claims"], run.record.get("profile"))}
    cards = []
    for run in runs:
        card = {
            "run": run,
            "recording": None,
            "counts": None,
            "date": run.record.get("finished_utc", ""),
            "shown": _shown(run.run_dir, runs_dir),
        }
        if run.ok:
            card["paragraph"], card["limitations"] = paper_paragraph(
                run.results, run.record.get("profile") or PAPER_PROFILE
            )
            card["recording"] = _recording_info(run, site, runs_dir)
            card["counts"] = _counts(run.results["claims"])
            assets = site / "runs" / run.name
            assets.mkdir(parents=True, exist_ok=True)
            shutil.copy2(run.run_dir / "results.json", assets / "results.json")
            nb = run.notebook
            render_notebook(
                nb,
                site / "notebooks" / f"{run.name}.html",
                run.name,
                card["recording"],
                _figures_not_inline(run, nb, assets),
            )
            run.cells = claim_cells(nb, [c["id"] for c in run.results["claims"]])
        cards.append(card)
    sweeps = [_sweep_page(env, csv_path, site) for csv_path in find_sweeps(runs_dir)]
    rows = _ledger_rows(runs)
    built = time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime())
    by_name = {r.name: (r.record, r.results) for r in runs}
    shown = profiles_shown(by_name) if any(r.ok for r in runs) else profile
    forest = forest_plot(forest_items(by_name), site / "forest.png")
    picture = robustness_picture(by_name, site / "robustness.png")
    common = {
        "root": "",
        "built": built,
        "profile": shown,
        "paper_scale": shown == PAPER_PROFILE,
        "source": _shown(source, runs_dir),
    }
    (site / "ledger.html").write_text(
        env.get_template("ledger.html").render(
            rows=rows,
            papers=[r.name for r in runs if r.ok],
            verdicts=[v for v, _ in _counts([c for r in runs if r.ok for c in r.results["claims"]])["verdicts"]],
            labels=(*ALL_LABELS, NO_LABEL),
            **common,
        )
    )
    _claim_pages(env, runs, site, common)
    first, papers, all_claims = _first_screen(runs, by_name)
    index = site / "index.html"
    index.write_text(
        env.get_template("index.html").render(
            cards=cards,
            sweeps=sweeps,
            totals=_counts(all_claims),
            n_claims=len(rows),
            first=first,
            summary=results_summary(all_claims, shown),
            papers=papers,
            forest="forest.png" if forest else None,
            robustness="robustness.png" if picture else None,
            **common,
        )
    )
