"""Paper 002: every claim's value pinned against an independent computation, and the comparators' wiring.

The claim values are read from a stand-in for the simulation results in which every algorithm's errors at every
simulation point are one fixed standard-normal sample ``Z`` (per object count) times a scale that depends on the
point (separation d, pixel Delta, photons m_k, frames T) and the algorithm. A variance-sum ratio of two such error
sets is then exactly the squared ratio of their scales, so each claim's value has a closed form written beside it:
a wrong reference point (separation, pixel size, frame count, photon count), a swapped numerator, a wrong
algorithm key or a wrong statistic changes it. The comparators (two-stage marks, the photon simulator, the EM's
practical stop) are checked on cases whose answer is known.
"""

from __future__ import annotations

import numpy as np
import pytest

from tvtrack.papers.p002_unified_location_em.claim_values import measure_claims
from tvtrack.papers.p002_unified_location_em.em_loop import CALM, EMState, Step, _aitken_gap
from tvtrack.papers.p002_unified_location_em.model import frame_times, simulate_counts
from tvtrack.papers.p002_unified_location_em.register import REGISTER
from tvtrack.papers.p002_unified_location_em.study import Scale, _points
from tvtrack.papers.p002_unified_location_em.two_stage import em_marks, propagate

DEFAULT = REGISTER.default()
D = (0.5, 1.0, 1.5, 2.0, 3.0, 4.0, 6.0, 8.0)
SCALE = Scale(n_trials=40, n_iter_trials=12, separations=D, n_bootstrap=60)
N = 40
#: One standard-normal error sample (n, Q, 4) per object count, shared by every point and algorithm.
Z = {q: np.random.default_rng(11).standard_normal((N, q, 4)) for q in (1, 2)}
#: Per-algorithm offset and phase of the log error scale (the algorithm interacts with the point).
ALG = {"ula": (0.0, 0.0), "em": (0.37, 0.9), "cr": (0.61, 1.7), "map": (-0.23, 2.3), "ula_vd": (-0.11, 3.1)}
ALG["em_vd"] = (0.29, 4.3)


def log_scale(d, pix, m, T, alg) -> float:
    """The log of the error scale of ``alg`` at the point (d / sigma, Delta / sigma, m_k, T): generic in each."""
    off, phase = ALG[alg]
    return off + 0.4 * np.sin(1.3 * d + 0.7 * pix + 0.11 * m + 0.23 * T + phase)


def v(d, pix, m, T, alg="ula") -> float:
    """Variance of ``alg`` at a point relative to the base sample's: exp(2 log scale)."""
    return float(np.exp(2 * log_scale(d, pix, m, T, alg)))


def rho(d, pix, m, T, num="em", den="ula") -> float:
    return v(d, pix, m, T, num) / v(d, pix, m, T, den)


def _var_sum(e) -> float:
    return float(np.var(e, axis=0, ddof=1).sum())


VZ_POS = _var_sum(Z[2][..., :2].reshape(N, -1))  # the base sample's summed position variance (first epoch)
VZ_VEL = _var_sum(Z[2][..., 2:].reshape(N, -1))


def iterations(d) -> np.ndarray:
    """Plain-EM steps of the ULA at separation d (per trial)."""
    return 30.0 + 40.0 / (0.5 + d) + np.arange(12) % 3


def mark_steps(d) -> np.ndarray:
    """Per-frame EM steps summed over the frames (per trial)."""
    return 55.0 + 7.0 * d + np.arange(12) % 5


class FakeResults:
    """``res[Config]``: the errors of every algorithm as ``scale x Z``, iteration counts and bounds (sigma^2)."""

    def __getitem__(self, c):
        out = {a: np.exp(log_scale(c.d, c.pix, c.m, c.T, a)) * Z[c.q] for a in ALG}
        out.update(
            T=c.T,
            plain_iter=iterations(c.d),
            em_plain_iter=mark_steps(c.d),
            crb_pos=0.2 + 0.05 * c.d,
            crb_vel=0.01 + 0.002 * c.d,
            bcrb_pos=0.15 + 0.05 * c.d,
            bcrb_vel=0.008 + 0.002 * c.d,
        )
        return out


