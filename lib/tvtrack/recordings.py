"""Rerun recordings: one ``recording.rrd`` per run, with the things every notebook logs.

Coordinates: the library puts pixel *centres* at integer coordinates (pixel ``(row v, col u)``
spans ``x in [u-1/2, u+1/2]``, ``y in [v-1/2, v+1/2]``). Rerun draws pixel ``u`` over
``[u, u+1]``, so :class:`Recorder` shifts every 2-D position by +1/2 when it logs; positions
passed in are always in the library's convention and land on the right pixel in the viewer.
For 2-D spaces that are not images (a scan-phase plot, a trajectory in metres) pass
``image_space=False`` to the geometry methods and positions are logged as they are.

Time lines: ``frame`` (sequence number) and ``time`` (seconds since the start of the run).

Entity paths explain themselves, e.g. ``camera/image``, ``camera/gate``, ``camera/truth``,
``camera/estimate``, ``errors/x``. :func:`image_and_series_blueprint` gives the usual layout.
"""

from __future__ import annotations

import importlib
import re
import uuid
from pathlib import Path
from typing import Callable, Sequence

import numpy as np

__all__ = ["Recorder", "image_and_series_blueprint", "ellipse_outline", "RECORDING_FILE"]


class _ImportedOnUse:
    """The module ``name``, imported at the first attribute read: ``rerun`` takes about 1 s to import, which a
    process that imports this module and records nothing never pays (the subprocess that checks a notebook's values
    before a run, a run whose validation refuses its values)."""

    def __init__(self, name: str):
        self._name = name

    def __getattr__(self, attr: str):
        return getattr(importlib.import_module(self._name), attr)


rr = _ImportedOnUse("rerun")
rrb = _ImportedOnUse("rerun.blueprint")

RECORDING_FILE = "recording.rrd"

_PIXEL_CENTRE_SHIFT = 0.5


def _xy(points, image_space: bool = True) -> np.ndarray:
    xy = np.asarray(points, dtype=np.float32).reshape(-1, 2)
    return xy + _PIXEL_CENTRE_SHIFT if image_space else xy


def ellipse_outline(center, covariance, n_sigma: float = 1.0, n_points: int = 48) -> np.ndarray:
    """Points on the ``n_sigma`` contour of a 2-D Gaussian.

    Parameters
    ----------
    center : array_like, shape (2,)
        Ellipse centre (x, y) in pixels.
    covariance : array_like, shape (2, 2)
        Covariance in pixels squared (symmetric positive semi-definite).

    Returns
    -------
    ndarray, shape (n_points + 1, 2)
        A closed polyline.
    """
    vals, vecs = np.linalg.eigh(np.asarray(covariance, dtype=float))
    axes = vecs * (n_sigma * np.sqrt(np.clip(vals, 0.0, None)))
    t = np.linspace(0.0, 2 * np.pi, n_points + 1)
    return np.asarray(center, dtype=float) + np.stack([np.cos(t), np.sin(t)], axis=1) @ axes.T


def image_and_series_blueprint(
    image_origin: str = "camera",
    series_origins: Sequence[str | Sequence[str]] = ("errors",),
    *,
    image_name: str = "Camera",
    series_names: Sequence[str | Sequence[str]] | None = None,
    image_share: float = 0.55,
    timeline: str = "frame",
    more_images: Sequence[tuple[str, str]] = (),
) -> rrb.Blueprint:
    """The one blueprint helper: the image space (image, gate, truth, estimates) on the left and one
    time-series view per series root stacked on the right; the viewer opens on ``timeline`` (the one
    that carries the per-frame data), paused at its start.

    Parameters
    ----------
    image_origin, image_name : str
        The main 2-D view.
    series_origins : sequence of str or of tuples of str
        One time-series view per root; a tuple of roots becomes tabs in one place.
    series_names : sequence, optional
        The views' names, shaped like ``series_origins`` (default: the roots' last components).
    image_share : float
        Width of the left column.
    timeline : str
        The timeline the viewer opens on.
    more_images : sequence of (origin, name)
        Further 2-D views under the main one (side by side when there are several).
    """

    def one(origin, name):
        return rrb.TimeSeriesView(origin=origin, name=name)

    names = (
        series_names
        if series_names is not None
        else [
            tuple(o.split("/")[-1] for o in s_) if not isinstance(s_, str) else s_.split("/")[-1]
            for s_ in series_origins
        ]
    )
    series = [
        one(o, n) if isinstance(o, str) else rrb.Tabs(*(one(oo, nn) for oo, nn in zip(o, n)))
        for o, n in zip(series_origins, names)
    ]
    right = rrb.Vertical(*series) if len(series) > 1 else series[0]
    left = rrb.Spatial2DView(origin=image_origin, name=image_name)
    if more_images:
        extra = [rrb.Spatial2DView(origin=o, name=n) for o, n in more_images]
        left = rrb.Vertical(left, rrb.Horizontal(*extra) if len(extra) > 1 else extra[0])
    return rrb.Blueprint(
        rrb.Horizontal(left, right, column_shares=[image_share, 1.0 - image_share]),
        rrb.TimePanel(timeline=timeline, play_state="paused"),
        collapse_panels=True,
    )


