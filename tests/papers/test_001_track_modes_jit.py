"""The compiled kernel of the 001 mode logic (``run_track_modes(engine="jit")``, numba) against the NumPy frame loop
(``engine="numpy"``, the fallback): same seed, same numbers. Detections, modes, gains and thresholds equal
exactly (NaN where not tested); states, statistic, variances and gates to ``rtol = 1e-10`` plus ``atol = 1e-9`` (the
restart-B least-squares fit and the 3x3 covariance products sum in another order). The JIT test skips only when numba
is not importable; the kernels' Python source (the same functions uncompiled) is checked against the NumPy loop
always, so the kernel logic is tested without numba too. The switch: ``TVTRACK_NO_JIT=1`` or ``engine="numpy"``."""

import numpy as np
import pytest

from tvtrack.filters.alphabeta import gain_schedule
from tvtrack.papers.p001_maneuver_occlusion_kf import _track_modes_kernel as kernel
from tvtrack.papers.p001_maneuver_occlusion_kf.maneuver_detector import scheduled_statistic_std, threshold_from_std
from tvtrack.papers.p001_maneuver_occlusion_kf.track_modes import TrackModeConfig, run_track_modes

T = 300
FIELDS = ("x", "var", "gate_var", "gains", "mode", "statistic", "threshold", "detection_frame")
EXACT = ("gains", "mode", "threshold", "detection_frame")
RTOL, ATOL = 1e-10, 1e-9


def _scenario(shape=(3, 4), seed=1):
    rng = np.random.default_rng(seed)
    f = np.arange(T)
    truth = 5.0 * f + 0.08 * np.clip(f - 110, 0, None) ** 2
    z = truth + 2.0 * rng.standard_normal(shape + (T,))
    z[0] = 5.0 * f + 2.0 * rng.standard_normal((shape[1], T))  # trials without a manoeuvre
    gap = (f < 170) | (f >= 215)
    per_trial = rng.random(shape + (T,)) > 0.1
    per_trial[..., :60] = True
    c = threshold_from_std(1e-3, scheduled_statistic_std(gain_schedule(1, 50, T), 25, 1.0))
    return z, {"none": np.ones(T, bool), "gap": gap, "per-trial": per_trial}, np.where(np.isfinite(c), c, np.inf)


def _configs(thr):
    for restart in "ABC":
        yield f"{restart} exact threshold", TrackModeConfig(threshold=thr, restart=restart)
        yield (
            f"{restart} detect in TRACK3",
            TrackModeConfig(threshold=3.0, restart=restart, detect_in_track3=True, k_bound3=60),
        )
        yield f"{restart} forced", TrackModeConfig(force_switch_k=40, restart=restart, k_bound3=60)
    yield "B forced early (short window)", TrackModeConfig(force_switch_k=2, restart="B", window=5)
    yield (
        "threshold by frame, re-arm 10",
        TrackModeConfig(threshold=np.full(T, 4.0), threshold_index="frame", arm_k=60, rearm_after_gap=10),
    )


def _cases():
    z, vis, thr = _scenario()
    for name, cfg in _configs(thr):
        for vname, v in vis.items():
            for cov in (True, False):
                if cfg.restart == "C" and not cov:
                    continue
                yield pytest.param(z, v, cfg, cov, id=f"{name}-{vname}-{'cov' if cov else 'nocov'}")


def _assert_same(a, b):
    for name in FIELDS:
        x, y = getattr(a, name), getattr(b, name)
        assert x.shape == y.shape, name
        if name in EXACT:
            np.testing.assert_array_equal(y, x, err_msg=name)
        else:
            np.testing.assert_allclose(y, x, rtol=RTOL, atol=ATOL, equal_nan=True, err_msg=name)


@pytest.mark.parametrize(("z", "vis", "cfg", "cov"), list(_cases()))
def test_jit_kernel_equals_the_numpy_loop(z, vis, cfg, cov):
    pytest.importorskip("numba")
    ref = run_track_modes(z, vis, cfg, 2.0, cov, engine="numpy")
    assert 0 < np.mean(ref.detection_frame >= 0) <= 1
    _assert_same(ref, run_track_modes(z, vis, cfg, 2.0, cov, engine="jit"))


