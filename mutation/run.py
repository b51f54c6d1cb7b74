"""Mutation testing of the claim wiring (``make mutate``): mutmut over each module of ``mutation/targets.toml`` with
the narrow test selection that pins it, one module at a time, one process.

For each target the module tree is copied into a scratch folder (``mutation/work/<name>/``, ignored by git) laid out
as mutmut expects (``src/tvtrack``; the tests copied beside it, ``mutants/src`` a link to ``mutants/lib`` so that
``tests/conftest.py`` finds the package inside the checkout), mutmut runs with ``--max-children 1`` over that one
module (over the mutants of its ``functions`` only, where the target names them: the claim-value functions of a large
study module), and every surviving mutant's diff is read back and sorted: a reviewed equivalent
(``mutation/equivalent.txt``, one line each with its reason), a string-only change (a text no test reads: listed,
counted apart), or a survivor.

Usage::

    python mutation/run.py [--only NAME ...] [--ci] [--list] [--max-logic-survival SHARE]

``--ci`` runs each target's ``ci`` patterns only (the sampled subset a CI job can afford) and fails when a module's
logic survival exceeds 10 % (``--max-logic-survival`` sets another share, or the gate for a full run). Prints one
row per module and writes ``mutation/work/report.md`` with every survivor's diff. Exits 1 when a run fails or a
module is over the gate, 0 otherwise (without a gate survivors are a measurement, not an error). mutmut must be importable (``environment.txt`` pins it).
"""

from __future__ import annotations

import argparse
import fnmatch
import json
import os
import re
import shutil
import subprocess
import sys
import time
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
HERE = ROOT / "mutation"
WORK = HERE / "work"
KILLED = {"killed", "timeout", "segfault", "caught by type check"}
_STRING = re.compile(r"""(?:[rbuf]{0,2})("(?:\\.|[^"\\])*"|'(?:\\.|[^'\\])*')""", re.I)


def targets() -> dict[str, dict]:
    return tomllib.loads((HERE / "targets.toml").read_text())


def equivalents() -> dict[str, str]:
    """``{key: reason}`` from ``equivalent.txt`` (``key  # reason``; key as :func:`key` writes it)."""
    out = {}
    for line in (HERE / "equivalent.txt").read_text().splitlines():
        if line.strip() and not line.startswith("#"):
            k, _, why = line.rpartition("  # ")  # the last one: a mutated line may hold a comment of its own
            out[k.strip()] = why.strip()
    return out


def key(name: str, diff: str) -> str:
    """A mutant's key that survives renumbering: its function, then each removed and added line, stripped."""
    function = name.partition("__mutmut_")[0]
    lines = [ln for ln in diff.splitlines() if ln[:1] in "+-" and not ln.startswith(("+++", "---"))]
    return function + " | " + " => ".join(ln[0] + ln[1:].strip() for ln in lines)


def string_only(diff: str) -> bool:
    """True when the removed and added lines differ only inside string literals."""
    minus = [ln[1:] for ln in diff.splitlines() if ln.startswith("-") and not ln.startswith("---")]
    plus = [ln[1:] for ln in diff.splitlines() if ln.startswith("+") and not ln.startswith("+++")]
    blank = lambda ls: [_STRING.sub('""', ln).strip() for ln in ls]  # noqa: E731
    return bool(minus) and blank(minus) == blank(plus) and minus != plus


#: Arguments equal to their parameter's default in :mod:`tvtrack.verdicts` (Ordering's relation ">" and measure
#: "difference"): in a claims module a surviving mutant that only drops one builds the same rule (dropped from a
#: call where a positional argument follows, the next one takes its place and the rule refuses it: killed).
DEFAULTS = ('">"', '"difference"')


