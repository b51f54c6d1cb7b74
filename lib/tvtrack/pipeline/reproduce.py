"""``make reproduce``: every paper notebook at paper scale, side by side, then the report.

Notebooks run in a process pool of ``jobs`` workers, longest first (by the runtime of their last
reproduce run, else a fixed order), each into ``papermill_runs/reproduce/<name>/`` (replacing the
earlier run only when the new one has ended). Another profile (``make reproduce PROFILE=smoke``) runs
into ``papermill_runs/reproduce-<profile>/`` with its own ``REPRODUCTION.md`` there, and leaves the
paper runs, the repository's ``REPRODUCTION.md`` and the README alone. A reproduce holds the lock of its
folder (:mod:`.lock`): a second one into the same folder is refused. Ctrl-C stops the notebooks,
keeps the earlier runs and exits with status 130 (:mod:`.interrupt`). So that ``jobs`` notebooks do not oversubscribe the
machine, each kernel gets ``cores // jobs`` BLAS/OpenMP threads; a notebook with an ``n_workers`` parameter gets
as many worker processes as the machine has usable cores, so that the notebook still running when the others have
ended does not keep to its share of the cores while the rest stand idle (while several run, the system shares the
cores between their workers; results do not depend on the number of workers). Kernel chatter on stderr (ipykernel's transport warning)
goes to ``papermill_runs/reproduce/kernels.log``, not to the terminal. ``scheduler`` sends every notebook's
explorations to a Dask cluster and ``max_replicates`` sets their sizing caps (:mod:`.scale`).

Started again, ``reproduce`` resumes: a notebook whose run in the folder finished (status ok) with the same
parameters from the same code (the commit and any uncommitted change to the code, recorded in its ``run.json``
as ``git_commit``, ``source_digest`` and ``parameters_digest``) is kept, said in one line; ``--force`` (``make
reproduce FORCE=1``) runs it again. A new run replaces the earlier one by renames, deleting only the files the
earlier run wrote (:mod:`.outputs`).
"""

from __future__ import annotations

import json
import os
import sys
from concurrent.futures import ProcessPoolExecutor, as_completed
from multiprocessing import get_context
from pathlib import Path

from .interrupt import shielded_spawn, stop_pool, worker_init
from .outputs import marked_files, replace_folder, replace_text
from .paths import PAPER_PROFILE, REPO_ROOT, RUNS_DIR, profile_name, reproduce_dir
from .preflight import UsageError
from .report import README_PATH, REPORT_PATH, check_readme, collect_runs, write_report
from .lock import LOCK_NAME, output_lock
from .runfiles import DamagedRun, load_run
from .runner import WriteFailed, list_notebooks, load_profile, remove_stale_temporaries, run_notebook
from .sweepfolder import clear_run, files_to_clear
from .scale import MIN_REPLICATES, check_caps, check_scheduler, explorer_runs, notebook_overrides, ran_on

__all__ = ["usable_cores", "reproduce", "source_identity", "parameters_digest", "finished_here", "check_records"]

# without a previous run to time, the heaviest notebooks start first
_DEFAULT_ORDER = ("002", "003", "004", "000", "001")


def usable_cores() -> int:
    """Cores this process may run on (``os.sched_getaffinity``)."""
    return len(os.sched_getaffinity(0))


def _last_runtime(folder: Path, name: str) -> float | None:
    try:
        return float(json.loads((folder / name / "run.json").read_text())["runtime_s"])
    except (OSError, ValueError, KeyError, TypeError):
        return None


def _order(notebooks: list[Path], folder: Path) -> list[Path]:
    def key(nb: Path):
        t = _last_runtime(folder, nb.stem)
        rank = next((i for i, p in enumerate(_DEFAULT_ORDER) if nb.stem.startswith(p)), len(_DEFAULT_ORDER))
        return (0, -t) if t is not None else (1, rank)

    return sorted(notebooks, key=key)


def _worker_init(threads: int, log_path: str) -> None:
    worker_init(threads)
    log = os.open(log_path, os.O_WRONLY | os.O_CREAT | os.O_APPEND, 0o644)
    os.dup2(log, 2)  # kernels inherit this stderr: their transport warnings land in the log


