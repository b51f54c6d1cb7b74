"""Issue 43 (notebook 001's cost): the compiled IMM twin equals imm_run to rounding, a batched grid of IMM
settings equals the per-setting runs bit for bit, and the cached comparator tuning equals a cold one bit for bit."""

import numpy as np
import pytest

from tvtrack import jit
from tvtrack.filters._imm_kernel import imm_states
from tvtrack.filters.imm import cv_ca_models, imm_run
from tvtrack.papers.p001_maneuver_occlusion_kf import comparators, study

GRIDS = (
    ("fixed2", (2, 10, 50)),
    ("fixed3", (3, 20, 100)),
    ("imm_q_ca", (1e-4, 1e-3)),
    ("imm_p_stay", (0.99, 0.999)),
    ("vdf_q_ca", (1e-6, 1e-5)),
    ("vdf_windows", (5, 10)),
)


def _series(n=6, seed=1):
    sc = study.scenario()
    z = study.measurements(sc.truth[:, :, 0], "white Gaussian", n, np.random.default_rng(seed))
    return sc, np.where(sc.visible, z, np.nan)


@pytest.mark.skipif(not jit.enabled(), reason="numba absent or switched off")
@pytest.mark.parametrize("coast", ["mix", "frozen", "mode"])
def test_compiled_imm_equals_imm_run(coast):
    sc, zz = _series()
    for q, p in ((1e-4, 0.99), (1e-2, 0.99999)):
        Fs, Qs = cv_ca_models(0.0, q)
        M = np.array([[p, 1 - p], [1 - p, p]])
        args = (Fs, Qs, 2.0, M, np.zeros(3), np.diag([1e6, 1e4, 1.0]), [0.5, 0.5], coast)
        ref = imm_run(zz[..., None], Fs, Qs, np.eye(1, 3), np.array([[2.0]]), *args[3:-1], coast=coast).x
        got = imm_states(zz, *args, engine="jit")
        assert got.shape == ref.shape == zz.shape + (3,)
        # the sums run in another order than BLAS's: equal to rounding, errors of hundreds of elements while lost
        np.testing.assert_allclose(got, ref, rtol=1e-9, atol=1e-9)
        assert np.array_equal(imm_states(zz, *args, engine="numpy"), ref)


def test_imm_run_over_a_grid_of_settings_equals_one_run_per_setting():
    sc, zz = _series(4)
    sets = [(1e-4, 0.99), (1e-3, 0.999), (1e-2, 0.9)]
    Fs = cv_ca_models(0.0, 1.0)[0]
    Qs = np.stack([cv_ca_models(0.0, q)[1] for q, _ in sets])[:, None, None]
    M = np.stack([np.array([[p, 1 - p], [1 - p, p]]) for _, p in sets])[:, None, None]
    zb = np.broadcast_to(zz[None, ..., None], (len(sets),) + zz.shape + (1,))
    args = (np.eye(1, 3), np.array([[1.0]]))
    prior = (np.zeros(3), np.diag([1e6, 1e4, 1.0]), [0.5, 0.5])
    grid = imm_run(zb, Fs, Qs, *args, M, *prior, coast="mode")
    for i, (q, _p) in enumerate(sets):
        one = imm_run(zz[..., None], Fs, cv_ca_models(0.0, q)[1], *args, M[i, 0, 0], *prior, coast="mode")
        assert np.array_equal(grid.x[i], one.x) and np.array_equal(grid.loglik[i], one.loglik)


def _clear():
    for f in (
        comparators.tuned_comparators,
        comparators._training,
        comparators._scores_without_alpha,
        comparators._vd_statistic,
        comparators._scores_vd,
    ):
        f.cache_clear()


def test_cached_tuning_equals_a_cold_tuning_bit_for_bit():
    key = (25.0, 5, 11)
    _clear()
    comparators.tuned_comparators(*key, 1e-3, 1.0, GRIDS)  # warms the world's grid runs
    warm = comparators.tuned_comparators(*key, 1e-2, 1.0, GRIDS)
    assert comparators._scores_without_alpha.cache_info().hits >= 1  # alpha reused the alpha-free grids
    _clear()
    cold = comparators.tuned_comparators(*key, 1e-2, 1.0, GRIDS)
    assert warm == cold
    # another world is tuned afresh: the weaker acceleration unit changes the training truth
    other = comparators.tuned_comparators(*key, 1e-2, 1.0, GRIDS, accel_unit="el/frame per s")
    assert other != cold
