"""Open a recording in the headless viewer and check what a user looks for (:func:`check_recording`).

What an overlay draws is measured by ablation (:meth:`~tvtrack.pipeline.viewer.HeadlessViewer.overlay_pixels`):
no golden images are involved. Re-exported by :mod:`tvtrack.pipeline.viewer`.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Iterable

import numpy as np

from .expectation import DEFAULT_EXPECTATION, Expectation
from .headless import HeadlessViewer
from .pixels import OverlayPixels, coloured_mask

__all__ = ["entities_under", "plays_role", "IMAGE_ARCHETYPES", "REPORT_SEVERITIES", "RecordingCheck", "check_recording"]


def entities_under(paths: Iterable[str], origin: str) -> list[str]:
    """Entity paths at or below ``origin`` (both with a leading ``/``)."""
    root = "/" + origin.strip("/")
    return [p for p in paths if p == root or p.startswith(root + "/")]


def plays_role(path: str, origin: str, role: str) -> bool:
    """Whether an entity below ``origin`` plays ``role``: one of its path parts below the origin
    starts with the role's name (``/camera/gate``, ``/camera/gate_rotated``, ``/camera/estimates/obj1``
    all play ``gate`` or ``estimate`` under origin ``/camera``)."""
    below = path[len("/" + origin.strip("/")) :].strip("/").split("/")
    return any(part.startswith(role) for part in below if part)


IMAGE_ARCHETYPES = frozenset({"Image", "EncodedImage", "DepthImage", "SegmentationImage"})
REPORT_SEVERITIES = frozenset({"error", "warning"})


@dataclass
class RecordingCheck:
    """What :func:`check_recording` saw; ``problems`` is empty when the recording looks right."""

    path: Path
    frame: int | None = None
    views: list = field(default_factory=list)
    entity_paths: list[str] = field(default_factory=list)
    pixels: dict[str, OverlayPixels] = field(default_factory=dict)  # role or view name -> pixels
    problems: list[str] = field(default_factory=list)
    load_s: float = 0.0
    check_s: float = 0.0


def check_recording(
    viewer: HeadlessViewer, path: str | Path, expect: Expectation = DEFAULT_EXPECTATION
) -> RecordingCheck:
    """Open ``path`` in ``viewer`` and check what a user looks for.

    At the middle frame: the blueprint has a 2-D view and a time-series view, all visible; an
    image and every overlay role of ``expect`` are under a 2-D view's origin and draw pixels
    there (coloured ones for the overlays); scalar series under ``expect.series_root`` are in a
    time-series view and draw coloured lines in the first such view; after painting the whole
    viewer, no view reports an error or a warning. Problems are collected, not raised, so one run lists them all.
    """
    t0 = time.monotonic()
    rec = viewer.open(path)
    check = RecordingCheck(path=Path(path), load_s=rec.load_s)
    problems = check.problems
    if expect.timeline not in rec.timelines:
        problems.append(f"no {expect.timeline!r} timeline; timelines: {sorted(rec.timelines)}")
        return check
    line = rec.timeline(expect.timeline)
    check.frame = frame = (line.start + line.end) // 2
    viewer.set_time(expect.timeline, frame)

    views = check.views = viewer.views()
    spatial = [v for v in views if v.view_class == "2D"]
    series_views = [v for v in views if v.view_class == "TimeSeries"]
    if not spatial or not series_views:
        problems.append(
            f"blueprint views {sorted(v.view_class for v in views)}: need a 2-D image view "
            "('2D') and a time series ('TimeSeries')"
        )
    problems += [f"view {v.name!r} ({v.view_class}) is not visible" for v in views if not v.visible]
    look = _Look(viewer, check, expect, viewer.entity_paths(), viewer.archetypes())
    check.entity_paths = look.paths
    look.image(spatial)
    look.overlays(spatial)
    look.series(series_views)
    look.reports()
    check.check_s = time.monotonic() - t0
    return check


class _Look:
    """One check's look at the paused viewer: the entities, the screenshots taken so far (each paints a whole
    frame: only the needed ones are taken, once), and the problems found, appended to ``check``."""

    def __init__(self, viewer: HeadlessViewer, check: RecordingCheck, expect: Expectation, paths, archetypes):
        self.viewer, self.check, self.expect = viewer, check, expect
        self.paths, self.archetypes = paths, archetypes
        self.problems = check.problems
        self._shots: dict[str, np.ndarray] = {}

    def shot(self, view) -> np.ndarray:
        if view.view_id not in self._shots:
            self._shots[view.view_id] = self.viewer.screenshot(view.view_id)
        return self._shots[view.view_id]

    def image(self, spatial) -> None:
        """The main image of a 2-D view covers at least ``min_image_fraction`` of it."""
        expect, paths = self.expect, self.paths
        images = [
            (v, p)
            for v in spatial
            for p in entities_under(paths, v.origin)
            if self.archetypes.get(p, set()) & IMAGE_ARCHETYPES
        ]
        # the view's main image first (an entity named ".../image"), not a small overlay such as a gate crop
        images.sort(key=lambda vp: not vp[1].rstrip("/").endswith("/image"))
        if expect.image and not images:
            self.problems.append(f"no image entity in the 2-D views {[v.origin for v in spatial]}; entities: {paths}")
        for view, image_path in images[:1] if expect.image else []:
            shown = self.shot(view)
            px = self.check.pixels["image"] = self.viewer.overlay_pixels(view, [image_path], shown=shown)
            area = shown.shape[0] * shown.shape[1]
            if px.changed < expect.min_image_fraction * area:
                self.problems.append(f"image {image_path} covers only {px.changed} of {area} px of view {view.name!r}")

    def overlays(self, spatial) -> None:
        """Each overlay role of the expectation draws at least ``min_overlay_px`` coloured pixels in a 2-D view."""
        expect, paths = self.expect, self.paths
        for role in expect.overlays:
            found = [
                (v, [p for p in entities_under(paths, v.origin) if plays_role(p, v.origin, role)]) for v in spatial
            ]
            found = [(v, ps) for v, ps in found if ps]
            if not found:
                self.problems.append(
                    f"no {role!r} entity in the 2-D views {[v.origin for v in spatial]}; entities: {paths}"
                )
                continue
            view, role_paths = found[0]
            px = self.check.pixels[role] = self.viewer.overlay_pixels(view, role_paths, shown=self.shot(view))
            if px.coloured < expect.min_overlay_px:
                self.problems.append(
                    f"{role} {role_paths} draws {px.coloured} coloured px in view {view.name!r} at "
                    f"{expect.timeline} {self.check.frame} ({px.changed} changed); need >= {expect.min_overlay_px}"
                )

    def series(self, series_views) -> None:
        """Scalar series under ``series_root`` are in a time-series view and draw a line in the first one."""
        expect, paths = self.expect, self.paths
        series = [p for p in entities_under(paths, expect.series_root) if "Scalars" in self.archetypes.get(p, set())]
        if not series:
            self.problems.append(f"no scalar series under /{expect.series_root}; entities: {paths}")
        plotting = [v for v in series_views if entities_under(series, v.origin)]
        if series and not plotting:
            self.problems.append(
                f"series {series} are in no time-series view (origins {[v.origin for v in series_views]})"
            )
        for view in plotting[:1]:
            in_view = entities_under(series, view.origin)
            total = int(coloured_mask(self.shot(view)).sum())
            px = self.check.pixels[f"series:{view.name}"] = self.viewer.overlay_pixels(
                view, in_view, shown=self.shot(view)
            )
            if min(total, px.coloured) < expect.min_line_px:
                self.problems.append(
                    f"time-series view {view.name!r}: {total} coloured px, {px.coloured} of them from "
                    f"{in_view}; need >= {expect.min_line_px} (a plotted line)"
                )

    def reports(self) -> None:
        """No view reports an error or a warning after the whole viewer is painted once more."""
        self.viewer.screenshot_png(max_size=64)  # paint every view once more, as the blueprint has them
        for view in self.viewer.views():  # reports describe the last paint
            self.problems += [
                f"view {view.name!r} reports {r.severity}: {r.summary} {r.details or ''}".strip()
                for r in view.reports
                if r.severity.lower() in REPORT_SEVERITIES
            ]