def measured(config=DEFAULT, claims=None) -> dict:
    g, _ = _points(config, SCALE)
    return measure_claims(config, g, FakeResults(), 3, SCALE.n_bootstrap, D, claims)


def value(x):
    return x.value


@pytest.fixture(scope="module")
def m():
    return measured()


def test_c1_reads_the_ula_variance_sum_of_fig_1a_at_twenty_photons_and_five_frames(m):
    # Fig 1a: Delta = 3 sigma, m_k = 20, T = 5 ("T of Figs 1a,b"); the value is absolute (sigma^2), per separation
    want = [v(d, 3.0, 20, 5) * VZ_POS for d in D]
    np.testing.assert_allclose([e.value for e in m["C002-1"]], want, rtol=1e-9)


def test_c2_is_the_photon_ratio_far_apart_over_near(m):
    # r_m = Sigma^2(m_k = 10) / Sigma^2(m_k = 20) of Fig 1a (Delta 3, T 5); "weakens": r_m(6 sigma) / r_m(1 sigma)
    r_far = v(6.0, 3.0, 10, 5) / v(6.0, 3.0, 20, 5)
    r_near = v(1.0, 3.0, 10, 5) / v(1.0, 3.0, 20, 5)
    assert m["C002-2"]["far apart"].value == pytest.approx(r_far, rel=1e-9)
    assert m["C002-2"]["weakens"].value == pytest.approx(r_far / r_near, rel=1e-9)


def test_c3_is_the_geometric_mean_photon_ratio_of_fine_over_coarse_pixels(m):
    # exp(mean_d ln r_m(Fig 1b, Delta 1) - mean_d ln r_m(Fig 1a, Delta 3)) over d = 1, 2, 3, 6 sigma
    ds = (1.0, 2.0, 3.0, 6.0)
    lr = {p: np.mean([np.log(v(d, p, 10, 5) / v(d, p, 20, 5)) for d in ds]) for p in (1.0, 3.0)}
    assert m["C002-3"].value == pytest.approx(np.exp(lr[1.0] - lr[3.0]), rel=1e-9)


def test_c4_is_the_growth_from_far_to_close_for_coarse_over_fine_pixels(m):
    # growth Sigma^2(d = 1) / Sigma^2(d = 6) at Fig 1c (m_k = 10, T = 5): Delta 5 sigma over Delta 3 sigma (> 1:
    # errors grow faster for the larger pixels)
    growth = {p: v(1.0, p, 10, 5) / v(6.0, p, 10, 5) for p in (5.0, 3.0)}
    assert m["C002-4"].value == pytest.approx(growth[5.0] / growth[3.0], rel=1e-9)


def test_c5_is_the_coarse_over_fine_pixel_ratio_at_five_ten_fifty_frames(m):
    want = [v(2.0, 3.0, 20, T) / v(2.0, 1.0, 20, T) for T in (5, 10, 50)]
    np.testing.assert_allclose([e.value for e in m["C002-5"]], want, rtol=1e-9)


def test_c6_is_the_mean_log_t_ratio_at_more_photons_minus_fewer(m):
    # |ln Sigma^2(T 5) / Sigma^2(T 10)| at Delta 1 over the small separations (<= 2 sigma), 20 minus 10 photons
    small = [d for d in D if d <= 2.0]

    def dep(mk):
        return np.mean([abs(np.log(v(d, 1.0, mk, 5) / v(d, 1.0, mk, 10))) for d in small])

    assert m["C002-6"].value == pytest.approx(dep(20) - dep(10), rel=1e-9, abs=1e-12)


def test_c7_c8_c9_read_one_object_at_ten_frames_with_the_marks_and_centres_in_their_places(m):
    T3 = 10  # "T of the Fig 3a claims"; one object (d = 0), m_k = 20
    c7, c8, c9 = m["C002-7"], m["C002-8"], m["C002-9"]
    assert c7["fine pixels"].value == pytest.approx(rho(0.0, 1.0, 20, T3), rel=1e-9)
    assert c7["coarse pixels"].value == pytest.approx(rho(0.0, 5.0, 20, T3), rel=1e-9)
    assert c8["worse than fine pixels"].value == pytest.approx(v(0.0, 5.0, 20, T3) / v(0.0, 1.0, 20, T3), rel=1e-9)
    assert c8["better than the marks"].value == pytest.approx(1 / rho(0.0, 5.0, 20, T3), rel=1e-9)
    p9 = c9["centre-of-region >= iterative marks"].value
    assert p9 == pytest.approx(rho(0.0, 3.0, 20, T3, "cr", "em"), rel=1e-9)
    assert c9["iterative marks >= ULA"].value == pytest.approx(rho(0.0, 3.0, 20, T3), rel=1e-9)


