"""Open recordings in the real Rerun viewer, headless on the CPU, and look at what a user sees.

The native viewer (``rerun --headless``) renders through Vulkan; on a machine without a GPU it
runs on Mesa's software rasteriser (llvmpipe, package ``mesa-vulkan-drivers``). Without any
Vulkan driver it cannot start, and :class:`HeadlessViewer` raises :class:`ViewerUnavailable`
with the exact package to install.

The viewer is driven through ``rerun.experimental.ViewerClient`` (pinned rerun-sdk): open a
file, wait until it has loaded, move the time cursor, read the blueprint's views and their
reports, the recording's entity paths, and take per-view screenshots. What an overlay draws is
measured by *ablation*: the view is shot once as the blueprint has it and once with the
overlay's entities excluded from the view's query, and the pixels that differ are the overlay.
Counting the coloured ones among them (chroma above a threshold) is a coarse, colour-agnostic
check that the gate, the truth or the estimate is visible; no golden images are involved.

Pitfalls handled here (``shared/notes/rerun-viewer-check.md``): ``rerun`` defers silently to
whatever already listens on its port, so every viewer gets a fresh free port and its own
process is checked to be alive; ``rerun`` is a Python wrapper around the real binary, so the
viewer runs in its own process group and the whole group is ended.

Example
-------
>>> with HeadlessViewer() as viewer:                       # doctest: +SKIP
...     rec = viewer.open("run/recording.rrd")
...     viewer.set_time("frame", rec.timeline("frame").end // 2)
...     views = viewer.views()
...     shot = viewer.screenshot(views[0].view_id)

Where things live (all importable from here, the one public path): :mod:`.environment` (can the viewer
run here: Vulkan, the ``rerun`` command, ``rerun rrd verify``, a free port), :mod:`.pixels` (coloured
pixels of a screenshot), :mod:`.headless` (the viewer process and its client), :mod:`.expectation` (what a
recording must show), :mod:`.check` (the check in the viewer) and :mod:`.layout` (the check of the file alone).
"""

from __future__ import annotations

from .check import IMAGE_ARCHETYPES, REPORT_SEVERITIES, RecordingCheck, check_recording, entities_under, plays_role
from .environment import INSTALL_HINT, ViewerUnavailable, free_port, rerun_executable, verify_rrd, vulkan_problem
from .expectation import Expectation
from .headless import HeadlessViewer, LoadedRecording
from .layout import RecordingLayout, layout_problems, read_layout
from .pixels import OverlayPixels, coloured_mask, dominant_colours

__all__ = [
    "INSTALL_HINT",
    "ViewerUnavailable",
    "vulkan_problem",
    "rerun_executable",
    "verify_rrd",
    "free_port",
    "coloured_mask",
    "dominant_colours",
    "LoadedRecording",
    "OverlayPixels",
    "HeadlessViewer",
    "entities_under",
    "plays_role",
    "Expectation",
    "RecordingCheck",
    "check_recording",
    "IMAGE_ARCHETYPES",
    "REPORT_SEVERITIES",
    "RecordingLayout",
    "read_layout",
    "layout_problems",
]