def drops_a_default(diff: str) -> bool:
    """True when the mutant only deletes an argument that equals its default (:data:`DEFAULTS`)."""
    squash = (
        lambda sign: "".join(  # noqa: E731
            ln[1:].replace(" ", "") for ln in diff.splitlines() if ln.startswith(sign) and not ln.startswith(sign * 3)
        )
    )
    minus, plus = squash("-"), squash("+")
    for arg in DEFAULTS:
        for form in (arg + ",", "," + arg):
            at = minus.find(form)
            while at >= 0:
                if minus[:at] + minus[at + len(form) :] in (plus, plus.rstrip(",")) or (
                    (minus[:at] + minus[at + len(form) :]).replace(",)", ")") == plus.replace(",)", ")")
                ):
                    return True
                at = minus.find(form, at + 1)
    return False


def prepare(name: str, target: dict) -> Path:
    """A fresh scratch folder for ``target``, with its mutmut configuration."""
    work = WORK / name
    shutil.rmtree(work, ignore_errors=True)
    ignore = shutil.ignore_patterns("__pycache__", "*.pyc")
    shutil.copytree(ROOT / "lib" / "tvtrack", work / "src" / "tvtrack", ignore=ignore)
    shutil.copytree(ROOT / "tests", work / "tests", ignore=ignore)
    (work / "mutants" / "lib").mkdir(parents=True)
    (work / "mutants" / "src").symlink_to("lib")
    module = "src/" + str(Path(target["module"]).relative_to("lib"))
    quote = lambda xs: "[" + ", ".join(f'"{x}"' for x in xs) + "]"  # noqa: E731
    args = ["-p", "no:xdist", "-p", "no:cacheprovider", "-q", *target.get("pytest_args", [])]
    config = (
        f'\n[tool.mutmut]\nsource_paths = ["src"]\nonly_mutate = ["{module}"]\n'
        f"pytest_add_cli_args = {quote(args)}\npytest_add_cli_args_test_selection = {quote(target['tests'])}\n"
    )
    (work / "pyproject.toml").write_text((ROOT / "pyproject.toml").read_text() + config)
    return work


def mutmut(work: Path, *args: str, code: str | None = None) -> subprocess.CompletedProcess:
    """``python -m mutmut ARGS`` (or ``python -c CODE ARGS``) in ``work``, with the checkout's ``lib`` off the path."""
    env = dict(os.environ, TVTRACK_NO_JIT="1", MPLBACKEND="Agg")
    paths = [p for p in env.get("PYTHONPATH", "").split(os.pathsep) if p and Path(p).resolve() != ROOT / "lib"]
    env["PYTHONPATH"] = os.pathsep.join(paths)
    cmd = [sys.executable, *(["-c", code] if code else ["-m", "mutmut"]), *args]
    return subprocess.run(cmd, cwd=work, env=env, capture_output=True, text=True)


_DIFFS = """
import contextlib, io, json, sys
from mutmut.__main__ import show
out = {}
for name in sys.argv[1:]:
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        show.callback(name)
    out[name] = buf.getvalue()
print(json.dumps(out))
"""


def _diffs(work: Path, names: list[str]) -> dict[str, str]:
    """Each mutant's diff, read in one process (``mutmut show`` costs seconds a call)."""
    if not names:
        return {}
    run = mutmut(work, *names, code=_DIFFS)
    if run.returncode != 0:
        raise RuntimeError(f"reading the mutants' diffs failed:\n{run.stderr[-2000:]}")
    return json.loads(run.stdout.strip().splitlines()[-1])


def selected(target: dict, ci: bool) -> list[str]:
    """The mutmut name patterns a run is restricted to: the target's ``ci`` sample under ``--ci``, else its
    ``functions`` (a module measured on the functions that compute claim values only), else none (every mutant)."""
    return list(target.get("ci", []) if ci else target.get("functions", []))


