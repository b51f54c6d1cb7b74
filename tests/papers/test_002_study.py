"""Tests of paper 002's measurement functions (the explorer's entry point) and its register."""

import numpy as np
import pytest

from tvtrack.montecarlo import Estimate
from tvtrack.papers.p002_unified_location_em import claim_values, extras, study
from tvtrack.papers.p002_unified_location_em.readings import COORDINATE6, FIG1_PANEL, TRIMMED
from tvtrack.papers.p002_unified_location_em.register import DEPENDS, REGISTER

TINY = study.Scale(
    n_trials=4,
    n_iter_trials=4,
    separations=(1.0, 2.0, 3.0, 4.0, 6.0, 8.0),
    fig3_frames=(5, 10, 50),
    crb_phases=2,
    n_workers=1,
    max_iter=40,
)
DEFAULT = REGISTER.default()


def _letters(jobs):
    return {(j[1]._replace(algs=""), j[1].algs): j[0] for j in jobs}


def test_register_covers_every_claim_and_names_real_entries():
    assert set(DEPENDS) == set(study.CLAIMS)
    for cid, names in DEPENDS.items():
        assert set(names) <= set(REGISTER.names), cid
    assert {e.origin for e in REGISTER.entries} == {"author", "adversarial"}


def test_a_statistic_reruns_nothing_and_a_comparator_reruns_only_its_algorithm():
    base = _letters(study.jobs_of(DEFAULT, 7, TINY))
    assert _letters(study.jobs_of({**DEFAULT, "statistic": "MSE", "epoch": "mid"}, 7, TINY)) == base
    two = _letters(study.jobs_of({**DEFAULT, "two-stage": "previous start + assignment"}, 7, TINY))
    changed = {k[1] for k in base if base[k] != two[k]}
    assert changed == {"e", "q"}
    vel = _letters(study.jobs_of({**DEFAULT, "velocity knowledge": "designated"}, 7, TINY))
    assert {k[1] for k in base if base[k] != vel[k]} == set()
    assert {k[1] for k in set(vel) - set(base)} == {"k"}  # the ML ULA given the designated velocity
    assert "m" not in {k[1] for k in base}  # the MAP-ULA runs only under its own reading of "ULA"
    mp = {**DEFAULT, "ULA": "MAP (designation prior)"}
    base_map = _letters(study.jobs_of(mp, 7, TINY))
    vel_map = _letters(study.jobs_of({**mp, "velocity knowledge": "designated"}, 7, TINY))
    assert {k[1] for k in base_map if base_map[k] != vel_map[k]} == {"m"}
    assert {k[1] for k in set(base_map) - set(base)} == {"m"}
    world = _letters(study.jobs_of({**DEFAULT, "photon model": "poisson"}, 7, TINY))
    assert all(base[k] != world[k] for k in base)  # a regime of the world redraws every scene


def test_replicates_are_independent_and_reproducible():
    study.clear_cache()
    a = study.measure(DEFAULT, 11, TINY)
    study.clear_cache()
    again = study.measure(DEFAULT, 11, TINY)
    other = study.measure(DEFAULT, 12, TINY)
    assert set(a) == set(study.CLAIMS) - {"C002-16"}
    assert a["C002-3"].value == again["C002-3"].value
    assert a["C002-3"].value != other["C002-3"].value
    assert set(a["C002-11"]) == {"d = 1 sigma (paper x4.5)", "d = 3 sigma (paper x4)"}
    assert len(a["C002-1"]) == len(TINY.separations) and len(a["C002-10"]["closer"]) == len(TINY.separations)


# Which claims a measurement returns does not depend on its size: the register sweep below runs at the smallest
# scale that still measures every claim (two trials, one CRB phase), half TINY's work over its 53 configurations.
SMALLEST = study.Scale(
    n_trials=2,
    n_iter_trials=2,
    separations=TINY.separations,
    fig3_frames=TINY.fig3_frames,
    crb_phases=1,
    n_workers=1,
    max_iter=20,
)