@pytest.mark.parametrize("cov", [True, False])
@pytest.mark.parametrize("restart", ["A", "B"])
def test_the_kernel_source_uncompiled_equals_the_numpy_loop(monkeypatch, restart, cov):
    """Without numba: the kernels' Python functions run in place of the compiled ones (small batch)."""
    z, vis, thr = _scenario(shape=(2, 3))
    cfg = TrackModeConfig(threshold=thr, restart=restart)
    monkeypatch.setattr(kernel, "available", lambda: True)
    monkeypatch.setattr(
        kernel, "get_kernel", lambda covariance=True: kernel.kernel_python if covariance else kernel.kernel_fast_python
    )
    for v in (vis["gap"], vis["per-trial"]):
        ref = run_track_modes(z, v, cfg, 2.0, cov, engine="numpy")
        assert np.any(ref.detection_frame >= 0) and np.any(ref.detection_frame < 0)
        _assert_same(ref, run_track_modes(z, v, cfg, 2.0, cov, engine="jit"))


def test_the_switch_forces_the_numpy_loop(monkeypatch):
    monkeypatch.setenv("TVTRACK_NO_JIT", "1")
    assert not kernel.use_jit_default()
    calls = []
    monkeypatch.setattr(kernel, "get_kernel", lambda covariance=True: calls.append(covariance))
    z, vis, thr = _scenario(shape=(1, 2))
    run_track_modes(z, vis["gap"], TrackModeConfig(threshold=thr), 1.0, engine="auto")
    assert calls == []  # the compiled kernel was not asked for
    monkeypatch.setenv("TVTRACK_NO_JIT", "0")
    assert kernel.use_jit_default() == kernel.available()


def test_without_numba_auto_is_numpy_and_jit_refuses(monkeypatch):
    monkeypatch.delenv("TVTRACK_NO_JIT", raising=False)
    monkeypatch.setattr(kernel, "available", lambda: False)
    assert not kernel.use_jit_default()
    z, vis, thr = _scenario(shape=(1, 2))
    with pytest.raises(ImportError, match="numba"):
        run_track_modes(z, vis["gap"], TrackModeConfig(threshold=thr), 1.0, engine="jit")
    with pytest.raises(ValueError, match="engine"):
        run_track_modes(z, vis["gap"], TrackModeConfig(threshold=thr), 1.0, engine="cuda")


def test_the_parallel_kernel_gives_the_same_numbers_on_one_thread_and_on_all():
    """The trials run on numba's threads (``prange``): they share nothing, so one thread and all threads give
    bit-identical outputs (a shared accumulator or a trial-indexed write to the wrong row would differ)."""
    numba = pytest.importorskip("numba")
    z, vis, thr = _scenario(shape=(8, 16))
    cfg = TrackModeConfig(threshold=thr, restart="B")
    before = numba.get_num_threads()
    try:
        numba.set_num_threads(1)
        one = [run_track_modes(z, vis["per-trial"], cfg, 2.0, cov, engine="jit") for cov in (True, False)]
        numba.set_num_threads(numba.config.NUMBA_NUM_THREADS)
        many = [run_track_modes(z, vis["per-trial"], cfg, 2.0, cov, engine="jit") for cov in (True, False)]
    finally:
        numba.set_num_threads(before)
    for a, b in zip(one, many):
        for name in FIELDS:
            np.testing.assert_array_equal(getattr(a, name), getattr(b, name), err_msg=name)


def test_reproduce_and_sweep_workers_cap_numba_threads(monkeypatch):
    import os

    from tvtrack.pipeline.interrupt import THREAD_VARS, worker_init

    assert "NUMBA_NUM_THREADS" in THREAD_VARS
    # a copy of the environment: numba re-reads NUMBA_NUM_THREADS at every compile and refuses a change once its
    # threads run, so this process's real environment must not see the worker's value even for a moment
    monkeypatch.setattr(os, "environ", {k: v for k, v in os.environ.items() if k not in THREAD_VARS})
    monkeypatch.setattr("signal.signal", lambda *a: None)
    worker_init(1)
    assert all(os.environ[var] == "1" for var in THREAD_VARS)


@pytest.mark.parametrize("sigma_eps", [0.0, -1.0, np.inf, np.nan])
@pytest.mark.parametrize("engine", ["numpy", "auto"])
def test_a_noise_sd_that_is_not_finite_and_positive_is_refused_by_both_engines(sigma_eps, engine):
    """An infinite noise SD passed the old ``> 0`` check, and the engines disagreed at the detection frame (NaN
    against 0 in the acceleration variance): it is refused, naming the parameter, before either engine runs."""
    z, vis, thr = _scenario(shape=(1, 2))
    with pytest.raises(ValueError, match="parameter 'sigma_eps'.*finite and > 0"):
        run_track_modes(z, vis["gap"], TrackModeConfig(threshold=thr), sigma_eps, engine=engine)
