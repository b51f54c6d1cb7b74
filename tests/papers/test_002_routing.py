"""002's measurement routing (``study.measure_batch``, ``run_jobs``, ``_Results``, ``rerun``), with the simulator and
the claims' statistics replaced by recorders.

A batch measures each claim at its configuration projected onto the entries it declares (so a track geometry reaches
only the claims that declare it), runs each simulation job once (the longest first, the cached ones never again),
hands each configuration's claims its own seed and points, and merges a point's algorithms from the jobs that ran.
A rerun of a point keeps its own settings variant and adds the one asked, on the same scenes, and is not cached.
"""

from dataclasses import replace

import pytest

from tvtrack.papers.p002_unified_location_em import study
from tvtrack.papers.p002_unified_location_em.register import DEPENDS, REGISTER
from tvtrack.projection import claim_groups

DEFAULT = REGISTER.default()
SCALE = study.Scale(n_trials=6, n_iter_trials=5, crb_phases=4, n_bootstrap=2000, n_workers=1)


@pytest.fixture
def sim(monkeypatch):
    """``run_config`` replaced by a recorder whose result names its job; ``measure_claims`` by one that returns,
    for each claim asked, the configuration, seed, results' settings and scale, resamples and distance axis it was
    handed."""
    ran, measured = [], []
    monkeypatch.setattr(study, "_CACHE", {})

    def run_config(settings, cfg):
        ran.append((settings, cfg))
        return {f"out_{cfg.algs}": (settings.seed, cfg), "timing": {cfg.algs: 1.0, "zero": 0.0}}

    def measure_claims(config, g, res, seed, n_bootstrap, D, claims=None):
        assert g == study._points(config, res.scale)[0]  # the claims' points of their own configuration
        measured.append((config, seed, claims))
        asked = list(DEPENDS) if claims is None else sorted(claims)
        return {cid: (config, seed, (res.settings, res.scale), n_bootstrap, tuple(D)) for cid in asked}

    monkeypatch.setattr(study, "run_config", run_config)
    monkeypatch.setattr(study, "measure_claims", measure_claims)
    return ran, measured


def test_each_claim_is_measured_at_its_projected_configuration_with_its_own_seed(sim):
    ran, measured = sim
    crossing = {**DEFAULT, "tracks": "crossing"}
    declares = sorted(c for c, names in DEPENDS.items() if "tracks" in names)
    others = sorted(c for c in DEPENDS if c not in declares)
    assert declares and others  # the track geometry is declared by some claims only
    out = study.measure_batch([crossing, DEFAULT], [11, 12], SCALE)
    assert set(out[0]) == set(out[1]) == set(DEPENDS)
    for cid in declares:
        assert out[0][cid][0]["tracks"] == "crossing" and out[0][cid][1] == 11
    for cid in others:
        assert out[0][cid][0]["tracks"] == "parallel" and out[0][cid][1] == 11
    assert all(v[0] == DEFAULT and v[1] == 12 for v in out[1].values())
    assert all(v[3] == 2000 and v[4] == study.D_GRID for v in out[0].values())  # the scale's resamples and axis
    # each group's results read the settings of its projected configuration and seed
    for cid in (declares[0], others[0]):
        config, seed, (settings, scale), *_ = out[0][cid]
        assert settings == study.settings_of(config, seed, SCALE) and scale is SCALE


def test_the_jobs_of_every_group_run_once(sim):
    ran, measured = sim
    configs = [{**DEFAULT, "tracks": "crossing"}, DEFAULT, DEFAULT]
    study.measure_batch(configs, [11, 12, 12], SCALE)
    want = set()
    for c, s in zip(configs, (11, 12, 12)):
        for pc, k in claim_groups(c, None, DEPENDS, DEFAULT):
            want |= set(study.jobs_of(pc, s, SCALE, claims=k))
    assert len(ran) == len(set(ran)) == len(want) and set(ran) == want
    n = len(ran)
    study.measure_batch([DEFAULT], [12], SCALE)  # every job cached: nothing runs again
    assert len(ran) == n


def test_claims_asked_per_configuration_run_only_their_jobs(sim):
    ran, measured = sim
    out = study.measure_batch([DEFAULT, DEFAULT], [3, 4], SCALE, claims=[{"C002-15"}, None])
    assert set(out[0]) == {"C002-15"} and set(out[1]) == set(DEPENDS)
    assert {(s.seed, c.algs) for s, c in ran if s.seed == 3} == {(3, "u"), (3, "r")}
    assert [m[2] for m in measured] == [{"C002-15"}, None]
    with pytest.raises(ValueError, match="1 claim sets for 2 configurations"):
        study.measure_batch([DEFAULT, DEFAULT], [3, 4], SCALE, claims=[None])


def test_one_measurement_is_the_batch_of_one(sim):
    assert (
        study.measure(DEFAULT, 5, SCALE, claims={"C002-1"})
        == study.measure_batch([DEFAULT], [5], SCALE, [{"C002-1"}])[0]
    )
    assert set(study.measure(DEFAULT, 5, SCALE)) == set(DEPENDS)


