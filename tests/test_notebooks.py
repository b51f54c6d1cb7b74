"""The notebook contract (docs/contributing.md, "Writing a notebook"), checked on every notebook in notebooks/:
the committed file, then an execution of its smoke profile."""

from __future__ import annotations

import ast
import base64
import hashlib
import io
import re
import subprocess
import sys
import tokenize
from pathlib import Path

import nbformat
import pytest

from conftest import NOTEBOOK_NAMES
from tvtrack.pipeline.audit import audit_claim
from tvtrack.pipeline.paths import NOTEBOOK_DIR, PROFILE_DIR, SWEEP_DIR
from tvtrack.results import VERDICTS, load_results
from tvtrack.labels import NO_PART_LABEL
from tvtrack.verdicts import LABELS
from tvtrack.pipeline.sweep import load_spec

COMMON = ("seed", "n_trials", "output_dir", "rerun_mode")


def read(name: str) -> nbformat.NotebookNode:
    return nbformat.read(NOTEBOOK_DIR / f"{name}.ipynb", as_version=4)


def parameters_cell(nb) -> nbformat.NotebookNode:
    code = [c for c in nb.cells if c.cell_type == "code"]
    assert code, "notebook has no code cell"
    assert "parameters" in code[0].metadata.get("tags", []), "the first code cell must be tagged 'parameters'"
    return code[0]


def assigned_names(source: str) -> list[str]:
    return [
        t.id
        for node in ast.parse(source).body
        if isinstance(node, ast.Assign)
        for t in node.targets
        if isinstance(t, ast.Name)
    ]


def test_there_are_notebooks_or_the_report_says_so():
    # with no notebooks the suite still runs the fixture; this documents the expectation
    assert all(Path(NOTEBOOK_DIR, f"{n}.ipynb").is_file() for n in NOTEBOOK_NAMES)


def committed(name: str) -> nbformat.NotebookNode:
    """The notebook as git holds it (HEAD), so a copy being edited and run in JupyterLab, whose outputs
    the nbstripout filter keeps out of git, does not fail the suite; the file itself outside a checkout."""
    path = NOTEBOOK_DIR / f"{name}.ipynb"
    try:
        rel = path.resolve().relative_to(
            Path(
                subprocess.run(
                    ["git", "rev-parse", "--show-toplevel"],
                    cwd=NOTEBOOK_DIR,
                    capture_output=True,
                    text=True,
                    check=True,
                ).stdout.strip()
            ).resolve()
        )
        blob = subprocess.run(
            ["git", "show", f"HEAD:{rel.as_posix()}"], cwd=NOTEBOOK_DIR, capture_output=True, text=True, check=True
        ).stdout
        return nbformat.reads(blob, as_version=4)
    except (subprocess.CalledProcessError, OSError, ValueError):
        return read(name)


@pytest.mark.parametrize("name", NOTEBOOK_NAMES)
def test_committed_notebook_has_no_outputs(name):
    nb = committed(name)
    nbformat.validate(nb)
    for cell in nb.cells:
        if cell.cell_type == "code":
            assert not cell.outputs and cell.execution_count is None, f"{name}: code cells must carry no outputs"


@pytest.mark.parametrize("name", NOTEBOOK_NAMES)
def test_parameters_cell_follows_the_contract(name):
    cell = parameters_cell(read(name))
    names = assigned_names(cell.source)
    for required in COMMON:
        assert required in names, f"{name}: the parameters cell lacks {required!r}"
    # one parameter per line, each with a comment (unit and allowed range)
    tokens = list(tokenize.generate_tokens(io.StringIO(cell.source).readline))
    comment_lines = {t.start[0] for t in tokens if t.type == tokenize.COMMENT}
    for node in ast.parse(cell.source).body:
        assert isinstance(node, ast.Assign), f"{name}: the parameters cell may hold only assignments"
        assert node.end_lineno in comment_lines or node.lineno in comment_lines, (
            f"{name}: parameter on line {node.lineno} has no comment giving its unit and range"
        )
    rerun_mode = next(n.value for n in ast.parse(cell.source).body if n.targets[0].id == "rerun_mode")
    assert ast.literal_eval(rerun_mode) == "file"


