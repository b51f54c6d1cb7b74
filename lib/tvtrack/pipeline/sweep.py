"""Parameter sweeps: a TOML spec -> many notebook runs -> ``summary.csv`` (+ a plot).

Spec format (see docs/contributing.md, "Sweeps")::

    notebook = "004_laser_spot_prediction"   # name in notebooks/ or a path relative to the spec
    profile = "smoke"                          # optional base profile (default: paper defaults)
    repeats = 2                                # distinct seeds seed, seed+1, ... (default 1)
                                               # (or a list `seed = [1, 2, 3]` in [grid], with repeats = 1)
    [fixed]    n_trials = 20                   # set in every run
    [grid]     horizon_frames = [1, 2, 5]      # cartesian product
    [zip]      a = [1, 2]; b = [10, 20]        # varied together (equal lengths)
    [summary]  x = "horizon_frames"; y = "rms_px.value"; hue = "noise"
               # optional: xlabel, ylabel, title, xscale/yscale = "log"

Each run's directory is ``<sweep dir>/runs/<hash>``, the hash a stable digest of the notebook
and its parameters, so a sweep started again skips the runs already finished (resume); two runs of one
spec never share a directory (a repeated value is refused), and a sweep holds the lock of its folder.
The summary's ``y`` is a metric the notebook writes, nested values by a dotted path (refused before any
run otherwise: :mod:`.summary`). A run
that fails is recorded in its directory (``run.json`` with the error, ``error.txt``) and never
stops the others; the sweep exits non-zero if any run failed. A run's directory appears only
when the run has ended (see :mod:`tvtrack.pipeline.runner`).

A sweep writes only into a folder that is new, empty or a sweep's (:func:`check_sweep_folder`: its marker lists
the files the sweep wrote there), and never deletes a file it did not write: a failed run tried again loses the
files its ``run.json`` lists, and a run folder holding anything else is refused in one line.
"""

from __future__ import annotations

import hashlib
import itertools
import json
import math
import os
from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait
from dataclasses import dataclass, field
from multiprocessing import get_context
from pathlib import Path

from ..executors import SchedulerError, connect_dask, parse_scheduler_address
from .interrupt import EXIT_INTERRUPTED, Interrupted, running_a_task, shielded_spawn, stop_pool, worker_init
from . import lean_imports
from .paths import CONFIRM_ABOVE_RUNS, RUNS_DIR
from .preflight import UsageError, check_names, check_values_many, name_given, refuse_unknown_keys
from .sweepcheck import (
    SEED_HOWTO,
    SEED_RULE,
    check_given_seeds,
    check_top_level,
    notebook_seed,
    seed_refused,
    spec_table,
)
from .sweepfolder import SWEEP_FILES, check_sweep_folder, clear_run, files_to_clear, held_sweep_folder, mark_sweep
from .runfiles import load_results, load_run
from .runner import (
    WriteFailed,
    load_profile,
    read_toml,
    remove_stale_temporaries,
    run_notebook,
)
from .summary import check_metric, check_metric_in, check_plot_values, check_summary_table, collect_summary

__all__ = [
    "SweepSpec",
    "RunSpec",
    "SweepSummary",
    "load_spec",
    "expand",
    "run_hash",
    "run_sweep",
    "collect_summary",
    "preflight",
    "check_scheduler_address",
    "check_sweep_folder",
]

DASK_CONNECT_TIMEOUT_S = 8
_SPEC_KEYS = {"notebook", "profile", "repeats", "fixed", "grid", "zip", "summary", "seed"}
_SUMMARY_KEYS = {"x", "y", "hue", "xlabel", "ylabel", "title", "xscale", "yscale"}


@dataclass(frozen=True)
class RunSpec:
    """One run of a sweep: the notebook, the full parameter overrides and the run's id."""

    notebook: str
    profile: str | None
    parameters: dict
    run_id: str


@dataclass
class SweepSpec:
    name: str
    notebook: Path
    profile: str | None
    repeats: int
    fixed: dict
    grid: dict
    zipped: dict
    summary: dict = field(default_factory=dict)
    path: Path | None = None


