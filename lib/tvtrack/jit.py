"""Optional just-in-time compilation (numba) with a pure-NumPy fallback.

A compiled kernel is used only where a loop is dominated by NumPy's per-call overhead or by scalar logic
(issue 30): notebook 001's mode logic (``papers.p001_maneuver_occlusion_kf._track_modes_kernel``), the IMM on a
scalar position measurement (``filters._imm_kernel``, notebook 001's comparator, issue 43) and notebook 002's EM
E-step (``papers.p002_unified_location_em._kernels``). Every kernel has a NumPy twin that the tests
always run and compare with it. Set the environment variable ``TVTRACK_NO_JIT=1`` to force the NumPy paths
(numba absent has the same effect). Compiled code is not cached on disk (numba's in-tree cache is not writable on
read-only installs): each process compiles at its first call (about 1 s a kernel).
"""

from __future__ import annotations

import os
from collections.abc import Callable

__all__ = ["available", "switched_off", "enabled", "njit", "prange"]

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


def njit(fn: Callable) -> Callable:
    """``numba.njit(fn)`` (compiled lazily at the first call, no caching on disk) or ``fn`` itself without
    numba. Call the result only when :func:`enabled` (the NumPy twin otherwise)."""
    if _numba is None:
        return fn
    return _numba.njit(fn, cache=False, nogil=True, error_model="numpy")
