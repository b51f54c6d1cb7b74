import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from rerun.chunk import RrdReader

from tvtrack.recordings import Recorder, ellipse_outline, image_and_series_blueprint


def rerun_cli() -> str:
    return str(Path(sys.executable).parent / "rerun")


def write_recording(tmp_path, n=6):
    rec = Recorder(
        tmp_path,
        "file",
        "tvtrack-test",
        blueprint=image_and_series_blueprint("camera", ["errors"]),
        frame_interval_s=0.04,
    )
    for k in range(n):
        rec.set_frame(k)
        rec.image("camera/image", np.full((8, 10), k, dtype=np.uint8))
        rec.boxes("camera/gate", [[4.0, 3.0]], [[2.0, 2.0]])
        rec.points("camera/truth", [[4.0, 3.0]])
        rec.lines("camera/covariance", ellipse_outline([4.0, 3.0], np.eye(2)))
    rec.series("errors/x", np.r_[np.nan, np.arange(n - 1.0)])
    path = rec.close()
    return path


def test_recording_has_entities_archetypes_and_rows(tmp_path):
    path = write_recording(tmp_path)
    assert path == tmp_path / "recording.rrd"
    store = RrdReader(path).store()
    summary = {line.split()[0]: line for line in store.summary().splitlines()}
    assert "rows=6" in summary["/camera/image"]
    assert "rows=6" in summary["/camera/gate"]
    assert "rows=5" in summary["/errors/x"]  # the NaN sample is dropped
    names = str(store.schema())
    for archetype in ("Boxes2D", "Scalars", "LineStrips2D", "Image", "Points2D"):
        assert f"rerun.archetypes.{archetype}" in names
    assert [b.kind for b in RrdReader(path).blueprints()] == ["blueprint"]


def test_positions_are_shifted_to_pixel_centres(tmp_path):
    path = write_recording(tmp_path, n=1)
    chunks = [c for c in RrdReader(path).store().stream().to_chunks() if c.entity_path == "/camera/truth"]
    batch = chunks[0].to_record_batch()
    positions = batch.column(batch.schema.names.index("Points2D:positions")).to_pylist()
    assert positions == [[[4.5, 3.5]]]  # library pixel centre (4, 3) drawn at Rerun's (4.5, 3.5)


def test_rerun_verifies_the_file(tmp_path):
    path = write_recording(tmp_path)
    out = subprocess.run([rerun_cli(), "rrd", "verify", str(path)], capture_output=True, text=True, timeout=60)
    assert out.returncode == 0, out.stderr


def test_off_mode_writes_nothing(tmp_path):
    rec = Recorder(tmp_path, "off")
    rec.set_frame(0)
    rec.points("camera/truth", [[1, 2]])
    assert rec.close() is None
    assert not any(tmp_path.iterdir())
    with pytest.raises(ValueError, match="rerun_mode"):
        Recorder(tmp_path, "web")


def test_a_layout_given_as_a_callable_is_built_only_when_the_recording_is_written(tmp_path):
    calls = []

    def layout():
        calls.append(1)
        return image_and_series_blueprint("camera", ["errors"])

    assert Recorder(tmp_path / "off", "off", blueprint=layout).close() is None and calls == []
    rec = Recorder(tmp_path, "file", "tvtrack-test", blueprint=layout)
    rec.set_frame(0)
    rec.points("camera/truth", [[1, 2]])
    assert rec.close() == tmp_path / "recording.rrd" and calls == [1]
    # the layout is in the file: its blueprint stream is there as with a Blueprint passed directly
    (tmp_path / "direct").mkdir()
    direct = Recorder(tmp_path / "direct", "file", "tvtrack-test", blueprint=layout())
    direct.set_frame(0)
    direct.points("camera/truth", [[1, 2]])
    direct.close()
    columns = _layout_columns(tmp_path / "recording.rrd")
    assert columns == _layout_columns(tmp_path / "direct" / "recording.rrd")
    assert columns.count("ViewBlueprint:class_identifier") == 2  # the image view and the one series view