def load_spec(path: str | Path) -> SweepSpec:
    """Read and check a sweep spec.

    Raises
    ------
    UsageError
        One line naming the file and the bad key: a value of the wrong type, a parameter the notebook does not
        define, a seed that is no integer in [0, 2**63-1], a ``[summary]`` scale Matplotlib has not, or the TOML
        line with a syntax error.
    """
    path = Path(path)
    if not path.is_file():
        raise UsageError(f"no sweep spec {str(path)!r}")
    raw = read_toml(path)
    refuse_unknown_keys(raw, _SPEC_KEYS, f"{path}: ")
    nb, repeats = check_top_level(raw, path)
    fixed, grid, zipped, summary = (spec_table(raw, key, path) for key in ("fixed", "grid", "zip", "summary"))
    for key, values in {**grid, **zipped}.items():
        if not isinstance(values, list) or not values:
            raise UsageError(f"{path}: grid/zip entry {key!r} must be a non-empty list")
    if len({len(v) for v in zipped.values()}) > 1:
        raise UsageError(
            f"{path}: all [zip] lists must have the same length, got { {k: len(v) for k, v in zipped.items()} }"
        )
    overlap = (set(grid) & set(zipped)) | ((set(grid) | set(zipped)) & set(fixed))
    if overlap:
        raise UsageError(f"{path}: parameters {sorted(overlap)} appear in more than one of fixed/grid/zip")
    refuse_unknown_keys(summary, _SUMMARY_KEYS, f"{path}: [summary]: ")
    if summary and not {"x", "y"} <= set(summary):
        raise UsageError(f"{path}: [summary] needs both 'x' and 'y'")
    check_summary_table(summary, f"{path}: [summary] ")
    check_plot_values(summary, {**{k: [v] for k, v in fixed.items()}, **grid, **zipped}, f"{path}: [summary] ")
    if ("seed" in grid or "seed" in zipped) and repeats > 1:
        raise UsageError(
            f"{path}: a seed list in [grid]/[zip] and repeats = {repeats} both vary the seed; {SEED_HOWTO}"
        )
    check_given_seeds(fixed, grid, zipped, path)
    for table, names in (
        ("[fixed]", fixed),
        ("[grid]", grid),
        ("[zip]", zipped),
        ("[summary] x/hue", [summary[k] for k in ("x", "hue") if k in summary]),
    ):
        check_names(nb, names, where=f"{path}: {table}: ")
    if "y" in summary:
        check_metric(nb, summary["y"], where=f"{path}: [summary] y: ")
    return SweepSpec(path.stem, nb, raw.get("profile"), repeats, dict(fixed), dict(grid), dict(zipped), summary, path)


def count_runs(spec: SweepSpec) -> int:
    """How many runs the spec makes (grid product x zipped rows x repeats), without listing them."""
    n_zip = len(next(iter(spec.zipped.values()))) if spec.zipped else 1
    return math.prod(len(v) for v in spec.grid.values()) * n_zip * spec.repeats


def run_hash(notebook: str, profile: str | None, parameters: dict) -> str:
    """Stable 12-hex-digit id of a run (independent of dict order)."""
    blob = json.dumps({"notebook": notebook, "profile": profile, "parameters": parameters}, sort_keys=True, default=str)
    return hashlib.sha256(blob.encode()).hexdigest()[:12]


def expand(spec: SweepSpec) -> list[RunSpec]:
    """All runs of a spec: grid product x zipped rows x repeats (seeds base, base+1, ...).

    The base seed is the spec's ``fixed.seed`` if given, else the profile's, else the
    notebook's default (read from the run's injected parameters, so it is set explicitly here
    to keep run ids stable: default 0 when nothing names it). A ``seed`` list in ``[grid]`` or ``[zip]``
    gives each run its own seed (``repeats`` is then 1: :func:`load_spec`).

    Raises
    ------
    UsageError
        Two runs would be the same run (the same parameters, so the same directory): a value listed twice.
    """
    base_params = {**load_profile(spec.notebook, spec.profile), **spec.fixed}
    where = f"{spec.path or spec.name}: "
    base_seed = base_params["seed"] if "seed" in base_params else notebook_seed(spec.notebook, where)
    if seed_refused(base_seed):
        source = "[fixed]" if "seed" in spec.fixed else f"profile {spec.profile!r}" if spec.profile else "notebook"
        raise UsageError(f"{where}the base seed {base_seed!r} ({source}) is not {SEED_RULE}; no run started")
    grid_keys = list(spec.grid)
    grid_rows = [dict(zip(grid_keys, combo)) for combo in itertools.product(*(spec.grid[k] for k in grid_keys))]
    zip_keys = list(spec.zipped)
    n_zip = len(next(iter(spec.zipped.values()))) if zip_keys else 1
    zip_rows = [{k: spec.zipped[k][i] for k in zip_keys} for i in range(n_zip)]
    runs = []
    for g in grid_rows:
        for z in zip_rows:
            for r in range(spec.repeats):
                seed = {**g, **z}.get("seed", int(base_seed) + r)
                params = {**spec.fixed, **g, **z, "seed": seed}
                runs.append(
                    RunSpec(
                        spec.notebook.stem, spec.profile, params, run_hash(spec.notebook.stem, spec.profile, params)
                    )
                )
    last = max(runs, key=lambda r: r.parameters["seed"])
    if seed_refused(last.parameters["seed"]):
        raise UsageError(
            f"{where}repeats = {spec.repeats} from the base seed {base_seed} reach seed {last.parameters['seed']}, "
            f"and a seed is {SEED_RULE}: lower the base seed ([fixed] seed) or the repeats; no run started"
        )
    seen: dict[str, RunSpec] = {}
    for run in runs:
        if run.run_id in seen:
            raise UsageError(
                f"{where}two runs have the same parameters {run.parameters} (a value listed twice in "
                "[grid]/[zip]?); each run needs its own directory: remove the repeated value"
            )
        seen[run.run_id] = run
    return runs


