"""Optional just-in-time compilation (numba) with a pure-NumPy fallback.

A compiled kernel is used only where a loop is dominated by NumPy's per-call overhead or by scalar logic:
notebook 001's mode logic (``papers.p001_maneuver_occlusion_kf._track_modes_kernel``), the IMM on a scalar position
measurement (``filters._imm_kernel``, notebook 001's comparator), notebook 000's filter steps
(``papers.p000_dissector_ekf._kernels``), notebook 002's EM E-step, photon histogram and bootstrap variances
(``papers.p002_unified_location_em._kernels``, ``._photon_kernel``, ``._spread_kernel``) and notebook 003's gate crops
(``papers.p003_rotating_marker_tracker._frame_kernels``). Every kernel has a NumPy twin that the tests always run and
compare with it. Set the environment variable ``TVTRACK_NO_JIT=1`` to force the NumPy paths
(numba absent has the same effect).

Compiled code is kept on disk only where ``TVTRACK_JIT_CACHE`` names a folder (``tvtrack run``, ``sweep``,
``reproduce`` and ``edit`` set it to the clone's ``.jit-cache/`` for their kernels; the test session to a folder of
its own): then a kernel compiled by one process is loaded by the next instead of compiled again (001's mode
kernels take about 13 s to compile). The compiled code lives in a subfolder named by a digest of every source
file of the package (:func:`source_digest`), so an edit anywhere in ``tvtrack`` (a kernel, or a function a kernel
calls, which numba's own cache check does not see) compiles afresh. Without the variable, or where the folder
cannot be written, each process compiles at its first call (numba's in-tree cache is not used: it is not
writable on read-only installs).
"""

from __future__ import annotations

import hashlib
import os
import re
import shutil
import time
from collections.abc import Callable
from pathlib import Path

__all__ = ["available", "switched_off", "enabled", "njit", "prange", "cache_folder", "source_digest", "CACHE_ENV"]

#: the environment variable naming the folder compiled kernels are kept in (unset: none kept)
CACHE_ENV = "TVTRACK_JIT_CACHE"
#: a digest folder not used for this many seconds is removed when another one is made
_STALE_S = 86_400.0
#: the file tvtrack writes in every digest folder it makes: only folders holding it are ever removed
_MARKER = ".tvtrack-jit"
_DIGEST_NAME = re.compile(r"[0-9a-f]{16}")

try:  # numba is pinned in environment.txt; a bare install without it still works
    import numba as _numba
except ImportError:  # pragma: no cover - exercised by the fallback tests via TVTRACK_NO_JIT=1
    _numba = None


#: ``numba.prange`` (a loop numba may run on several threads when the function is compiled with
#: ``parallel=True``; plain ``range`` when the same source runs uncompiled) or ``range`` without numba.
prange = _numba.prange if _numba is not None else range


def available() -> bool:
    """Whether numba can be imported."""
    return _numba is not None


def switched_off() -> bool:
    """Whether ``TVTRACK_NO_JIT`` asks for the NumPy paths (set and not ``"0"``)."""
    return os.environ.get("TVTRACK_NO_JIT", "0") not in ("", "0")


def enabled() -> bool:
    """Whether compiled kernels are used: numba importable and not :func:`switched_off`."""
    return available() and not switched_off()


def source_digest(root: Path | None = None) -> str:
    """A digest (16 hex digits) of the relative path and bytes of every ``.py`` file under ``root`` (default: the
    ``tvtrack`` package): the name of the cache subfolder, so that compiled code is never reused across an edit."""
    root = Path(__file__).parent if root is None else Path(root)
    h = hashlib.sha256()
    for path in sorted(root.rglob("*.py")):
        h.update(path.relative_to(root).as_posix().encode() + b"\0" + path.read_bytes() + b"\0")
    return h.hexdigest()[:16]


def _prune(base: Path, keep: Path) -> None:
    """Remove the digest folders of ``base`` other than ``keep`` that no process used for a day.

    Only folders tvtrack made are candidates: named by a digest (16 hex digits), not a symbolic link, and holding
    the marker file :data:`_MARKER`. ``TVTRACK_JIT_CACHE`` may name a folder that holds other things (a user's
    cache folder), and nothing else in it is ever touched."""
    for other in base.iterdir():
        try:
            if (
                other != keep
                and _DIGEST_NAME.fullmatch(other.name)
                and not other.is_symlink()
                and (other / _MARKER).is_file()
                and time.time() - other.stat().st_mtime > _STALE_S
            ):
                shutil.rmtree(other, ignore_errors=True)
        except OSError:
            pass


def cache_folder() -> Path | None:
    """The folder this process keeps compiled kernels in (``$TVTRACK_JIT_CACHE/<source digest>``), made if
    needed; ``None`` when the variable is unset or the folder cannot be written (each process then compiles)."""
    base = os.environ.get(CACHE_ENV)
    if not base or _numba is None:
        return None
    folder = Path(base) / source_digest()
    try:
        folder.mkdir(parents=True, exist_ok=True)
        if not (folder / _MARKER).is_file():
            (folder / _MARKER).write_text("compiled kernels of tvtrack; removed after a day unused\n")
        os.utime(folder)
        _prune(Path(base), folder)
    except OSError:
        return None
    return folder if os.access(folder, os.W_OK) else None


_CACHE = cache_folder()
if _CACHE is not None:
    _numba.config.CACHE_DIR = str(_CACHE)  # numba's locator reads it when a cached function first compiles


def njit(fn: Callable, parallel: bool = False, error_model: str = "numpy", inline: bool = False) -> Callable:
    """``numba.njit(fn)`` (compiled lazily at the first call; kept on disk when :func:`cache_folder` is set) or
    ``fn`` itself without numba. ``parallel`` lets numba run ``prange`` loops on the process's threads; ``inline``
    has numba write ``fn`` into every compiled function that calls it (``inline="always"``: a step of a kernel
    split into functions compiles to the code of its statements in place, where a call LLVM does not inline costs
    the call and its arrays' reference counts). Call the result only when :func:`enabled` (the NumPy twin
    otherwise)."""
    if _numba is None:
        return fn
    return _numba.njit(
        fn,
        cache=_CACHE is not None,
        nogil=True,
        error_model=error_model,
        parallel=parallel,
        inline="always" if inline else "never",
    )
