"""The frame rate is an unreported setting of the paper's own experiment: the paper states its motion per frame
("10 элементов растра за кадр", "ускорением 0,2 элемента растра за кадр") and its times in seconds (the onset at
5 s, the loss at 12 s, the return at 22 s), so at any frame rate the motion stays 10 el/frame and 0.2 el/frame² and
only the seconds become frames."""

import numpy as np
import pytest

from tvtrack.papers.p001_maneuver_occlusion_kf import scenario as scn
from tvtrack.papers.p001_maneuver_occlusion_kf import study
from tvtrack.papers.p001_maneuver_occlusion_kf.register import build_register

REG = build_register()


@pytest.mark.parametrize("fps", [25.0, 50.0])
def test_the_paper_s_per_frame_motion_holds_at_every_frame_rate(fps):
    sc = scn.config_scenario({**REG.default(), "frame_rate_hz": fps})
    assert (sc.onset, sc.f_loss, sc.f_back, sc.T) == (5 * fps, 12 * fps, 22 * fps, 25 * fps)
    x, v, a = sc.truth[0, :, 0], sc.truth[0, :, 1], sc.truth[0, :, 2]
    assert np.allclose(v[: sc.onset], 10.0) and np.allclose(np.diff(x[: sc.onset + 1]), 10.0)  # 10 el/frame
    assert np.allclose(a[sc.onset :], 0.2) and np.allclose(a[: sc.onset], 0.0)  # 0.2 el/frame²
    assert v[sc.f_loss] == pytest.approx(10.0 + 0.2 * (sc.f_loss - sc.onset))
    assert np.allclose(sc.truth[1, : sc.onset, 1], -6.0)  # the second channel per frame too


@pytest.mark.parametrize("fps", [25.0, 50.0])
def test_the_per_second_acceleration_reading_is_0_2_over_the_frame_rate(fps):
    sc = scn.config_scenario({**REG.default(), "frame_rate_hz": fps, "accel_unit": "el/frame per s"})
    assert sc.truth[0, sc.onset, 2] == pytest.approx(0.2 / fps)  # 0.2 el/frame gained in fps frames
    # one second after the onset the velocity has grown by 0.2 el/frame
    assert sc.truth[0, sc.onset + int(fps), 1] - sc.truth[0, sc.onset, 1] == pytest.approx(0.2)


def test_the_step_alternative_and_the_null_runs_are_per_frame_at_50_hz():
    sc = scn.config_scenario({**REG.default(), "frame_rate_hz": 50.0})
    step = study._step_truth({"step_dv": 1.0}, sc, sc.onset + 10)
    assert np.allclose(np.diff(step[0, : sc.onset + 1]), 10.0) and np.allclose(np.diff(step[0, sc.onset + 1 :]), 11.0)
    assert np.allclose(np.diff(step[1, sc.onset + 1 :]), -7.0)  # away from the second channel's -0.2
    assert np.allclose(np.diff(scn.uniform_truth(40)), 10.0)


def test_the_entry_is_filed_and_worded_as_an_unreported_setting():
    e = REG["frame_rate_hz"]
    assert e.kind == "unreported setting"
    words = " ".join([e.title, e.why, *map(str, e.phrases.values())]).lower()
    assert "elements per second" not in words and "elements/s" not in words and "fixed motion" not in words
    assert "per frame" in words and "never printed" in words


# ----------------------------------------------------------------------------------- C001-9 at the frame rate