class Recorder:
    """One Rerun recording of one run.

    Parameters
    ----------
    output_dir : str or Path
        The run's output directory; the recording is ``output_dir/recording.rrd``.
    mode : {"file", "off", "notebook"}
        ``"off"`` makes every method a no-op; ``"notebook"`` writes the file and, on
        :meth:`close`, shows it in an inline viewer (rerun's notebook extra, pinned).
    application_id : str
        Rerun application id, e.g. ``"tvtrack-004_laser_spot_prediction"`` (other characters
        are replaced by ``-``).
    blueprint : rerun.blueprint.Blueprint or callable, optional
        Default layout the viewer opens on; a callable (no arguments) giving it is called only when the
        recording is written, so a run with ``mode="off"`` never imports rerun to build a layout it discards.
    frame_interval_s : float, optional
        If given, :meth:`set_frame` also sets the ``time`` line to ``frame * frame_interval_s``.
    """

    def __init__(
        self,
        output_dir,
        mode: str = "file",
        application_id: str = "tvtrack",
        blueprint: rrb.Blueprint | Callable[[], rrb.Blueprint] | None = None,
        frame_interval_s: float | None = None,
    ):
        if mode not in ("file", "off", "notebook"):
            raise ValueError(f"parameter 'rerun_mode' = {mode!r}; it must be one of 'file', 'off', 'notebook'")
        self.mode = mode
        self.frame_interval_s = frame_interval_s
        self.path: Path | None = None
        self._rec: rr.RecordingStream | None = None
        if mode == "off":
            return
        self.path = Path(output_dir) / RECORDING_FILE
        # Rerun application ids are entry names: letters, digits, '-' and '_' only
        app = re.sub(r"[^A-Za-z0-9_-]+", "-", application_id)
        self._app = app
        self._rec = rr.RecordingStream(app, recording_id=uuid.uuid4())
        self._rec.save(self.path, default_blueprint=blueprint() if callable(blueprint) else blueprint)

    @property
    def enabled(self) -> bool:
        return self._rec is not None

    # -- time -----------------------------------------------------------------------------
    def set_frame(self, frame: int, time_s: float | None = None) -> None:
        """Set the ``frame`` line (and ``time``, from ``time_s`` or ``frame_interval_s``)."""
        if not self.enabled:
            return
        self._rec.set_time("frame", sequence=int(frame))
        if time_s is None and self.frame_interval_s is not None:
            time_s = frame * self.frame_interval_s
        if time_s is not None:
            self._rec.set_time("time", duration=float(time_s))

    def _time_columns(self, frames, times_s):
        frames = np.asarray(frames, dtype=np.int64)
        cols = [rr.TimeColumn("frame", sequence=frames)]
        if times_s is None and self.frame_interval_s is not None:
            times_s = frames * self.frame_interval_s
        if times_s is not None:
            cols.append(rr.TimeColumn("time", duration=np.asarray(times_s, dtype=float)))
        return cols

    # -- images ---------------------------------------------------------------------------
    def image(
        self, path: str, image, *, offset=None, jpeg_quality: int | None = None, draw_order: float | None = None
    ) -> None:
        """Log an image (rows x cols, or rows x cols x 3) at the current frame.

        ``offset`` = (x0, y0), the integer pixel of the full frame where a gate crop's first
        pixel lies, places a crop in the full frame's coordinates. ``jpeg_quality`` compresses
        8-bit images to keep the file small. ``draw_order`` puts one image above another
        (higher is drawn on top, e.g. a gate crop over a decimated full frame).
        """
        if not self.enabled:
            return
        img = rr.Image(np.asarray(image), draw_order=draw_order)
        if jpeg_quality is not None:
            img = img.compress(jpeg_quality=jpeg_quality)  # drops draw_order: logged again below
            if draw_order is not None and isinstance(img, rr.EncodedImage):
                self._rec.log(path, rr.EncodedImage.from_fields(draw_order=draw_order))
        self._rec.log(path, img)
        if offset is not None:
            x0, y0 = (float(v) for v in offset)
            self._rec.log(path, rr.Transform3D(translation=[x0, y0, 0.0]))

    # -- geometry -------------------------------------------------------------------------
    def points(
        self,
        path: str,
        xy,
        *,
        radii=None,
        colors=None,
        labels=None,
        image_space: bool = True,
        draw_order: float | None = None,
    ) -> None:
        """Log 2-D points (N, 2) in pixels at the current frame (higher ``draw_order`` on top;
        negative ``radii`` are in screen points, so markers keep their size when zoomed). Each marker is
        labelled with the entity's own name (``camera/estimate`` -> "estimate") unless ``labels`` is
        given, or ``False`` for none: overlapping markers of truth, measurement and estimate stay apart."""
        if self.enabled:
            pts = _xy(xy, image_space)
            if labels is None:
                labels = [path.rstrip("/").rsplit("/", 1)[-1]] * len(pts)
            elif labels is False:
                labels = None
            self._rec.log(path, rr.Points2D(pts, radii=radii, colors=colors, labels=labels, draw_order=draw_order))

    def boxes(
        self,
        path: str,
        centers,
        half_sizes,
        *,
        colors=None,
        labels=None,
        image_space: bool = True,
        draw_order: float | None = None,
    ) -> None:
        """Log axis-aligned gates (N, 2) centres and half-sizes in pixels."""
        if self.enabled:
            self._rec.log(
                path,
                rr.Boxes2D(
                    centers=_xy(centers, image_space),
                    half_sizes=np.asarray(half_sizes, dtype=np.float32).reshape(-1, 2),
                    colors=colors,
                    labels=labels,
                    draw_order=draw_order,
                ),
            )

    def lines(
        self,
        path: str,
        strips,
        *,
        colors=None,
        radii=None,
        labels=None,
        image_space: bool = True,
        draw_order: float | None = None,
    ) -> None:
        """Log polylines: one (N, 2) array or a list of them (trajectories, rotated gates,
        ellipses from :func:`ellipse_outline`)."""
        if not self.enabled:
            return
        if isinstance(strips, np.ndarray) and strips.ndim == 2:
            strips = [strips]
        self._rec.log(
            path,
            rr.LineStrips2D(
                [_xy(s, image_space) for s in strips], colors=colors, radii=radii, labels=labels, draw_order=draw_order
            ),
        )

    # -- scalars --------------------------------------------------------------------------
    def series(self, path: str, values, frames=None, times_s=None, *, timeline: str = "frame") -> None:
        """Log a whole scalar series at once (column logging).

        Parameters
        ----------
        values : array_like, shape (T,)
            NaN entries are dropped (e.g. before a filter has an estimate).
        frames : array_like of int, shape (T,), optional
            Frame numbers (or indices on ``timeline``); default ``0..T-1``.
        times_s : array_like, shape (T,), optional
            Times in seconds; default ``frames * frame_interval_s`` if that is set.
        timeline : str
            ``"frame"`` (with ``time``), or another sequence time line for series that are not
            indexed by frame, e.g. ``"iteration"`` for an iterative estimator's history.
        """
        if not self.enabled:
            return
        v = np.asarray(values, dtype=float).ravel()
        f = np.arange(v.size) if frames is None else np.asarray(frames).ravel()
        keep = np.isfinite(v)
        if timeline == "frame":
            t = None if times_s is None else np.asarray(times_s, dtype=float).ravel()[keep]
            indexes = self._time_columns(f[keep], t)
        else:
            indexes = [rr.TimeColumn(timeline, sequence=np.asarray(f[keep], dtype=np.int64))]
        self._rec.send_columns(path, indexes=indexes, columns=rr.Scalars.columns(scalars=v[keep]))

    def series_style(self, path: str, *, name: str | None = None, color=None, width: float | None = None) -> None:
        """Give a series a display name, colour and line width (static)."""
        if self.enabled:
            self._rec.log(path, rr.SeriesLines(names=name, colors=color, widths=width), static=True)

    def text(self, path: str, message: str, level: str = "INFO") -> None:
        """Log a text entry at the current frame (mode changes, detections, loss of lock)."""
        if self.enabled:
            self._rec.log(path, rr.TextLog(message, level=level))

    # -- end ------------------------------------------------------------------------------
    def close(self) -> Path | None:
        """Flush and close the file; returns its path (``None`` when off)."""
        if not self.enabled:
            return None
        self._rec.flush()
        self._rec.disconnect()
        self._rec = None
        if self.mode == "notebook":
            self._show_inline()
        return self.path

    def _show_inline(self) -> None:
        """Replay the finished file into an inline viewer widget. (In rerun 0.41 showing a live
        stream inline takes the stream away from its file sink, so the file would stay empty.)"""
        import os

        os.environ.setdefault("RERUN_NOTEBOOK_ASSET", "inline")  # the viewer shipped with the package: works offline
        from rerun.notebook import Viewer

        replay = rr.RecordingStream(self._app, recording_id=uuid.uuid4())
        Viewer(recording=replay).display()
        replay.log_file_from_path(self.path)
        replay.flush()