def preflight(spec: SweepSpec, runs: list[RunSpec], where: str = "") -> None:
    """Check every distinct parameter set of the sweep with the notebook's validation cell (as ``tvtrack run``
    does) before any kernel starts; raise one :class:`UsageError` naming the first refused set and how many.

    The sets differ from each other by the swept values only, so one subprocess checks them all
    (:func:`.preflight.check_values_many`). Of the seeds (each an integer in [0, 2**63-1] already: :func:`expand`),
    the lowest and the highest are checked too, for a notebook whose own seed rule is narrower."""
    base = load_profile(spec.notebook, spec.profile)
    distinct: dict[str, RunSpec] = {}
    for run in runs:
        key = json.dumps({k: v for k, v in run.parameters.items() if k != "seed"}, sort_keys=True, default=str)
        distinct.setdefault(key, run)
    n_sets = len(distinct)  # the sweep's parameter sets; the seed checks below are not counted among them
    for run in (min(runs, key=lambda r: r.parameters["seed"]), max(runs, key=lambda r: r.parameters["seed"])):
        distinct.setdefault(run.run_id, run)
    sets = list(distinct.values())
    errors = check_values_many(spec.notebook, [{**base, **r.parameters} for r in sets])
    refused = [(r, e) for r, e in zip(sets, errors) if e]
    if refused:
        run, error = refused[0]
        given = {k: v for k, v in run.parameters.items() if k in {**spec.grid, **spec.zipped, **spec.fixed}}
        n_refused = sum(bool(e) for e in errors[:n_sets])
        more = f" (and {n_refused - 1} more of the {n_sets} parameter sets)" if n_refused > 1 else ""
        raise UsageError(f"{where}{spec.notebook.stem}: {name_given(error, given)}{more}; no run started")


def _execute(run: RunSpec, notebook_path: str, runs_dir: str) -> tuple[str, str, str | None, float]:
    """Worker: one run (top-level so process pools and Dask can pickle it): ``(run id, status, error,
    runtime)``, status ``"absent"`` when its outputs could not be written (nothing kept). A pool worker told
    to stop (:class:`.interrupt.Interrupted`) exits once the run has ended its kernel and removed its folder."""
    try:
        with running_a_task():
            outcome = run_notebook(
                notebook_path,
                Path(runs_dir) / run.run_id,
                run.parameters,
                run.profile,
                extra_record={"run_id": run.run_id},
            )
    except Interrupted:
        os._exit(EXIT_INTERRUPTED)
    except WriteFailed as exc:
        return run.run_id, "absent", str(exc), 0.0
    return run.run_id, outcome.status, outcome.error, outcome.runtime_s


@dataclass
class SweepSummary:
    sweep_dir: Path
    n_runs: int
    n_skipped: int
    n_ok: int
    n_failed: int
    summary_csv: Path
    plot: Path | None
    n_absent: int = 0