def test_c001_9_reads_the_paper_s_per_frame_rates_at_the_frame_rate():
    """The paper's rates are 10 el/frame (6°/712 an element) and 0.02°/frame: 2.107°/s and 0.5°/s at 25 Hz, twice
    that at 50 Hz; C001-9 declares the frame rate it reads."""
    from tvtrack.papers.p001_maneuver_occlusion_kf import spherical
    from tvtrack.papers.p001_maneuver_occlusion_kf.register import DEPENDS

    assert "frame_rate_hz" in DEPENDS["C001-9"] and "k_bound3" in DEPENDS["C001-9"]
    at25 = list(spherical.paper_rates(25.0).values())
    assert at25 == pytest.approx([10 * 25 * 6 / 712, 0.02 * 25]) and at25[0] == pytest.approx(2.107, abs=1e-3)
    assert list(spherical.paper_rates(50.0).values()) == pytest.approx([10 * 50 * 6 / 712, 0.02 * 50])
    sz = {"defaults": REG.default(), "prediction_rms": 7.6}
    slow = "0.5°/s (0.02°/frame)"
    m25 = spherical.measure_spherical({}, 0, sz)["C001-9"][slow]
    m50 = spherical.measure_spherical({"frame_rate_hz": 50.0}, 0, sz)["C001-9"][slow]
    assert m25 == pytest.approx(spherical.field_deviation(0.5, 10.0, "quadratic")["deviation_el"])
    assert m50 == pytest.approx(spherical.field_deviation(1.0, 10.0, "quadratic")["deviation_el"]) and m50 > m25


def test_c001_9_s_filter_memory_is_k_b3_frames_at_the_frame_rate():
    """The filter-memory horizon is k_b3 frames: 100 frames are 4 s at 25 Hz, 2 s at 50 Hz; 200 frames 8 s."""
    from tvtrack.papers.p001_maneuver_occlusion_kf import spherical

    cfg = {**REG.default(), "horizon": "k_b3 filter memory"}
    assert spherical.horizon_seconds(cfg) == pytest.approx(4.0)
    assert spherical.horizon_seconds({**cfg, "frame_rate_hz": 50.0}) == pytest.approx(2.0)
    assert spherical.horizon_seconds({**cfg, "k_bound3": 200}) == pytest.approx(8.0)
    assert spherical.horizon_seconds(REG.default()) == 10.0
    with pytest.raises(ValueError, match=r"horizon '4 s'; it must be one of \('10 s loss', 'k_b3 filter memory'\)"):
        spherical.horizon_seconds({**cfg, "horizon": "4 s"})
    sz = {"defaults": REG.default(), "prediction_rms": 7.6}
    # in frames the deviation is the same at both rates: 2 s at 1°/s is 4 s at 0.5°/s
    lin = {"horizon": "k_b3 filter memory", "extrapolation": "linear"}
    m25 = spherical.measure_spherical(lin, 0, sz)["C001-9"]["0.5°/s (0.02°/frame)"]
    m50 = spherical.measure_spherical(lin | {"frame_rate_hz": 50.0}, 0, sz)["C001-9"]["0.5°/s (0.02°/frame)"]
    assert m25 == pytest.approx(2.954, abs=0.01) and m50 == pytest.approx(m25)


def test_fig4_grid_spans_the_same_seconds_at_every_frame_rate_so_the_optimum_is_not_cut_off():
    """The bound is counted in frames, but the grid's range is this project's: at 50 frames/s the reference grid
    (20-200 frames) ends before the switch-to-loss gap of 325 frames, and curve 3 would sit lowest on its edge for
    want of points. Stretched with the frame rate, the optimum is interior and at the same time as at 25 frames/s
    (100 frames at 25, 200 at 50: 4 s)."""
    from tvtrack.papers.p001_maneuver_occlusion_kf import curves
    from tvtrack.papers.p001_maneuver_occlusion_kf.register import build_register

    d = build_register().default()
    grid = [20, 30, 40, 50, 60, 70, 80, 90, 100, 110, 120, 130, 140, 160, 200]
    sizes = dict(defaults=d, sigma_eps=1.0, kb3_grid=grid)
    assert curves.kb3_grid(d, sizes) == grid
    at = {}
    for fps in (25.0, 50.0):
        cur = curves.fig4_curves({"frame_rate_hz": fps}, sizes)
        assert list(cur["kb3"]) == [round(k * fps / 25.0) for k in grid]
        assert curves.c8_parts(cur)["interior minimum"] > 0
        at[fps] = cur["kb3"][cur["sum"].argmin()] / fps
    assert at[50.0] == pytest.approx(at[25.0])