@pytest.mark.slow
def test_every_register_value_measures_every_claim():
    configs = [{**DEFAULT, e.name: v} for e in REGISTER.entries for v in e.alternatives]
    outs = study.measure_batch(configs, [5] * len(configs), SMALLEST)
    for cfg, out in zip(configs, outs):
        assert set(out) == set(study.CLAIMS) - {"C002-16"}, cfg


def test_map_headline_compares_with_the_twin_of_the_same_knowledge():
    study.clear_cache()
    cfg = {**DEFAULT, "ULA": "MAP (designation prior)"}
    out = study.measure(cfg, 3, TINY)["C002-11"]
    g, res = study.figure_data(cfg, 3, TINY)
    r, rm = res[g["5ab"][50][1.0]], res[g["head_map"][1.0]]
    # the same statistic computed here from the free-velocity twin (the plain line fit) and the MAP-ULA
    direct = (
        claim_values.errors(r, "em").var(axis=0, ddof=1).sum()
        / claim_values.errors(rm, "map").var(axis=0, ddof=1).sum()
    )
    assert out["d = 1 sigma (paper x4.5)"].value == pytest.approx(direct)


def test_word_follows_the_interval():
    assert extras.word(Estimate(2.0, 0.1, 1.5, 2.5, 10)) == "above"
    assert extras.word(Estimate(0.5, 0.1, 0.3, 0.8, 10)) == "below"
    assert extras.word(Estimate(1.0, 0.1, 0.8, 1.2, 10)) == "not distinguishable from"
    assert extras.word(Estimate(1.0, np.nan, np.nan, np.nan, 10)) == "undetermined against"


def test_crossing_tracks_swap_sides_at_mid_sequence():
    from tvtrack.papers.p002_unified_location_em.model import frame_times, scene_geometry
    from tvtrack.papers.p002_unified_location_em.simulation import track_velocities

    v = track_velocities((0.2, 0.1), "crossing", 2, 3.0, 11)
    g = scene_geometry(2, 11, 3.0, 1.0, v)
    t = frame_times(11)
    dy = (g.theta[1, 1] + g.theta[1, 3] * t) - (g.theta[0, 1] + g.theta[0, 3] * t)
    np.testing.assert_allclose(dy[[0, 5, 10]], [3.0, 0.0, -3.0])
    np.testing.assert_allclose(track_velocities((0.2, 0.1), "parallel", 2, 3.0, 11), [[0.2, 0.1], [0.2, 0.1]])
    np.testing.assert_allclose(track_velocities((0.2, 0.1), "crossing", 1, 3.0, 11), [[0.2, 0.1]])
    # diverging (the paper's satellites separating after release): d apart at the start, 3 d at the end
    g = scene_geometry(2, 11, 3.0, 1.0, track_velocities((0.2, 0.1), "diverging", 2, 3.0, 11))
    dy = (g.theta[1, 1] + g.theta[1, 3] * t) - (g.theta[0, 1] + g.theta[0, 3] * t)
    np.testing.assert_allclose(dy[[0, 5, 10]], [3.0, 6.0, 9.0])


def test_mean_log_gain_recovers_a_known_ratio_of_gains():
    """exp(mean log rho_hi - mean log rho_lo) on normal errors with known variances: rho_hi = 4, rho_lo = 2 -> 2."""
    rng = np.random.default_rng(4)
    n = 1500

    def pair(var_num, var_den):
        return np.hstack(
            [rng.normal(scale=np.sqrt(var_num), size=(n, 2)), rng.normal(scale=np.sqrt(var_den), size=(n, 2))]
        )

    est = claim_values.mean_log_gain(
        [pair(4.0, 1.0), pair(8.0, 2.0)], [pair(2.0, 1.0), pair(1.0, 0.5)], np.random.default_rng(0), 1000
    )
    assert est.ci_low < 2.0 < est.ci_high and abs(est.value - 2.0) < 0.25
    e = rng.normal(size=(n, 2))
    v = claim_values.gain(2 * e, e, np.random.default_rng(0), 2000)
    s = claim_values.gain(2 * e, e, np.random.default_rng(0), 2000, statistic="SD ratio")
    assert v.value == pytest.approx(4.0) and s.value == pytest.approx(2.0)