def _layout_columns(path) -> list:
    """The layout columns of a recording file's blueprint store (one per view, container and panel setting), sorted."""
    out = subprocess.run([rerun_cli(), "rrd", "print", "-v", str(path)], capture_output=True, text=True, check=True)
    return sorted(re.findall(r"@(\w+Blueprint:\w+)", out.stdout))


def test_a_sweep_run_that_records_nothing_never_imports_rerun(tmp_path):
    """A run with ``rerun_mode="off"`` (every run of a sweep by default) pays nothing for the layout it discards:
    the fixture notebook's code cells, as they stand, executed in a fresh interpreter with the recording off."""
    fixture = Path(__file__).parent / "fixtures" / "fixture_centroid.ipynb"
    code = (
        "import json, sys\n"
        f"cells = [c for c in json.load(open({str(fixture)!r}))['cells'] if c['cell_type'] == 'code']\n"
        "ns = {}\n"
        "exec(''.join(cells[0]['source']), ns)\n"
        f"ns.update(n_trials=2, n_frames=2, rerun_mode='off', output_dir={str(tmp_path)!r})\n"
        "for cell in cells[1:]:\n"
        "    exec(''.join(cell['source']), ns)\n"
        "assert ns['results'].recording is None\n"
        "print(sorted(m for m in sys.modules if m == 'rerun' or m.startswith('rerun.')))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, cwd=tmp_path)
    assert out.stdout.strip().splitlines()[-1] == "[]"


def test_ellipse_outline_lies_on_the_mahalanobis_contour():
    cov = np.array([[4.0, 1.0], [1.0, 2.0]])
    pts = ellipse_outline([1.0, -1.0], cov, n_sigma=2.0)
    d = pts - [1.0, -1.0]
    m = np.einsum("ni,ij,nj->n", d, np.linalg.inv(cov), d)
    assert np.allclose(m, 4.0)


def test_non_image_spaces_are_logged_unshifted(tmp_path):
    rec = Recorder(tmp_path, "file", "tvtrack-test")
    rec.set_frame(0)
    rec.points("plot/samples", [[10.0, 20.0]], image_space=False)
    chunks = [c for c in RrdReader(rec.close()).store().stream().to_chunks() if c.entity_path == "/plot/samples"]
    batch = chunks[0].to_record_batch()
    assert batch.column(batch.schema.names.index("Points2D:positions")).to_pylist() == [[[10.0, 20.0]]]


def test_notebook_mode_still_writes_the_whole_file(tmp_path):
    # outside Jupyter the widget cannot display, but the file must hold the data either way
    rec = Recorder(tmp_path, "notebook", "tvtrack-test")
    rec.set_frame(0)
    rec.points("camera/truth", [[1.0, 2.0]])
    path = rec.close()
    assert "/camera/truth rows=1" in RrdReader(path).store().summary()


def test_series_on_another_timeline(tmp_path):
    rec = Recorder(tmp_path, "file", "tvtrack-test", frame_interval_s=0.04)
    rec.series("em/loglik", [-10.0, -5.0, -4.5], timeline="iteration")
    store = RrdReader(rec.close()).store()
    line = next(l for l in store.summary().splitlines() if l.startswith("/em/loglik"))
    assert "rows=3" in line and "timelines=['iteration']" in line


@pytest.mark.parametrize("jpeg_quality", [None, 80])
def test_image_draw_order_is_kept(tmp_path, jpeg_quality):
    rec = Recorder(tmp_path, "file", "tvtrack-test")
    rec.set_frame(0)
    rec.image("camera/gate_crop", np.full((8, 8), 100, dtype=np.uint8), jpeg_quality=jpeg_quality, draw_order=5.0)
    assert "draw_order" in str(RrdReader(rec.close()).store().schema())
