"""Command line: ``python -m tvtrack {run, sweep, reproduce, report, site, edit, view, new}``.

A user error (a missing notebook, profile or spec, an unknown parameter or a bad value, an output
directory that exists or that another tvtrack is writing, an unreachable scheduler, a ``TVTRACK_KERNEL`` that names
no installed kernel spec, a notebook whose cells are not notebook cells) prints one line
``error: ...`` on stderr and exits with status 2 before any kernel starts; ``--debug`` shows the traceback
instead. Outputs that cannot be written during a run (a full disk, a read-only folder) print one line,
leave no temporary folder and exit with status 1. Ctrl-C ends the
running kernels, removes the temporary folders, prints one line ``interrupted: ...`` and exits with
status 130; the same command started again resumes (finished runs are kept).
"""

from __future__ import annotations

import argparse
import ast
import os
import signal
import sys
import time
from pathlib import Path

from .interrupt import EXIT_INTERRUPTED, quiet_cut_coroutines
from .paths import CONFIRM_ABOVE_RUNS, JIT_CACHE_DIR, REPO_ROOT, RUNS_DIR, writable_directory
from .preflight import NotebookBug, UsageError, check_names, check_values
from .runner import WriteFailed


class _Parser(argparse.ArgumentParser):
    """argparse with its errors on one line, like the rest of the command line."""

    def error(self, message: str):
        self.exit(2, f"error: {message} (see {self.prog} --help)\n")


def _parse_value(name: str, text: str):
    """A ``-p NAME VALUE`` value: a Python literal (number, string in quotes, list, bool), else the plain string.

    Raises
    ------
    UsageError
        ``text`` is Python but no value (``{[1]: 2}``: a list as a key) or nested too deeply to read.
    """
    try:
        return ast.literal_eval(text)
    except (ValueError, SyntaxError):
        return text
    except (TypeError, RecursionError, MemoryError) as exc:
        shown = text if len(text) <= 60 else text[:57] + "..."
        raise UsageError(
            f"-p {name} {shown!r}: not a value ({type(exc).__name__}); give a number, a string, a list or a bool"
        ) from None