def measure(name: str, target: dict, ci: bool, equivalent: dict[str, str]) -> tuple[dict, list[str]]:
    """Run mutmut on one target; ``(counts, report lines)``."""
    work = prepare(name, target)
    patterns = selected(target, ci)
    start = time.monotonic()
    run = mutmut(work, "run", "--max-children", "1", *patterns)
    seconds = time.monotonic() - start
    if run.returncode != 0:
        tail = (run.stdout + run.stderr)[-3000:]
        raise RuntimeError(f"mutmut failed on {name} (exit {run.returncode}):\n{tail}")
    results = mutmut(work, "results", "--all", "true").stdout
    status = dict(ln.strip().rsplit(": ", 1) for ln in results.splitlines() if "__mutmut_" in ln)
    if patterns:  # only the selected mutants ran
        status = {m: v for m, v in status.items() if any(fnmatch.fnmatch(m, p) for p in patterns)}
    counts = {"mutants": len(status), "killed": 0, "equivalent": 0, "string-only": 0, "survived": 0, "seconds": seconds}
    report = [f"## {name} ({target['module']})", ""]
    alive = sorted(m for m, s in status.items() if s not in KILLED)
    counts["killed"] = len(status) - len(alive)
    diffs = _diffs(work, alive)
    for mutant in alive:
        state, diff = status[mutant], diffs[mutant]
        k = key(mutant, diff)
        if k in equivalent or (target.get("defaults_equivalent") and drops_a_default(diff)):
            kind = "equivalent"
        else:
            kind = "string-only" if string_only(diff) else "survived"
        counts[kind] += 1
        report += [f"### {mutant}: {state}, {kind}", "", f"key: `{k}`", "", "```diff", diff.strip(), "```", ""]
    return counts, report


def rate(c: dict) -> tuple[float, float]:
    """Survival among non-equivalent mutants, with and without the string-only ones."""
    real = c["mutants"] - c["equivalent"]
    logic = real - c["string-only"]
    return (c["survived"] + c["string-only"]) / max(real, 1), c["survived"] / max(logic, 1)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--only", nargs="*", default=None, help="target names (mutation/targets.toml)")
    parser.add_argument("--ci", action="store_true", help="each target's sampled CI subset only")
    parser.add_argument("--list", action="store_true", help="list the targets and exit")
    parser.add_argument(
        "--max-logic-survival",
        type=float,
        default=None,
        help="exit 1 when a module's logic survival exceeds this share (e.g. 0.10; --ci sets 0.10)",
    )
    args = parser.parse_args(argv)
    gate = args.max_logic_survival if args.max_logic_survival is not None else (0.10 if args.ci else None)
    table = targets()
    names = args.only or list(table)
    unknown = [n for n in names if n not in table]
    if unknown:
        print(f"error: --only {unknown[0]!r} is not a target; targets: {', '.join(table)}", file=sys.stderr)
        return 2
    if args.list:
        print("\n".join(f"{n}: {table[n]['module']}" for n in names))
        return 0
    equivalent, report = equivalents(), ["# Mutation report (generated by mutation/run.py)", ""]
    over = []
    print(f"{'module':<34} {'mutants':>7} {'killed':>6} {'equiv':>5} {'string':>6} {'surv':>5} {'rate':>6} "
          f"{'logic':>6} {'time':>6}")  # fmt: skip
    for name in names:
        if args.ci and not table[name].get("ci"):
            continue
        try:
            c, lines = measure(name, table[name], args.ci, equivalent)
        except RuntimeError as e:
            print(f"error: {e}", file=sys.stderr)
            return 1
        report += lines
        r_all, r_logic = rate(c)
        print(f"{table[name]['module']:<34} {c['mutants']:>7} {c['killed']:>6} {c['equivalent']:>5} "
              f"{c['string-only']:>6} {c['survived']:>5} {r_all:>6.1%} {r_logic:>6.1%} {c['seconds']:>5.0f}s",
              flush=True)  # fmt: skip
        if gate is not None and r_logic > gate:
            over.append(f"{table[name]['module']}: logic survival {r_logic:.1%} > {gate:.0%}")
    WORK.mkdir(exist_ok=True)
    (WORK / "report.md").write_text("\n".join(report) + "\n")
    print(f"survivors' diffs: {WORK / 'report.md'}")
    for line in over:
        print(f"error: {line}", file=sys.stderr)
    return 1 if over else 0


if __name__ == "__main__":
    sys.exit(main())
