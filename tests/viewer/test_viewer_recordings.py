"""Every notebook's smoke-profile recording opens in the real Rerun viewer and shows what a user
looks for: the blueprint's 2-D image view and time-series view, the image, gate, truth and
estimate entities and the error series, no view reporting an error or warning, and per-view
screenshots in which the gate, the truth, the estimate and a plotted line are visible
(coarse coloured-pixel counts by ablation, see :mod:`tvtrack.viewer`; no golden images).

``TVTRACK_UPDATE_SCREENSHOTS=1`` also writes ``docs/screenshots/<notebook>.png`` (the whole
viewer, as a user sees it on opening the file) for the notebooks in ``notebooks/``.
"""

from __future__ import annotations

import os
import time
from dataclasses import dataclass

import pytest

from tvtrack.paths import REPO_ROOT
from tvtrack.viewer import coloured_mask, entities_under, verify_rrd

from smoke_runs import smoke_notebooks

SCREENSHOT_DIR = REPO_ROOT / "docs" / "screenshots"
UPDATE_SCREENSHOTS = os.environ.get("TVTRACK_UPDATE_SCREENSHOTS") == "1"
IMAGE_ARCHETYPES = {"Image", "EncodedImage", "DepthImage", "SegmentationImage"}
REPORT_SEVERITIES = {"error", "warning"}


@dataclass(frozen=True)
class Expect:
    """What a notebook's recording must show.

    overlays : roles drawn over the image in a 2-D view; an entity plays a role when one of its
        path parts below the view's origin starts with the role's name (``gate``,
        ``gate_rotated``, ``estimates/obj1`` ...).
    series_root : entity root of the error series (``errors/x`` ...), shown in a time-series view.
    timeline : sequence timeline whose middle the screenshots are taken at.
    min_overlay_px : coloured pixels an overlay role must change in its view (a 3 px dot or more).
    min_line_px : coloured pixels the series must draw in their time-series view.
    """

    overlays: tuple[str, ...] = ("gate", "truth", "estimate")
    series_root: str = "errors"
    timeline: str = "frame"
    min_overlay_px: int = 3
    min_line_px: int = 150


DEFAULT = Expect()
# Per-notebook deviations from DEFAULT, each with its reason.
EXPECT: dict[str, Expect] = {}


def _plays(path: str, origin: str, role: str) -> bool:
    below = path[len("/" + origin.strip("/")):].strip("/").split("/")
    return any(part.startswith(role) for part in below if part)


def _time_series_views_for(views, path: str):
    return [v for v in views if v.view_class == "TimeSeries" and entities_under([path], v.origin)]


def _save_docs_screenshot(viewer, stem: str) -> None:
    """Whole-viewer PNG, 900 px wide at most, palette-quantised to stay small."""
    import io

    from PIL import Image

    # the viewer's start-up notifications cover the top right for its first ~8 s
    time.sleep(max(0.0, 10.0 - viewer.seconds_since_start()))
    png = viewer.screenshot_png(max_size=900)
    with Image.open(io.BytesIO(png)) as im:
        small = im.convert("RGB").quantize(colors=128, method=Image.Quantize.MEDIANCUT)
    SCREENSHOT_DIR.mkdir(parents=True, exist_ok=True)
    small.save(SCREENSHOT_DIR / f"{stem}.png", optimize=True)