def test_c10_reads_the_two_stage_over_ula_gain_and_its_trends(m):
    c10 = m["C002-10"]
    np.testing.assert_allclose([e.value for e in c10["closer"]], [rho(d, 3.0, 20, 10) for d in D], rtol=1e-9)
    close = (1.0, 2.0, 3.0)

    def lg(pix, m_, T):
        return np.mean([np.log(rho(d, pix, m_, T)) for d in close])

    assert c10["coarser pixels"].value == pytest.approx(np.exp(lg(5.0, 20, 10) - lg(3.0, 20, 10)), rel=1e-9)
    assert c10["more frames"].value == pytest.approx(np.exp(lg(3.0, 20, 50) - lg(3.0, 20, 5)), rel=1e-9)


def test_c11_is_the_two_stage_over_ula_gain_at_fifty_frames_and_one_and_three_sigma(m):
    c11 = m["C002-11"]
    assert c11["d = 1 sigma (paper x4.5)"].value == pytest.approx(rho(1.0, 3.0, 20, 50), rel=1e-9)
    assert c11["d = 3 sigma (paper x4)"].value == pytest.approx(rho(3.0, 3.0, 20, 50), rel=1e-9)


@pytest.mark.parametrize(
    "entry, value_, num, den",
    [("velocity knowledge", "designated", "em_vd", "ula_vd"), ("ULA", "MAP (designation prior)", "em", "map")],
)
def test_c11_compares_like_with_like_under_each_velocity_reading(entry, value_, num, den):
    # designated velocity: the line fit that keeps it (em_vd) against the ULA that knows it (ula_vd); MAP: the
    # ordinary two-stage against the MAP-ULA
    c11 = measured({**DEFAULT, entry: value_}, {"C002-11"})["C002-11"]
    for d, part in ((1.0, "d = 1 sigma (paper x4.5)"), (3.0, "d = 3 sigma (paper x4)")):
        assert c11[part].value == pytest.approx(rho(d, 3.0, 20, 50, num, den), rel=1e-9)


def test_c12_is_the_gain_at_eight_sigma_with_fine_pixels(m):
    c12 = m["C002-12"]
    for p in (0.5, 1.0):
        assert c12[f"Delta = {p:g} sigma"].value == pytest.approx(rho(8.0, p, 20, 10), rel=1e-9)


def test_c13_c14_read_iterations_and_work_in_frames(m):
    # C002-13: mean ULA steps closest / farthest; C002-14: ULA work = steps x T frames (T = 10) against the marks'
    # per-frame steps summed over the frames, both separations pooled
    lo, hi = min(D), max(D)
    assert m["C002-13"].value == pytest.approx(iterations(lo).mean() / iterations(hi).mean(), rel=1e-12)
    ula = np.concatenate([iterations(lo), iterations(hi)]) * 10
    marks = np.concatenate([mark_steps(lo), mark_steps(hi)])
    assert m["C002-14"].value == pytest.approx(ula.mean() / marks.mean(), rel=1e-12)


def test_c15_is_the_ula_spread_over_the_crb_of_positions_and_velocities(m):
    c15 = m["C002-15"]
    for d, part in ((1.0, "very close"), (2.0, "d = 2 sigma"), (4.0, "d = 4 sigma")):
        assert c15[part].value == pytest.approx(v(d, 3.0, 20, 10) * VZ_POS / (0.2 + 0.05 * d), rel=1e-9)
    want_vel = v(1.0, 3.0, 20, 10) * VZ_VEL / (0.01 + 0.002)
    assert c15["velocities, very close"].value == pytest.approx(want_vel, rel=1e-9)


# -- the comparators ---------------------------------------------------------------------------------------------


