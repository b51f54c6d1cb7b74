"""Parameter sweeps: a TOML spec -> many notebook runs -> ``summary.csv`` (+ a plot).

Spec format (see README, "Sweeps")::

    notebook = "004_laser_spot_prediction"   # name in notebooks/ or a path relative to the spec
    profile = "smoke"                          # optional base profile (default: paper defaults)
    repeats = 2                                # distinct seeds seed, seed+1, ... (default 1)
    [fixed]    n_trials = 20                   # set in every run
    [grid]     horizon_frames = [1, 2, 5]      # cartesian product
    [zip]      a = [1, 2]; b = [10, 20]        # varied together (equal lengths)
    [summary]  x = "horizon_frames"; y = "rms_px.value"; hue = "noise"
               # optional: xlabel, ylabel, title, xscale/yscale = "log"

Each run's directory is ``<sweep dir>/runs/<hash>``, the hash a stable digest of the notebook
and its parameters, so a sweep started again skips the runs already finished (resume). A run
that fails is recorded in its directory (``run.json`` with the error, ``error.txt``) and never
stops the others; the sweep exits non-zero if any run failed. A run's directory appears only
when the run has ended (see :mod:`tvtrack.pipeline.runner`).
"""

from __future__ import annotations

import csv
import hashlib
import itertools
import json
import os
import shutil
from concurrent.futures import ProcessPoolExecutor, as_completed
from dataclasses import dataclass, field
from multiprocessing import get_context
from pathlib import Path
from typing import Any

from ..executors import SchedulerError, connect_dask, parse_scheduler_address
from .interrupt import EXIT_INTERRUPTED, Interrupted, shielded_spawn, stop_pool, worker_init
from .paths import RUNS_DIR, writable_directory
from .preflight import UsageError, check_names, check_values_many, name_given
from .runner import read_toml, find_notebook, load_profile, read_run, remove_stale_temporaries, run_notebook

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
]

DASK_CONNECT_TIMEOUT_S = 8
_SPEC_KEYS = {"notebook", "profile", "repeats", "fixed", "grid", "zip", "summary", "seed"}


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


def load_spec(path: str | Path) -> SweepSpec:
    """Read and check a sweep spec; raises :class:`UsageError` naming the file and the bad key,
    a parameter the notebook does not define, or the TOML line with a syntax error."""
    path = Path(path)
    if not path.is_file():
        raise UsageError(f"no sweep spec {str(path)!r}")
    raw = read_toml(path)
    unknown = set(raw) - _SPEC_KEYS
    if unknown:
        raise UsageError(f"{path}: unknown keys {sorted(unknown)}; allowed: {sorted(_SPEC_KEYS)}")
    if "notebook" not in raw:
        raise UsageError(f"{path}: 'notebook' is required")
    nb_name = raw["notebook"]
    nb = find_notebook(path.parent / nb_name) if (path.parent / nb_name).exists() else find_notebook(nb_name)
    repeats = raw.get("repeats", 1)
    if not isinstance(repeats, int) or repeats < 1:
        raise UsageError(f"{path}: 'repeats' = {repeats!r}; it must be an integer >= 1")
    grid, zipped = raw.get("grid", {}), raw.get("zip", {})
    for key, values in {**grid, **zipped}.items():
        if not isinstance(values, list) or not values:
            raise UsageError(f"{path}: grid/zip entry {key!r} must be a non-empty list")
    if len({len(v) for v in zipped.values()}) > 1:
        raise UsageError(
            f"{path}: all [zip] lists must have the same length, got { {k: len(v) for k, v in zipped.items()} }"
        )
    overlap = (set(grid) & set(zipped)) | ((set(grid) | set(zipped)) & set(raw.get("fixed", {})))
    if overlap:
        raise UsageError(f"{path}: parameters {sorted(overlap)} appear in more than one of fixed/grid/zip")
    summary = raw.get("summary", {})
    if summary and not {"x", "y"} <= set(summary):
        raise UsageError(f"{path}: [summary] needs both 'x' and 'y'")
    for table, names in (
        ("[fixed]", raw.get("fixed", {})),
        ("[grid]", grid),
        ("[zip]", zipped),
        ("[summary] x/hue", [summary[k] for k in ("x", "hue") if k in summary]),
    ):
        check_names(nb, names, where=f"{path}: {table}: ")
    if "y" in summary and not isinstance(summary["y"], str):
        raise UsageError(f"{path}: [summary] y = {summary['y']!r}; it must be a metric name (a string)")
    return SweepSpec(
        name=path.stem,
        notebook=nb,
        profile=raw.get("profile"),
        repeats=repeats,
        fixed=dict(raw.get("fixed", {})),
        grid=dict(grid),
        zipped=dict(zipped),
        summary=summary,
    )