def _run_one(
    nb: str, profile: str | None, parameters: dict, folder: str, record: dict | None = None
) -> tuple[str, bool, str | None, float]:
    name = Path(nb).stem
    fresh = Path(folder) / f".new-{name}"
    if os.path.lexists(fresh):  # a run that a killed reproduce left before its rename (checked: check_records)
        remove_new_run(fresh)
    try:
        outcome = run_notebook(nb, fresh, parameters, profile=profile, progress=False, extra_record=record)
        _record_runs(fresh)
    except WriteFailed as exc:  # nothing kept; the earlier run of this notebook stays
        return name, False, str(exc), 0.0
    left = replace_folder(fresh, Path(folder) / name, legacy_run=True)  # of the earlier run, only what it wrote
    if left:
        print(
            f"{name}: the earlier run held {len(left)} file(s) its run.json does not list as tvtrack's (or a damaged "
            f"run.json); kept in {Path(left[0]).parent}"
        )
    return name, outcome.ok, outcome.error, outcome.runtime_s


def remove_new_run(fresh: Path, dry_run: bool = False) -> bool:
    """Remove a ``.new-<notebook>`` run folder (a run made but not yet put in place when reproduce was stopped) if
    it holds only the files its ``run.json`` lists (:func:`.sweepfolder.files_to_clear`).

    Parameters
    ----------
    fresh : Path
        The folder.
    dry_run : bool
        Only tell whether it would be removed.

    Returns
    -------
    bool
        Whether it is (or would be) removed. A folder holding anything else, or no sound ``run.json``, is not
        tvtrack's alone and is left as it is.
    """
    try:
        record = load_run(fresh) if fresh.is_dir() and not fresh.is_symlink() else None
        files = files_to_clear(fresh, record)  # no run.json: only an empty folder goes
        if not dry_run:
            clear_run(*files)
    except (UsageError, DamagedRun, OSError):
        return False
    return True


def source_identity() -> dict:
    """What the code of this clone is: ``{"git_commit": HEAD or None, "source_digest": ...}``, the digest of the
    commit and of any uncommitted change to the code, notebooks, profiles and pins (``None`` outside git)."""
    import hashlib
    import subprocess

    paths = ["lib", "notebooks", "papermill_runs/profiles", "environment.txt", "pyproject.toml"]
    try:
        head = subprocess.run(["git", "rev-parse", "HEAD"], cwd=REPO_ROOT, capture_output=True, text=True, timeout=30)
        diff = subprocess.run(
            ["git", "diff", "HEAD", "--", *paths], cwd=REPO_ROOT, capture_output=True, text=True, timeout=60
        )
    except (OSError, subprocess.SubprocessError):
        return {"git_commit": None, "source_digest": None}
    if head.returncode != 0 or diff.returncode != 0:
        return {"git_commit": None, "source_digest": None}
    digest = hashlib.sha256((head.stdout.strip() + "\n" + diff.stdout).encode()).hexdigest()[:16]
    return {"git_commit": head.stdout.strip(), "source_digest": digest}


def parameters_digest(nb: Path, profile: str | None, max_replicates: int | None = None) -> str:
    """A digest of a notebook's run parameters: its name, the profile, the profile's values and a sizing cap set
    for every notebook (the worker count and the Dask scheduler, which change no result, left out)."""
    import hashlib

    values = {**load_profile(nb, profile), **({"max_replicates": max_replicates} if max_replicates else {})}
    blob = json.dumps(
        {"notebook": nb.stem, "profile": profile_name(profile), "values": values},
        sort_keys=True,
        default=str,
    )
    return hashlib.sha256(blob.encode()).hexdigest()[:16]


def finished_here(folder: Path, nb: Path, identity: dict) -> bool:
    """Whether ``folder/<notebook>`` holds a successful run of the same parameters made from the same code
    (:func:`source_identity`): ``reproduce`` then keeps it instead of running it again. A damaged record is not
    finished (it is run again and replaced)."""
    try:
        record = load_run(folder / nb.stem)
    except DamagedRun:
        return False
    return (
        record is not None
        and record["status"] == "ok"
        and identity.get("source_digest") is not None
        and all(record.get(k) == v for k, v in identity.items())
    )