@pytest.mark.slow
def test_variance_sum_interval_coverage_near_the_resolution_limit():
    """The variance-sum interval at the sizes used (80 trials a replicate, 3 replicates pooled) at d = sigma, where
    the errors are heavy-tailed: one replicate's BCa interval covers a little under 95 % (a review measured 0.915;
    here 56 of 60), the pooled replicates' interval (what decides) covers. Deterministic seeds."""
    from dataclasses import replace

    from tvtrack.explore import pool
    from tvtrack.papers.p002_unified_location_em.simulation import Config, run_config
    from tvtrack.papers.p002_unified_location_em.summaries import variance_sum

    errs = [
        claim_values.errors(
            run_config(
                replace(study._CANON, seed=1000 + k), Config(2, 1.0, 3.0, 20, 10, "u", 0.3, None, None, 80, "cov", 0.0)
            ),
            "ula",
        )
        for k in range(60)
    ]
    truth = np.concatenate(errs).var(axis=0, ddof=1).sum()
    ests = [variance_sum(e) for e in errs]
    single = np.mean([e.ci_low <= truth <= e.ci_high for e in ests])
    pooled = np.mean([(p := pool(ests[i : i + 3])).ci_low <= truth <= p.ci_high for i in range(0, 60, 3)])
    assert 0.85 <= single <= 1.0 and pooled >= 0.9, (single, pooled)


def test_flips_by_entry_reads_single_conditions_unless_asked_for_joint_ones():
    class Ex:
        def record(self, cid, rule):
            ref = {"replicates": [{"parts": {"a": "reproduced"}}]}
            conds = [
                {"kind": "single", "changed": {"tracks": "crossing"}, "parts": {"a": "partly"}},
                {"kind": "single", "changed": {"bound": "CRB2"}, "parts": {"a": "reproduced"}},
                {"kind": "joint", "changed": {"bound": "x", "epoch": "mid"}, "parts": {"a": "partly"}},
            ]
            return {**ref, "conditions": conds}

    assert extras.flips_by_entry(Ex(), {"C002-1": None}, ["tracks", "bound", "epoch"]) == {
        "tracks": ["C002-1"],
        "bound": [],
        "epoch": [],
    }
    # a joint condition counts only when asked for, and then for every entry it changed
    assert extras.flips_by_entry(Ex(), {"C002-1": None}, ["tracks", "bound", "epoch"], ("joint", "pinned")) == {
        "tracks": [],
        "bound": ["C002-1"],
        "epoch": ["C002-1"],
    }


def test_wrong_q_and_estimated_weights_are_reported_on_the_same_trials():
    study.clear_cache()
    g, res = study.figure_data(DEFAULT, 9, TINY)
    rng = np.random.default_rng(0)
    wq, wc = extras.wrong_q_cost(g, res, rng, 2000), extras.estimation_cost(g, res, rng, 2000)
    assert set(wq) == set(wc) == {1.0, 2.0, 4.0}
    r = res[g["w"][4.0]]
    assert r["ula_q1"].shape == (TINY.n_iter_trials, 1, 4) and r["ula_w"].shape == r["ula"].shape
    # far apart one track through the pair's centre is a poor model: its centre error is no smaller
    assert wq[4.0].value > 0.5 and all(np.isfinite(e.value) for e in wc.values())


def test_trimmed_reading_reruns_nothing_and_ignores_a_few_gross_errors():
    base = _letters(study.jobs_of(DEFAULT, 7, TINY))
    assert _letters(study.jobs_of({**DEFAULT, "gross errors": TRIMMED}, 7, TINY)) == base
    e = np.random.default_rng(3).standard_normal((400, 2))
    e[:5] = 1e3  # five lost objects
    assert claim_values.spread_sum(e).value > 1e4
    trimmed = claim_values.spread_sum(e, "trimmed")
    assert 1.0 < trimmed.value < 2.0 and trimmed.ci_low <= trimmed.value <= trimmed.ci_high
    g = claim_values.gain(e * 2.0, e, np.random.default_rng(4), 400, "trimmed")
    assert g.value == pytest.approx(4.0)