def _positive_int(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        value = 0
    if value < 1:
        raise argparse.ArgumentTypeError(f"{text!r} is not an integer >= 1")
    return value


def _replicate_cap(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        value = 0
    if value < 3:
        raise argparse.ArgumentTypeError(f"{text!r} is not an integer >= 3 (the explorer's minimum of replicates)")
    return value


def _fresh_directory(path: Path) -> Path:
    """A run directory that does not exist yet and whose parent can be created."""
    if os.path.lexists(path):  # a symbolic link too, even one that leads nowhere or to itself
        raise UsageError(f"output directory {path} exists already; choose another -o or remove it")
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise UsageError(f"cannot create the output directory {path}: {exc.strerror}") from exc
    writable_directory(path.parent, "output directory's parent")
    return path


def _cmd_run(args) -> int:
    from .runner import find_notebook, load_profile, remove_stale_temporaries, run_notebook

    from .kernels import check_kernel_variable

    nb = find_notebook(args.notebook)
    params = {name: _parse_value(name, value) for name, value in args.parameter}
    check_names(nb, params)
    profile = load_profile(nb, args.profile)
    check_values(nb, {**profile, **params}, given=params)
    check_kernel_variable()
    out = _fresh_directory(
        Path(args.output)
        if args.output
        else RUNS_DIR / "runs" / f"{nb.stem}-{args.profile or 'paper'}-{time.strftime('%Y%m%d-%H%M%S')}"
    )
    remove_stale_temporaries(out.parent)
    try:
        outcome = run_notebook(nb, out, params, args.profile, progress=not args.quiet and sys.stderr.isatty())
    except KeyboardInterrupt as exc:
        raise KeyboardInterrupt(f"{nb.stem}: kernel ended, nothing written to {out}") from exc
    if outcome.ok:
        print(f"ok: {nb.stem} in {outcome.runtime_s:.1f} s -> {outcome.run_dir}")
        return 0
    print(f"FAILED: {nb.stem}: {outcome.error}\n  details: {outcome.run_dir / 'error.txt'}", file=sys.stderr)
    return 1


def _cmd_sweep(args) -> int:
    from .kernels import check_kernel_variable
    from .sweep import run_sweep

    if args.executor == "local":  # a Dask worker reads its own environment
        check_kernel_variable()
    summary = run_sweep(
        args.spec,
        jobs=args.jobs,
        output=args.output,
        executor=args.executor,
        scheduler=args.scheduler,
        progress=sys.stderr.isatty(),
        yes=args.yes,
    )
    return 0 if summary.n_failed == 0 else 1


def _cmd_reproduce(args) -> int:
    from .kernels import check_kernel_variable
    from .reproduce import reproduce

    check_kernel_variable()
    return reproduce(
        profile=args.profile,
        only=args.only,
        jobs=args.jobs,
        force=args.force,
        scheduler=args.scheduler,
        max_replicates=args.max_replicates,
    )


def _cmd_report(args) -> int:
    from .paths import PAPER_PROFILE, profile_name, reproduce_dir
    from .report import README_PATH, REPORT_PATH, check_readme, write_report

    folder = reproduce_dir(args.profile)
    if profile_name(args.profile) != PAPER_PROFILE and not folder.is_dir():
        raise UsageError(
            f"no runs at the {args.profile} profile ({folder} does not exist): "
            f"`make reproduce PROFILE={args.profile}` makes them (one notebook: "
            f"`python -m tvtrack reproduce --profile {args.profile} --only NAME`)"
        )
    if profile_name(args.profile) == PAPER_PROFILE:
        check_readme(README_PATH)
        path = write_report(folder, REPORT_PATH, readme=README_PATH)
    else:
        path = write_report(folder, writable_directory(folder, "report folder") / "REPRODUCTION.md")
    print(f"wrote {path}")
    return 0


def _cmd_site(args) -> int:
    from .site import build_site

    index = build_site(Path(args.runs), Path(args.output) if args.output else None, profile=args.profile)
    print(f"wrote {index} (open it in a browser; no network needed)")
    return 0


def _cmd_screenshots(args) -> int:
    from .screenshots import take_screenshots

    paths = take_screenshots(Path(args.runs), Path(args.output), claim=args.claim, recording=args.recording)
    print("wrote " + ", ".join(str(p) for p in paths))
    return 0


def _cmd_edit(args) -> int:
    import os
    import shutil

    from .edit import working_copy

    copy, written = working_copy(args.notebook, profile=args.profile, fresh=args.fresh)
    shown = os.path.relpath(copy)
    print(
        f"{'wrote' if written else 'kept (it holds your edits; --fresh replaces it)'} {shown}: "
        f"the {args.profile} profile, outputs in {os.path.relpath(copy.with_name(copy.stem + '-out'))}/"
    )
    if not args.lab:
        print(f"open it in JupyterLab (Run All), or: {Path(sys.executable).parent / 'jupyter'} lab {shown}")
        return 0
    from .kernels import install_clone_kernel

    install_clone_kernel()  # the clone's own kernel, in this environment, which the copy names
    jupyter = shutil.which("jupyter", path=str(Path(sys.executable).parent)) or "jupyter"
    os.execv(jupyter, lab_command(jupyter, copy))


def lab_command(jupyter: str, copy: Path) -> list[str]:
    """``jupyter lab COPY``, with ``--allow-root`` when this process runs as root (JupyterLab refuses root
    otherwise: a container's default user)."""
    return [jupyter, "lab", str(copy)] + (["--allow-root"] if os.geteuid() == 0 else [])


def _cmd_view(args) -> int:
    from .webview import serve

    return serve(
        args.target, host=args.host, port=args.port, grpc_port=args.grpc_port, open_browser=not args.no_browser
    )


def _cmd_new(args) -> int:
    from .new_paper import new_paper

    written = new_paper(args.number, args.name, title=args.title)
    for path in written:
        print(f"wrote {path}")
    stem = f"{args.number}_{args.name}"
    root = next(p for p in written if p.suffix == ".ipynb").parent.parent  # notebooks/<stem>.ipynb
    print(
        f"next: docs/adding_a_paper.md walks through these files and what to change; check the paper, in {root}, with\n"
        f"  python -m pytest -q tests/test_contract.py tests/papers/test_{stem}.py\n"
        f"  python -m tvtrack run {stem} --profile smoke -o /tmp/{stem}-smoke"
    )
    return 0


def _add_run(sub) -> None:
    """The ``run`` command: one notebook through papermill."""
    r = sub.add_parser("run", help="execute one notebook through papermill into its own directory")
    r.add_argument("notebook", help="name in notebooks/ (with or without .ipynb) or a path")
    r.add_argument(
        "-p",
        "--parameter",
        nargs=2,
        action="append",
        default=[],
        metavar=("NAME", "VALUE"),
        help="override a parameter (VALUE is a Python literal or a plain string)",
    )
    r.add_argument("--profile", default=None, help="parameter profile, e.g. 'smoke' (default: paper)")
    r.add_argument("-o", "--output", default=None, help="run directory (must not exist)")
    r.add_argument("-q", "--quiet", action="store_true", help="no progress bar")
    r.set_defaults(func=_cmd_run)


def _add_sweep(sub) -> None:
    """The ``sweep`` command: a TOML sweep spec."""
    s = sub.add_parser(
        "sweep",
        help="run a TOML sweep spec (grid x repeats) in a process pool",
        description=(
            "Runs every run of the spec not finished yet, after stating how many. A sweep of more than "
            f"{CONFIRM_ABOVE_RUNS:,} runs starts only with --yes. Ctrl-C stops it within seconds (no run starts after "
            "it); the same command resumes."
        ),
    )
    s.add_argument("spec", help="sweep spec TOML (see docs/contributing.md, 'Sweeps')")
    s.add_argument("--jobs", type=_positive_int, default=1, help="parallel runs (local executor)")
    s.add_argument("-o", "--output", default=None, help="sweep directory (default papermill_runs/<spec name>)")
    s.add_argument("--executor", choices=["local", "dask"], default="local")
    s.add_argument("--scheduler", default=None, help="Dask scheduler address, with --executor dask")
    s.add_argument(
        "--yes",
        action="store_true",
        help=f"start a sweep of more than {CONFIRM_ABOVE_RUNS:,} runs (refused without it)",
    )
    s.set_defaults(func=_cmd_sweep)


def _add_reproduce(sub) -> None:
    """The ``reproduce`` command: every notebook side by side."""
    rp = sub.add_parser("reproduce", help="run every notebook side by side, then write REPRODUCTION.md")
    rp.add_argument("--profile", default=None, help="profile for every notebook (default: paper)")
    rp.add_argument("--only", nargs="*", default=None, help="notebook names to run (default: all)")
    rp.add_argument("--jobs", type=_positive_int, default=None, help="notebooks at once (default: the usable cores)")
    rp.add_argument(
        "--force",
        action="store_true",
        help="run every notebook again, also those whose run finished at this commit with the same parameters "
        "(by default those are kept: the command resumes)",
    )
    rp.add_argument(
        "--scheduler",
        default=None,
        help="Dask scheduler address (tcp://HOST:PORT) every notebook's explorations run on (default: this machine)",
    )
    rp.add_argument(
        "--max-replicates",
        type=_replicate_cap,
        default=None,
        metavar="N",
        help="every notebook's sizing cap, at least 3 (default: the profile's, else the notebook's own)",
    )
    rp.set_defaults(func=_cmd_reproduce)


def _add_report(sub) -> None:
    """The ``report`` command: REPRODUCTION.md from existing outputs."""
    rep = sub.add_parser("report", help="rebuild REPRODUCTION.md from existing outputs")
    rep.add_argument(
        "--profile",
        default=None,
        help="report on papermill_runs/reproduce-PROFILE/ into its own REPRODUCTION.md (default: paper)",
    )
    rep.set_defaults(func=_cmd_report)


def _add_site(sub) -> None:
    """The ``site`` command: the offline HTML site."""
    st = sub.add_parser("site", help="build the offline HTML site from papermill_runs/ into papermill_runs/site/")
    st.add_argument("--runs", default=str(RUNS_DIR), help="runs directory (default papermill_runs/)")
    st.add_argument(
        "-o", "--output", default=None, help="site directory (default RUNS/site; replaced; not a symbolic link)"
    )
    st.add_argument(
        "--profile", default=None, help="show RUNS/reproduce-PROFILE/ in RUNS/site-PROFILE/ (default: the paper runs)"
    )
    st.set_defaults(func=_cmd_site)


def _add_screenshots(sub) -> None:
    """The ``screenshots`` command: the README's pictures of the site and a recording, from the paper runs."""
    sc = sub.add_parser(
        "screenshots", help="photograph the site of the paper runs and one recording for the README (Chromium)"
    )
    sc.add_argument("--runs", default=str(RUNS_DIR), help="runs directory holding reproduce/ (default papermill_runs/)")
    sc.add_argument(
        "-o",
        "--output",
        default=str(REPO_ROOT / "docs" / "screenshots"),
        help="folder of the PNG files (default: the clone's docs/screenshots, wherever the command is run from)",
    )
    sc.add_argument("--claim", default=None, help="claim whose page is shown (default: the first not reproduced)")
    sc.add_argument("--recording", default=None, help="notebook whose recording is shown (default: the last with one)")
    sc.set_defaults(func=_cmd_screenshots)


def _add_edit(sub) -> None:
    """The ``edit`` command: a working copy of a notebook."""
    e = sub.add_parser("edit", help="a working copy of a notebook at the smoke profile, to edit and run in JupyterLab")
    e.add_argument("notebook", help="name in notebooks/ (with or without .ipynb) or a path")
    e.add_argument("--profile", default="smoke", help="profile injected into the copy (default: smoke)")
    e.add_argument("--fresh", action="store_true", help="replace an existing working copy (your edits are lost)")
    e.add_argument("--lab", action="store_true", help="then start JupyterLab on it")
    e.set_defaults(func=_cmd_edit)


def _add_view(sub) -> None:
    """The ``view`` command: a run's recording in the web viewer."""
    from .webview import DEFAULT_GRPC_PORT, DEFAULT_HOST, DEFAULT_WEB_PORT

    v = sub.add_parser("view", help="serve a run's recording in the Rerun web viewer (Ctrl-C stops)")
    v.add_argument("target", help="run directory holding recording.rrd, or an .rrd file")
    v.add_argument("--host", default=DEFAULT_HOST, help=f"address to bind (default {DEFAULT_HOST}, this machine only)")
    v.add_argument("--port", type=int, default=DEFAULT_WEB_PORT, help=f"web viewer port (default {DEFAULT_WEB_PORT})")
    v.add_argument(
        "--grpc-port",
        type=int,
        default=DEFAULT_GRPC_PORT,
        help=f"port the recording is streamed from (default {DEFAULT_GRPC_PORT})",
    )
    v.add_argument("--no-browser", action="store_true", help="only print the URL")
    v.set_defaults(func=_cmd_view)


def _add_new(sub) -> None:
    """The ``new`` command: a new paper from the template."""
    n = sub.add_parser(
        "new",
        help="a new paper's package, notebook, tests and smoke profile from the template",
        description=(
            f"Writes, into the clone this tvtrack is imported from (the repository root of its lib/: {REPO_ROOT}), "
            "lib/tvtrack/papers/pNNN_NAME/, notebooks/NNN_NAME.ipynb, tests/papers/test_NNN_NAME.py and "
            "papermill_runs/profiles/NNN_NAME.smoke.toml, and adds a placeholder reference to CITATION.cff; "
            "it never overwrites a file. As written, the paper passes the lint, its tests and the paper contract, "
            "and runs at smoke size. docs/adding_a_paper.md walks through what to change."
        ),
    )
    n.add_argument("number", help="three digits, e.g. 005")
    n.add_argument("name", help="lower case, digits and '_', e.g. spot_tracker")
    n.add_argument("--title", default=None, help="the paper's title in a few words (default: the name)")
    n.set_defaults(func=_cmd_new)


def build_parser() -> argparse.ArgumentParser:
    p = _Parser(prog="python -m tvtrack", description=__doc__)
    p.add_argument("--debug", action="store_true", help="show the traceback of an error")
    sub = p.add_subparsers(dest="command", required=True, parser_class=_Parser)
    _add_run(sub)
    _add_sweep(sub)
    _add_reproduce(sub)
    _add_report(sub)
    _add_site(sub)
    _add_screenshots(sub)
    _add_edit(sub)
    _add_view(sub)
    _add_new(sub)
    return p


_stopped_by: list[int] = []  # the signal that stopped the command, if SIGTERM or SIGHUP


def _terminate(signum, frame):
    """SIGTERM or SIGHUP (``kill PID``, a closed terminal, a CI time-out) stops the command as Ctrl-C does: kernels
    ended, temporaries removed, locks released; the exit status is then 128 + the signal's number."""
    _stopped_by.append(signum)
    quiet_cut_coroutines()
    raise KeyboardInterrupt(f"stopped by {signal.Signals(signum).name}")


def program() -> int:
    """The ``tvtrack`` program (``python -m tvtrack`` and the installed script): :func:`main`, then Ctrl-C ignored.

    Once the command has done its work and printed its last line, a Ctrl-C during Python's shut-down would end
    the process by SIGINT, with no line and an exit status that says "interrupted" for a command that finished.
    :func:`main` itself leaves signals as they were, for callers that run a command in their own process."""
    code = None
    try:
        code = main()
    except KeyboardInterrupt:
        if code is None:  # not from the command (main handles its own), e.g. while Python read the arguments
            raise
    finally:
        signal.signal(signal.SIGINT, signal.SIG_IGN)
        for sig in (signal.SIGTERM, signal.SIGHUP):  # still stop the process, no longer through KeyboardInterrupt
            if signal.getsignal(sig) is _terminate:
                signal.signal(sig, signal.SIG_DFL)
    return code


def main(argv=None) -> int:
    args = build_parser().parse_args(argv)
    # the kernels this command starts keep their compiled code in the clone (tvtrack.jit), unless told otherwise
    os.environ.setdefault("TVTRACK_JIT_CACHE", str(JIT_CACHE_DIR))
    for sig in (signal.SIGTERM, signal.SIGHUP):
        if signal.getsignal(sig) is signal.SIG_DFL:  # a command run in-process by a caller keeps the caller's
            signal.signal(sig, _terminate)
    try:
        return args.func(args)
    except (UsageError, NotebookBug, WriteFailed) as exc:
        if args.debug:
            raise
        print(f"error: {exc}", file=sys.stderr)
        return 2 if isinstance(exc, UsageError) else 1
    except OSError as exc:
        if args.debug or not getattr(exc, "filename", None):
            raise
        print(
            f"error: cannot write {exc.filename}: {exc.strerror or exc} (--debug shows the traceback)", file=sys.stderr
        )
        return 1
    except KeyboardInterrupt as exc:
        if args.debug:
            raise
        quiet_cut_coroutines()  # one collected at exit would print after the line below
        print(f"interrupted: {str(exc) or args.command + ' stopped'}", file=sys.stderr)
        return 128 + _stopped_by[-1] if _stopped_by else EXIT_INTERRUPTED
