"""Running the explorer's jobs (:mod:`tvtrack.explore`): each stage's configurations handed to the measurement in
process, as one batch, or on an executor (``concurrent.futures`` or a ``dask.distributed.Client``), guarded so that a
job reads only the register entries its claims declare; and the stage clock that keeps, per stage, the
configurations, wall seconds and CPU seconds (this process, an executor's workers and the pools a measurement
starts); and the pool of forked processes a measurement spreads a batch over, each with its share of the BLAS
threads."""

from __future__ import annotations

import os
import time
from typing import Any, Callable, Mapping, Sequence

from .conditions import Run
from .declared import takes_claims
from .register import guard as guarded_config

__all__ = ["StageClock", "blas_share", "cpu_seconds", "execute", "fork_pool"]


def _configs(measure: Callable, jobs: list[Run], depends: Mapping[str, Sequence[str]] | None) -> list[dict]:
    """The configurations handed to ``measure``: plain copies, or with ``depends`` guarded
    (:func:`tvtrack.register.guard`): a job may read only the entries its asked claims declare (a measurement
    that does not take ``claims`` is asked for every claim: the entries any claim declares)."""
    if depends is None:
        return [dict(j.config) for j in jobs]
    everything = {k for names in depends.values() for k in names}
    kw = takes_claims(measure)
    out = []
    for j in jobs:
        asked = j.claims if kw and j.claims is not None else None
        allowed = everything if asked is None else {k for c in asked for k in depends.get(c, ())}
        out.append(guarded_config(j.config, allowed))
    return out


def execute(measure: Callable, jobs: list[Run], batched: bool, executor: Any, depends=None) -> None:
    """Run ``jobs`` through ``measure``; a job's outputs are updated with what it measured (a confirmation at
    full size replaces the screened values of the claims it re-measures and keeps the others). With ``depends``
    each configuration is guarded (:func:`_configs`)."""
    if not jobs:
        return
    kw = takes_claims(measure)
    cfgs = _configs(measure, jobs, depends)
    if batched and executor is None:
        extra = {"claims": [j.claims for j in jobs]} if kw else {}
        outs = measure(cfgs, [j.seed for j in jobs], **extra)
        if len(outs) != len(jobs):
            raise ValueError(f"a batched measurement returned {len(outs)} results for {len(jobs)} configurations")
        for j, o in zip(jobs, outs):
            j.outputs.update(o)
        return
    if executor is None:
        for j, c in zip(jobs, cfgs):
            j.outputs.update(measure(c, j.seed, **({"claims": j.claims} if kw else {})))
        return
    # on an executor a batched measurement gets one configuration per task (it measures each as in a batch)
    wrap = (lambda x: [x]) if batched else (lambda x: x)
    futures = [
        executor.submit(measure, wrap(c), wrap(j.seed), **({"claims": wrap(j.claims)} if kw else {}))
        for j, c in zip(jobs, cfgs)
    ]
    try:
        for j, f in zip(jobs, futures):
            out = f.result()
            j.outputs.update(out[0] if batched else out)
    except BaseException:
        for f in futures:
            f.cancel()
        raise


def cpu_seconds() -> float:
    """CPU seconds of this process, of its children that ended and were waited for (a pool a measurement
    starts and shuts down) and of its live children with what each has waited for (an executor's workers, which
    the other clocks do not see until they end). A child counted live at one reading and ended at the next is
    counted in full at the next, so the difference of two readings charges each child's seconds between them
    once."""
    import psutil

    t = os.times()
    total = t.user + t.system + t.children_user + t.children_system
    for child in psutil.Process().children(recursive=True):
        try:
            c = child.cpu_times()
        except psutil.Error:  # ended meanwhile
            continue
        total += c.user + c.system + getattr(c, "children_user", 0.0) + getattr(c, "children_system", 0.0)
    return total


class StageClock:
    """Runs the stages' jobs and keeps where the exploration's time goes: per stage its configurations, wall
    seconds and CPU seconds (:func:`cpu_seconds`: this process and an executor's workers)."""

    def __init__(self, batched: bool, executor: Any, depends: Mapping[str, Sequence[str]] | None = None):
        self.batched, self.executor, self.depends = batched, executor, depends
        self.rows: dict[str, list] = {}

    def run(self, fn: Callable, jobs: list[Run], stage: str, guarded: bool = True) -> None:
        """Measure ``jobs`` (their configurations guarded by ``depends`` unless ``guarded`` is False)."""
        t0, c0 = time.perf_counter(), cpu_seconds()
        execute(fn, jobs, self.batched, self.executor, self.depends if guarded else None)
        row = self.rows.setdefault(stage, [0, 0.0, 0.0])
        row[0] += len(jobs)
        row[1] += time.perf_counter() - t0
        row[2] += max(0.0, cpu_seconds() - c0)

    def table(self) -> dict:
        return {
            k: {"configurations": n, "wall_s": round(w, 3), "cpu_s": round(c, 3)}
            for k, (n, w, c) in self.rows.items()
            if n
        }


def blas_share(workers: int) -> int:
    """BLAS/OpenMP threads for each of ``workers`` processes on this process's usable cores: ``cores // workers``,
    at least 1. Each worker keeping to its share keeps the machine from running more threads than cores: on two
    busy cores, OpenBLAS's default of a thread per core made a 4000 x 101 SVD about five times slower."""
    return max(1, len(os.sched_getaffinity(0)) // max(1, int(workers)))


def _limit_blas(threads: int) -> None:
    """Pool initializer: at most ``threads`` BLAS/OpenMP threads in this process (never more than it had: a
    limit the parent was given, e.g. by ``tvtrack reproduce``, stands)."""
    from threadpoolctl import threadpool_info, threadpool_limits

    have = [i["num_threads"] for i in threadpool_info()]
    if have and threads < max(have):
        threadpool_limits(limits=threads)


def _exit_with_parent(poll_s: float = 1.0) -> None:
    """End this process when the one that started it has ended: a forked worker whose kernel was stopped (Ctrl-C, a
    kernel killed after its grace period) would otherwise wait on its task queue for ever. A daemon thread checks the
    parent's pid every ``poll_s`` seconds."""
    import threading

    parent = os.getppid()

    def watch() -> None:
        while os.getppid() == parent:
            time.sleep(poll_s)
        os._exit(1)

    threading.Thread(target=watch, name="tvtrack-parent-watch", daemon=True).start()


def _start_worker(threads: int) -> None:
    """:func:`fork_pool`'s initializer: a worker that ends with its parent, with at most ``threads`` BLAS threads."""
    _exit_with_parent()
    _limit_blas(threads)


def fork_pool(workers: int):
    """A ``ProcessPoolExecutor`` of ``workers`` forked processes (they inherit the caller's caches), each limited to
    :func:`blas_share` BLAS threads and ending with the process that started it, for a measurement that spreads a
    batch over processes. Results do not depend on the limit (each process computes whole configurations)."""
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor

    return ProcessPoolExecutor(
        workers,
        mp_context=multiprocessing.get_context("fork"),
        initializer=_start_worker,
        initargs=(blas_share(workers),),
    )
