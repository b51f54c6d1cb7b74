"""What a tracking recording must show in the viewer: the expectation the viewer check and the layout
check read (a paper states its deviations from the defaults in ``recording.VIEWER_EXPECTATIONS``,
:data:`tvtrack.contract.VIEWER_KEYS`). Re-exported by :mod:`tvtrack.pipeline.viewer`.
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["Expectation", "DEFAULT_EXPECTATION"]


@dataclass(frozen=True)
class Expectation:
    """What a tracking recording must show in the viewer.

    Attributes
    ----------
    image : bool
        Whether a 2-D view must show an image (``Image``, ``EncodedImage`` ... archetype).
    overlays : tuple of str
        Roles drawn over the image in a 2-D view (see :func:`plays_role`).
    series_root : str
        Entity root of the error series (``errors`` for ``errors/x`` ...), which must be plotted
        in a time-series view.
    timeline : str
        Sequence timeline; the screenshots are taken at the middle of its range.
    min_overlay_px : int
        Coloured pixels each overlay role must change in its view (a small dot is ~5).
    min_line_px : int
        Coloured pixels the series must draw in each time-series view showing them.
    min_image_fraction : float
        Fraction of its view's pixels the image must change.
    labels_when_overlapping : bool
        Whether point markers of two entities that overlap must carry labels (:func:`layout_problems`).
    other_timelines : tuple of str
        Timelines a view may hold all its data on although the recording opens on another (an iterative
        estimator's history on ``iteration``): that view is shown once the user picks its timeline.
    """

    image: bool = True
    overlays: tuple[str, ...] = ("gate", "truth", "estimate")
    series_root: str = "errors"
    timeline: str = "frame"
    min_overlay_px: int = 3
    min_line_px: int = 150
    min_image_fraction: float = 0.01
    labels_when_overlapping: bool = True
    other_timelines: tuple[str, ...] = ()


#: The expectation of a recording whose paper states no deviation (frozen: safe as a default argument).
DEFAULT_EXPECTATION = Expectation()
