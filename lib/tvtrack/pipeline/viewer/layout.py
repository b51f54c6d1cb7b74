"""The recording's layout, read from the ``.rrd`` file with no viewer (:func:`read_layout`), and what a user
would see wrong on opening it (:func:`layout_problems`). Re-exported by :mod:`tvtrack.pipeline.viewer`.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .expectation import Expectation

__all__ = ["RecordingLayout", "read_layout", "layout_problems"]

_NOT_TIMELINES = {"rerun.controls.RowId"}
_COLOUR_COMPONENTS = (
    "Points2D:colors",
    "Boxes2D:colors",
    "LineStrips2D:colors",
    "SeriesLines:colors",
    "SeriesPoints:colors",
)


@dataclass
class RecordingLayout:
    """What a recording file says about how it opens (:func:`read_layout`).

    Attributes
    ----------
    opening_timeline : str or None
        The timeline the blueprint's time panel opens on (``None``: the viewer chooses).
    views : list of dict
        ``{"name", "kind", "origin"}`` of each view in the blueprint (kind ``"2D"``, ``"TimeSeries"`` ...).
    timelines : dict
        Entity path -> the timelines it has data on (empty for static-only entities).
    colours : dict
        Entity path -> the packed RGBA colours it was logged with (points, boxes, lines, series styles).
    labels : set
        Entity paths logged with text labels (``Points2D:labels`` ...).
    positions : dict
        Entity path -> (frame, (N, 2) positions) of points, box centres and line vertices, in logging order.
    images : dict
        Entity path -> (width, height) of its images.
    markers : set
        Entity paths logged as points (``Points2D``): markers that can hide one another.
    bounds : dict
        View origin -> ``(x_min, x_max, y_min, y_max)`` of the blueprint's visual bounds, where it sets them.
    """

    opening_timeline: str | None = None
    views: list = field(default_factory=list)
    timelines: dict = field(default_factory=dict)
    colours: dict = field(default_factory=dict)
    labels: set = field(default_factory=set)
    positions: dict = field(default_factory=dict)
    images: dict = field(default_factory=dict)
    markers: set = field(default_factory=set)
    bounds: dict = field(default_factory=dict)


def _column(batch, name):
    return batch.column(name).to_pylist() if name in batch.schema.names else None


def _first_string(value):
    while isinstance(value, list) and value:
        value = value[0]
    return value if isinstance(value, str) else None


def read_layout(path: str | Path) -> RecordingLayout:
    """Read the blueprint (views, opening timeline, visual bounds) and the recording's entities (timelines with
    data, colours, labels, positions, image sizes) from an ``.rrd`` file."""
    from rerun.chunk import RrdReader

    reader = RrdReader(Path(path))
    layout = RecordingLayout()
    blueprints = reader.blueprints()
    views: dict[str, dict] = {}
    if blueprints:
        for chunk in reader.stream(store=blueprints[0]).to_chunks():
            _read_blueprint_chunk(chunk, layout, views)
    for view in views.values():
        if "origin" in view:
            origin = "/" + view["origin"].strip("/")
            layout.views.append({"name": view.get("name") or origin, "kind": view.get("kind"), "origin": origin})
            if "bounds" in view:
                layout.bounds[origin] = view["bounds"]
    for chunk in reader.stream().to_chunks():
        _read_entity_chunk(chunk, layout)
    return layout


def _read_blueprint_chunk(chunk, layout: RecordingLayout, views: dict[str, dict]) -> None:
    """One chunk of the blueprint: the opening timeline into ``layout``, a view's kind, name, origin and visual
    bounds into ``views`` (blueprint entity ``/view/<id>`` -> its fields)."""
    batch, entity = chunk.to_record_batch(), str(chunk.entity_path)
    timeline = _column(batch, "TimePanelBlueprint:timeline")
    if timeline:
        layout.opening_timeline = _first_string(timeline[-1]) or layout.opening_timeline
    if entity.startswith("/view/") and entity.count("/") == 2:
        view = views.setdefault(entity, {})
        for key, column in (
            ("kind", "ViewBlueprint:class_identifier"),
            ("name", "ViewBlueprint:display_name"),
            ("origin", "ViewBlueprint:space_origin"),
        ):
            values = _column(batch, column)
            if values:
                view[key] = _first_string(values[-1])
    for name in batch.schema.names:
        if name.startswith("VisualBounds2D:"):
            ranges = batch.column(name).to_pylist()[-1]
            while isinstance(ranges, list) and len(ranges) == 1:
                ranges = ranges[0]
            if isinstance(ranges, dict):  # {"x_range": [x0, x1], "y_range": [y0, y1]}
                ranges = [ranges.get("x_range"), ranges.get("y_range")]
            try:
                flat = np.asarray(ranges, dtype=float).ravel()
            except (TypeError, ValueError):
                continue
            if flat.size == 4:
                views.setdefault("/".join(entity.split("/")[:3]), {})["bounds"] = tuple(flat)


def _read_entity_chunk(chunk, layout: RecordingLayout) -> None:
    """One chunk of the recording: its entity's timelines with data, colours, labels, positions and image size."""
    batch, entity = chunk.to_record_batch(), str(chunk.entity_path)
    if entity.startswith("/__"):
        return
    names = batch.schema.names
    timelines = {
        n
        for n in names
        if ":" not in n
        and n not in _NOT_TIMELINES
        and n != "log_time"
        and batch.num_rows
        and batch.column(n).null_count < batch.num_rows
    }
    layout.timelines.setdefault(entity, set()).update(timelines)
    for name in _COLOUR_COMPONENTS:
        for row in _column(batch, name) or []:
            if row:
                layout.colours.setdefault(entity, set()).add(int(row[0]))
    if any(n.endswith(":labels") and any(_column(batch, n) or []) for n in names):
        layout.labels.add(entity)
    frames = _column(batch, "frame") or [None] * batch.num_rows
    for name in ("Points2D:positions", "Boxes2D:centers", "LineStrips2D:strips"):
        for frame, row in zip(frames, _column(batch, name) or []):
            if row and name.startswith("Points2D"):
                layout.markers.add(entity)
            if row:
                xy = np.asarray(
                    [p for item in row for p in (item if name.startswith("Line") else [item])], dtype=float
                ).reshape(-1, 2)
                layout.positions.setdefault(entity, []).append((frame, xy))
    for fmt in _column(batch, "Image:format") or []:
        if fmt:
            layout.images[entity] = (fmt[0].get("width"), fmt[0].get("height"))