def test_photons_of_c002_12_change_only_its_far_apart_points():
    base = _letters(study.jobs_of(DEFAULT, 7, TINY))
    faint = _letters(study.jobs_of({**DEFAULT, "m_k of C002-12": 10}, 7, TINY))
    new = {k[0] for k in set(faint) - set(base)}
    assert new and all(c.d == 8.0 and c.m == 10 and c.pix in (0.5, 1.0) for c in new)


def test_fig7_tolerance_reruns_only_the_iteration_points_on_the_same_scenes():
    base = _letters(study.jobs_of(DEFAULT, 7, TINY))
    loose = _letters(study.jobs_of({**DEFAULT, "EM tolerance of Fig 7": "log-likelihood gap 0.1"}, 7, TINY))
    new = set(loose) - set(base)
    assert new and all(k[0].variant == (("tol_loglik", 0.1),) and k[0].n == TINY.n_iter_trials for k in new)
    # the Fig 7 points only, the letters the claims read of them (the plain EM's counts; 'u' runs with the figures)
    assert {k[1] for k in new} == {"p", "q"}
    # what the loose reading no longer asks for is the default's Fig 7 points (a 'u' point may be shared)
    assert set(base) - set(loose) <= {(k[0]._replace(variant=()), k[1]) for k in new}
    assert study.fig7_variant(DEFAULT) == ()  # the default's cache keys are those of before the row


def test_a_loose_practical_tolerance_stops_plain_em_in_fewer_steps_on_the_same_trials():
    from tvtrack.papers.p002_unified_location_em.simulation import Config, run_config

    settings = study.settings_of(DEFAULT, 3, TINY)
    tight = Config(2, 1.0, 3.0, 20, 5, "p", 0.3, None, None, 6, "explore", 0.0)
    loose = tight._replace(variant=(("tol_loglik", 0.1),))
    a, b = run_config(settings, tight), run_config(settings, loose)
    assert np.array_equal(a["truth"], b["truth"])  # a variant sees the same draws (common random numbers)
    assert np.all(b["plain_iter"] <= a["plain_iter"]) and b["plain_iter"].mean() < a["plain_iter"].mean()
    assert np.all(b["plain_iter"] >= 1)


def test_c002_6_photon_pair_and_coordinate_readings():
    base = _letters(study.jobs_of(DEFAULT, 7, TINY))
    assert _letters(study.jobs_of({**DEFAULT, "coordinate of C002-6": "along the separation"}, 7, TINY)) == base
    faint = _letters(study.jobs_of({**DEFAULT, "m_k pair of C002-6": "10 vs 5"}, 7, TINY))
    new = {k[0] for k in set(faint) - set(base)}
    assert new and all(c.m == 5 and c.pix == 1.0 and c.T in (5, 10) and c.d <= 2.0 for c in new)
    whole = _letters(study.jobs_of({**DEFAULT, "small separations of C002-6 (sigma)": 8.0}, 7, TINY))
    assert {k[0].d for k in set(whole) - set(base)} == {d for d in TINY.separations if d > 2.0}
    e = np.arange(12.0).reshape(3, 4)  # columns x1, y1, x2, y2; the objects are separated along y
    assert e[:, COORDINATE6["along the separation"]].tolist() == e[:, [1, 3]].tolist()
    assert e[:, COORDINATE6["across the separation"]].tolist() == e[:, [0, 2]].tolist()
    study.clear_cache()
    out = study.measure_batch(
        [
            DEFAULT,
            {**DEFAULT, "coordinate of C002-6": "along the separation"},
            {**DEFAULT, "m_k pair of C002-6": "10 vs 5"},
        ],
        [7, 7, 7],
        TINY,
    )
    assert len({o["C002-6"].value for o in out}) == 3 and all(np.isfinite(o["C002-6"].value) for o in out)
    assert out[1]["C002-3"].value == out[0]["C002-3"].value  # the coordinate reading is C002-6's alone