def test_the_longest_jobs_run_first_and_cached_ones_never(sim):
    ran, _ = sim
    s = study.settings_of(DEFAULT, 1, SCALE)
    P = study._Points(DEFAULT, SCALE)
    a, b = P(2, 1, 3, 20, 5, "u"), P(2, 1, 3, 20, 5, "e", n=12)
    c, d = P(2, 1, 3, 20, 25, "u"), P(2, 1, 3, 20, 35, "u")
    jobs = [(s, a), (s, b), (s, c), (s, d), (s, a)]
    study.run_jobs(jobs)
    # frames x trials, three times for the EM algorithms: d 35 x 6 = 210, b 5 x 12 x 3 = 180, c 150, a 30
    assert [c_ for _, c_ in ran] == [d, b, c, a]
    study.run_jobs(jobs)
    assert len(ran) == 4
    assert study._CACHE[(s, d)] == {"out_u": (1, d), "timing": {"u": 1.0, "zero": 0.0}}


@pytest.fixture
def pool(monkeypatch):
    """``fork_pool`` replaced by one that maps here and records its workers and chunk sizes."""
    pools = []

    class Pool:
        def __init__(self, n):
            pools.append([n])

        def __enter__(self):
            return self

        def __exit__(self, *exc):
            return False

        def map(self, fn, items, chunksize=None):
            pools[-1].append(chunksize)
            return [fn(j) for j in items]

    monkeypatch.setattr(study, "fork_pool", Pool)
    return pools


def test_jobs_run_in_workers_give_what_they_give_here(sim, pool):
    ran, _ = sim
    s = study.settings_of(DEFAULT, 1, SCALE)
    P = study._Points(DEFAULT, SCALE)
    jobs = [(s, P(2, d, 3, 20, 10, "u")) for d in (1.0, 2.0)]
    study.run_jobs(jobs, n_workers=2)
    assert pool == [[2, 1]] and len(ran) == 2  # one job at a time, so the longest start first
    assert all(study._CACHE[j] == {"out_u": (1, j[1]), "timing": {"u": 1.0, "zero": 0.0}} for j in jobs)
    study.run_jobs([(s, P(2, 4.0, 3, 20, 10, "u"))], n_workers=2)  # one job: here, no pool
    assert pool == [[2, 1]] and len(ran) == 3


def test_a_batch_and_the_figures_run_their_jobs_in_the_scales_workers(sim, pool):
    two = replace(SCALE, n_workers=2)
    study.measure_batch([DEFAULT], [5], two, [{"C002-15"}])
    study.figure_data(DEFAULT, 6, two)
    assert [p[0] for p in pool] == [2, 2]


def test_a_points_results_merge_the_letters_that_ran(sim):
    s = study.settings_of({**DEFAULT, "tracks": "crossing"}, 1, SCALE)
    P = study._Points(DEFAULT, SCALE)
    point = P(2, 1.0, 3.0, 20, 10, "ue")
    study.run_jobs([(study._job_settings(s, a, SCALE, 2), point._replace(algs=a)) for a in "ue"])
    one = P(1, 0.0, 3.0, 20, 10, "up")
    study.run_jobs([(study._job_settings(s, a, SCALE, 1), one._replace(algs=a)) for a in "up"])
    res = study._Results(s, SCALE)
    assert res[one]["out_p"] == (1, one._replace(algs="p"))  # one object's jobs: parallel tracks, its own key
    got = res[point]
    assert got["out_u"] == (1, point._replace(algs="u")) and got["out_e"] == (1, point._replace(algs="e"))
    assert got["timing"] == {"u": 1.0, "e": 1.0}  # the zero timings left out
    only_u = res[point._replace(algs="uc")]  # a letter that did not run is missing, the others are there
    assert "out_u" in only_u and "out_c" not in only_u
    with pytest.raises(KeyError, match="no algorithm of"):
        res[point._replace(algs="c")]


def test_a_rerun_keeps_the_points_variant_adds_the_one_asked_and_is_not_cached(sim):
    ran, _ = sim
    s = study.settings_of({**DEFAULT, "tracks": "crossing"}, 1, SCALE)
    res = study._Results(s, SCALE)
    P = study._Points(DEFAULT, SCALE)
    point = P(2, 1.0, 3.0, 20, 10, "upq", variant=(("tol_loglik", 0.1),))
    out = study.rerun(res, point, "pu", max_iter=10**6)
    assert [c.algs for _, c in ran] == ["p", "u"]
    for job, c in ran:
        assert c.variant == (("max_iter", 10**6), ("tol_loglik", 0.1))  # sorted by name
        assert job == study._job_settings(s, c.algs, SCALE, c.q)
    assert set(out) == {"out_p", "out_u", "timing"} and study._CACHE == {}
    plain = P(2, 1.0, 3.0, 20, 10, "u")
    study.rerun(res, plain, "u", tol_loglik=0.01)
    assert ran[-1][1].variant == (("tol_loglik", 0.01),)
    one = P(1, 0.0, 3.0, 20, 10, "u")
    study.rerun(res, one, "u")
    assert ran[-1][0] == study._job_settings(s, "u", SCALE, 1) and ran[-1][0].tracks == "parallel"


def test_the_figures_data_run_every_figure_job_and_read_them_back(sim):
    ran, _ = sim
    g, res = study.figure_data(DEFAULT, 9, SCALE)
    assert set(ran) == set(study.jobs_of(DEFAULT, 9, SCALE, figures=True))
    assert g.keys() == study._points(DEFAULT, SCALE, figures=True)[0].keys()
    assert res.settings == study.settings_of(DEFAULT, 9, SCALE) and res.scale is SCALE
    point = g["4"][50][8.0]
    assert res[point]["out_r"] == (9, point._replace(algs="r"))