def run_hash(notebook: str, profile: str | None, parameters: dict) -> str:
    """Stable 12-hex-digit id of a run (independent of dict order)."""
    blob = json.dumps({"notebook": notebook, "profile": profile, "parameters": parameters}, sort_keys=True, default=str)
    return hashlib.sha256(blob.encode()).hexdigest()[:12]


def expand(spec: SweepSpec) -> list[RunSpec]:
    """All runs of a spec: grid product x zipped rows x repeats (seeds base, base+1, ...).

    The base seed is the spec's ``fixed.seed`` if given, else the profile's, else the
    notebook's default (read from the run's injected parameters, so it is set explicitly here
    to keep run ids stable: default 0 when nothing names it)."""
    base_params = {**load_profile(spec.notebook, spec.profile), **spec.fixed}
    base_seed = base_params.get("seed", _default_seed(spec.notebook))
    grid_keys = list(spec.grid)
    grid_rows = [dict(zip(grid_keys, combo)) for combo in itertools.product(*(spec.grid[k] for k in grid_keys))]
    zip_keys = list(spec.zipped)
    n_zip = len(next(iter(spec.zipped.values()))) if zip_keys else 1
    zip_rows = [{k: spec.zipped[k][i] for k in zip_keys} for i in range(n_zip)]
    runs = []
    for g in grid_rows:
        for z in zip_rows:
            for r in range(spec.repeats):
                params = {**spec.fixed, **g, **z, "seed": int(base_seed) + r}
                runs.append(
                    RunSpec(
                        spec.notebook.stem, spec.profile, params, run_hash(spec.notebook.stem, spec.profile, params)
                    )
                )
    return runs


def _default_seed(notebook: Path) -> int:
    """The ``seed`` default in the notebook's parameters cell."""
    import ast

    import nbformat

    nb = nbformat.read(notebook, as_version=4)
    for cell in nb.cells:
        if cell.cell_type == "code" and "parameters" in cell.metadata.get("tags", []):
            for node in ast.parse(cell.source).body:
                if isinstance(node, ast.Assign) and any(getattr(t, "id", None) == "seed" for t in node.targets):
                    return int(ast.literal_eval(node.value))
    return 0


def preflight(spec: SweepSpec, runs: list[RunSpec], where: str = "") -> None:
    """Check every distinct parameter set of the sweep with the notebook's validation cell (as ``tvtrack run``
    does) before any kernel starts; raise one :class:`UsageError` naming the first refused set and how many.

    The sets differ from each other by the swept values only (seeds aside), so one subprocess checks them all
    (:func:`.preflight.check_values_many`)."""
    base = load_profile(spec.notebook, spec.profile)
    distinct: dict[str, RunSpec] = {}
    for run in runs:
        key = json.dumps({k: v for k, v in run.parameters.items() if k != "seed"}, sort_keys=True, default=str)
        distinct.setdefault(key, run)
    sets = list(distinct.values())
    errors = check_values_many(spec.notebook, [{**base, **r.parameters} for r in sets])
    refused = [(r, e) for r, e in zip(sets, errors) if e]
    if refused:
        run, error = refused[0]
        given = {k: v for k, v in run.parameters.items() if k in {**spec.grid, **spec.zipped, **spec.fixed}}
        more = f" (and {len(refused) - 1} more of the {len(sets)} parameter sets)" if len(refused) > 1 else ""
        raise UsageError(f"{where}{spec.notebook.stem}: {name_given(error, given)}{more}; no run started")


def _execute(run: RunSpec, notebook_path: str, runs_dir: str) -> tuple[str, str, str | None, float]:
    """Worker: one run (top-level so process pools and Dask can pickle it). A pool worker told to stop
    (:class:`.interrupt.Interrupted`) exits once the run has ended its kernel and removed its folder."""
    try:
        outcome = run_notebook(
            notebook_path, Path(runs_dir) / run.run_id, run.parameters, run.profile, extra_record={"run_id": run.run_id}
        )
    except Interrupted:
        os._exit(EXIT_INTERRUPTED)
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


