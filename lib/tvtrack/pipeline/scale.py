"""``reproduce --scheduler ADDRESS --max-replicates N``: the explorations on a Dask cluster, with raised caps.

A notebook's ``scheduler`` parameter sends its explorations' configurations to the Dask scheduler at that
address (:func:`tvtrack.explore.executor_for`); the kernel itself, its figures and its report stay on this
machine. Under a scheduler a notebook with an ``n_workers`` parameter gets ``n_workers = 1`` (the cluster's
workers do the parallel work, and a Dask worker process may not start processes of its own), and
``max_replicates`` raises (or sets) every notebook's sizing cap. Each configuration is computed from its own
seed, so a run on a cluster gives what the same parameters give on this machine.

What a run used goes into its ``run.json``: ``ran_on`` (where its explorations ran: this machine, or the
scheduler's address with the workers and threads it had when the reproduce started) and ``explorer_runs``
(configurations the explorer measured, summed over the notebook's explorations, from ``results.json``).

:func:`decide_plan` reads a finished reproduce and lists, per undecided claim, the replicates its record
projects would decide it, the runs, and the core-hours from the exploration's own CPU seconds per replicate.
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

from ..executors import SchedulerError, connect_dask
from .preflight import UsageError, check_values_each, name_given, parameter_defaults

__all__ = [
    "MIN_REPLICATES",
    "SCHEDULER_TIMEOUT_S",
    "check_scheduler",
    "check_caps",
    "notebook_overrides",
    "ran_on",
    "explorer_runs",
    "decide_plan",
]

MIN_REPLICATES = 3  # the explorer's minimum of independent replicates
SCHEDULER_TIMEOUT_S = 8.0
_HINT = "start one with `dask scheduler` and `dask worker ADDRESS`, or leave out --scheduler"


def check_scheduler(address: str, timeout_s: float = SCHEDULER_TIMEOUT_S) -> dict[str, Any]:
    """Connect to the Dask scheduler at ``address`` once, before any notebook starts.

    Returns
    -------
    dict
        ``{"scheduler": address, "workers": int, "threads": int}`` as the scheduler reports them now.

    Raises
    ------
    UsageError
        One line naming ``--scheduler`` and the address: malformed, nothing listens there, no Dask scheduler
        answers within ``timeout_s`` seconds, or the scheduler has no worker.
    """
    try:
        client = connect_dask(address, timeout_s, hint=_HINT)
    except SchedulerError as exc:
        raise UsageError(f"--scheduler: {exc}") from None
    try:
        workers = client.scheduler_info().get("workers", {})
    finally:
        client.close()
    if not workers:
        raise UsageError(f"--scheduler: the Dask scheduler at {address!r} has no worker; start one with `dask worker`")
    threads = sum(int(w.get("nthreads", 1)) for w in workers.values())
    return {"scheduler": address, "workers": len(workers), "threads": threads}


def notebook_overrides(
    notebook: Path, threads: int, scheduler: str | None = None, max_replicates: int | None = None
) -> dict[str, Any]:
    """The parameters ``reproduce`` injects into ``notebook``: ``n_workers`` (``threads`` on this machine, 1 under
    a scheduler), ``scheduler`` and ``max_replicates`` where the notebook has those parameters."""
    defaults = parameter_defaults(notebook)
    out: dict[str, Any] = {}
    if "n_workers" in defaults:
        out["n_workers"] = 1 if scheduler else threads
    if scheduler and "scheduler" in defaults:
        out["scheduler"] = scheduler
    if max_replicates is not None and "max_replicates" in defaults:
        out["max_replicates"] = int(max_replicates)
    return out


def check_caps(notebooks: list[Path], profiles: list[dict], overrides: list[dict], max_replicates: int) -> None:
    """Each notebook's validation cell with its profile and ``--max-replicates``, before any notebook starts.

    Raises
    ------
    UsageError
        One line naming ``--max-replicates`` and the notebook whose validation refused the value.
    """
    asked = [
        (nb, extra, {**prof, **{k: v for k, v in extra.items() if k != "scheduler"}})
        for nb, prof, extra in zip(notebooks, profiles, overrides)
        if "max_replicates" in extra
    ]
    errors = check_values_each([(nb, [values]) for nb, _, values in asked]) if asked else []
    for (nb, extra, _), (error,) in zip(asked, errors):
        if error:
            raise UsageError(f"--max-replicates {max_replicates}: {nb.stem}: {name_given(error, extra)}")


def ran_on(overrides: dict[str, Any], cluster: dict[str, Any] | None) -> dict[str, Any]:
    """Where a notebook's explorations ran, for its ``run.json``."""
    if cluster and overrides.get("scheduler"):
        return {"where": "dask", **cluster}
    return {"where": "this machine", "workers": int(overrides.get("n_workers", 1))}


def explorer_runs(results_path: Path) -> int | None:
    """Configurations the explorer measured in one notebook run (every exploration once), from its
    ``results.json``; ``None`` where there is none or it records no exploration."""
    try:
        claims = json.loads(Path(results_path).read_text()).get("claims", [])
    except (OSError, ValueError, AttributeError):
        return None
    designs = {}
    for c in claims:
        design = ((c or {}).get("robustness") or {}).get("design") or {}
        if design.get("timing"):
            designs[json.dumps(design, sort_keys=True, default=str)] = design["timing"]
    if not designs:
        return None
    return sum(int(row.get("configurations", 0)) for timing in designs.values() for row in timing.values())


def _cpu_per_replicate(design: dict) -> float | None:
    """CPU seconds of one full-size replicate of an exploration: its ``replicates`` stage over its runs."""
    row = (design.get("timing") or {}).get("replicates") or {}
    n, cpu = row.get("configurations"), row.get("cpu_s")
    return float(cpu) / int(n) if n and cpu is not None else None


def decide_plan(folder: Path) -> list[dict[str, Any]]:
    """Per undecided claim of a reproduce folder: the sizing cap that would decide it and what it costs.

    Returns
    -------
    list of dict
        ``{notebook, claim, part, now, replicates, runs, cpu_s_per_replicate, core_hours}``: the replicates now
        and projected (the record's ``runs_to_decide``; ``None`` where no number of runs is projected to decide
        it), the runs they hold, the CPU seconds of one full-size replicate (the exploration's ``replicates``
        stage) and the core-hours of the replicates still to add (hours of one core).
    """
    rows = []
    for results in sorted(Path(folder).glob("*/results.json")):
        data = json.loads(results.read_text())
        for c in data.get("claims", []):
            rob = c.get("robustness") or {}
            per_rep = _cpu_per_replicate(rob.get("design") or {})
            for part, p in (rob.get("parts") or {}).items():
                r = (p or {}).get("runs_to_decide") or {}
                if p.get("verdict") != "undecided" or not r:
                    continue
                reps = r.get("replicates")
                hours = (reps - r["now"]) * per_rep / 3600 if reps and per_rep is not None else None
                rows.append(
                    {
                        "notebook": results.parent.name,
                        "claim": c.get("id"),
                        "part": part,
                        "now": r.get("now"),
                        "replicates": reps,
                        "runs": r.get("runs"),
                        "cpu_s_per_replicate": per_rep,
                        "core_hours": None if hours is None or not math.isfinite(hours) else hours,
                    }
                )
    return rows
