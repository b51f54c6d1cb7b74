"""Pickling that keeps every array's memory layout, for the runs a worker process sends back to the study's cache.

A plain pickle stores an array's values and gives back a C-contiguous array; a run's series are views in another
axis order (``numpy.moveaxis``), and a NumPy reduction over a view in one order and over a copy in another sums in
another order: the last bits of a mean differ. Here an array whose axes are a permutation of a dense layout is sent
in that layout and given back with the same strides, so a run computed in a worker and read in the parent gives the
numbers it gives in the worker, bit for bit (tests/papers/test_004_caching.py).
"""

from __future__ import annotations

import io
import pickle

import numpy as np

__all__ = ["dumps", "loads"]


def _restore(dense: np.ndarray, inverse: tuple) -> np.ndarray:
    """The array ``dense`` seen in its original axis order."""
    return dense.transpose(inverse)


def _same_layout(a: np.ndarray, b: np.ndarray) -> bool:
    """Whether ``a`` and ``b`` step through memory alike (axes of length 1 are never stepped through)."""
    return a.shape == b.shape and all(n == 1 or s == t for n, s, t in zip(a.shape, a.strides, b.strides))


class _LayoutPickler(pickle.Pickler):
    def reducer_override(self, obj):
        if type(obj) is not np.ndarray or obj.ndim < 2 or obj.flags.c_contiguous or obj.dtype.hasobject:
            return NotImplemented
        order = tuple(sorted(range(obj.ndim), key=lambda i: (obj.shape[i] > 1, abs(obj.strides[i])), reverse=True))
        dense = np.ascontiguousarray(obj.transpose(order))
        inverse = tuple(int(i) for i in np.argsort(order))
        if not _same_layout(dense.transpose(inverse), obj):
            return NotImplemented  # not a permutation of a dense layout (a broadcast or a strided slice)
        return _restore, (dense, inverse)


def dumps(obj) -> bytes:
    """``pickle.dumps(obj)`` keeping the layout of every array that is a permutation of a dense one."""
    buf = io.BytesIO()
    _LayoutPickler(buf, protocol=pickle.HIGHEST_PROTOCOL).dump(obj)
    return buf.getvalue()


def loads(data: bytes):
    """What :func:`dumps` stored."""
    return pickle.loads(data)