def run_sweep(
    spec_path: str | Path,
    jobs: int = 1,
    output: str | Path | None = None,
    executor: str = "local",
    scheduler: str | None = None,
    progress: bool = True,
) -> SweepSummary:
    """Run every run of a spec that has not finished yet, then write the summary.

    Parameters
    ----------
    jobs : int
        Parallel runs in the local process pool (>= 1).
    output : path, optional
        Sweep directory (default ``papermill_runs/<spec name>``).
    executor : {"local", "dask"}
        ``"dask"`` submits the runs to an existing Dask cluster at ``scheduler``.
    """
    if jobs < 1:
        raise UsageError(f"--jobs = {jobs}; it must be an integer >= 1")
    if executor == "dask" and not scheduler:
        raise UsageError("executor 'dask' needs --scheduler ADDRESS (e.g. tcp://127.0.0.1:8786)")
    if executor == "dask":
        check_scheduler_address(scheduler)
    spec = load_spec(spec_path)
    client = _dask_client(scheduler) if executor == "dask" else None  # before the preflight: fail fast
    runs = expand(spec)
    try:
        preflight(spec, runs, where=f"{spec_path}: ")
    except UsageError:
        if client is not None:
            client.close()
        raise
    sweep_dir = Path(output) if output else RUNS_DIR / spec.name
    runs_dir = sweep_dir / "runs"
    try:
        runs_dir.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise UsageError(f"cannot create the sweep directory {sweep_dir}: {exc.strerror}") from exc
    writable_directory(runs_dir, "sweep directory")
    remove_stale_temporaries(runs_dir)
    (sweep_dir / "spec.toml").write_bytes(Path(spec_path).read_bytes())
    todo = []
    for run in runs:
        record = read_run(runs_dir / run.run_id)
        if record and record.get("status") == "ok":
            continue
        if (runs_dir / run.run_id).exists():  # a failed run is tried again
            shutil.rmtree(runs_dir / run.run_id)
        todo.append(run)
    n_skipped = len(runs) - len(todo)

    from tqdm import tqdm

    bar = tqdm(total=len(runs), initial=n_skipped, desc=spec.name, disable=not progress, unit="run")
    failed = 0
    nb_path = str(spec.notebook)

    def tick(status: str) -> None:
        nonlocal failed
        failed += status != "ok"
        bar.update(1)
        bar.set_postfix(failed=failed, remaining=bar.total - bar.n)

    try:
        if executor == "dask":
            _run_on_dask(client, todo, nb_path, str(runs_dir), tick)
        elif jobs == 1:
            for r in todo:
                tick(_execute(r, nb_path, str(runs_dir))[1])
        else:
            _run_in_pool(jobs, todo, nb_path, str(runs_dir), tick)
    except KeyboardInterrupt as exc:
        bar.close()
        remove_stale_temporaries(runs_dir)
        done = sum((read_run(runs_dir / r.run_id) or {}).get("status") == "ok" for r in runs)
        raise KeyboardInterrupt(
            f"{spec.name}: {done} of {len(runs)} runs finished, the others cancelled; the same command resumes"
        ) from exc
    bar.close()
    csv_path, plot = collect_summary(sweep_dir, runs, spec.summary)
    records = [read_run(runs_dir / r.run_id) or {} for r in runs]
    n_ok = sum(rec.get("status") == "ok" for rec in records)
    n_failed = len(runs) - n_ok
    print(f"{spec.name}: {n_ok} ok, {n_failed} failed, {n_skipped} skipped (already done) -> {sweep_dir}")
    for r, rec in zip(runs, records):
        if rec.get("status") != "ok":
            print(f"  failed {r.run_id} {r.parameters}: {rec.get('error')}")
    return SweepSummary(sweep_dir, len(runs), n_skipped, n_ok, n_failed, csv_path, plot)