def check_records(folder: Path, names: list[str], to_run: list[str]) -> None:
    """Check, before any notebook runs, the run files the report will read as they are (those of ``names`` not in
    ``to_run``: :func:`.report.collect_runs`) and the file lists of the runs ``to_run`` will replace.

    Parameters
    ----------
    folder : Path
        The reproduce folder.
    names : list of str
        Every notebook the report shows.
    to_run : list of str
        The notebooks about to run (their earlier runs are replaced, not read).

    Raises
    ------
    UsageError
        One line naming the damaged file (:mod:`.runfiles`), the ``run.json`` whose ``files`` lists a path
        outside its run folder (:func:`.outputs.marked_files`), a run folder to replace that is a symbolic link
        (the new run is put in place by renames, which would replace the link), or a ``.new-<notebook>`` folder
        left in the way that holds more than a stopped reproduce's run (:func:`remove_new_run`).
    """
    collect_runs(folder, [name for name in names if name not in to_run])
    for name in to_run:
        fresh = folder / f".new-{name}"
        if os.path.lexists(fresh) and not remove_new_run(fresh, dry_run=True):
            raise UsageError(
                f"{fresh}: the place of {name}'s new run holds what no stopped reproduce wrote alone (files its "
                "run.json does not list, or no sound run.json); move it out of the way (tvtrack never deletes a file "
                "it did not write), then run reproduce again"
            )
        if (folder / name).is_symlink():
            raise UsageError(
                f"{folder / name}: a symbolic link (to {os.readlink(folder / name)}); its new run is put in place by "
                "renames, which would replace the link: remove the link, or move the run folder it leads to here"
            )
        if (folder / name).is_dir():
            marked_files(folder / name)


def _record_runs(run_dir: Path) -> None:
    """Add ``explorer_runs`` (configurations the explorer measured) to a finished run's ``run.json``."""
    path = run_dir / "run.json"
    try:
        record = json.loads(path.read_text())
        record["explorer_runs"] = explorer_runs(run_dir / "results.json")
        replace_text(path, json.dumps(record, indent=2, default=str))
    except OSError as exc:
        raise WriteFailed(f"cannot write {path}: {exc.strerror or exc}") from exc


