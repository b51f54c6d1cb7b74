"""One writer per output folder: a run, a sweep or a reproduce holds an exclusive lock while it writes.

The lock is an advisory ``flock`` on a small file (``<parent>/.<run name>.lock`` for a run,
``<folder>/.tvtrack.lock`` for a sweep or a reproduce) that holds the writer's process id and host. The
kernel ends a lock with its process, so a writer killed with SIGKILL never leaves a folder locked. A
second writer is refused with one line naming the holder's process id (:class:`FolderBusy`, a
:class:`.preflight.UsageError`: exit status 2) before it starts anything.
"""

from __future__ import annotations

import contextlib
import errno
import fcntl
import os
import socket
import time
from pathlib import Path
from typing import Iterator

from .preflight import UsageError

__all__ = ["FolderBusy", "output_lock", "remove_stale_locks", "written_by_tvtrack", "LOCK_NAME"]

LOCK_NAME = ".tvtrack.lock"


class FolderBusy(UsageError):
    """Another process writes the same output folder."""


def _holder(path: Path) -> str:
    """``"pid N on HOST"`` from the lock file (the holder writes it right after locking)."""
    for _ in range(20):
        try:
            pid, host = path.read_text().split()[:2]
            return f"pid {pid}" + ("" if host == socket.gethostname() else f" on {host}")
        except (OSError, ValueError):
            time.sleep(0.05)
    return "pid unknown"


@contextlib.contextmanager
def output_lock(lock_file: Path, target: Path, what: str = "output folder") -> Iterator[Path]:
    """Hold the exclusive lock ``lock_file`` while writing ``target``; removed on exit.

    Raises
    ------
    FolderBusy
        Another process holds the lock: one line naming ``target`` and the holder's process id.
    """
    lock_file = Path(lock_file)
    while True:
        try:
            fd = os.open(lock_file, os.O_RDWR | os.O_CREAT, 0o644)
        except OSError as exc:
            raise UsageError(f"cannot write the {what} {target}: {exc.strerror or exc}") from exc
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError as exc:
            os.close(fd)
            if exc.errno not in (errno.EWOULDBLOCK, errno.EAGAIN):
                raise
            raise FolderBusy(
                f"the {what} {target} is being written by another tvtrack ({_holder(lock_file)}); "
                "wait for it to end, or choose another -o"
            ) from None
        try:  # the holder before us may have removed the file between our open and our lock: lock the new one
            same = os.fstat(fd).st_ino == os.stat(lock_file).st_ino
        except FileNotFoundError:
            same = False
        if same:
            break
        os.close(fd)
    try:
        with contextlib.suppress(OSError):  # a full disk: the lock holds, only the holder's name is missing
            os.ftruncate(fd, 0)
            os.write(fd, f"{os.getpid()} {socket.gethostname()}\n".encode())
        yield lock_file
    finally:
        with contextlib.suppress(OSError):
            lock_file.unlink()
        os.close(fd)


def written_by_tvtrack(path: Path) -> bool:
    """A lock file tvtrack wrote: empty (killed before it wrote its holder) or ``"<pid> <host>"``."""
    try:
        words = path.read_text().split()
    except (OSError, UnicodeDecodeError):
        return False
    return not words or (len(words) == 2 and words[0].isdigit())


def remove_stale_locks(folder: Path) -> int:
    """Delete tvtrack's lock files in ``folder`` that nobody holds (left by a writer killed with SIGKILL: its
    ``flock`` ended with it, its file stays); returns how many. A lock file is taken before it is removed, so a
    live writer's lock is never touched, and a ``.*.lock`` file tvtrack did not write is left alone."""
    n = 0
    for path in Path(folder).glob(".*.lock"):
        if not written_by_tvtrack(path):
            continue
        try:
            fd = os.open(path, os.O_RDWR)
        except OSError:
            continue
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            path.unlink()
            n += 1
        except OSError:
            pass
        finally:
            os.close(fd)
    return n