def _moving_scene(n=3, T=8, photons=400):
    """One bright object moving 2 px/frame along x (far from its frame-0 place by the last frame), no noise."""
    truth = np.tile(np.array([[[6.0, 7.5, 2.0, 0.25]]]), (n, 1, 1))
    times = frame_times(T)
    counts = simulate_counts(np.random.default_rng(2), truth, times, (16, 26), 1.0, photons, 0.0)
    return truth, times, counts


def test_two_stage_marks_start_each_frame_at_the_propagated_designation():
    # with no photons no mark forms and each mark is its start: the designation moved to that frame's time
    truth, times, counts = _moving_scene()
    mk = em_marks(np.zeros_like(counts), truth, times, 1.0, np.array([0.9]), 0.1)
    assert not mk.valid.any()
    np.testing.assert_allclose(mk.xy, propagate(truth, times), atol=1e-12)
    assert np.ptp(mk.xy[0, :, 0, 0]) == pytest.approx(2.0 * (len(times) - 1))


def test_two_stage_marks_find_a_moving_object_in_every_frame():
    # 400 photons, sigma 1 px, no noise: each frame's mark is the object's centroid to ~0.05 px; a mark started at
    # the frame-0 designation in every frame would sit 2 px per frame behind (14 px by the last frame)
    truth, times, counts = _moving_scene()
    mk = em_marks(counts, truth, times, 1.0, np.array([0.999]), 0.001)
    assert mk.valid.all()
    err = np.abs(mk.xy - propagate(truth, times))
    assert err.max() < 0.2


def test_two_stage_marks_use_only_their_own_frame():
    # the information of a mark is its frame's counts: blanking the other frames leaves it unchanged
    truth, times, counts = _moving_scene()
    args = (truth, times, 1.0, np.array([0.999]), 0.001)
    full = em_marks(counts, *args)
    alone = counts.copy()
    alone[:, 1:] = 0
    np.testing.assert_allclose(em_marks(alone, *args).xy[:, 0], full.xy[:, 0], atol=1e-9)


def test_simulated_counts_centre_on_the_truth_with_the_psf_spread():
    # fixed photons: per frame, the counts' centroid is the object's position at that frame (pixel centres at
    # integers) and their variance along each axis sigma^2 + 1/12 (a Gaussian histogrammed in unit pixels)
    truth = np.array([[[9.3, 8.5, 0.7, -0.4]]])
    times = frame_times(5)
    c = simulate_counts(np.random.default_rng(4), np.repeat(truth, 8, axis=0), times, (18, 22), 1.3, 4000, 0.0)
    assert c.shape == (8, 5, 18, 22)
    assert (c.sum(axis=(-1, -2)) == 4000).all()  # the object is far from the edges: every photon lands
    img = c.sum(axis=0).astype(float)  # (T, rows, cols)
    yy, xx = np.mgrid[:18, :22]
    w = img / img.sum(axis=(-1, -2), keepdims=True)
    cx, cy = (w * xx).sum(axis=(-1, -2)), (w * yy).sum(axis=(-1, -2))
    np.testing.assert_allclose(cx, 9.3 + 0.7 * times, atol=0.02)
    np.testing.assert_allclose(cy, 8.5 - 0.4 * times, atol=0.02)
    vx = (w * (xx - cx[:, None, None]) ** 2).sum(axis=(-1, -2))
    np.testing.assert_allclose(vx, 1.3**2 + 1 / 12, rtol=0.03)


def test_poisson_photons_are_drawn_afresh_in_every_frame():
    # "poisson": each frame's target count is its own Poisson(m) draw: the totals of two frames of one trial are
    # uncorrelated (a count drawn once per trial would correlate them fully) and their dispersion var / mean is 1
    truth = np.tile(np.array([[[10.0, 9.0, 0.3, 0.1]]]), (3000, 1, 1))
    c = simulate_counts(np.random.default_rng(6), truth, frame_times(3), (20, 20), 1.0, 25, 0.0, "poisson")
    tot = c.sum(axis=(-1, -2)).astype(float)  # (n, T)
    r = np.corrcoef(tot[:, 0], tot[:, 2])[0, 1]
    assert abs(r) < 5 / np.sqrt(len(tot)), r
    assert tot.var(ddof=1) / tot.mean() == pytest.approx(1.0, abs=5 * np.sqrt(2 / tot.size))


