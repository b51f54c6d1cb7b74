"""Every notebook's smoke-profile recording opens in the real Rerun viewer and shows what a user
looks for (:func:`tvtrack.pipeline.viewer.check_recording`): the blueprint's 2-D image view and
time-series view, the image, gate, truth and estimate entities and the error series, no view
reporting an error or warning, and per-view screenshots in which the gate, the truth, the
estimate and a plotted line are visible (coarse coloured-pixel counts by ablation; no golden
images). ``rerun rrd verify`` passes first.

``TVTRACK_UPDATE_SCREENSHOTS=1`` also writes ``docs/screenshots/<notebook>.png`` (the whole
viewer, as a user sees it on opening the file) for the notebooks in ``notebooks/``.
"""

from __future__ import annotations

import importlib
import io
import os
import time
from dataclasses import replace

import pytest
from load import wall_budget

from tvtrack.pipeline.paths import REPO_ROOT
from tvtrack.pipeline.viewer import Expectation, check_recording, layout_problems, read_layout, verify_rrd

SCREENSHOT_DIR = REPO_ROOT / "docs" / "screenshots"
UPDATE_SCREENSHOTS = os.environ.get("TVTRACK_UPDATE_SCREENSHOTS") == "1"

DEFAULT = Expectation()
FIXTURE = "fixture_centroid"
# the test fixture (not a paper notebook) draws truth and estimate in two colours without labels
FIXTURE_EXPECTATION = Expectation(labels_when_overlapping=False)


def expectation(stem: str) -> Expectation:
    """What the viewer must show for notebook ``stem``: the paper's deviations from :data:`DEFAULT`, written with
    their reasons in its package's ``recording.VIEWER_EXPECTATIONS`` (the paper contract, ``tvtrack.contract``)."""
    if stem == FIXTURE:
        return FIXTURE_EXPECTATION
    recording = importlib.import_module(f"tvtrack.papers.p{stem}.recording")
    return replace(DEFAULT, **recording.VIEWER_EXPECTATIONS)


def _save_docs_screenshot(viewer, stem: str) -> None:
    """Whole-viewer PNG, 900 px wide at most, true colour (palette quantisation merges the
    near-black count images with the background)."""
    from PIL import Image

    # the viewer's start-up notifications cover the top right for its first ~8 s
    time.sleep(max(0.0, 10.0 - viewer.seconds_since_start()))
    png = viewer.screenshot_png(max_size=900)
    SCREENSHOT_DIR.mkdir(parents=True, exist_ok=True)
    with Image.open(io.BytesIO(png)) as im:
        im.convert("RGB").save(SCREENSHOT_DIR / f"{stem}.png", optimize=True)


@pytest.mark.notebook
def test_recording_in_viewer(viewer_notebook, notebook_run, headless_viewer):
    stem = viewer_notebook.stem
    outcome = notebook_run(viewer_notebook)
    assert outcome.ok, f"{stem} smoke run failed: {outcome.error} (see {outcome.run_dir / 'error.txt'})"
    rrd = outcome.run_dir / "recording.rrd"
    assert rrd.is_file(), f"{stem} smoke run wrote no recording.rrd (the smoke profile must keep rerun_mode='file')"
    verify_rrd(rrd)

    check = check_recording(headless_viewer, rrd, expectation(stem))
    for look in (2, 3):  # a headless viewer on a loaded machine can miss repaints: look again (say so), up to 3 looks
        if not check.problems:
            break
        print(f"{stem}: look {look - 1} found {check.problems}; checking again")
        time.sleep(wall_budget(2.0))
        check = check_recording(headless_viewer, rrd, expectation(stem))
    print(
        f"{stem}: loaded in {check.load_s:.1f} s, viewer check {check.check_s:.1f} s, "
        + ", ".join(f"{k} {v.coloured} px" for k, v in check.pixels.items())
    )
    assert not check.problems, f"{stem} in the Rerun viewer ({rrd}):\n  " + "\n  ".join(check.problems)
    if UPDATE_SCREENSHOTS and viewer_notebook.parent.name == "notebooks":
        _save_docs_screenshot(headless_viewer, stem)
    assert check.check_s < wall_budget(30), (
        f"{stem}: viewer check took {check.check_s:.1f} s (30 s per recording, idle)"
    )


@pytest.mark.notebook
def test_recording_opens_on_the_timeline_with_data_with_distinct_colours_and_framed(viewer_notebook, notebook_run):
    """Read from the file, no viewer needed: the timeline the recording opens on holds every view's data; compared
    series and overlays of one view have distinct colours; overlapping markers carry labels; a 2-D view's bounds
    neither cut off nor drown the data (:func:`tvtrack.pipeline.viewer.layout_problems`)."""
    stem = viewer_notebook.stem
    outcome = notebook_run(viewer_notebook)
    assert outcome.ok, f"{stem} smoke run failed: {outcome.error}"
    layout = read_layout(outcome.run_dir / "recording.rrd")
    problems = layout_problems(layout, expectation(stem))
    assert not problems, f"{stem}: opens on {layout.opening_timeline!r}:\n  " + "\n  ".join(problems)
