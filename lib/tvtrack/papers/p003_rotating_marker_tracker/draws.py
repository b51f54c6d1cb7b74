"""Common random numbers of notebook 003's batched runs: trials
that share their draws across SIR values or markers, and blocks of trials drawing from one generator each.
"""

from __future__ import annotations

import numpy as np

__all__ = ["CommonNormal", "BlockNormal", "tile_rows", "generator_blocks", "stream_rng"]


class CommonNormal:
    """Standard normal draws shared by blocks of trials (common random numbers).

    Wraps a generator; ``standard_normal(shape)`` with ``shape[0] = blocks * n_common`` draws
    ``n_common`` rows and repeats them, so trial ``j n_common + i`` gets the draws of trial ``i``.
    Used to run one set of trials at several SIR values (or markers) on the same noise.
    """

    def __init__(self, rng: np.random.Generator, n_common: int):
        if n_common < 1:
            raise ValueError(f"parameter 'n_common' = {n_common}; it must be >= 1")
        self.rng = rng
        self.n_common = int(n_common)

    def standard_normal(self, shape, dtype=np.float64):
        shape = tuple(np.atleast_1d(shape))
        if shape[0] % self.n_common:
            raise ValueError(f"leading size {shape[0]} is not a multiple of n_common = {self.n_common}")
        z = self.rng.standard_normal((self.n_common, *shape[1:]), dtype=dtype)
        return np.tile(z, (shape[0] // self.n_common,) + (1,) * (len(shape) - 1))


class BlockNormal:
    """Standard normal draws made block by block from several sources (one per seed), concatenated
    along the leading axis; each source is a generator or a :class:`CommonNormal`."""

    def __init__(self, sources, block: int):
        self.sources = list(sources)
        self.block = int(block)

    def standard_normal(self, shape, dtype=np.float64):
        shape = tuple(np.atleast_1d(shape))
        if shape[0] != self.block * len(self.sources):
            raise ValueError(f"leading size {shape[0]} is not {len(self.sources)} blocks of {self.block}")
        return np.concatenate([g.standard_normal((self.block, *shape[1:]), dtype=dtype) for g in self.sources])


def tile_rows(a, n: int):
    """Repeat the leading axis of ``a`` until it has ``n`` rows (``n`` a multiple of its length)."""
    a = np.asarray(a)
    return np.tile(a, (n // a.shape[0],) + (1,) * (a.ndim - 1))


def generator_blocks(rng, n: int, n_common: int | None):
    """Split ``n`` trials into one consecutive block per generator (``rng`` one or a list), and check
    that ``n_common`` (trials sharing common random numbers; default: the whole block) divides a block.

    Returns ``(generators, trials per generator, n_common)``."""
    rngs = list(rng) if isinstance(rng, (list, tuple)) else [rng]
    n_block = n // len(rngs)
    n_common = n_block if n_common is None else int(n_common)
    if n % len(rngs) or n_common < 1 or n_block % n_common:
        raise ValueError(
            f"parameter 'n_common' = {n_common}; it must divide the trials per generator ({n} trials, "
            f"{len(rngs)} generators)"
        )
    return rngs, n_block, n_common


def stream_rng(stream: int, seed: int) -> np.random.Generator:
    """The seeded generator of one study stream: ``default_rng([stream, seed])`` (a stream per claim or figure)."""
    return np.random.default_rng([int(stream), int(seed)])
