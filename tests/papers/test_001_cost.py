"""Notebook 001's cost: the compiled IMM twin equals imm_run to rounding, a batched grid of IMM
settings equals the per-setting runs bit for bit, and the cached comparator tuning equals a cold one bit for bit."""

import re

import numpy as np
import pytest

from tvtrack import jit
from tvtrack.filters._imm_kernel import imm_states
from tvtrack.filters.imm import cv_ca_models, imm_run
from tvtrack.papers.p001_maneuver_occlusion_kf import comparators, study
from tvtrack.papers.p001_maneuver_occlusion_kf import curves
from tvtrack.papers.p001_maneuver_occlusion_kf import scenario
from tvtrack.papers.p001_maneuver_occlusion_kf import spherical

GRIDS = (
    ("fixed2", (2, 10, 50)),
    ("fixed3", (3, 20, 100)),
    ("imm_q_ca", (1e-4, 1e-3)),
    ("imm_p_stay", (0.99, 0.999)),
    ("vdf_q_ca", (1e-6, 1e-5)),
    ("vdf_windows", (5, 10)),
)


def _series(n=6, seed=1):
    sc = scenario.scenario()
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


_FS, _QS = cv_ca_models(0.01, 0.1)
_M = np.array([[0.95, 0.05], [0.05, 0.95]])
_IMM = dict(Fs=_FS, Qs=_QS, R=2.0, transition=_M, x0=np.zeros(3), P0=np.diag([10.0, 1.0, 0.1]), mu0=[0.5, 0.5])
#: arguments imm_run refuses, on which the compiled kernel ran (reading past its arrays' ends, or on numbers that
#: are not probabilities); Fs, Qs (2, 3, 3), two trials
_REFUSED = {
    "x0 of length 2": dict(x0=np.zeros(2)),
    "x0 of other trials": dict(x0=np.zeros((3, 3))),
    "P0 2 x 2": dict(P0=np.eye(2)),
    "Qs (2, 2, 2)": dict(Qs=np.ones((2, 2, 2))),
    "Fs (2, 3, 4)": dict(Fs=np.zeros((2, 3, 4)), Qs=np.zeros((2, 3, 4)), x0=np.zeros(4), P0=np.eye(4)),
    "mu0 of length 1": dict(mu0=[1.0]),
    "mu0 summing to 1.8": dict(mu0=[0.9, 0.9]),
    "mu0 negative": dict(mu0=[1.5, -0.5]),
    "transition 1 x 1": dict(transition=[[1.0]]),
    "transition 3 x 3": dict(transition=np.eye(3)),
    "transition not stochastic": dict(transition=[[0.5, 0.2], [0.9, 0.9]]),
    "transition negative": dict(transition=[[1.1, -0.1], [0.05, 0.95]]),
    "R negative": dict(R=-2.0),  # both engines ran, to different meaningless numbers (imm_run's log|S|)
    "R NaN": dict(R=np.nan),
    "R infinite": dict(R=np.inf),
}


def _zz(n=2, seed=2):
    z = 0.5 * np.arange(50.0) ** 1.2 + np.random.default_rng(seed).standard_normal((n, 50))
    z[:, 20:26] = np.nan
    return z


@pytest.mark.parametrize("case", list(_REFUSED))
def test_compiled_imm_refuses_what_imm_run_refuses(case):
    args = _IMM | _REFUSED[case]
    with pytest.raises(ValueError, match="parameter|inconsistent IMM shapes") as refused:
        imm_states(_zz(), **args, engine="numpy")
    with pytest.raises(ValueError, match=re.escape(str(refused.value))):
        imm_states(_zz(), **args, engine="jit")


@pytest.mark.skipif(not jit.enabled(), reason="numba absent or switched off")
@pytest.mark.parametrize("coast", ["mix", "mode"])
def test_compiled_imm_broadcasts_its_parameters_as_imm_run(coast):
    """A scalar x0 made the kernel read past the array's end (other numbers at each call); a scalar P0 and parameters
    per trial (a grid of settings) did not compile. The kernel takes them as imm_run does, and a parameter per trial
    gives each trial the numbers of its own call, bit for bit."""
    rng = np.random.default_rng(4)
    per_trial = dict(
        Qs=np.stack([_QS, 3 * _QS, 0.5 * _QS]),
        transition=np.stack([_M, np.eye(2), [[0.9, 0.1], [0.2, 0.8]]]),
        x0=rng.standard_normal((3, 3)),
        P0=np.stack([np.eye(3), np.diag([10.0, 1.0, 0.1]), 2 * np.eye(3)]),
    )
    zz = _zz(3)
    cases = [dict(x0=5.0), dict(x0=[[5.0, 1.0, 0.5]]), dict(P0=4.0), dict(x0=per_trial["x0"]), per_trial]
    for case in cases:
        args = _IMM | case | dict(coast=coast)
        got = imm_states(zz, **args, engine="jit")
        np.testing.assert_allclose(got, imm_states(zz, **args, engine="numpy"), rtol=1e-9, atol=1e-9)
        assert np.array_equal(got, imm_states(zz, **args, engine="jit"))  # the same numbers at each call
    for b in range(3):
        one = args | {k: v[b] for k, v in per_trial.items()}
        assert np.array_equal(got[b], imm_states(zz[b], **one, engine="jit"))


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