def run_sweep(
    spec_path: str | Path,
    jobs: int = 1,
    output: str | Path | None = None,
    executor: str = "local",
    scheduler: str | None = None,
    progress: bool = True,
    yes: bool = False,
) -> SweepSummary:
    """Run every run of a spec that has not finished yet, then write the summary.

    The sweep holds the lock of its folder (:mod:`.lock`) from its first write to its summary, and checks the folder
    again once it holds it (:func:`.sweepfolder.held_sweep_folder`): a second sweep into the same folder is refused
    with one line naming this one's process id.

    Parameters
    ----------
    jobs : int
        Parallel runs in the local process pool (>= 1).
    output : path, optional
        Sweep directory (default ``papermill_runs/<spec name>``).
    executor : {"local", "dask"}
        ``"dask"`` submits the runs to an existing Dask cluster at ``scheduler``.
    yes : bool
        Start a sweep of more than :data:`CONFIRM_ABOVE_RUNS` runs (refused without it, naming the count).

    Returns
    -------
    SweepSummary
        ``n_failed`` counts every run not ``ok`` (failed, or ``absent``: its outputs could not be written).
    """
    if jobs < 1:
        raise UsageError(f"--jobs = {jobs}; it must be an integer >= 1")
    if executor == "dask" and not scheduler:
        raise UsageError("executor 'dask' needs --scheduler ADDRESS (e.g. tcp://127.0.0.1:8786)")
    if executor == "dask":
        check_scheduler_address(scheduler)
    spec = load_spec(spec_path)
    n_runs = count_runs(spec)
    if n_runs > CONFIRM_ABOVE_RUNS and not yes:
        raise UsageError(
            f"{spec_path}: {n_runs:,} runs, more than {CONFIRM_ABOVE_RUNS:,}: add --yes to start them "
            "(Ctrl-C stops the sweep and the same command resumes it), or make the grid smaller"
        )
    sweep_dir = _sweep_folder(spec, output)
    client = _dask_client(scheduler) if executor == "dask" else None  # before the preflight: fail fast
    runs = expand(spec)
    # the pool's workers start (and import what a run needs) while the preflight checks the values: the
    # sweep's serial part shrinks by a worker's start-up; a refused sweep stops them before any run
    pool = _start_pool(jobs) if executor == "local" and jobs > 1 and len(runs) > 1 else None
    try:
        preflight(spec, runs, where=f"{spec_path}: ")
        with held_sweep_folder(sweep_dir, "-o" if output else "sweep folder") as runs_dir:  # checked again, locked
            todo = _runs_to_do(spec, spec_path, sweep_dir, runs)
            at_once = "on the Dask cluster" if executor == "dask" else f"{jobs if pool is not None else 1} at once"
            print(
                f"{spec.name}: {len(runs):,} runs, {len(runs) - len(todo):,} finished before, {len(todo):,} to run "
                f"({at_once}) -> {sweep_dir}",
                flush=True,
            )
            errors = _run_all(spec, spec_path, runs, todo, (executor, client, pool), runs_dir, progress)
            return _finish(spec, sweep_dir, runs, len(runs) - len(todo), errors)
    except BaseException as exc:
        if client is not None:
            client.close()
        if pool is not None:
            stop_pool(pool)
        if isinstance(exc, KeyboardInterrupt) and not str(exc):  # before the runs started, or while summing up
            raise KeyboardInterrupt(
                f"{spec.name}: sweep stopped; the runs finished so far are kept and the same command resumes"
            ) from exc
        raise
    finally:
        if pool is not None:
            pool.shutdown()


def _sweep_folder(spec: SweepSpec, output: str | Path | None) -> Path:
    """The sweep's folder (``output``, or ``papermill_runs/<spec name>``), checked (:func:`check_sweep_folder`)."""
    sweep_dir = Path(output) if output else RUNS_DIR / spec.name
    check_sweep_folder(sweep_dir, "-o" if output else "sweep folder")
    return sweep_dir