def test_photons_that_land_outside_the_window_are_lost():
    # an object centred on the last column: about half its photons land beyond the right edge and are lost (none
    # wraps into the first column of the next row)
    truth = np.array([[[11.0, 5.0, 0.0, 0.0]]] * 20)
    c = simulate_counts(np.random.default_rng(7), truth, frame_times(2), (11, 12), 1.0, 500, 0.0)
    assert c[..., 0].sum() == 0
    lost = 1 - c.sum() / (20 * 2 * 500)
    assert lost == pytest.approx(0.3085, abs=0.01)  # beyond x = 11.5, half a pixel from the centre: P(Z > 0.5)


def test_simulated_noise_has_its_mean_per_pixel():
    c = simulate_counts(np.random.default_rng(5), np.zeros((50, 1, 4)), frame_times(4), (10, 12), 1.0, 0, 0.3)
    assert c.mean() == pytest.approx(0.3, rel=0.03)


def test_aitken_gap_is_the_remaining_gain_of_a_geometric_climb():
    # L_k = L* - c a^k: rises r_k = c a^(k-1) (1 - a), ratio a, remaining gain after step k exactly c a^k
    a, c, L = 0.6, 5.0, 10.0
    ll = L - c * a ** np.arange(6)
    k = np.arange(2, 6)
    gap = _aitken_gap(ll[k], ll[k - 1], ll[k - 1] - ll[k - 2])
    np.testing.assert_allclose(gap, c * a**k, rtol=1e-12)
    # unknown previous rise, a rise that grows or a fall: no estimate (inf)
    assert np.isinf(_aitken_gap(np.array([1.0]), np.array([0.0]), np.array([np.nan])))[0]
    assert np.isinf(_aitken_gap(np.array([3.0]), np.array([1.0]), np.array([1.0])))[0]


def _step(ll):
    n = len(ll)
    z = np.zeros(n)
    return Step(np.zeros((n, 1, 4)), z[:, None], z, z[:, None] + 1, np.asarray(ll, float), z.astype(bool), z + 1, 1)


def test_the_practical_stop_needs_calm_successive_small_gaps():
    # a geometric climb whose remaining gain falls below tol at step 3 (gap 0.6^3 = 0.216 < 0.25): with CALM = 2
    # the trial stops at the second successive small gap (step 4), not at the first; a lull followed by a fresh
    # climb resets the count
    assert CALM == 2
    ll = 10.0 - 1.0 * 0.6 ** np.arange(8)
    st = EMState.start(np.zeros((1, 1, 4)), True, np.ones((1, 1)), np.ones(1), np.ones((1, 1)), np.ones(1))
    active, live = np.arange(1), np.ones(1, bool)
    stops = [bool(st.stopped(active, live, _step([x]), 1e-6, 0.25)[0]) for x in ll[:6]]
    assert stops.index(True) == 4 and not any(stops[:4])
    st2 = EMState.start(np.zeros((1, 1, 4)), True, np.ones((1, 1)), np.ones(1), np.ones((1, 1)), np.ones(1))
    jumpy = [0.0, 1.0, 1.1, 3.0, 3.01, 3.011]  # small gap at step 2, a fresh climb at 3, small at 4 and 5
    out = [bool(st2.stopped(active, live, _step([x]), 1e-6, 0.05)[0]) for x in jumpy]
    assert out == [False, False, False, False, False, True]