def _run_in_pool(jobs: int, todo: list[RunSpec], nb_path: str, runs_dir: str, tick) -> None:
    """The runs in a pool of ``jobs`` worker processes; Ctrl-C stops the pool (:func:`.interrupt.stop_pool`)."""
    threads = max(1, len(os.sched_getaffinity(0)) // jobs)  # jobs kernels at once share the cores
    pool = ProcessPoolExecutor(
        max_workers=jobs, mp_context=get_context("spawn"), initializer=worker_init, initargs=(threads,)
    )
    try:
        with shielded_spawn():  # workers are spawned by submit(): they start with Ctrl-C ignored
            futures = [pool.submit(_execute, r, nb_path, runs_dir) for r in todo]
        for fut in as_completed(futures):
            tick(fut.result()[1])
    except KeyboardInterrupt:
        stop_pool(pool)
        raise
    pool.shutdown()


def _run_on_dask(client, todo: list[RunSpec], nb_path: str, runs_dir: str, tick) -> None:
    """The runs on a Dask cluster; Ctrl-C cancels the runs not started yet (running ones finish on the
    workers, and their temporary folders, if a worker dies, are removed at the next start)."""
    from distributed import as_completed as dask_completed

    with client:
        futures = [client.submit(_execute, r, nb_path, runs_dir, pure=False) for r in todo]
        try:
            for fut in dask_completed(futures):
                tick(fut.result()[1])
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


def _flatten_metrics(metrics: dict) -> dict[str, Any]:
    """Scalars as they are; Estimate-like dicts as NAME.value / NAME.ci_low / NAME.ci_high;
    lists and other nested values are left out of the table."""
    out: dict[str, Any] = {}
    for name, value in metrics.items():
        if isinstance(value, (int, float, bool)) or value is None:
            out[name] = value
        elif isinstance(value, dict) and "value" in value:
            for key in ("value", "ci_low", "ci_high"):
                out[f"{name}.{key}"] = value.get(key)
    return out


def collect_summary(sweep_dir: Path, runs: list[RunSpec], summary: dict | None = None) -> tuple[Path, Path | None]:
    """Write ``summary.csv`` (one row per run: id, status, error, parameters, metrics, verdicts)
    and, if ``summary`` names ``x`` and ``y``, ``summary.png``."""
    rows = []
    for run in runs:
        run_dir = sweep_dir / "runs" / run.run_id
        rec = read_run(run_dir) or {"status": "missing"}
        row: dict[str, Any] = {
            "run_id": run.run_id,
            "status": rec.get("status"),
            "error": rec.get("error") or "",
            "runtime_s": rec.get("runtime_s"),
        }
        row.update(run.parameters)
        res = run_dir / "results.json"
        if res.is_file():
            data = json.loads(res.read_text())
            row.update(_flatten_metrics(data.get("metrics", {})))
            row.update({f"verdict {c['id']}": c["verdict"] for c in data.get("claims", [])})
        rows.append(row)
    columns: list[str] = []
    for row in rows:
        columns += [k for k in row if k not in columns]
    csv_path = sweep_dir / "summary.csv"
    with csv_path.open("w", newline="") as fh:
        writer = csv.DictWriter(fh, fieldnames=columns)
        writer.writeheader()
        for row in rows:
            writer.writerow({k: (json.dumps(v) if isinstance(v, (list, dict)) else v) for k, v in row.items()})
    plot = _summary_plot(sweep_dir, rows, summary) if summary else None
    return csv_path, plot


def _summary_plot(sweep_dir: Path, rows: list[dict], summary: dict) -> Path | None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    x, y, hue = summary["x"], summary["y"], summary.get("hue")
    ok = [r for r in rows if r.get("status") == "ok" and r.get(y) is not None and x in r]
    if not ok:
        return None
    groups: dict[Any, list[dict]] = {}
    for r in ok:
        groups.setdefault(r.get(hue) if hue else None, []).append(r)
    fig, ax = plt.subplots(figsize=(6, 4))
    base = y[: -len(".value")] if y.endswith(".value") else None
    for key, items in groups.items():
        xs = sorted({r[x] for r in items})
        mean = [np.mean([r[y] for r in items if r[x] == v]) for v in xs]
        label = f"{hue} = {key}" if hue else None
        (line,) = ax.plot(xs, mean, marker="o", label=label)
        if base and all(f"{base}.ci_low" in r for r in items):
            lo = [np.mean([r[f"{base}.ci_low"] for r in items if r[x] == v]) for v in xs]
            hi = [np.mean([r[f"{base}.ci_high"] for r in items if r[x] == v]) for v in xs]
            ax.fill_between(xs, lo, hi, alpha=0.2, color=line.get_color())
    ax.set_xscale(summary.get("xscale", "linear"))
    ax.set_yscale(summary.get("yscale", "linear"))
    ax.set_xlabel(summary.get("xlabel", x))
    ax.set_ylabel(summary.get("ylabel", y))
    ax.set_title(summary.get("title", sweep_dir.name))
    if hue:
        ax.legend()
    ax.grid(alpha=0.3)
    path = sweep_dir / "summary.png"
    fig.savefig(path, dpi=110, bbox_inches="tight")
    plt.close(fig)
    return path