def _runs_to_do(spec: SweepSpec, spec_path, sweep_dir: Path, runs: list[RunSpec]) -> list[RunSpec]:
    """The runs not finished yet (a failed run's files are removed and it is tried again); refuses a damaged run
    file, a run folder holding files its run did not write, and a summary metric that the finished runs do not
    hold, before anything is removed."""
    runs_dir = sweep_dir / "runs"
    remove_stale_temporaries(runs_dir)
    mark_sweep(sweep_dir, set(SWEEP_FILES))  # the names the sweep writes, listed before any is written
    (sweep_dir / "spec.toml").write_bytes(Path(spec_path).read_bytes())
    todo, retried = [], []
    checked = False
    for run in runs:
        record = load_run(runs_dir / run.run_id)  # a damaged run file: one line naming it (:mod:`.runfiles`)
        if record and record["status"] == "ok":
            load_results(runs_dir / run.run_id, for_report=False)
            if "y" in spec.summary and not checked:  # the runs of one notebook hold the same metrics
                check_metric_in(
                    runs_dir / run.run_id / "results.json", spec.summary["y"], f"{spec_path}: [summary] y: "
                )
                checked = True
            continue
        if os.path.lexists(runs_dir / run.run_id):  # a failed run is tried again
            retried.append(files_to_clear(runs_dir / run.run_id, record))
        todo.append(run)
    for run_dir, files in retried:
        clear_run(run_dir, files)
    return todo


def _run_all(spec, spec_path, runs, todo, where: tuple, runs_dir: Path, progress: bool) -> dict[str, str]:
    """Execute ``todo`` (``where``: the executor's name, the Dask client or None, the local pool or None);
    returns ``{run id: why}`` for the runs whose outputs could not be written.

    The first run that finishes is checked for the ``[summary]`` metric (:func:`.summary.check_metric_in`): a
    path its results do not hold stops the sweep there (exit status 2), not after the last run."""
    from tqdm import tqdm

    executor, client, pool = where

    bar = tqdm(total=len(runs), initial=len(runs) - len(todo), desc=spec.name, disable=not progress, unit="run")
    failed, ok = 0, 0
    errors: dict[str, str] = {}
    nb_path = str(spec.notebook)
    y_checked = "y" not in spec.summary or len(todo) < len(runs)  # finished runs were checked (:func:`_runs_to_do`)

    def tick(result: tuple) -> None:
        nonlocal failed, ok, y_checked
        run_id, status, error, _ = result
        failed += status != "ok"
        ok += status == "ok"
        if status == "absent":
            errors[run_id] = error
        bar.update(1)
        bar.set_postfix(failed=failed, remaining=bar.total - bar.n)
        if status == "ok" and not y_checked:
            y_checked = True
            try:
                check_metric_in(runs_dir / run_id / "results.json", spec.summary["y"], f"{spec_path}: [summary] y: ")
            except UsageError as exc:
                bar.close()
                raise UsageError(f"{exc}; the sweep stopped after its first run (the same command resumes)") from None

    try:
        if executor == "dask":
            _run_on_dask(client, todo, nb_path, str(runs_dir), tick)
        elif pool is None:  # one job (or one run): in this process
            for r in todo:
                tick(_execute(r, nb_path, str(runs_dir)))
        else:
            _run_in_pool(pool, todo, nb_path, str(runs_dir), tick)
    except KeyboardInterrupt as exc:
        bar.close()
        remove_stale_temporaries(runs_dir)
        done = len(runs) - len(todo) + ok
        raise KeyboardInterrupt(
            f"{spec.name}: {done:,} of {len(runs):,} runs finished, the others cancelled; the same command resumes"
        ) from exc
    bar.close()
    return errors


def _finish(spec: SweepSpec, sweep_dir: Path, runs: list[RunSpec], n_skipped: int, errors: dict) -> SweepSummary:
    """Write the summary and print one line per run that is not ok."""
    runs_dir = sweep_dir / "runs"
    notes: list[str] = []  # why no plot was drawn, where Matplotlib could not draw it
    csv_path, plot = collect_summary(sweep_dir, runs, spec.summary, errors, notes)
    records = [load_run(runs_dir / r.run_id) or {"status": "absent", "error": errors.get(r.run_id)} for r in runs]
    n_ok = sum(rec.get("status") == "ok" for rec in records)
    n_absent = sum(rec.get("status") == "absent" for rec in records)
    absent = f", {n_absent} absent (outputs not written)" if n_absent else ""
    print(
        f"{spec.name}: {n_ok} ok, {len(runs) - n_ok - n_absent} failed, {n_skipped} skipped (already done)"
        f"{absent} -> {sweep_dir}"
    )
    for r, rec in zip(runs, records):
        if rec.get("status") != "ok":
            print(f"  {rec.get('status')} {r.run_id} {r.parameters}: {rec.get('error')}")
    if notes:
        print(f"  no summary.png: {notes[0]}")
    elif spec.summary and plot is None and n_ok:
        first = next(r for r, rec in zip(runs, records) if rec.get("status") == "ok")
        try:
            check_metric_in(runs_dir / first.run_id / "results.json", spec.summary["y"])
            print(f"  no summary.png: no finished run has both {spec.summary['x']!r} and {spec.summary['y']!r}")
        except UsageError as exc:
            print(f"  no summary.png: {exc}")
    return SweepSummary(sweep_dir, len(runs), n_skipped, n_ok, len(runs) - n_ok, csv_path, plot, n_absent)