def test_c002_6_pixel_frame_pair_and_gap_readings():
    # the fourth adversarial pass's C002-6 rows: Fig 2's comparison at Fig 1a's coarser pixels, over 5 to 50 frames
    # and as the absolute gap between the T curves; each reruns at most C002-6's own ULA points and changes only it
    assert {"Delta of C002-6 (sigma)", "T pair of C002-6"} <= set(DEPENDS["C002-6"])
    assert [c for c, names in DEPENDS.items() if "T pair of C002-6" in names] == ["C002-6"]
    base = _letters(study.jobs_of(DEFAULT, 7, TINY))
    for reading, pix, frames in (
        ({"Delta of C002-6 (sigma)": 3.0}, 3.0, {5, 10}),
        ({"T pair of C002-6": "5 vs 50"}, 1.0, {50}),
    ):
        other = _letters(study.jobs_of({**DEFAULT, **reading}, 7, TINY))
        new = set(other) - set(base)
        assert new and all(k[1] == "u" for k in new)
        assert all(c.q == 2 and c.pix == pix and c.T in frames and c.m in (10, 20) and c.d <= 2.0 for c, _ in new)
        assert all(other[k] == base[k] for k in set(base) & set(other))  # common random numbers
    gap = {"T dependence of C002-6": "absolute (variance gap)"}
    assert _letters(study.jobs_of({**DEFAULT, **gap}, 7, TINY)) == base  # a statistic reruns nothing
    study.clear_cache()
    readings = [{}, {"Delta of C002-6 (sigma)": 3.0}, {"T pair of C002-6": "5 vs 50"}, gap]
    out = study.measure_batch([{**DEFAULT, **r} for r in readings], [7] * 4, TINY)
    assert len({o["C002-6"].value for o in out}) == 4 and all(np.isfinite(o["C002-6"].value) for o in out)
    # the gap reading: mean over d <= 2 sigma of |Sigma^2(5) - Sigma^2(10)| at 20 photons minus that at 10 photons
    g, res = study.figure_data(DEFAULT, 7, TINY)
    v = {
        k: [claim_values.spread_total(claim_values.errors(res[g["2"][k][d]], "ula")[None])[0] for d in (1.0, 2.0)]
        for k in g["2"]
    }
    want = np.mean(np.abs(np.subtract(v[(5, 20)], v[(10, 20)]))) - np.mean(np.abs(np.subtract(v[(5, 10)], v[(10, 10)])))
    assert out[3]["C002-6"].value == pytest.approx(want, rel=1e-9)
    assert all(o[c].value == out[0][c].value for o in out[1:] for c in ("C002-3", "C002-13"))


def test_em_stopping_never_reaches_the_iteration_counts_of_fig7():
    # C002-13 does not list "EM stopping": its plain-EM counts must not change with it (a loose tolerance would)
    base = _letters(study.jobs_of(DEFAULT, 7, TINY))
    for value in REGISTER["EM stopping"].alternatives:
        other = _letters(study.jobs_of({**DEFAULT, "EM stopping": value}, 7, TINY))
        pq = {k for k in base if k[1] in "pq"}
        assert pq and all(other.get(k) == base[k] for k in pq), value
    assert "EM stopping" not in DEPENDS["C002-13"] and "EM stopping" not in DEPENDS["C002-14"]


@pytest.mark.parametrize(
    ("reading", "pix", "m"),
    [({"m_k of C002-1": 10}, 3.0, 10), ({"Delta of C002-1 (sigma)": 1.0}, 1.0, 20)],
)
def test_c002_1_panel_readings_read_that_panels_whole_distance_axis(reading, pix, m):
    # the third adversarial pass's C002-1 readings: another Fig 1 curve, simulated on the same scenes' seeds,
    # over the whole distance axis; nothing else is rerun, and the claim reads that curve
    base = _letters(study.jobs_of(DEFAULT, 7, TINY))
    other = _letters(study.jobs_of({**DEFAULT, **reading}, 7, TINY))
    new = {k[0] for k in set(other) - set(base)}
    assert {c.d for c in new} == set(TINY.separations) - {1.0, 2.0, 3.0, 6.0}
    assert all(c.pix == pix and c.m == m and c.T == DEFAULT["T of Figs 1a,b"] for c in new)
    assert all(other[k] == base[k] for k in set(base) & set(other))  # common random numbers
    study.clear_cache()
    got = study.measure({**DEFAULT, **reading}, 7, TINY)["C002-1"]
    g, res = study.figure_data({**DEFAULT, **reading}, 7, TINY)
    panel = g[FIG1_PANEL[pix]][m]
    assert [e.value for e in got] == [
        claim_values.spread_sum(claim_values.errors(res[panel[d]], "ula", "first"), "variance").value
        for d in TINY.separations
    ]


