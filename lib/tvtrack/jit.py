"""Optional just-in-time compilation (numba) with a pure-NumPy fallback.

A compiled kernel is used only where a loop over many small arrays is dominated by NumPy's per-call
overhead (issue 30); every kernel has a NumPy twin that is always tested against it. Set the environment
variable ``TVTRACK_JIT=0`` to force the NumPy paths (numba absent has the same effect).
"""

from __future__ import annotations

import os
from collections.abc import Callable

__all__ = ["enabled", "njit"]

try:  # numba is pinned in environment.txt; a bare install without it still works
    import numba as _numba
except ImportError:  # pragma: no cover - exercised by the fallback tests via TVTRACK_JIT=0
    _numba = None


def enabled() -> bool:
    """Whether compiled kernels are used: numba importable and ``TVTRACK_JIT`` not ``"0"``."""
    return _numba is not None and os.environ.get("TVTRACK_JIT", "1") != "0"


def njit(fn: Callable) -> Callable:
    """``numba.njit(fn)`` (compiled lazily at the first call, no caching on disk) or ``fn`` itself without
    numba. Call the result only when :func:`enabled` (the NumPy twin otherwise)."""
    if _numba is None:
        return fn
    return _numba.njit(fn, cache=False, nogil=True, error_model="numpy")