@pytest.mark.notebook
@pytest.mark.parametrize("notebook", smoke_notebooks(), ids=lambda p: p.stem)
def test_recording_in_viewer(notebook, smoke_run, headless_viewer):
    expect = EXPECT.get(notebook.stem, DEFAULT)
    outcome = smoke_run(notebook)
    assert outcome.ok, f"{notebook.stem} smoke run failed: {outcome.error} (see {outcome.run_dir / 'error.txt'})"
    rrd = outcome.run_dir / "recording.rrd"
    assert rrd.is_file(), f"{notebook.stem} smoke run wrote no recording.rrd (the smoke profile must keep rerun_mode='file')"
    verify_rrd(rrd)

    t0 = time.monotonic()
    viewer = headless_viewer
    rec = viewer.open(rrd)
    problems: list[str] = []
    if expect.timeline not in rec.timelines:
        pytest.fail(f"{notebook.stem}: no {expect.timeline!r} timeline; timelines: {sorted(rec.timelines)}")
    line = rec.timeline(expect.timeline)
    frame = (line.start + line.end) // 2
    viewer.set_time(expect.timeline, frame)

    views = viewer.views()
    classes = sorted(v.view_class for v in views)
    spatial = [v for v in views if v.view_class == "2D"]
    series_views = [v for v in views if v.view_class == "TimeSeries"]
    if not spatial or not series_views:
        problems.append(f"blueprint views {classes}: need a 2-D image view ('2D') and a time series ('TimeSeries')")
    problems += [f"view {v.name!r} ({v.view_class}) is not visible" for v in views if not v.visible]

    paths = viewer.entity_paths()
    archetypes = viewer.archetypes()
    shots = {v.view_id: viewer.screenshot(v.view_id) for v in views}   # paints every view once

    # the image, and each overlay role, in some 2-D view
    images = [(v, p) for v in spatial for p in entities_under(paths, v.origin)
              if archetypes.get(p, set()) & IMAGE_ARCHETYPES]
    if not images:
        problems.append(f"no image entity in the 2-D views {[v.origin for v in spatial]}; entities: {paths}")
    for view, path in images[:1]:
        px = viewer.overlay_pixels(view, [path], shown=shots[view.view_id])
        area = shots[view.view_id].shape[0] * shots[view.view_id].shape[1]
        if px.changed < 0.01 * area:
            problems.append(f"image {path} covers only {px.changed} of {area} px of view {view.name!r}")
    for role in expect.overlays:
        found = [(v, [p for p in entities_under(paths, v.origin) if _plays(p, v.origin, role)]) for v in spatial]
        found = [(v, ps) for v, ps in found if ps]
        if not found:
            problems.append(f"no {role!r} entity in the 2-D views {[v.origin for v in spatial]}; entities: {paths}")
            continue
        view, role_paths = found[0]
        px = viewer.overlay_pixels(view, role_paths, shown=shots[view.view_id])
        if px.coloured < expect.min_overlay_px:
            problems.append(f"{role} ({role_paths}) draws {px.coloured} coloured px in view {view.name!r} at "
                            f"{expect.timeline} {frame} (changed {px.changed}); need >= {expect.min_overlay_px}")

    # the error series, plotted as coloured lines
    series = [p for p in entities_under(paths, expect.series_root) if "Scalars" in archetypes.get(p, set())]
    if not series:
        problems.append(f"no scalar series under /{expect.series_root}; entities: {paths}")
    shown_in = {v.view_id: v for p in series for v in _time_series_views_for(views, p)}
    if series and not shown_in:
        problems.append(f"series {series} are in no time-series view (origins {[v.origin for v in series_views]})")
    for view in shown_in.values():
        in_view = entities_under(series, view.origin)
        total = int(coloured_mask(shots[view.view_id]).sum())
        px = viewer.overlay_pixels(view, in_view, shown=shots[view.view_id])
        if min(total, px.coloured) < expect.min_line_px:
            problems.append(f"time series view {view.name!r}: {total} coloured px, {px.coloured} of them from "
                            f"{in_view}; need >= {expect.min_line_px} (a plotted line)")

    # what the views report after being painted
    for view in viewer.views():
        problems += [f"view {view.name!r} reports {r.severity}: {r.summary} {r.details or ''}".strip()
                     for r in view.reports if r.severity.lower() in REPORT_SEVERITIES]

    if UPDATE_SCREENSHOTS and notebook.parent.name == "notebooks" and not problems:
        _save_docs_screenshot(viewer, notebook.stem)
    elapsed = time.monotonic() - t0
    assert not problems, f"{notebook.stem} in the Rerun viewer ({rrd}):\n  " + "\n  ".join(problems)
    assert elapsed < 30, f"{notebook.stem}: viewer check took {elapsed:.1f} s (budget 30 s per recording)"