def _warm_up() -> None:
    """A pool worker's first task: import what a run needs (papermill, through the runner) while the sweep's
    preflight runs (a sweep refused or stopped meanwhile ends the worker: :func:`.interrupt.running_a_task`)."""
    lean_imports.papermill()


def _start_pool(jobs: int) -> ProcessPoolExecutor:
    """A pool of ``jobs`` spawned workers, each started now with a warm-up task; Ctrl-C ignored in them (their
    kernels end through :func:`.interrupt.stop_pool`), each kernel given its share of the cores' threads."""
    threads = max(1, len(os.sched_getaffinity(0)) // jobs)  # jobs kernels at once share the cores
    pool = ProcessPoolExecutor(
        max_workers=jobs, mp_context=get_context("spawn"), initializer=worker_init, initargs=(threads,)
    )
    with shielded_spawn():  # workers are spawned by submit(): they start with Ctrl-C ignored
        for _ in range(jobs):
            pool.submit(_warm_up)
    return pool


def _run_in_pool(pool: ProcessPoolExecutor, todo: list[RunSpec], nb_path: str, runs_dir: str, tick) -> None:
    """The runs in the pool's workers (:func:`_start_pool`), handed over one per free worker, so that however many
    runs a sweep has, a Ctrl-C finds only the running ones to stop and none queued to start
    (:func:`.interrupt.stop_pool`)."""
    pending = iter(todo)
    in_flight: set = set()

    def submit_next() -> None:
        run = next(pending, None)
        if run is not None:
            in_flight.add(pool.submit(_execute, run, nb_path, runs_dir))

    try:
        # no shield here: the workers all started in :func:`_start_pool` (a submit spawns one only while the
        # pool has fewer than max_workers), and a thread started since (the progress bar's) could take a
        # Ctrl-C the shield holds for this thread and drop it as ignored
        for _ in range(pool._max_workers):
            submit_next()
        while in_flight:
            done, _ = wait(in_flight, return_when=FIRST_COMPLETED)
            for fut in done:
                in_flight.discard(fut)
                tick(fut.result())
                submit_next()
    except KeyboardInterrupt:
        stop_pool(pool)
        raise


def _run_on_dask(client, todo: list[RunSpec], nb_path: str, runs_dir: str, tick) -> None:
    """The runs on a Dask cluster; Ctrl-C cancels the runs not started yet (running ones finish on the
    workers, and their temporary folders, if a worker dies, are removed at the next start)."""
    from distributed import as_completed as dask_completed

    with client:
        futures = [client.submit(_execute, r, nb_path, runs_dir, pure=False) for r in todo]
        try:
            for fut in dask_completed(futures):
                tick(fut.result())
        except KeyboardInterrupt:
            client.cancel(futures)
            raise


def check_scheduler_address(address: str) -> tuple[str, int]:
    """``(host, port)`` of a Dask scheduler address such as ``tcp://127.0.0.1:8786`` or ``host:8786``.

    Raises
    ------
    UsageError
        The address has no port, a port that is not a number in [1, 65535], or another scheme than
        ``tcp``/``tls`` (one line naming the address; :func:`tvtrack.executors.parse_scheduler_address`)."""
    try:
        return parse_scheduler_address(address)
    except SchedulerError as exc:
        raise UsageError(str(exc)) from None


def _dask_client(scheduler: str, timeout_s: float = DASK_CONNECT_TIMEOUT_S):
    """A client of the running Dask scheduler at ``scheduler``, within ``timeout_s`` seconds.

    Raises
    ------
    UsageError
        One line naming the address: nothing listens there, or what listens does not answer as a Dask
        scheduler within the time limit (a web server, a database ...), with how to start one.
    """
    hint = "start one with `dask scheduler` (and `dask worker ADDRESS`), or use --executor local"
    try:
        return connect_dask(scheduler, timeout_s, hint=hint)
    except SchedulerError as exc:
        raise UsageError(str(exc)) from None