def _under(entity: str, origin: str) -> bool:
    origin = origin.rstrip("/") or "/"
    return origin == "/" or entity == origin or entity.startswith(origin + "/")


_BAND_EDGES = {"minus", "plus", "lo", "hi", "low", "high", "lower", "upper"}
_ROLES = {
    "truth",
    "estimate",
    "estimated",
    "measured",
    "measurement",
    "predicted",
    "prediction",
    "gate",
    "detection",
    "detected",
    "interferer",
    "decoy",
}


def _leaf_tokens(entity: str) -> list[str]:
    return [t for t in entity.rstrip("/").rsplit("/", 1)[-1].lower().split("_") if t]


def _compared_series(a: str, b: str) -> bool:
    """Two series of one time-series view are compared unless they are the two edges of one band
    (``estimate_minus_sigma`` / ``estimate_plus_sigma``), which share their colour on purpose."""
    strip = lambda e: [t for t in _leaf_tokens(e) if t not in _BAND_EDGES]
    return strip(a) != strip(b)


def _compared_overlays(a: str, b: str) -> bool:
    """Two overlays of a 2-D view are compared when they play different roles (truth and estimate); parts of one
    thing (``gate``, ``gate_path``) or the same role of two objects (``center/truth``, ``marker/truth``) may share."""
    ra, rb = _leaf_tokens(a)[:1], _leaf_tokens(b)[:1]
    return bool(ra and rb) and ra != rb and ra[0] in _ROLES and rb[0] in _ROLES


def _hex(rgba: int) -> str:
    return f"#{rgba >> 8:06x}"