@pytest.mark.parametrize("name", NOTEBOOK_NAMES)
def test_validation_is_the_next_code_cell(name):
    code = [c for c in read(name).cells if c.cell_type == "code"]
    assert "validate_parameters(globals()" in code[1].source or "PAPER.validate(globals())" in code[1].source, (
        f"{name}: the cell after the parameters must validate them with PAPER.validate(globals()) or "
        "validate_parameters(globals(), ...)"
    )


@pytest.mark.parametrize("name", NOTEBOOK_NAMES)
def test_smoke_profile_exists_and_names_known_parameters(name):
    import tomllib

    path = PROFILE_DIR / f"{name}.smoke.toml"
    assert path.is_file(), f"{name}: no smoke profile {path}"
    with path.open("rb") as fh:
        profile = tomllib.load(fh)
    unknown = set(profile) - set(assigned_names(parameters_cell(read(name)).source))
    assert not unknown, f"{name}: smoke profile sets unknown parameters {sorted(unknown)}"


@pytest.mark.parametrize("spec", sorted(SWEEP_DIR.glob("*.toml")), ids=lambda p: p.stem)
def test_sweep_specs_parse_and_name_known_parameters(spec):
    s = load_spec(spec)
    known = set(assigned_names(parameters_cell(nbformat.read(s.notebook, as_version=4)).source))
    unknown = (set(s.fixed) | set(s.grid) | set(s.zipped)) - known
    assert not unknown, f"{spec.name}: unknown parameters {sorted(unknown)}"


