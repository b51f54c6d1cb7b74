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

from tvtrack.recordings import Recorder, image_and_series_blueprint
from tvtrack.pipeline.viewer import (
    INSTALL_HINT,
    Expectation,
    HeadlessViewer,
    ViewerUnavailable,
    check_recording,
    coloured_mask,
    dominant_colours,
    entities_under,
    layout_problems,
    plays_role,
    read_layout,
    verify_rrd,
    vulkan_problem,
)

YELLOW, GREEN, RED = (255, 215, 0), (0, 200, 0), (255, 40, 40)


def _write_recording(out, *, gate=True, series_view=True, n_frames=12, first=0):
    """A small tracking recording: a grey spot image, a yellow gate, green truth, red estimate,
    error series, from frame ``first`` on; ``gate=False`` leaves the gate out, ``series_view=False`` shows no time
    series."""
    blueprint = (
        image_and_series_blueprint("camera", ["errors"])
        if series_view
        else rrb.Blueprint(rrb.Spatial2DView(origin="camera", name="Camera"), auto_views=False)
    )
    rec = Recorder(out, "file", "tvtrack-viewer-test", blueprint=blueprint)
    yy, xx = np.mgrid[0:32, 0:32]
    for k in range(first, first + n_frames):
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
def _layout_recording(
    out, *, timeline="frame", series_colours=((0, 114, 178), (213, 94, 0)), labels=True, bounds=None, apart=6.0
):
    """A recording whose layout can be made wrong one way at a time (:func:`layout_problems`)."""
    from tvtrack.recordings import Recorder as CoreRecorder

    views = [
        rrb.Spatial2DView(
            origin="camera",
            name="Camera",
            visual_bounds=rrb.VisualBounds2D(x_range=bounds[:2], y_range=bounds[2:]) if bounds else None,
        ),
        rrb.TimeSeriesView(origin="errors", name="errors"),
        rrb.TimeSeriesView(origin="em", name="EM"),
    ]
    blueprint = rrb.Blueprint(rrb.Horizontal(*views), rrb.TimePanel(timeline=timeline), collapse_panels=True)
    out.mkdir(parents=True, exist_ok=True)
    rec = CoreRecorder(out, "file", "tvtrack-layout-test", blueprint=blueprint)
    for k in range(10):
        rec.set_frame(k)
        rec.image("camera/image", np.full((32, 32), 10.0 + k, np.float32))
        c = np.array([10.0 + k, 15.0])
        rec.points("camera/truth", c, colors=[GREEN], labels=["truth"] if labels else False)
        rec.points("camera/estimate", c + [apart * 0.01, 0.0], colors=[RED], labels=["estimate"] if labels else False)
    rec.series("errors/x", np.sin(np.arange(10)))
    rec.series("errors/y", np.cos(np.arange(10)))
    rec.series_style("errors/x", color=series_colours[0])
    rec.series_style("errors/y", color=series_colours[1])
    rec.series("em/log_likelihood", np.arange(5.0), timeline="iteration")
    return rec.close()


def test_layout_of_a_good_recording_has_no_problem(tmp_path):
    layout = read_layout(_layout_recording(tmp_path))
    assert layout.opening_timeline == "frame"
    assert {v["origin"] for v in layout.views} == {"/camera", "/errors", "/em"}
    assert layout.timelines["/camera/image"] >= {"frame"} and layout.images["/camera/image"] == (32, 32)
    # the EM history lives on its own timeline: allowed only where the expectation names that timeline
    assert layout_problems(layout, Expectation(other_timelines=("iteration",))) == []
    assert layout_problems(layout) == [
        "view 'EM' has no data on the opening timeline 'frame' (its data is on "
        "iteration): it opens on 'No data available'"
    ]


def test_layout_catches_the_wrong_opening_timeline(tmp_path):
    """002's recording opened on ``iteration``: three of four views said "No data available"."""
    problems = layout_problems(read_layout(_layout_recording(tmp_path, timeline="iteration")))
    assert any("view 'Camera' has no data on the opening timeline 'iteration'" in p for p in problems)
    assert any("view 'errors' has no data" in p for p in problems)