def test_every_register_entry_and_value_is_in_plain_words():
    for e in REGISTER.entries:
        assert e.title and e.title != e.name, e.name
        assert set(e.phrases) == set(e.values), (e.name, set(e.values) - set(e.phrases))
    assert REGISTER["tracks"].kind == "unreported setting" and REGISTER["EM stopping"].side == "reading"


def test_screen_scale_is_a_quarter_of_the_trials_with_fewer_resamples():
    small = study.screen_scale(study.Scale(n_trials=80, n_iter_trials=40, n_bootstrap=2000, crb_phases=64), 0.25)
    assert (small.n_trials, small.n_iter_trials, small.n_bootstrap, small.crb_phases) == (20, 10, 1000, 16)
    assert study.screen_scale(TINY, 0.25).n_trials == 8  # never below 8 trials


def test_failure_rates_and_bic_shares_read_the_figure_points():

    study.clear_cache()
    g, res = study.figure_data(DEFAULT, 3, TINY)
    rates = extras.failure_rates(g, res)
    assert list(rates) == [label for *_, label in extras.FAILURE_GROUPS] + ["Fig 7 (plain EM)"]
    r7 = res[g["7"][min(g["7"])]]
    assert rates["Fig 7 (plain EM)"][min(g["7"])]["ULA cap hit"].value == r7["plain_cap"].mean()
    assert np.all(r7["plain_cap"] == (r7["plain_iter"] >= TINY.max_iter))  # TINY caps plain EM at 40 steps
    r = res[g["4"][20][1.0]]
    row = rates["Fig 4a (m_k = 20)"][1.0]
    assert row["ULA label swap"].value == r["ula_flags"][:, 0].mean()
    assert row["two-stage cap hit"].value == r["em_flags"][:, 2].mean()
    shares = extras.bic_correct_q(g, res)
    assert set(shares) == set(TINY.separations)
    for d, s in shares.items():
        assert sum(e.value for e in s.values()) == pytest.approx(1.0)
        pick = np.argmin(res[g["bic"][d]]["bic"], axis=1)
        assert s["Q' = 2 (correct)"].value == pytest.approx((pick == 1).mean())


