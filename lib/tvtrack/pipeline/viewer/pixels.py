"""What a screenshot shows: coloured (not grey) pixels, their dominant colours, and the pixels an overlay
draws (:class:`OverlayPixels`, measured by :meth:`tvtrack.pipeline.viewer.HeadlessViewer.overlay_pixels`).
Re-exported by :mod:`tvtrack.pipeline.viewer`.
"""

from __future__ import annotations

import io
from dataclasses import dataclass

import numpy as np

__all__ = ["coloured_mask", "dominant_colours", "OverlayPixels", "decode_png"]


def coloured_mask(image: np.ndarray, min_chroma: int = 60) -> np.ndarray:
    """Pixels whose colour is clearly not grey.

    Parameters
    ----------
    image : ndarray, shape (H, W, 3), uint8
        RGB screenshot.
    min_chroma : int
        Threshold on ``max(R,G,B) - min(R,G,B)``, in 8-bit levels (0..255). Grey images,
        text, axes and grid lines stay below ~20; the viewer's palette colours are above 80.

    Returns
    -------
    ndarray of bool, shape (H, W)
    """
    rgb = np.asarray(image, dtype=np.int16)[..., :3]
    return (rgb.max(axis=-1) - rgb.min(axis=-1)) >= min_chroma


def dominant_colours(image: np.ndarray, mask: np.ndarray, n: int = 3, quantum: int = 32) -> list[tuple]:
    """The ``n`` most frequent colours among ``image[mask]``, each channel rounded to the middle
    of a ``quantum``-wide bin, as ``((r, g, b), count)`` (for messages, not for asserting)."""
    pixels = np.asarray(image)[..., :3][mask].astype(np.int32)
    if pixels.size == 0:
        return []
    binned = (pixels // quantum) * quantum + quantum // 2
    colours, counts = np.unique(binned, axis=0, return_counts=True)
    order = np.argsort(-counts)[:n]
    return [(tuple(int(c) for c in colours[i]), int(counts[i])) for i in order]


def decode_png(png: bytes) -> np.ndarray:
    """A PNG image as an RGB array.

    Parameters
    ----------
    png : bytes
        The encoded image (a viewer's screenshot).

    Returns
    -------
    numpy.ndarray
        ``uint8`` pixels, shape (height, width, 3).
    """
    from PIL import Image

    with Image.open(io.BytesIO(png)) as im:
        return np.asarray(im.convert("RGB"))


@dataclass
class OverlayPixels:
    """What excluding some entities from a view changed in its screenshot."""

    view_name: str
    entities: list[str]
    changed: int  # pixels that differ between shown and hidden
    coloured: int  # of those, pixels whose shown colour is not grey
    colours: list[tuple]  # dominant shown colours among the changed coloured pixels