def reproduce(
    profile: str | None = None,
    only: list[str] | None = None,
    jobs: int | None = None,
    runs_dir: Path = RUNS_DIR,
    force: bool = False,
    scheduler: str | None = None,
    max_replicates: int | None = None,
) -> int:
    """Run the notebooks (all, or ``only``) side by side, then write the report.

    Parameters
    ----------
    profile : str, optional
        Profile for every notebook (default: paper scale).
    only : list of str, optional
        Notebook names to run.
    jobs : int, optional
        Notebooks at once (default: :func:`usable_cores`).
    runs_dir : Path
        The folder holding ``reproduce/`` and ``reproduce-<profile>/`` (default ``papermill_runs/``).
    force : bool
        Run every notebook, also those whose run finished with these parameters at this commit
        (:func:`finished_here`; without it they are kept, said in one line).
    scheduler : str, optional
        Dask scheduler address (``tcp://host:port``) every notebook's explorations run on (default: this machine).
    max_replicates : int, optional
        Every notebook's sizing cap (at least 3; default: the profile's or the notebook's own).

    Returns
    -------
    int
        Exit status: 1 if any notebook failed (the others still run and are reported).

    Raises
    ------
    FolderBusy
        Another ``reproduce`` writes the same folder (one line naming its process id, exit status 2).
    """
    jobs = usable_cores() if jobs is None else jobs
    if jobs < 1:
        raise UsageError(f"--jobs = {jobs}; it must be an integer >= 1")
    if max_replicates is not None and max_replicates < MIN_REPLICATES:
        raise UsageError(f"--max-replicates = {max_replicates}; it must be an integer >= {MIN_REPLICATES}")
    if profile_name(profile) == PAPER_PROFILE:
        check_readme(README_PATH)  # the results block goes there at the end: a README it cannot go into stops now
    cluster = check_scheduler(scheduler) if scheduler is not None else None  # "" is a malformed address, not "here"
    notebooks = list_notebooks()
    if only:
        wanted = {Path(n).stem for n in only}
        unknown = wanted - {nb.stem for nb in notebooks}
        if unknown:
            raise UsageError(f"unknown notebooks {sorted(unknown)}; known: {', '.join(nb.stem for nb in notebooks)}")
        notebooks = [nb for nb in notebooks if nb.stem in wanted]
    folder = reproduce_dir(profile, runs_dir)
    notebooks = _order(notebooks, folder)
    jobs = min(jobs, len(notebooks))
    threads = max(1, usable_cores() // jobs)
    params = [notebook_overrides(nb, usable_cores(), scheduler, max_replicates) for nb in notebooks]
    if max_replicates is not None:
        check_caps(notebooks, [load_profile(nb, profile) for nb in notebooks], params, max_replicates)
    places = [ran_on(p, cluster) for p in params]
    # before the folder is made: an unknown profile stops here and leaves nothing
    digests = {nb.stem: parameters_digest(nb, profile, max_replicates) for nb in notebooks}
    folder.mkdir(parents=True, exist_ok=True)
    with output_lock(folder / LOCK_NAME, folder, "reproduce folder"):
        source = source_identity()
        identities = {nb.stem: {**source, "parameters_digest": digests[nb.stem]} for nb in notebooks}
        kept = [] if force else [nb for nb in notebooks if finished_here(folder, nb, identities[nb.stem])]
        check_records(folder, [nb.stem for nb in list_notebooks()], [nb.stem for nb in notebooks if nb not in kept])
        if kept:
            print(
                f"reproduce: kept {len(kept)} run{'s' * (len(kept) > 1)} finished at this commit "
                f"({str(source['git_commit'])[:10]}) with the same parameters: {', '.join(nb.stem for nb in kept)} "
                "(--force, or make reproduce FORCE=1, runs them again)"
            )
        setups = [
            (p, {**identities[nb.stem], "ran_on": where})
            for nb, p, where in zip(notebooks, params, places)
            if nb not in kept
        ]
        todo = [nb for nb in notebooks if nb not in kept]
        failures = _run_notebooks(todo, profile, folder, jobs, threads, setups) if todo else []
        paper = profile_name(profile) == PAPER_PROFILE
        path = write_report(
            folder,
            REPORT_PATH if paper else folder / "REPRODUCTION.md",
            notebooks=[nb.stem for nb in list_notebooks()],
            readme=README_PATH if paper else None,
        )
    print(f"wrote {path}" + (f"; failed: {', '.join(failures)}" if failures else ""))
    return 1 if failures else 0


def _used(run_dir: Path) -> str:
    """``"; 340 explorer runs on tcp://..."`` from a finished run's ``run.json`` (empty where it has none)."""
    try:
        record = json.loads((run_dir / "run.json").read_text())
    except (OSError, ValueError):
        return ""
    where = record.get("ran_on") or {}
    runs = record.get("explorer_runs")
    place = where.get("scheduler") if where.get("where") == "dask" else "this machine"
    return f"; {runs if runs is not None else 'no'} explorer runs on {place}"


def _run_notebooks(
    notebooks: list[Path], profile: str | None, folder: Path, jobs: int, threads: int, setups: list[tuple[dict, dict]]
) -> list[str]:
    """The notebooks in a pool of ``jobs`` workers, each with its (parameters, run record) of ``setups``; returns
    the names of those that failed."""
    from tqdm import tqdm

    remove_stale_temporaries(folder)
    log = folder / "kernels.log"
    failures = []
    pool = ProcessPoolExecutor(
        jobs, mp_context=get_context("spawn"), initializer=_worker_init, initargs=(threads, str(log))
    )
    bar = None
    try:
        futures = {}
        with shielded_spawn():  # before the progress bar's thread starts: no thread but this one takes a Ctrl-C
            for nb, (params, record) in zip(notebooks, setups):
                futures[pool.submit(_run_one, str(nb), profile, params, str(folder), record)] = nb.stem
        bar = tqdm(
            total=len(notebooks),
            desc=f"reproduce {profile_name(profile)} ({jobs} at once)",
            unit="notebook",
            disable=not sys.stderr.isatty(),
        )
        for fut in as_completed(futures):
            name, ok, error, runtime = fut.result()
            bar.write(f"{name}: {'ok' if ok else 'FAILED: ' + str(error)} ({runtime:.0f} s{_used(folder / name)})")
            if not ok:
                failures.append(name)
            bar.update(1)
    except KeyboardInterrupt as exc:
        stop_pool(pool)
        if bar is not None:
            bar.close()
        remove_stale_temporaries(folder)
        for nb in notebooks:  # only the new runs of this command's notebooks
            remove_new_run(folder / f".new-{nb.stem}")
        raise KeyboardInterrupt(f"reproduce: notebooks stopped; the runs finished before are kept in {folder}") from exc
    pool.shutdown()
    bar.close()
    return failures
