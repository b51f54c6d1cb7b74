"""Ctrl-C for runs that span processes: queued work cancelled, running kernels ended, temporaries removed.

A terminal's Ctrl-C sends SIGINT to the foreground process group: the ``tvtrack`` process and the pool
workers it started (Jupyter kernels run in sessions of their own and never see it). The workers are
started with SIGINT ignored (:func:`shielded_spawn`), so only the main process reacts: it cancels what is
queued, asks each worker to stop with SIGTERM (:func:`stop_pool`), and a worker that receives it raises
:class:`Interrupted` inside the run, which ends the run's kernel and removes its temporary folder
(:func:`tvtrack.pipeline.runner.run_notebook`) before the worker exits. The command line then prints one
line and exits with status 130 (:data:`EXIT_INTERRUPTED`, the shell's convention for SIGINT).
"""

from __future__ import annotations

import contextlib
import os
import signal
import time
import warnings

__all__ = [
    "EXIT_INTERRUPTED",
    "Interrupted",
    "shielded_spawn",
    "worker_init",
    "kernels_end_on_ctrl_c",
    "stop_pool",
    "end_children",
    "child_pids",
    "quiet_cut_coroutines",
]

EXIT_INTERRUPTED = 130
STOP_GRACE_S = 5.0
"""Seconds a worker gets to end its kernel and remove its temporary folder before it is killed."""


class Interrupted(KeyboardInterrupt):
    """Raised in a pool worker asked to stop (SIGTERM), so the run it executes cleans up like after Ctrl-C."""


@contextlib.contextmanager
def shielded_spawn():
    """Ignore SIGINT while worker processes are started in this block, so they inherit the ignored disposition;
    a Ctrl-C that arrives meanwhile is held and raised in this process when the block ends, never lost.

    Python installs its KeyboardInterrupt handler only where SIGINT is not ignored at start-up, so a spawned
    worker keeps ignoring Ctrl-C from the first instruction on (an initializer would leave a window in which
    a Ctrl-C prints the worker's traceback). SIGINT is also blocked in the calling thread for the block: the
    kernel then keeps a Ctrl-C pending instead of discarding it as ignored, and delivers it once the handler
    is back. Threads started in the block (a pool's manager and feeder threads) inherit the block, so they
    never take a Ctrl-C meant for this thread; the workers unblock it in :func:`worker_init`."""
    held = signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT})
    previous = signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)
        signal.pthread_sigmask(signal.SIG_SETMASK, held)  # a Ctrl-C held meanwhile is delivered now


_busy = False  # a pool worker inside a task that must clean up when stopped (:func:`running_a_task`)


@contextlib.contextmanager
def running_a_task():
    """Mark this pool worker busy: a SIGTERM from :func:`stop_pool` in this block ends the kernel and raises
    :class:`Interrupted` (the run removes its temporary folder); outside it the worker simply exits."""
    global _busy
    _busy = True
    try:
        yield
    finally:
        _busy = False


def quiet_cut_coroutines() -> None:
    """Silence, from now on in this process, Python's warning for a coroutine that was made but never awaited.

    A stop raises its exception wherever the process is, possibly between the moment jupyter_client makes its
    kernel-launch coroutine and the moment it awaits it. Python then prints ``RuntimeWarning: coroutine ...
    was never awaited`` (when the coroutine is collected, during the unwinding or at exit) on the user's
    terminal, before the command's one ``interrupted:`` line. After a stop such a coroutine is expected and
    harmless, so the handlers that raise the stop call this first; until a stop nothing is silenced."""
    warnings.filterwarnings("ignore", message=r"coroutine .* was never awaited", category=RuntimeWarning)


def _end_kernels_and_raise_interrupted(signum, frame):
    if not _busy:  # idle, waiting for a task or starting up: nothing to clean up, and no traceback to print
        os._exit(EXIT_INTERRUPTED)
    quiet_cut_coroutines()
    end_children()
    raise Interrupted()