def test_the_study_gives_the_two_stage_the_propagated_designation_and_the_ulas_stop(monkeypatch):
    # at the register's default the marks start from each frame's propagated designation (the whole designated
    # state, position and velocity) and stop by the same rule as the ULA (tolerance, log-likelihood gap, cap,
    # acceleration)
    from tvtrack.papers.p002_unified_location_em import simulation
    from tvtrack.papers.p002_unified_location_em.study import settings_of

    calls = {"marks": [], "ula": []}

    def spy(kind, real):
        def f(*args, **kw):
            calls[kind].append((args, kw))
            return real(*args, **kw)

        return f

    monkeypatch.setattr(simulation, "em_marks", spy("marks", simulation.em_marks))
    monkeypatch.setattr(simulation, "unified_location_em", spy("ula", simulation.unified_location_em))
    settings = settings_of(DEFAULT, 1, Scale(n_trials=4))
    cfg = simulation.Config(2, 2.0, 3.0, 20, 5, "ue", 0.3, None, None, 4, "pin", 0.0)
    res = simulation.run_config(settings, cfg)
    (m_args, m_kw), (u_args, u_kw) = calls["marks"][0], calls["ula"][0]
    designation = u_args[1]
    assert designation.shape == (4, 2, 4) and np.any(designation[..., 2:] != 0)
    np.testing.assert_array_equal(m_args[1], designation)
    np.testing.assert_array_equal(m_args[2], frame_times(5))
    assert m_kw["init"] == "designation" and m_kw["association"] == "designation"
    for k in ("tol_px", "tol_loglik", "max_iter", "accelerate"):
        assert m_kw[k] == u_kw[k], k
    assert res["em"].shape == res["ula"].shape == (4, 2, 4)


def test_every_claim_value_holds_each_part_its_rule_decides():
    """A part's value is read by its name (``tvtrack.labels.part_pairs``), and a part whose name the value lacks is
    dropped without a word: every part of every rule must be measured at the default, under its own name."""
    from tvtrack.labels import part_pairs, rule_parts
    from tvtrack.papers.p002_unified_location_em.claims import claim_rules

    rules = claim_rules()
    m = measured()  # measured here, not from the module's fixture: the test itself calls every claim's function
    assert set(m) <= set(rules)
    for cid, value in m.items():
        assert set(part_pairs(rules[cid], value)) == set(rule_parts(rules[cid])), cid


#: The parts whose value is a ratio of two algorithms' errors on the same scenes (the same trials resampled together)
#: and the parts that compare independent configurations (their trials resampled apart).
PAIRED_PARTS = [
    ("C002-7", "fine pixels"),
    ("C002-7", "coarse pixels"),
    ("C002-8", "better than the marks"),
    ("C002-9", "centre-of-region >= iterative marks"),
    ("C002-9", "iterative marks >= ULA"),
    ("C002-10", "closer"),
    ("C002-11", "d = 1 sigma (paper x4.5)"),
    ("C002-11", "d = 3 sigma (paper x4)"),
    ("C002-12", "Delta = 0.5 sigma"),
    ("C002-12", "Delta = 1 sigma"),
]
UNPAIRED_PARTS = [("C002-2", "far apart"), ("C002-5", None), ("C002-8", "worse than fine pixels")]


def _widths(m, cid, part) -> list:
    e = m[cid] if part is None else m[cid][part]
    return [(x.ci_high - x.ci_low) / abs(x.value) for x in (e if isinstance(e, list) else [e])]


@pytest.mark.parametrize("cid, part", PAIRED_PARTS)
def test_a_ratio_on_the_same_scenes_is_resampled_in_pairs(m, cid, part):
    # every algorithm's errors are a scale times the one sample Z: resampled in pairs, the ratio is the same in every
    # resample and its interval has no width; resampled apart, it would scatter
    assert max(_widths(m, cid, part)) < 1e-9


@pytest.mark.parametrize("cid, part", UNPAIRED_PARTS)
def test_a_ratio_between_independent_configurations_is_resampled_apart(m, cid, part):
    assert min(_widths(m, cid, part)) > 0.1


def test_each_rule_says_paired_exactly_where_its_value_is_paired():
    from tvtrack.papers.p002_unified_location_em.claims import claim_rules

    rules = claim_rules()

    def leaf(cid, part):
        r = rules[cid]
        return r if part is None else r.parts[part]

    paired = [("C002-8", "better than the marks"), ("C002-9", "centre-of-region >= iterative marks")]
    paired += [("C002-9", "iterative marks >= ULA"), ("C002-14", None)]
    apart = [("C002-2", "weakens"), ("C002-3", None), ("C002-4", None), ("C002-6", None)]
    apart += [("C002-8", "worse than fine pixels"), ("C002-10", "coarser pixels"), ("C002-10", "more frames")]
    assert [leaf(c, p).paired for c, p in paired] == [True] * len(paired)
    assert [leaf(c, p).paired for c, p in apart] == [False] * len(apart)
    assert all("unpaired" in leaf(c, p).text() for c, p in apart)