@pytest.mark.notebook
@pytest.mark.parametrize("name", NOTEBOOK_NAMES)
def test_smoke_run_writes_valid_results_and_recording(name, smoke_run):
    outcome = smoke_run(name)
    assert outcome.ok, f"{name} failed: {outcome.error}\n{(outcome.run_dir / 'error.txt').read_text()}"
    data = load_results(outcome.run_dir / "results.json")
    assert data["notebook"] == name
    params = data["parameters"]
    for key in assigned_names(parameters_cell(read(name)).source):
        assert key in params, f"{name}: parameter {key!r} missing from results.json (not validated?)"
    assert data["claims"], f"{name}: no claims checked"
    prefix = "C" + name[:3] + "-"
    for claim in data["claims"]:
        assert claim["id"].startswith(prefix) and claim["verdict"] in VERDICTS
        assert claim["acceptance"] == claim["rule"]["text"] and claim["statement"]
        if claim["verdict"] != "not checkable":
            assert claim["measured"] is not None, f"{claim['id']}: a verdict needs a measured value"
            # an undecided claim with no decided part has nothing to flip: no label ("-")
            unlabelled = claim["verdict"] == "undecided" and claim["robustness"]["label"] == NO_PART_LABEL
            assert claim["robustness"]["label"] in LABELS or unlabelled, claim["id"]
            assert claim["robustness"].get("coverage"), f"{claim['id']}: the label must say what it covers"
    # the labels the machinery wrote, re-read against their own records (tvtrack.pipeline.audit)
    assert [p for claim in data["claims"] for p in audit_claim(claim)] == []
    for fig in data["figures"]:
        assert (outcome.run_dir / fig["file"]).is_file() and fig["caption"]
        assert not fig.get("problems"), f"{name}: {fig['file']}: {fig.get('problems')}"  # labels, colour bars
    written = {p.name for p in outcome.run_dir.iterdir()}
    assert written <= {"results.json", "run.json", "notebook.ipynb", "recording.rrd", "error.txt"} | {
        f["file"] for f in data["figures"]
    }, f"{name}: unexpected outputs {sorted(written)}"
    rrd = outcome.run_dir / "recording.rrd"
    assert data["recording"] == "recording.rrd" and rrd.is_file()
    verify = subprocess.run(
        [str(Path(sys.executable).parent / "rerun"), "rrd", "verify", str(rrd)],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert verify.returncode == 0, verify.stderr


# An output that is only a bare repr: a text/plain result with no richer form, e.g. PosixPath('x'),
# Claim(id=...), np.False_, <Figure size ...>, [<matplotlib.lines.Line2D ...>].
BARE_REPR = re.compile(r"^(\w+(\.\w+)*\(.*\)|np\.\w+_?(\(.*\))?|<[\w.]+ .*>|\[<[\w.]+ .*>\]|Text\(.*\))$", re.S)


def _outputs(nb):
    for i, cell in enumerate(nb.cells):
        if cell.cell_type == "code":
            for out in cell.outputs:
                yield i, out


@pytest.mark.notebook
@pytest.mark.parametrize("name", NOTEBOOK_NAMES)
def test_executed_notebook_shows_every_figure_inline_with_its_caption(name, smoke_run):
    outcome = smoke_run(name)
    assert outcome.ok, outcome.error
    data = load_results(outcome.run_dir / "results.json")
    nb = nbformat.read(outcome.run_dir / "notebook.ipynb", as_version=4)
    shown = {
        hashlib.sha256(base64.b64decode(out["data"]["image/png"])).hexdigest()
        for _, out in _outputs(nb)
        if "data" in out and "image/png" in out["data"]
    }
    markdown = "\n".join(
        out["data"]["text/markdown"] for _, out in _outputs(nb) if "data" in out and "text/markdown" in out["data"]
    )
    for fig in data["figures"]:
        digest = hashlib.sha256((outcome.run_dir / fig["file"]).read_bytes()).hexdigest()
        assert digest in shown, f"{name}: {fig['file']} is saved but not shown inline"
        assert fig["caption"] in markdown, f"{name}: the caption of {fig['file']} is not shown"


@pytest.mark.notebook
@pytest.mark.parametrize("name", NOTEBOOK_NAMES)
def test_executed_notebook_has_no_bare_reprs_or_warnings(name, smoke_run):
    outcome = smoke_run(name)
    assert outcome.ok, outcome.error
    nb = nbformat.read(outcome.run_dir / "notebook.ipynb", as_version=4)
    for i, out in _outputs(nb):
        if out["output_type"] == "stream":
            assert out["name"] != "stderr", f"{name} cell {i}: stderr output {out['text'][:200]!r}"
            assert "Warning" not in out["text"], f"{name} cell {i}: a warning in the output {out['text'][:200]!r}"
        elif out["output_type"] in ("execute_result", "display_data"):
            data = out["data"]
            if set(data) == {"text/plain"}:
                text = data["text/plain"].strip()
                assert not BARE_REPR.match(text), f"{name} cell {i}: bare repr {text[:120]!r}"


@pytest.mark.parametrize("name", NOTEBOOK_NAMES)
def test_no_verdict_is_typed_in_a_code_cell(name):
    for cell in read(name).cells:
        if cell.cell_type == "code":
            strings = [
                node.value
                for node in ast.walk(ast.parse(cell.source))
                if isinstance(node, ast.Constant) and isinstance(node.value, str)
            ]
            typed = [s for s in strings if s.strip() in ("reproduced", "partly", "not reproduced")]
            assert not typed, f"{name}: a verdict typed in code {typed}; a rule object decides verdicts"


# ----------------------------------------------------------------------------- a notebook reads like a paper
MAX_CODE_LINES, MAX_CELL_LINES, MAX_FUNCTIONS = 400, 30, 3


def _code_lines(source: str) -> int:
    return sum(1 for line in source.splitlines() if line.strip())


@pytest.mark.parametrize("name", NOTEBOOK_NAMES)
def test_notebook_keeps_the_budget_of_a_short_paper(name):
    """At most 400 code lines, no code cell over 30 lines (the parameters cell aside), at most three
    functions defined in the notebook (study code lives in the paper's package, with tests)."""
    code = [c for c in read(name).cells if c.cell_type == "code"]
    total = sum(_code_lines(c.source) for c in code)
    assert total <= MAX_CODE_LINES, f"{name}: {total} code lines (budget {MAX_CODE_LINES})"
    long = [(i, _code_lines(c.source)) for i, c in enumerate(code[1:], 1) if _code_lines(c.source) > MAX_CELL_LINES]
    assert not long, f"{name}: code cells over {MAX_CELL_LINES} lines (index, lines): {long}"
    defs = [
        n.name
        for c in code
        for n in ast.walk(ast.parse(c.source))
        if isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef))
    ]
    assert len(defs) <= MAX_FUNCTIONS, f"{name}: {len(defs)} functions or classes defined in the notebook: {defs}"


