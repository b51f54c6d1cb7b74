"""The library's two layers: science modules never import the pipeline, and no import circle."""

import ast
import functools
from pathlib import Path

import tvtrack

PKG = Path(tvtrack.__file__).resolve().parent


@functools.cache
def parse(source: str) -> ast.Module:
    """``ast.parse(source)``, once per distinct text: every rule here walks the whole library, and the trees are only
    read (never changed), so the rules share them."""
    return ast.parse(source)


@functools.cache
def walk(tree: ast.AST) -> tuple[ast.AST, ...]:
    """Every node of ``tree`` (``ast.walk``), listed once per tree: the rules walk the same trees many times."""
    return tuple(ast.walk(tree))


def _module_name(path: Path) -> str:
    parts = path.relative_to(PKG.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _resolve(module: str, node: ast.ImportFrom, is_package: bool) -> list[str]:
    if node.level == 0:
        base = node.module or ""
    else:
        pkg = module.split(".") if is_package else module.split(".")[:-1]
        pkg = pkg[: len(pkg) - (node.level - 1)]
        base = ".".join(pkg + ([node.module] if node.module else []))
    names = [f"{base}.{a.name}" for a in node.names]
    return [base] + names


@functools.cache
def import_graph() -> dict[str, set[str]]:
    """``module -> tvtrack modules it imports`` (at any depth of the file, lazy imports included)."""
    files = {_module_name(p): p for p in PKG.rglob("*.py")}
    graph = {}
    for name, path in files.items():
        deps = set()
        for node in walk(parse(path.read_text())):
            if isinstance(node, ast.ImportFrom):
                targets = _resolve(name, node, path.name == "__init__.py")
            elif isinstance(node, ast.Import):
                targets = [a.name for a in node.names]
            else:
                continue
            deps |= {t for t in targets if t in files and t != name}
        graph[name] = deps
    return graph


def test_science_modules_import_nothing_from_the_pipeline():
    offenders = {
        m: sorted(d for d in deps if d.startswith("tvtrack.pipeline"))
        for m, deps in import_graph().items()
        if not m.startswith("tvtrack.pipeline") and m != "tvtrack.__main__"
    }  # `python -m tvtrack` is the CLI
    assert {m: d for m, d in offenders.items() if d} == {}


def test_import_graph_has_no_circle():
    graph = import_graph()
    # a package's __init__ importing nothing of its children keeps edges child -> parent harmless
    state: dict[str, int] = {}
    cycle: list[str] = []

    def visit(node, stack):
        state[node] = 1
        for nxt in sorted(graph[node]):
            if state.get(nxt) == 1:
                cycle.extend(stack[stack.index(nxt) :] + [node, nxt] if nxt in stack else [node, nxt])
                return True
            if state.get(nxt) is None and visit(nxt, stack + [node]):
                return True
        state[node] = 2
        return False

    for start in sorted(graph):
        if state.get(start) is None and visit(start, []):
            break
    assert cycle == []


def test_graph_sees_the_lazy_import_of_the_discriminators_from_the_scene():
    # guards the test itself: a lazy import inside a function counts as an edge
    assert (
        "tvtrack.papers.p003_rotating_marker_tracker.discriminators"
        in import_graph()["tvtrack.papers.p003_rotating_marker_tracker.scene"]
    )


PAPERS = "tvtrack.papers."


def _paper_of(module: str) -> str | None:
    return module.split(".")[2] if module.startswith(PAPERS) and module.count(".") >= 2 else None


def test_the_core_never_imports_a_paper_package():
    offenders = {
        m: sorted(d for d in deps if d.startswith(PAPERS))
        for m, deps in import_graph().items()
        if not m.startswith("tvtrack.papers")
    }
    assert {m: d for m, d in offenders.items() if d} == {}


def test_paper_packages_never_import_each_other():
    offenders = {}
    for m, deps in import_graph().items():
        own = _paper_of(m)
        if own is None:
            continue
        other = sorted(d for d in deps if _paper_of(d) not in (None, own))
        if other:
            offenders[m] = other
    assert offenders == {}


def test_the_pipeline_imports_neither_papers_nor_science():
    science = {
        m for m in import_graph() if not m.startswith("tvtrack.pipeline") and m not in ("tvtrack", "tvtrack.__main__")
    }
    allowed = {
        "tvtrack.results",
        "tvtrack.verdicts",
        "tvtrack.montecarlo",
        "tvtrack.register",
        "tvtrack.plotting",
        "tvtrack.executors",
    }
    offenders = {
        m: sorted(d for d in deps if d in science - allowed)
        for m, deps in import_graph().items()
        if m.startswith("tvtrack.pipeline")
    }
    assert {m: d for m, d in offenders.items() if d} == {}


def test_the_layout_rules_see_a_planted_offence(tmp_path, monkeypatch):
    # guards the rules themselves: a core module importing a paper package is an edge they report
    graph = {"tvtrack.render": {"tvtrack.papers.p000_x.model"}, "tvtrack.papers.p000_x.model": set()}
    assert _paper_of("tvtrack.papers.p000_x.model") == "p000_x"
    assert [
        m for m, deps in graph.items() if not m.startswith("tvtrack.papers") and any(d.startswith(PAPERS) for d in deps)
    ] == ["tvtrack.render"]


#: How the project's own making could show in its files: work-item numbers, work sessions, stops, working branches.
_PROCESS_WORDS = (
    r"\b(" + "|".join(("iss" + "ue [0-9]+", "sess" + "ion[- ][0-9]", "this st" + "op", "last st" + "op")) + r")\b"
)


def _process_words(root: Path) -> list[str]:
    import re
    import subprocess

    files = subprocess.run(["git", "ls-files"], cwd=root, capture_output=True, text=True, check=True).stdout.split()
    hits = []
    for name in files:
        path = root / name
        if path.suffix not in (".py", ".md", ".ipynb", ".toml", ".txt", ".cff", ".yml", ".yaml") or not path.is_file():
            continue
        for n, line in enumerate(path.read_text(errors="replace").splitlines(), 1):
            if re.search(_PROCESS_WORDS, line, re.IGNORECASE):
                hits.append(f"{name}:{n}: {line.strip()[:100]}")
    return hits


def test_the_project_speaks_of_itself_not_of_how_it_was_made(tmp_path):
    """No file names the work items, sessions or stops it came from: a maintainer needs what the code does and what
    was tried against each claim (docs/validity), not a log. The check itself sees a planted line."""
    root = Path(tvtrack.__file__).resolve().parents[2]
    assert _process_words(root) == []
    import subprocess

    subprocess.run(["git", "init", "-q", str(tmp_path)], check=True)
    (tmp_path / "a.py").write_text("# fixed in " + "iss" + "ue 12\n")
    subprocess.run(["git", "add", "a.py"], cwd=tmp_path, check=True)
    assert len(_process_words(tmp_path)) == 1


#: The size budgets of the library: a module's lines, and a function's lines below its docstring.
MODULE_LINES, FUNCTION_LINES = 600, 80


def _docstring_end(node: ast.AST) -> int:
    """The first line of a function's code: below its docstring where it has one (and more than it)."""
    body = node.body
    first = body[0]
    doc = isinstance(first, ast.Expr) and isinstance(first.value, ast.Constant) and isinstance(first.value.value, str)
    return first.end_lineno + 1 if doc and len(body) > 1 else first.lineno


def over_budget(root: Path) -> list[str]:
    """Modules of more than :data:`MODULE_LINES` lines and functions whose code (below the docstring) runs over
    :data:`FUNCTION_LINES` lines, under ``root``."""
    out = []
    for path in sorted(root.rglob("*.py")):
        text = path.read_text()
        n = len(text.splitlines())
        if n > MODULE_LINES:
            out.append(f"{path.relative_to(root)}: {n} lines")
        for node in walk(parse(text)):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                lines = node.end_lineno - _docstring_end(node) + 1
                if lines > FUNCTION_LINES:
                    out.append(f"{path.relative_to(root)}: {node.name} has {lines} lines of code")
    return out


def test_modules_and_functions_keep_their_size_budgets():
    """Every module of the library within 600 lines and every function's code within 80: a module split along an
    idea, a function that does one thing."""
    assert over_budget(PKG) == []


def test_the_size_budgets_see_a_planted_offence(tmp_path):
    body = "\n".join(f"    x{i} = {i}" for i in range(FUNCTION_LINES + 1))
    (tmp_path / "long.py").write_text(f'def f():\n    """Doc."""\n{body}\n    return x0\n')
    (tmp_path / "short.py").write_text(
        'def g():\n    """Doc\n    over\n    lines."""\n' + "    y = 1\n" * 78 + "    return y\n"
    )
    (tmp_path / "big.py").write_text("x = 1\n" * (MODULE_LINES + 1))
    assert over_budget(tmp_path) == ["big.py: 601 lines", "long.py: f has 82 lines of code"]


def _modules(root: Path) -> dict[str, ast.Module]:
    """``dotted module name -> its parsed source`` for every module under the package directory ``root``."""
    return {
        ".".join(p.relative_to(root.parent).with_suffix("").parts).removesuffix(".__init__"): parse(p.read_text())
        for p in sorted(root.rglob("*.py"))
    }


def _is_private(name: str) -> bool:
    return name.startswith("_") and not (name.startswith("__") and name.endswith("__"))


def _from_imports(module: str, tree: ast.Module, is_package: bool):
    """``(imported module, name, bound as)`` for every ``from ... import`` in ``tree``, at any depth."""
    for node in walk(tree):
        if isinstance(node, ast.ImportFrom):
            base = _resolve(module, node, is_package)[0]
            for alias in node.names:
                yield base, alias.name, alias.asname or alias.name


def _names_taken(module: str, tree: ast.Module, trees: dict, is_package: bool, bound: dict):
    """``(module, name)`` for every name ``module`` takes by ``from ... import`` from another module under the root;
    a submodule taken that way is recorded in ``bound`` (local name -> module it stands for) instead."""
    for base, name, asname in _from_imports(module, tree, is_package):
        if f"{base}.{name}" in trees:
            bound[asname] = f"{base}.{name}"
        elif base in trees and base != module:
            yield base, name


def private_imports(root: Path) -> list[str]:
    """``"importer: module._name"`` for every private name (one leading underscore) a module under ``root`` takes
    from another: ``from module import _name``, or ``module._name`` on a module it imported. A private module's
    public names are not counted (``from ._kernel import step`` is the package's own seam)."""
    trees = _modules(root)
    packages = {m for m in trees if (root.parent / Path(*m.split("."), "__init__.py")).exists()}
    out = set()
    for m, tree in trees.items():
        bound = {}  # local name -> module it stands for
        out |= {
            f"{m}: {base}.{name}"
            for base, name in _names_taken(m, tree, trees, m in packages, bound)
            if _is_private(name)
        }
        for node in walk(tree):
            if isinstance(node, ast.Import):
                bound.update({a.asname: a.name for a in node.names if a.asname and a.name in trees})
            elif isinstance(node, ast.Attribute) and _is_private(node.attr):
                chain, value = [], node.value
                while isinstance(value, ast.Attribute):
                    chain, value = [value.attr, *chain], value.value
                if isinstance(value, ast.Name):
                    head = bound.get(value.id, value.id)
                    owner = ".".join([head, *chain])
                    if owner in trees and owner != m:
                        out.add(f"{m}: {owner}.{node.attr}")
    return sorted(out)


def _defined(body: list[ast.stmt]) -> set[str]:
    """Names a module's top level binds other than by importing them (in branches and ``try`` blocks too)."""
    out = set()
    for node in body:
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            out.add(node.name)
        elif isinstance(node, (ast.Assign, ast.AnnAssign, ast.AugAssign)):
            targets = node.targets if isinstance(node, ast.Assign) else [node.target]
            out |= {n.id for t in targets for n in ast.walk(t) if isinstance(n, ast.Name)}
        elif isinstance(node, (ast.If, ast.Try, ast.With, ast.For)):
            inner = [getattr(node, f, []) for f in ("body", "orelse", "finalbody")]
            out |= _defined([s for block in inner for s in block])
            out |= {s for h in getattr(node, "handlers", []) for s in _defined(h.body)}
    return out


def facade_imports(root: Path) -> list[str]:
    """``"importer: facade.name"`` for every name a module under ``root`` takes from another module that does not
    define it but imported it itself (``from facade import name`` or ``facade.name`` on a module it imported): the
    import points at a facade, not where the name lives."""
    trees = _modules(root)
    packages = {m for m in trees if (root.parent / Path(*m.split("."), "__init__.py")).exists()}
    defined = {m: _defined(t.body) for m, t in trees.items()}
    out = set()
    for m, tree in trees.items():
        bound = {}  # local name -> module it stands for
        for base, name in _names_taken(m, tree, trees, m in packages, bound):
            if name != "*" and name not in defined[base]:
                out.add(f"{m}: {base}.{name}")
        bound.update({a.asname: a.name for n in walk(tree) if isinstance(n, ast.Import) for a in n.names if a.asname})
        for node in walk(tree):
            if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id in bound:
                owner = bound[node.value.id]
                if owner in trees and f"{owner}.{node.attr}" not in trees and node.attr not in defined[owner]:
                    out.add(f"{m}: {owner}.{node.attr}")
    return sorted(out)


#: Private names allowed to cross a module, each with why (none: a name another module needs is public).
PRIVATE_IMPORTS_ALLOWED: set[str] = set()


def test_no_private_name_is_imported_across_modules():
    """A name another module uses is part of its module's interface: public, documented, in ``__all__``."""
    assert sorted(set(private_imports(PKG)) - PRIVATE_IMPORTS_ALLOWED) == []


#: The one door the pipeline has into the science (the pipeline rule above): it reads the claim words through
#: :mod:`tvtrack.results` and estimates through :mod:`tvtrack.montecarlo`, which re-export them for it.
PIPELINE_DOORS = ("tvtrack.results", "tvtrack.montecarlo")
#: Imports through a re-export still allowed, each with why.
FACADE_IMPORTS_ALLOWED = {
    "tvtrack.labels: tvtrack.verdicts.as_estimate",  # pending: labels.py is being pinned by its own tests first
}


def test_imports_point_where_names_live():
    """A module imports a name from the module that defines it, not through another that re-exports it."""
    offenders = [
        f
        for f in facade_imports(PKG)
        if f not in FACADE_IMPORTS_ALLOWED
        and not (f.startswith("tvtrack.pipeline.") and f.split(": ")[1].rsplit(".", 1)[0] in PIPELINE_DOORS)
    ]
    assert offenders == []


def reexports(root: Path) -> list[str]:
    """``"module: name"`` for every name a module under ``root`` imports from another of them and never uses itself
    (at most lists in ``__all__``): a re-export, there only for others to import through it."""
    trees = _modules(root)
    packages = {m for m in trees if (root.parent / Path(*m.split("."), "__init__.py")).exists()}
    out = []
    for m, tree in trees.items():
        used = {n.id for n in walk(tree) if isinstance(n, ast.Name)}
        for base, name, bound in _from_imports(m, ast.Module(body=tree.body, type_ignores=[]), m in packages):
            if base in trees and f"{base}.{name}" not in trees and bound not in used:
                out.append(f"{m}: {bound}")
    return sorted(out)


#: The modules that re-export names on purpose, each with why.
REEXPORTING_MODULES = {
    "tvtrack.filters": "a package's public API: the filters by role",
    "tvtrack.pipeline.viewer": "a package's public API: the viewer check",
    "tvtrack.results": "the pipeline's door into the claim words (the pipeline rule)",
    "tvtrack.montecarlo": "the statistics' public entry point: coverage and counts keep their import paths",
    "tvtrack.verdicts": "pending: as_estimate, which labels.py imports from here while it is pinned by its tests",
    "tvtrack.explore": "pending: explore.py is pinned by its tests before anything in it moves",
}


def test_no_module_re_exports_names_for_others_to_import_through_it():
    """A paper's study or any other module does not stand in for where its names live: only the entry points
    above re-export."""
    assert [r for r in reexports(PKG) if r.split(": ")[0] not in REEXPORTING_MODULES] == []


def test_the_seam_rules_see_planted_offences(tmp_path):
    pkg = tmp_path / "pkg"
    (pkg / "sub").mkdir(parents=True)
    (pkg / "__init__.py").write_text("")
    (pkg / "sub" / "__init__.py").write_text("from .b import helper\n")
    (pkg / "a.py").write_text("_hidden = 1\nshown = 2\n")
    (pkg / "sub" / "b.py").write_text(
        "from ..a import _hidden, shown\nfrom .. import a\nimport pkg.a as aa\n\n"
        "def helper():\n    return a._hidden + aa._hidden + shown\n"
    )
    (pkg / "c.py").write_text(
        "from .sub import helper\nfrom .sub.b import shown\nfrom .a import shown as s\nfrom .sub import b\n\nx = b.shown\n"
    )
    assert private_imports(pkg) == ["pkg.sub.b: pkg.a._hidden"]
    assert facade_imports(pkg) == ["pkg.c: pkg.sub.b.shown", "pkg.c: pkg.sub.helper"]  # b.shown: an attribute
    assert reexports(pkg) == ["pkg.c: helper", "pkg.c: s", "pkg.c: shown", "pkg.sub.b: _hidden", "pkg.sub: helper"]


#: "card" as a citation: the project's texts cite the paper itself (its equations, figures, sections) or say what is
#: this project's own choice; nothing points a reader at a document the repository does not ship.
_CARD_WORD = r"\bcards?\b|\bcard's\b"
_CARD_SCOPE, _CARD_SUFFIXES = ("lib/", "notebooks/", "docs/", "README.md"), (".py", ".md", ".ipynb", ".tmpl", ".html")
#: The site's UI cards (one box per paper run on the site's first page) are a layout element, not a citation.
_CARD_UI = ("lib/tvtrack/pipeline/site.py", "lib/tvtrack/pipeline/site_templates/")
#: Pending: phrases kept, with why, until what they wait for lands.
_CARD_PENDING: dict[str, str] = {}  # phrase -> why it waits (none waits now)


def _card_citations(root: Path, pending_phrases=_CARD_PENDING) -> list[str]:
    """``file:line: text`` for each "card"/"cards"/"card's" in the project's texts, less the UI and pending ones."""
    import re
    import subprocess

    files = subprocess.run(["git", "ls-files"], cwd=root, capture_output=True, text=True, check=True).stdout.split()
    pending = [re.compile(r"\s+".join(map(re.escape, p.split()))) for p in pending_phrases]
    hits = []
    for name in files:
        path = root / name
        if not name.startswith(_CARD_SCOPE) or not name.endswith(_CARD_SUFFIXES) or name.startswith(_CARD_UI):
            continue
        text = path.read_text(errors="replace")
        kept = [m.span() for p in pending for m in p.finditer(text)]  # a quoted phrase may wrap over lines
        # a register value whose code name is "card" (003's default motion and Fig. 2 law) is a name, not a
        # citation: renaming it would change every record's configurations, so it stays, quoted as code
        kept += [m.span() for m in re.finditer(r"([\"'`])card\1", text)]
        for m in re.finditer(_CARD_WORD, text, re.IGNORECASE):
            if not any(a <= m.start() < b for a, b in kept):
                line = text.count("\n", 0, m.start()) + 1
                hits.append(f"{name}:{line}: {text.splitlines()[line - 1].strip()[:100]}")
    return hits


def test_no_text_cites_the_paper_cards(tmp_path):
    """No docstring, comment, notebook, doc or README line cites the paper cards the project was built from: they
    are not shipped, so a reader could not look the citation up. The check sees a planted line, and passes the
    site's UI cards and a pending phrase (even wrapped over two lines)."""
    root = Path(tvtrack.__file__).resolve().parents[2]
    assert _card_citations(root) == []
    import subprocess

    subprocess.run(["git", "init", "-q", str(tmp_path)], check=True)
    (tmp_path / "lib/tvtrack/pipeline/site_templates").mkdir(parents=True)
    (tmp_path / "lib/a.py").write_text("x = 1\n# the gain (card 4.1)\n")
    (tmp_path / "lib/b.md").write_text(
        "The Card's default; amplitude, relative to the card's (10 px RMS\nin x, 20 px in y).\n"
    )
    (tmp_path / "docs.md").write_text("as in the cards\n")  # outside the scanned folders
    (tmp_path / "lib/c.py").write_text('MOTIONS = ("card", "sinusoids")  # a value\'s code name: `card`\n')
    (tmp_path / "lib/tvtrack/pipeline/site_templates/index.html").write_text('<div class="cards">\n')
    subprocess.run(["git", "add", "."], cwd=tmp_path, check=True)
    assert _card_citations(tmp_path, ["relative to the card's (10 px RMS in x, 20 px in y)"]) == [
        "lib/a.py:2: # the gain (card 4.1)",
        "lib/b.md:1: The Card's default; amplitude, relative to the card's (10 px RMS",
    ]
