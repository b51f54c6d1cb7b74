"""The viewer check itself: it must notice what a user would miss (no gate drawn, series in no
time-series view, a truncated file), report a missing Vulkan driver with the package to install,
and clean up its viewer process group."""

from __future__ import annotations

import uuid

import numpy as np
import psutil
import pytest
import rerun as rr
import rerun.blueprint as rrb

from tvtrack.record import Recorder, image_and_series_blueprint
from tvtrack.pipeline.viewer import (INSTALL_HINT, Expectation, HeadlessViewer, ViewerUnavailable, check_recording,
                            coloured_mask, dominant_colours, entities_under, plays_role, verify_rrd,
                            vulkan_problem)

YELLOW, GREEN, RED = (255, 215, 0), (0, 200, 0), (255, 40, 40)


def _write_recording(out, *, gate=True, series_view=True, n_frames=12):
    """A small tracking recording: a grey spot image, a yellow gate, green truth, red estimate,
    error series; ``gate=False`` leaves the gate out, ``series_view=False`` shows no time series."""
    blueprint = (image_and_series_blueprint("camera", ["errors"]) if series_view
                 else rrb.Blueprint(rrb.Spatial2DView(origin="camera", name="Camera"), auto_views=False))
    rec = Recorder(out, "file", "tvtrack-viewer-test", blueprint=blueprint)
    yy, xx = np.mgrid[0:32, 0:32]
    for k in range(n_frames):
        rec.set_frame(k)
        c = np.array([12.0 + 0.5 * k, 15.0])
        img = 20 + 200 * np.exp(-((xx - c[0]) ** 2 + (yy - c[1]) ** 2) / 8.0)
        rec.image("camera/image", img.astype(np.float32))
        if gate:
            rec.boxes("camera/gate", c, [6.0, 6.0], colors=[YELLOW])
        rec.points("camera/truth", c, colors=[GREEN], radii=-3.0)
        rec.points("camera/estimate", c + 1.5, colors=[RED], radii=-3.0)
    rec.series("errors/x", np.sin(np.arange(n_frames)))
    rec.series("errors/y", np.cos(np.arange(n_frames)))
    return rec.close()


# -- without a viewer ------------------------------------------------------------------------
def test_colour_helpers():
    img = np.zeros((4, 5, 3), np.uint8)
    img[...] = 128                      # grey
    img[0, :2] = YELLOW
    img[1, 0] = RED
    mask = coloured_mask(img)
    assert mask.sum() == 3 and mask[0, 0] and mask[1, 0] and not mask[2, 2]
    colours = dominant_colours(img, mask)
    assert colours[0][1] == 2 and colours[0][0][0] > 200 and colours[0][0][2] < 32


def test_entity_helpers():
    paths = ["/camera/image", "/camera/gate_box", "/camera/estimates/obj1", "/cameras/x", "/errors/x"]
    assert entities_under(paths, "camera") == paths[:3]
    assert entities_under(paths, "/errors") == ["/errors/x"]
    assert plays_role("/camera/gate_box", "/camera", "gate")
    assert plays_role("/camera/estimates/obj1", "camera", "estimate")
    assert not plays_role("/camera/image", "/camera", "gate")
    assert not plays_role("/gate/x", "/gate", "gate")      # the origin itself plays no role


def test_vulkan_problem_names_the_package(monkeypatch, tmp_path):
    monkeypatch.setenv("VK_ICD_FILENAMES", str(tmp_path / "missing_icd.json"))
    monkeypatch.delenv("VK_DRIVER_FILES", raising=False)
    problem = vulkan_problem()
    assert problem is not None and INSTALL_HINT in problem
    with pytest.raises(ViewerUnavailable, match="mesa-vulkan-drivers"):
        HeadlessViewer().start()


def test_verify_rrd_rejects_a_truncated_file(tmp_path):
    good = _write_recording(tmp_path)
    assert "without error" in verify_rrd(good)
    bad = tmp_path / "truncated.rrd"
    bad.write_bytes(good.read_bytes()[: good.stat().st_size // 2])
    with pytest.raises(ValueError, match="verify"):
        verify_rrd(bad)


def test_bad_arguments():
    with pytest.raises(ValueError, match="window_size"):
        HeadlessViewer(window_size=(10, 700))
    with pytest.raises(ValueError, match="startup_timeout_s"):
        HeadlessViewer(startup_timeout_s=0)


# -- in the viewer ---------------------------------------------------------------------------
def test_good_recording_passes_with_the_logged_colours(headless_viewer, tmp_path):
    check = check_recording(headless_viewer, _write_recording(tmp_path))
    assert check.problems == []
    assert {v.view_class for v in check.views} == {"2D", "TimeSeries"}
    for role, colour in (("gate", YELLOW), ("truth", GREEN), ("estimate", RED)):
        px = check.pixels[role]
        top = np.array(px.colours[0][0])
        assert px.coloured >= 10, (role, px)
        assert np.abs(top - colour).max() <= 48, (role, px.colours)
    assert check.pixels["series:errors"].coloured >= 150


def test_missing_gate_and_series_view_are_reported(headless_viewer, tmp_path):
    check = check_recording(headless_viewer, _write_recording(tmp_path, gate=False, series_view=False))
    text = "\n".join(check.problems)
    assert "no 'gate' entity" in text
    assert "TimeSeries" in text and "in no time-series view" in text


def test_view_error_report_is_reported(headless_viewer, tmp_path):
    """An image whose buffer is shorter than its format says makes the 2-D view report an error."""
    path = tmp_path / "broken.rrd"
    rec = rr.RecordingStream("tvtrack-viewer-test-broken", recording_id=str(uuid.uuid4()))
    rec.save(path, default_blueprint=rrb.Blueprint(rrb.Spatial2DView(origin="camera"), auto_views=False))
    for k in range(3):
        rec.set_time("frame", sequence=k)
        rec.log("camera/broken", rr.Image(bytes=bytes(10), width=32, height=32, color_model="L", datatype="u8"))
    rec.flush()
    rec.disconnect()
    check = check_recording(headless_viewer, path)
    assert any("reports error" in p and "/camera/broken" in p for p in check.problems), check.problems


def test_overlay_outside_the_image_view_is_reported(headless_viewer, tmp_path):
    """An expectation for a role whose entity lies outside every 2-D view's origin fails."""
    check = check_recording(headless_viewer, _write_recording(tmp_path),
                            Expectation(overlays=("gate", "errors")))
    assert any("'errors'" in p for p in check.problems)


def test_viewer_process_group_ends(tmp_path):
    viewer = HeadlessViewer()
    try:
        viewer.start()
    except ViewerUnavailable as exc:
        pytest.skip(f"Rerun viewer check cannot run: {exc}")
    group = [viewer._proc.pid] + [c.pid for c in psutil.Process(viewer._proc.pid).children(recursive=True)]
    assert len(group) >= 2, "expected the rerun wrapper and the viewer binary"
    viewer.close()
    for pid in group:
        try:
            assert psutil.Process(pid).status() == psutil.STATUS_ZOMBIE, f"viewer process {pid} still runs"
        except psutil.NoSuchProcess:
            pass