def _flat(x):
    """A measured value as plain numbers (Estimate fields, lists, dicts of parts), for exact comparison."""
    if isinstance(x, Estimate):
        return (x.value, x.stderr, x.ci_low, x.ci_high, x.n, x.confidence, x.method)
    if isinstance(x, dict):
        return {k: _flat(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [_flat(v) for v in x]
    return x


@pytest.mark.parametrize(
    "config, subset",
    [
        (DEFAULT, {"C002-11"}),
        (DEFAULT, {"C002-6", "C002-15"}),
        ({**DEFAULT, "ULA": "MAP (designation prior)", "statistic": "MSE"}, {"C002-11", "C002-2"}),
        ({**DEFAULT, "velocity knowledge": "designated", "gross errors": TRIMMED}, {"C002-11", "C002-9"}),
    ],
)
def test_a_claims_subset_measures_those_claims_bit_for_bit_and_runs_only_their_jobs(config, subset):
    study.clear_cache()
    part = study.measure(config, 5, TINY, claims=frozenset(subset))
    ran = set(study._CACHE)
    assert ran == set(study.jobs_of(config, 5, TINY, claims=subset))
    assert len(ran) < len(study.jobs_of(config, 5, TINY))  # fewer jobs than the whole study
    study.clear_cache()
    whole = study.measure(config, 5, TINY)
    assert set(part) == set(subset)
    assert _flat(part) == _flat({k: whole[k] for k in subset})
    batch = study.measure_batch([config, config], [5, 6], TINY, claims=[frozenset(subset), None])
    assert _flat(batch[0]) == _flat(part) and set(batch[1]) == set(whole)


@pytest.mark.parametrize(
    "config, subset, letters",
    [
        (DEFAULT, {"C002-13"}, {"p"}),
        (DEFAULT, {"C002-14"}, {"p", "q"}),
        (DEFAULT, {"C002-7", "C002-8"}, {"u", "e"}),
        ({**DEFAULT, "velocity knowledge": "designated"}, {"C002-11"}, {"e", "k"}),
        ({**DEFAULT, "ULA": "MAP (designation prior)"}, {"C002-11"}, {"e", "m"}),
    ],
)
def test_a_claim_runs_only_the_algorithms_it_reads_and_keeps_its_value_bit_for_bit(config, subset, letters):
    """Of its points a claim runs only the algorithms it reads (C002-13 the plain ULA's counts, not the accelerated
    ULA or the marks that share its points); its value is the one with every algorithm of those points run."""
    study.clear_cache()
    g, _ = study._points(config, TINY)
    settings = study.settings_of(config, 5, TINY)
    every = [
        (study._job_settings(settings, a, TINY, c.q), c._replace(algs=a))
        for c in claim_values.needed_points(config, g, TINY.separations, subset)
        for a in c.algs
    ]
    study.run_jobs(every)
    assert {j[1].algs for j in every} > letters  # the points hold algorithms the claims do not read
    ref = study.measure(config, 5, TINY, claims=frozenset(subset))  # every algorithm cached: nothing more runs
    study.clear_cache()
    part = study.measure(config, 5, TINY, claims=frozenset(subset))
    assert {j[1].algs for j in study._CACHE} == letters
    assert _flat(part) == _flat(ref) and set(part) == subset


def test_every_claims_points_are_among_the_studys_points():
    g, asked = study._points(DEFAULT, TINY)
    for cid in study.CLAIMS:
        if cid != "C002-16":
            need = claim_values.needed_points(DEFAULT, g, TINY.separations, {cid})
            assert need and set(need) <= set(asked), cid


def test_the_bounds_run_only_where_they_are_read():
    """The bounds (letter r: CRB and van Trees) are computed once per point, for C002-15's points and the figures',
    never inside an algorithm's job (they cost a fifth of a screened configuration when every job drew them)."""
    jobs = study.jobs_of(DEFAULT, 7, TINY, claims={"C002-15", "C002-12"})
    assert sorted(j[1].d for j in jobs if j[1].algs == "r") == [1.0, 2.0, 4.0]
    study.run_jobs(jobs)
    assert all(("crb_pos" in study._CACHE[j]) == (j[1].algs == "r") for j in jobs)
    fig = {j[1]._replace(algs="") for j in study.jobs_of(DEFAULT, 7, TINY, figures=True) if j[1].algs == "r"}
    g, _ = study._points(DEFAULT, TINY, figures=True)
    assert {c._replace(algs="") for c in g["4"][50].values()} <= fig and {g["6"][20][2.0]._replace(algs="")} <= fig


def test_the_track_geometry_reaches_only_the_claims_that_declare_it():
    # a crossing-track configuration measured for C002-1 (parallel tracks: it does not declare "tracks") together
    # with C002-15 (which does): C002-1 is its value at the default, bit for bit, C002-15 its value on crossing tracks
    assert "tracks" not in DEPENDS["C002-1"] and "tracks" in DEPENDS["C002-15"]
    crossing = {**DEFAULT, "tracks": "crossing"}
    both = study.measure(crossing, 7, TINY, claims=frozenset({"C002-1", "C002-15"}))
    alone = study.measure(DEFAULT, 7, TINY, claims=frozenset({"C002-1"}))
    assert repr(both["C002-1"]) == repr(alone["C002-1"])
    c15 = study.measure(DEFAULT, 7, TINY, claims=frozenset({"C002-15"}))
    assert repr(both["C002-15"]) != repr(c15["C002-15"])