def test_layout_catches_compared_series_of_one_colour(tmp_path):
    problems = layout_problems(read_layout(_layout_recording(tmp_path, series_colours=((0, 114, 178),) * 2)))
    assert any("view 'errors': /errors/x and /errors/y share the colour #0072b2" in p for p in problems)


def test_colour_rule_spares_band_edges_and_parts_of_one_thing():
    from tvtrack.pipeline.viewer.layout import _compared_overlays, _compared_series

    assert _compared_series("/errors/x", "/errors/y") and _compared_series("/v/variant_1", "/v/variant_2")
    assert not _compared_series("/track/estimate_minus_sigma", "/track/estimate_plus_sigma")
    assert _compared_overlays("/camera/truth", "/camera/estimate")
    assert not _compared_overlays("/camera/gate", "/camera/gate_path")
    assert not _compared_overlays("/camera/center/truth", "/camera/marker/truth")


def test_layout_catches_unlabelled_overlapping_markers(tmp_path):
    problems = layout_problems(read_layout(_layout_recording(tmp_path, labels=False)))
    assert any("/camera/truth and /camera/estimate overlap" in p for p in problems)
    far = layout_problems(read_layout(_layout_recording(tmp_path / "far", labels=False, apart=500.0)))
    assert not any("overlap" in p for p in far)


def test_layout_catches_bad_framing(tmp_path):
    cut = layout_problems(read_layout(_layout_recording(tmp_path, bounds=(0.0, 12.0, 0.0, 32.0))))
    assert any("view 'Camera': its visual bounds" in p and "cut off" in p for p in cut)
    fine = layout_problems(read_layout(_layout_recording(tmp_path / "fine", bounds=(0.0, 32.0, 0.0, 32.0))))
    assert not any("Camera" in p for p in fine)


def test_colour_helpers():
    img = np.zeros((4, 5, 3), np.uint8)
    img[...] = 128  # grey
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
    assert not plays_role("/gate/x", "/gate", "gate")  # the origin itself plays no role


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


def test_the_check_sees_the_frame_it_set_not_the_one_the_file_opened_on(headless_viewer, tmp_path):
    """The viewer opens a file at frame 0; a recording whose overlays start at frame 1 (as 000's scans do) is blank
    there. ``set_time`` returns only once the viewer reports its cursor at the frame asked for, so every screenshot
    of the check is of that frame."""
    path = _write_recording(tmp_path, n_frames=40, first=1)
    store_id = headless_viewer.open(path).store_id
    view = next(v for v in headless_viewer.views() if v.view_class == "2D")
    assert coloured_mask(headless_viewer.screenshot(view.view_id)).sum() == 0  # frame 0: nothing logged yet
    for frame in (31, 7):
        headless_viewer.set_time("frame", frame)
        # the very next picture is of that frame (without the wait it was still frame 0's: 0 coloured px)
        assert coloured_mask(headless_viewer.screenshot(view.view_id)).sum() >= 30, frame
        rec = next(r for r in headless_viewer.state().recordings if r.store_id == store_id)
        assert (rec.current_timeline, rec.current_time) == ("frame", frame)
    check = check_recording(headless_viewer, path)
    assert check.frame == 20 and check.problems == [], check.problems
    assert min(check.pixels[role].coloured for role in ("gate", "truth", "estimate")) >= 10, check.pixels


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
    check = check_recording(headless_viewer, _write_recording(tmp_path), Expectation(overlays=("gate", "errors")))
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


# -- python -m tvtrack view: checked before it serves, stopped by any signal ----------------------
def _view(*args, timeout=60):
    import subprocess
    import sys

    return subprocess.run(
        [sys.executable, "-m", "tvtrack", "view", *map(str, args), "--no-browser"],
        capture_output=True,
        text=True,
        timeout=timeout,
    )