SIZES = dict(
    n_trials=40,
    n_fa_runs=600,
    fa_duration_s=12.0,
    sigma_eps=1.0,
    n_train=5,
    n_tradeoff_trials=12,
    train_seed=9,
    kb3_grid=[20, 100, 200],
    loss_grid_s=[6.0, 12.0],
    grids=dict(GRIDS),
    prediction_rms=3.0,
)


@pytest.fixture(scope="module")
def sizes():
    from tvtrack.papers.p001_maneuver_occlusion_kf.register import build_register

    return SIZES | {"defaults": build_register().default()}


@pytest.mark.parametrize("cfg", [{}, {"alternative": "step", "noise": "Student t, 3 dof"}])
def test_detection_measures_only_the_asked_claims_and_each_as_in_a_full_run(cfg, sizes):
    full = study.measure_detection(cfg, 5, sizes)
    assert set(full) == {"C001-1", "C001-2", "C001-3"}
    for asked in ({"C001-1"}, {"C001-2"}, {"C001-3"}, {"C001-1", "C001-3"}):
        got = study.measure_detection(cfg, 5, sizes, claims=frozenset(asked))
        assert set(got) == asked
        assert repr(got) == repr({k: full[k] for k in full if k in asked})  # bit for bit (repr keeps NaNs)
    assert study.measure_detection(cfg, 5, sizes, claims=frozenset({"C001-4"})) == {}


def test_the_other_measurements_take_claims(sizes):
    full = curves.measure_curves({}, 0, sizes)
    for cid in ("C001-7", "C001-8"):
        assert repr(curves.measure_curves({}, 0, sizes, claims=frozenset({cid}))) == repr({cid: full[cid]})
    assert study.measure_tradeoff({}, 3, sizes, claims=frozenset({"C001-1"})) == {}
    assert repr(study.measure_tradeoff({}, 3, sizes, claims=frozenset({"C001-4"}))) == repr(
        study.measure_tradeoff({}, 3, sizes)
    )
    assert spherical.measure_spherical({}, 0, sizes, claims=frozenset()) == {}
    assert set(spherical.measure_spherical({}, 0, sizes, claims=None)) == {"C001-9"}


def test_vd_filter_over_a_grid_of_process_noises_equals_one_run_per_setting():
    from tvtrack.filters.vdf import vd_filter_run

    sc, zz = _series(5, seed=3)
    z = np.where(np.isnan(zz), 0.0, zz)
    qs = (1e-6, 1e-4, 1e-2)
    grid = vd_filter_run(np.broadcast_to(z, (3,) + z.shape), sc.visible, 0.0, np.reshape(qs, (3, 1, 1)), 1.0, 5, 8.0)
    assert (grid.detection_frame >= 0).any()  # the restart branch runs
    for i, q in enumerate(qs):
        one = vd_filter_run(z, sc.visible, 0.0, q, 1.0, 5, 8.0)
        assert np.array_equal(grid.x[i], one.x) and np.array_equal(grid.detection_frame[i], one.detection_frame)
    with pytest.raises(ValueError):
        vd_filter_run(z, sc.visible, 0.0, np.full((5, 2), -1.0), 1.0, 5, 8.0)


def test_detector_benchmark_with_no_manoeuvre_runs_shorter_than_the_loss_time(sizes):
    """fa_duration_s = 8 s (its range's floor) against the loss at 12 s: the benchmark failed (null statistic
    shorter than the scenario runs); the null runs now last at least to the loss, the same as 12 s."""
    a = study.detector_benchmark({}, 2, sizes | {"fa_duration_s": 8.0, "n_fa_runs": 300})
    b = study.detector_benchmark({}, 2, sizes | {"fa_duration_s": 12.0, "n_fa_runs": 300})
    assert repr(a) == repr(b)


def test_the_detection_exploration_asking_for_claims_keeps_every_record(sizes):
    """The explorer asks measure_detection only for the claims a run needs (claims=): every claim's record (parts,
    verdicts, flips, label) is the one of an exploration that measures every claim in every run."""
    import functools
    import json

    from tvtrack.explore import explore
    from tvtrack.papers.p001_maneuver_occlusion_kf.claims import RULES
    from tvtrack.papers.p001_maneuver_occlusion_kf.register import DEPENDS, GROUPS, build_register, group_register

    sz = sizes | {"n_trials": 30, "n_fa_runs": 300}
    ids = GROUPS["detection"]

    def every_claim(config, seed):
        return study.measure_detection(config, seed, sz)

    records = []
    for fn in (functools.partial(study.measure_detection, sizes=sz), every_claim):
        ex = explore(
            fn,
            group_register(build_register(), "detection"),
            {c: RULES[c] for c in ids},
            depends=DEPENDS,
            seed=7,
            replicates=3,
            joint=4,
            max_subset=2,  # pairs are searched as triples are: the same asked-claims path at a third of the cost
        )
        rec = {c: json.loads(json.dumps(ex.record(c, RULES[c]), default=repr)) for c in ids}
        for r in rec.values():
            for k in ("timing", "measures_claims_asked"):
                r["design"].pop(k, None)
        records.append(rec)
    assert records[0] == records[1]
