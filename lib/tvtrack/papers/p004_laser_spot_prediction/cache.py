"""A dictionary of scenes and runs that keeps at most a stated number of bytes, dropping the least recently used.

The study keeps every rendered scene and every run of the methods between the calls of one exploration, so the
subset search reuses what the one-at-a-time and joint stages computed (:func:`.study.measure_batch`). At paper size
a scene is about 1.5 MB and a run of the methods about 7 MB; an exploration of some two thousand configurations
would hold gigabytes. Dropping an entry costs only its recomputation: a scene or run computed again from its key
gives the same numbers bit for bit, so what the cache holds never changes a result, only the time.
"""

from __future__ import annotations

import dataclasses
from collections import OrderedDict

import numpy as np

__all__ = ["BoundedCache", "nbytes"]

#: The study's default budget, bytes: about 500 paper-size runs; with two notebooks side by side on a machine of
#: 24 GiB the two stay well within its memory.
DEFAULT_BYTES = 4 * 2**30


def nbytes(obj, _depth: int = 0) -> int:
    """Bytes of the NumPy arrays ``obj`` holds, through dataclass fields, mappings and sequences (an array
    shared by two holders is counted twice: the estimate errs on the large side); other objects count 0."""
    if isinstance(obj, np.ndarray):
        return int(obj.nbytes)
    if _depth > 4:
        return 0
    if dataclasses.is_dataclass(obj) and not isinstance(obj, type):
        return sum(nbytes(getattr(obj, f.name), _depth + 1) for f in dataclasses.fields(obj))
    if isinstance(obj, dict):
        return sum(nbytes(v, _depth + 1) for v in obj.values())
    if isinstance(obj, (list, tuple)):
        return sum(nbytes(v, _depth + 1) for v in obj)
    return 0


class BoundedCache(dict):
    """A dictionary whose values' arrays (:func:`nbytes`) stay within ``max_bytes``: storing a value past it drops
    the least recently stored or read entries first (never the one just stored). The order of use is kept beside
    the dictionary, so reading an entry while iterating over it is safe.

    Parameters
    ----------
    max_bytes : int
        Budget in bytes (:data:`DEFAULT_BYTES` by default).
    """

    def __init__(self, max_bytes: int = DEFAULT_BYTES):
        super().__init__()
        self.max_bytes = int(max_bytes)
        self._used: OrderedDict = OrderedDict()  # key -> bytes, least recently used first

    @property
    def held(self) -> int:
        """Bytes held now (the sum of :func:`nbytes` of the values)."""
        return sum(self._used.values())

    def __getitem__(self, key):
        value = super().__getitem__(key)
        self._used.move_to_end(key)
        return value

    def get(self, key, default=None):
        return self[key] if key in self else default

    def __setitem__(self, key, value):
        super().__setitem__(key, value)
        self._used[key] = nbytes(value)
        self._used.move_to_end(key)
        while len(self._used) > 1 and self.held > self.max_bytes:
            del self[next(iter(self._used))]

    def __delitem__(self, key):
        super().__delitem__(key)
        self._used.pop(key, None)

    def update(self, other=(), **kw):
        for k, v in dict(other, **kw).items():
            self[k] = v

    def clear(self):
        super().clear()
        self._used.clear()