def _one_line_error(proc, *fragments):
    assert proc.returncode == 2, (proc.returncode, proc.stdout, proc.stderr)
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), proc.stderr
    assert "Traceback" not in proc.stderr + proc.stdout and "serving" not in proc.stdout
    for f in fragments:
        assert f in lines[0], (f, lines[0])
    return lines[0]


def test_view_refuses_a_corrupt_or_truncated_recording_before_serving(tmp_path):
    from tvtrack.pipeline.viewer import free_port

    good = _write_recording(tmp_path)
    ports = ["--port", free_port(), "--grpc-port", free_port()]
    garbage = tmp_path / "garbage.rrd"
    garbage.write_bytes(b"this is not a recording " * 40)
    _one_line_error(_view(garbage, *ports), "garbage.rrd", "not a readable Rerun recording", "RRD")
    half = tmp_path / "half.rrd"
    half.write_bytes(good.read_bytes()[: good.stat().st_size // 2])
    _one_line_error(_view(half, *ports), "half.rrd", "not a readable Rerun recording")
    for name, content in (("empty.rrd", b""), ("short.rrd", b"xxxx")):  # rerun rrd verify passes these
        (tmp_path / name).write_bytes(content)
        _one_line_error(_view(tmp_path / name, *ports), name, "not a readable Rerun recording", "RRF header")


def test_view_checks_port_and_host_in_one_line_each(tmp_path):
    from tvtrack.pipeline.viewer import free_port

    rec = _write_recording(tmp_path)
    _one_line_error(_view(rec, "--port", 70000, "--grpc-port", free_port()), "--port 70000", "[1, 65535]")
    _one_line_error(_view(rec, "--port", free_port(), "--grpc-port", 0), "--grpc-port 0", "[1, 65535]")
    line = _one_line_error(
        _view(rec, "--host", "no-such-host.invalid", "--port", free_port(), "--grpc-port", free_port()),
        "'no-such-host.invalid'",
        "does not resolve",
    )
    assert "listens" not in line  # not reported as a busy port
    _one_line_error(
        _view(rec, "--host", "192.0.2.1", "--port", free_port(), "--grpc-port", free_port()),
        "192.0.2.1",
        "not an address of this machine",
    )
    import socket

    with socket.socket() as busy:
        busy.bind(("127.0.0.1", 0))
        busy.listen(1)
        port = busy.getsockname()[1]
        _one_line_error(_view(rec, "--port", port, "--grpc-port", free_port()), f"--port {port}", "already listens")


@pytest.mark.parametrize("signame", ["SIGHUP", "SIGTERM"])
def test_a_hangup_or_a_kill_stops_the_viewer_and_frees_its_ports(tmp_path, signame):
    import signal
    import subprocess
    import sys
    import time

    from tvtrack.pipeline.viewer import free_port
    from tvtrack.pipeline.webview import port_free

    rec = _write_recording(tmp_path)
    web, grpc = free_port(), free_port()
    proc = subprocess.Popen(
        [sys.executable, "-m", "tvtrack", "view", rec, "--no-browser", "--port", str(web), "--grpc-port", str(grpc)],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        start_new_session=True,  # like a terminal's job: the signal goes to tvtrack only
    )
    try:
        lines = [proc.stdout.readline() for _ in range(2)]
        assert lines[1].startswith("open http://127.0.0.1:"), (lines, proc.stderr.read() if proc.poll() else "")
        assert not port_free("127.0.0.1", web) and not port_free("127.0.0.1", grpc)
        proc.send_signal(getattr(signal, signame))
        proc.wait(timeout=20)
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
    assert proc.returncode == 0, proc.stderr.read()
    deadline = time.time() + 10
    while not (port_free("127.0.0.1", web) and port_free("127.0.0.1", grpc)) and time.time() < deadline:
        time.sleep(0.2)
    assert port_free("127.0.0.1", web) and port_free("127.0.0.1", grpc), "the viewer still holds its ports"