@pytest.mark.parametrize("name", NOTEBOOK_NAMES)
def test_notebook_opens_with_findings_and_ends_with_conclusions(name):
    cells = read(name).cells
    md = [c for c in cells if c.cell_type == "markdown"]
    assert md and md[0].source.lstrip().startswith("# "), f"{name}: the first cell is the title (# ...)"
    first_code = next(i for i, c in enumerate(cells) if c.cell_type == "code")
    head = "\n".join(c.source for c in cells[: first_code + 3])
    assert re.search(r"^#+ .*Findings", head, re.M | re.I), f"{name}: a Findings section opens the notebook"
    assert "results.findings()" in head, f"{name}: the findings are shown near the top (results.findings())"
    code = [c for c in cells if c.cell_type == "code"]
    assert any("results.finish()" in c.source for c in code[-3:]), f"{name}: results.finish() ends the run"
    tail = "\n".join(c.source for c in cells[-4:] if c.cell_type == "markdown")
    assert re.search(r"^#+ .*Conclusions", tail, re.M | re.I), f"{name}: Conclusions close the notebook"


@pytest.mark.notebook
@pytest.mark.parametrize("name", NOTEBOOK_NAMES)
def test_executed_notebook_fills_its_findings_before_any_figure(name, smoke_run):
    outcome = smoke_run(name)
    assert outcome.ok, outcome.error
    nb = nbformat.read(outcome.run_dir / "notebook.ipynb", as_version=4)
    outs = list(_outputs(nb))
    table = [
        k
        for k, (_, out) in enumerate(outs)
        if "| claim | the paper says" in out.get("data", {}).get("text/markdown", "")
    ]
    images = [k for k, (_, out) in enumerate(outs) if "image/png" in out.get("data", {})]
    assert table, f"{name}: the findings table is not in the executed notebook"
    assert not images or table[0] < images[0], f"{name}: the findings come after a figure"


_RANGE = re.compile(r"(?:integer|real|number)s?[^\[\(]*?in ([\[\(])([^,\]\)]+), ([^\]\)]+)([\]\)])")


def _bound(text: str):
    text = text.strip().replace("inf", "float('inf')")
    try:
        return float(eval(text, {"__builtins__": {"float": float}}))  # noqa: S307 - numbers like 2**63-1 only
    except Exception:  # a bound that names another parameter: checked by the notebook's cross-checks
        return None


@pytest.mark.parametrize("name", NOTEBOOK_NAMES)
def test_parameter_ranges_are_written_once(name):
    """Every range a parameter's comment states is the range its rule in the paper package enforces."""
    import importlib

    pkg = importlib.import_module(f"tvtrack.papers.p{name}.params")
    rules = getattr(pkg, "RULES", None) or pkg.PARAMETERS
    cell = parameters_cell(read(name)).source
    checked = 0
    for line in cell.splitlines():
        m = re.match(r"\s*(\w+)\s*=.*#(.*)$", line)
        if not m or m.group(1) not in rules:
            continue
        rng = _RANGE.search(m.group(2))
        rule = rules[m.group(1)]
        if not rng or not hasattr(rule, "low"):
            continue
        lo, hi = _bound(rng.group(2)), _bound(rng.group(3))
        inf = float("inf")
        want_lo = -inf if rule.low is None else float(rule.low)
        want_hi = inf if rule.high is None else float(rule.high)
        if lo is not None:
            assert lo == pytest.approx(want_lo), f"{name}: {m.group(1)}'s comment says {rng.group(0)}; rule {rule}"
        if hi is not None:
            assert hi == pytest.approx(want_hi), f"{name}: {m.group(1)}'s comment says {rng.group(0)}; rule {rule}"
        checked += 1
    assert checked >= 3, f"{name}: no parameter comment states a range the test could read"