THREAD_VARS = ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS", "NUMBA_NUM_THREADS")


def worker_init(threads: int | None = None) -> None:
    """Pool-worker initializer: SIGTERM (from :func:`stop_pool`) ends the worker's kernel and raises
    :class:`Interrupted` in the run; with ``threads``, the worker's kernels get that many BLAS/OpenMP threads
    (so that ``jobs`` kernels at once do not oversubscribe the cores)."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGINT})  # started blocked (:func:`shielded_spawn`)
    signal.signal(signal.SIGTERM, _end_kernels_and_raise_interrupted)
    if threads is not None:
        for var in THREAD_VARS:
            os.environ[var] = str(threads)


@contextlib.contextmanager
def kernels_end_on_ctrl_c():
    """In this block a Ctrl-C first kills this process's kernels, then raises ``KeyboardInterrupt``.

    Killing the kernel before the exception unwinds papermill spares the kernel's graceful shutdown (seconds,
    and a traceback the kernel prints on the user's terminal). Outside the main thread, or where SIGINT is
    not Python's default handler (ignored in a pool worker, or a caller's own), nothing changes."""
    import threading

    if (
        threading.current_thread() is not threading.main_thread()
        or signal.getsignal(signal.SIGINT) is not signal.default_int_handler
    ):
        yield
        return
    spare = child_pids()

    def end_kernels_and_raise(signum, frame):
        quiet_cut_coroutines()
        end_children(spare=spare)
        raise KeyboardInterrupt()

    signal.signal(signal.SIGINT, end_kernels_and_raise)
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, signal.default_int_handler)


def child_pids(pid: int | None = None) -> set[int]:
    """Process ids of every descendant of process ``pid`` (default: this one)."""
    import psutil

    try:
        return {c.pid for c in psutil.Process(pid).children(recursive=True)}
    except psutil.NoSuchProcess:
        return set()


def end_children(pid: int | None = None, spare: set[int] | frozenset = frozenset()) -> int:
    """Kill every descendant of process ``pid`` (default: this one) but those in ``spare`` (processes that were
    there before the run started, e.g. a caller's own Dask workers), e.g. a Jupyter kernel; returns how many.

    Kernels run in sessions of their own, so they are found by parentage, not by process group. They are
    killed outright (SIGKILL): a kernel asked to terminate mid-cell prints its own traceback, and what it
    was writing goes to a temporary folder that is removed anyway."""
    import psutil

    try:
        children = [c for c in psutil.Process(pid).children(recursive=True) if c.pid not in spare]
    except psutil.NoSuchProcess:
        return 0
    for child in children:
        with contextlib.suppress(psutil.NoSuchProcess):
            child.kill()
    psutil.wait_procs(children, timeout=2.0)
    return len(children)


def stop_pool(pool, grace_s: float = STOP_GRACE_S) -> None:
    """Stop a ``concurrent.futures.ProcessPoolExecutor`` now: queued runs cancelled, running ones asked to end.

    Each worker gets SIGTERM and ``grace_s`` seconds to end its kernel and remove its temporary folder; a
    worker (or a kernel) still there after that is killed."""
    import psutil

    processes = dict(getattr(pool, "_processes", None) or {})
    descendants = []
    for pid in processes:
        with contextlib.suppress(psutil.NoSuchProcess):
            descendants += psutil.Process(pid).children(recursive=True)
    pool.shutdown(wait=False, cancel_futures=True)
    for pid in processes:
        with contextlib.suppress(ProcessLookupError):
            os.kill(pid, signal.SIGTERM)
    deadline = time.monotonic() + grace_s
    for process in processes.values():
        process.join(max(0.0, deadline - time.monotonic()))
        if process.is_alive():
            process.kill()
            process.join(1.0)
    for child in descendants:
        with contextlib.suppress(psutil.NoSuchProcess):
            child.kill()