def layout_problems(layout: RecordingLayout, expectation: Expectation | None = None) -> list[str]:
    """What a user would see wrong on opening the recording, before any pixel is drawn:

    - the viewer opens on a timeline on which a view has no data ("No data available": 002 opened on
      ``iteration`` with its images on ``frame``), or the blueprint leaves the timeline to chance;
    - compared things in one view share a colour (two series, or two overlays of a 2-D view);
    - markers of two entities lie on top of each other (closer than 2 % of the view) with no labels to tell
      them apart;
    - a 2-D view's visual bounds cut off the data, or frame it so loosely that it fills under a tenth of the view.
    """
    expectation = expectation or Expectation()
    problems = []
    timeline = layout.opening_timeline
    if timeline is None:
        problems.append("the blueprint does not choose the timeline the viewer opens on (TimePanel(timeline=...))")
    for view in layout.views:
        entities = [e for e in layout.timelines if _under(e, view["origin"])]
        timed = {e: layout.timelines[e] for e in entities if layout.timelines[e]}
        on_other = set().union(*timed.values()) <= set(expectation.other_timelines) if timed else False
        if timeline and timed and not on_other and not any(timeline in t for t in timed.values()):
            elsewhere = sorted(set().union(*timed.values()))
            problems.append(
                f"view {view['name']!r} has no data on the opening timeline {timeline!r} "
                f"(its data is on {', '.join(elsewhere)}): it opens on 'No data available'"
            )
        single = {e: next(iter(layout.colours[e])) for e in entities if len(layout.colours.get(e, ())) == 1}
        compared = _compared_series if view.get("kind") == "TimeSeries" else _compared_overlays
        items = sorted(single.items())
        for i, (a, rgba) in enumerate(items):
            for b, other in items[i + 1 :]:
                if rgba == other and compared(a, b):
                    problems.append(f"view {view['name']!r}: {a} and {b} share the colour {_hex(rgba)}")
        if view.get("kind") == "2D":
            problems += _framing_problems(layout, view, entities, expectation)
    return problems


def _framing_problems(layout: RecordingLayout, view: dict, entities: list[str], expectation: Expectation) -> list[str]:
    problems = []
    drawn = [np.concatenate([xy for _, xy in layout.positions[e]]) for e in entities if e in layout.positions]
    images = [layout.images[e] for e in entities if e in layout.images]
    points = np.concatenate(drawn) if drawn else np.empty((0, 2))
    points = points[np.all(np.isfinite(points), axis=1)]
    if view["origin"] in layout.bounds:
        x0, x1, y0, y1 = layout.bounds[view["origin"]]
    elif images:
        x0, y0, x1, y1 = 0.0, 0.0, float(max(w for w, _ in images)), float(max(h for _, h in images))
    elif len(points):
        (x0, y0), (x1, y1) = points.min(axis=0), points.max(axis=0)
    else:
        return problems
    span = max(x1 - x0, y1 - y0, 1e-12)
    if len(points) and view["origin"] in layout.bounds:
        (px0, py0), (px1, py1) = points.min(axis=0), points.max(axis=0)
        margin = 0.02 * span
        if px0 < x0 - margin or px1 > x1 + margin or py0 < y0 - margin or py1 > y1 + margin:
            problems.append(
                f"view {view['name']!r}: its visual bounds [{x0:.4g}, {x1:.4g}] x [{y0:.4g}, {y1:.4g}] "
                f"cut off data spanning [{px0:.4g}, {px1:.4g}] x [{py0:.4g}, {py1:.4g}]"
            )
        elif not images and max(px1 - px0, py1 - py0) < 0.1 * span:
            problems.append(f"view {view['name']!r}: the data fills under a tenth of its visual bounds")
    if expectation.labels_when_overlapping:
        problems += _overlap_problems(layout, view, entities, 0.02 * span)
    return problems


def _overlap_problems(layout: RecordingLayout, view: dict, entities: list[str], distance: float) -> list[str]:
    """Pairs of point entities in a 2-D view whose markers overlap in most frames, with neither labelled."""
    problems = []
    points = [e for e in entities if e in layout.markers and e not in layout.labels]
    by_frame = {e: {f: xy.mean(axis=0) for f, xy in layout.positions[e] if len(xy) == 1} for e in points}
    for i, a in enumerate(points):
        for b in points[i + 1 :]:
            common = sorted(set(by_frame[a]) & set(by_frame[b]))
            if len(common) < 2:
                continue
            gaps = np.array([np.linalg.norm(by_frame[a][f] - by_frame[b][f]) for f in common])
            if np.median(gaps) < distance:
                problems.append(
                    f"view {view['name']!r}: {a} and {b} overlap (median {np.median(gaps):.3g} apart) "
                    f"with no labels to tell them apart"
                )
    return problems
