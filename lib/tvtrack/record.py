"""Deprecated alias of :mod:`tvtrack.recordings` (kept while the notebooks move; removed after)."""

from .recordings import *  # noqa: F401,F403
from .recordings import Recorder, ellipse_outline, image_and_series_blueprint  # noqa: F401
