"""002's register read into the simulation (``study``): settings, the settings each algorithm reads, and each
claim's simulation points.

The points are written out here from the paper's figures (Fig 1a: Delta = 3 sigma, Fig 1b: 1 sigma, m_k 10 and 20;
Fig 1c: Delta 3 and 5 sigma, T = 5; Fig 2: Delta = 1 sigma, T 5 and 10, m_k 10 and 20; Fig 3a: one object; Fig 4:
m_k 20 (and 50); Fig 5: T 5 and 50; Fig 6: Delta = 5 sigma; Fig 7: the iteration counts) and the register's stated
readings, not computed by the module under test: every point's objects, separation, pixel size, photons, frames,
algorithms, trials and settings variant at the default, and for every register value the points it moves and how.
Nothing is simulated, so these tests take milliseconds.
"""

from dataclasses import fields, replace

import pytest

from tvtrack.papers.p002_unified_location_em import study
from tvtrack.papers.p002_unified_location_em.register import REGISTER
from tvtrack.papers.p002_unified_location_em.sim_config import ALGORITHMS, CANONICAL_SETTINGS, Config

DEFAULT = REGISTER.default()
SCALE = study.Scale(n_trials=12, n_iter_trials=7, crb_phases=9, n_bootstrap=2100, fig3_frames=(2, 5, 20))
D = (0.5, 1.0, 1.5, 2.0, 3.0, 4.0, 6.0, 8.0)  # the study's distance axis d / sigma
N, NI = 12, 7  # trials of a point, of the iteration study


def _flat(g, path=()):
    """``{(group, key..., d): (q, d, Delta, m_k, T, algorithms, trials, variant)}``."""
    if isinstance(g, Config):
        assert (g.init, g.assoc, g.tag, g.vsd) == (None, None, "explore", 0.0)
        return {path: (g.q, g.d, g.pix, g.m, g.T, g.algs, g.n, g.variant)}
    out = {}
    for k, v in g.items():
        out.update(_flat(v, (*path, k)))
    return out


def _default_points():
    """The default's points as the claims read them (no figure extras), from the paper's figures."""
    p = {}
    for m in (10, 20):  # Fig 1a (Delta 3): C002-1 reads its whole axis at m_k 20; Fig 1b (Delta 1): 1, 2, 3, 6 sigma
        for d in D if m == 20 else (1.0, 2.0, 3.0, 6.0):
            p[("1a", m, d)] = (2, d, 3.0, m, 5, "u", N, ())
        for d in (1.0, 2.0, 3.0, 6.0):
            p[("1b", m, d)] = (2, d, 1.0, m, 5, "u", N, ())
    for pix in (3.0, 5.0):  # Fig 1c: T = 5, m_k 10 (the text), at the axis' ends the claim compares
        for d in (1.0, 6.0):
            p[("1c", pix, d)] = (2, d, pix, 10, 5, "u", N, ())
    for T in (5, 10):  # Fig 2: Delta 1, T 5 and 10, m_k 10 and 20, the small separations (up to 2 sigma)
        for m in (10, 20):
            for d in (0.5, 1.0, 1.5, 2.0):
                p[("2", (T, m), d)] = (2, d, 1.0, m, T, "u", N, ())
    for pix in (3.0, 1.0):  # C002-5: 3 vs 1 sigma pixels at d = 2 sigma, T 5, 10, 50; three times the trials
        for T in (5, 10, 50):
            p[("5", (pix, T), 2.0)] = (2, 2.0, pix, 20, T, "u", 3 * N, ())
    for pix in (1.0, 3.0, 5.0):  # Fig 3a: one object at T = 10, the ULA, iterative and centre-of-region marks
        p[("3a", pix, 10)] = (1, 0.0, pix, 20, 10, "uec", N, ())
    for d in D:  # Fig 4a: m_k 20, Delta 3, T 10
        p[("4", 20, d)] = (2, d, 3.0, 20, 10, "ue", N, ())
    for T in (5, 50):  # Fig 5a, 5b at the close separations 1, 2, 3 sigma
        for d in (1.0, 2.0, 3.0):
            p[("5ab", T, d)] = (2, d, 3.0, 20, T, "ue", N, ())
    for d in (1.0, 3.0):  # C002-11: Fig 5b's points, ULA and marks, MAP-ULA
        p[("head", d)] = (2, d, 3.0, 20, 50, "ue", N, ())
        p[("head_map", d)] = (2, d, 3.0, 20, 50, "m", N, ())
    for d in (1.0, 2.0, 3.0):  # Fig 6b: Delta 5, m_k 20
        p[("6", 20, d)] = (2, d, 5.0, 20, 10, "ue", N, ())
    for d in (1.0, 2.0, 4.0):  # C002-15: the ULA and the bounds
        p[("c15", d)] = (2, d, 3.0, 20, 10, "ur", N, ())
    for pix in (0.5, 1.0):  # C002-12: far apart (8 sigma), pixels below sigma
        p[("good", pix)] = (2, 8.0, pix, 20, 10, "ue", N, ())
    for d in (0.5, 8.0):  # Fig 7: the iteration counts at the axis' ends
        p[("7", d)] = (2, d, 3.0, 20, 10, "upq", NI, ())
    return p


def _points(config, figures=False):
    g, asked = study._points(config, SCALE, figures)
    flat = _flat(g)
    assert len(asked) == len(flat)  # every point built is recorded once
    assert {c.dsd for c in asked} == {float(config["designation error (sigma)"])}
    return flat


def test_the_default_simulates_the_paper_s_figure_points_and_no_other():
    assert _points(DEFAULT) == _default_points()
    assert _flat(study._points(DEFAULT, SCALE)[0]) == _default_points()  # the claims' points unless told
    # a configuration written before C002-12's photons were an entry reads the paper's 20
    older = {k: v for k, v in DEFAULT.items() if k != "m_k of C002-12"}
    assert {v[3] for k, v in _flat(study._points(older, SCALE)[0]).items() if k[0] == "good"} == {20}


def _moved(config):
    """The points a configuration adds (its value), drops (None) and changes (its new value) against the default's."""
    a, b = _default_points(), _points(config)
    return {k: b.get(k) for k in set(a) | set(b) if a.get(k) != b.get(k)}


def _pt(q, d, pix, m, T, algs, n=N, variant=()):
    return (q, d, pix, m, T, algs, n, variant)


def _set(p, groups, i, value):
    """Field ``i`` of every point of ``groups`` set to ``value``."""
    return {k: (*v[:i], value, *v[i + 1 :]) for k, v in p.items() if k[0] in groups}


def _regroup(p, group, keep, new):
    """The points of ``group`` whose key fails ``keep`` dropped, and ``new`` added."""
    return {**{k: None for k in p if k[0] == group and not keep(k)}, **new}


FIG4 = ("4", "5ab", "head", "head_map", "c15", "7")  # Delta of Figs 4, 5, 7 (and C002-11, C002-15 at Fig 5's)
T4 = ("4", "6", "c15", "good", "7")  # T of Figs 4, 6, 7 (and C002-12, C002-15)
NOT_CORE = [d for d in D if d not in (1.0, 2.0, 3.0, 6.0)]
SMALL = (0.5, 1.0, 1.5, 2.0)


def _moves(name, value, p):
    """What ``{**DEFAULT, name: value}`` does to the default's points ``p``, from the entry's description."""
    if name == "T of Figs 1a,b":
        return _set(p, ("1a", "1b"), 4, value)
    if name == "m_k of Fig 1c":
        return _set(p, ("1c",), 3, value)
    if name == "T of Figs 4, 6, 7":
        return _set(p, T4, 4, value)
    if name == "Delta of Figs 4, 5, 7 (sigma)":
        return _set(p, FIG4, 2, value)
    if name == "m_k of Fig 5":
        return _set(p, ("5ab", "head", "head_map"), 3, value)
    if name == "m_k of C002-12":
        return _set(p, ("good",), 3, value)
    if name == "Delta of C002-6 (sigma)":
        return _set(p, ("2",), 2, value)
    if name == "separation of C002-5 (sigma)":
        new = {("5", (pix, T), value): _pt(2, value, pix, 20, T, "u", 3 * N) for pix in (3.0, 1.0) for T in (5, 10, 50)}
        return _regroup(p, "5", lambda k: False, new)
    if name == "pixel pair of C002-5":  # "5 vs 3": Fig 1c's own pair
        new = {("5", (5.0, T), 2.0): _pt(2, 2.0, 5.0, 20, T, "u", 3 * N) for T in (5, 10, 50)}
        return _regroup(p, "5", lambda k: k[1][0] == 3.0, new)
    if name == "T of the Fig 3a claims":
        new = {("3a", pix, value): _pt(1, 0.0, pix, 20, value, "uec") for pix in (1.0, 3.0, 5.0)}
        return _regroup(p, "3a", lambda k: False, new)
    if name == "T pair of C002-6":  # "5 vs 50"
        new = {("2", (50, m), d): _pt(2, d, 1.0, m, 50, "u") for m in (10, 20) for d in SMALL}
        return _regroup(p, "2", lambda k: k[1][0] == 5, new)
    if name == "m_k pair of C002-6":  # "10 vs 5"
        new = {("2", (T, 5), d): _pt(2, d, 1.0, 5, T, "u") for T in (5, 10) for d in SMALL}
        return _regroup(p, "2", lambda k: k[1][1] == 10, new)
    if name == "small separations of C002-6 (sigma)":
        new = {("2", (T, m), d): _pt(2, d, 1.0, m, T, "u") for T in (5, 10) for m in (10, 20) for d in D if d <= value}
        return _regroup(p, "2", lambda k: k[-1] <= value, new)
    if name == "close separations of C002-10 (sigma)":  # Fig 5's curves keep 1 and 3 sigma
        return {k: None for k in p if k[0] in ("5ab", "6") and k[-1] not in (1.0, 3.0) and k[-1] > value}
    if name == "very close separation of C002-15 (sigma)":
        return {("c15", 1.0): None, ("c15", value): _pt(2, value, 3.0, 20, 10, "ur")}
    if name == "distance unit of C002-11":  # "pixel": 1 and 3 pixels of 3 sigma, i.e. 3 and 9 sigma
        return {**{(g, 1.0): None for g in ("head", "head_map")}, ("head", 9.0): _pt(2, 9.0, 3.0, 20, 50, "ue"),
                ("head_map", 9.0): _pt(2, 9.0, 3.0, 20, 50, "m")}  # fmt: skip
    if name == "velocity knowledge":  # "designated": the ULA with the designated velocity at C002-11's points
        return {("head_known", d): _pt(2, d, 3.0, 20, 50, "k") for d in (1.0, 3.0)}
    if name == "m_k of C002-1":  # C002-1 reads Fig 1a's whole axis at its photons
        return {**{("1a", value, d): _pt(2, d, 3.0, value, 5, "u") for d in NOT_CORE},
                **{("1a", 20, d): None for d in NOT_CORE}}  # fmt: skip
    if name == "Delta of C002-1 (sigma)":  # 1 sigma: Fig 1b's whole axis
        return {**{("1b", 20, d): _pt(2, d, 1.0, 20, 5, "u") for d in NOT_CORE},
                **{("1a", 20, d): None for d in NOT_CORE}}  # fmt: skip
    if name == "EM tolerance of Fig 7":
        return _set(p, ("7",), 7, (("tol_loglik", float(value.rsplit(" ", 1)[1])),))
    assert name in NO_POINT, name
    return {}


NO_POINT = {
    "epoch", "statistic", "accuracy ratio of C002-11", "gross errors", "photon model", "noise (photons/sigma^2/frame)",
    "velocity (sigma/frame)", "tracks", "EM stopping", "two-stage", "ULA", "coarse Delta of C002-7, C002-8 (sigma)",
    "Delta of the C002-9 order (sigma)", "coordinate of C002-6", "T dependence of C002-6", "bound",
    "designation error (sigma)",  # every point's designation error (checked by _points): no point moves
}  # fmt: skip


def _other_values():
    for name in REGISTER.names:
        for v in REGISTER[name].values:
            if v != REGISTER[name].default:
                yield name, v


@pytest.mark.parametrize("name,value", list(_other_values()))
def test_each_register_value_moves_the_points_it_names_and_no_other(name, value):
    p = _default_points()
    want = {k: v for k, v in _moves(name, value, p).items() if p.get(k) != v}
    assert _moved({**DEFAULT, name: value}) == want
    assert want or name in NO_POINT or (name, value) == ("close separations of C002-10 (sigma)", 2.0)


def test_every_register_entry_is_pinned_here():
    assert NO_POINT < set(REGISTER.names)
    assert len(list(_other_values())) == 53


def test_the_figures_add_their_whole_axes_and_the_bounds_once():
    fig = _points(DEFAULT, figures=True)
    claims = _default_points()
    for k, v in claims.items():  # the claims' points are among the figures', some with the bounds added
        assert fig[k][:5] == v[:5] and fig[k][6:] == v[6:], k
        assert fig[k][5] in (v[5], v[5] + "r"), k
    assert {k[-1] for k in fig if k[:2] == ("1b", 10)} == set(D)  # every panel's whole axis
    assert {k[-1] for k in fig if k[0] == "1c"} == set(D)
    assert {k[1] for k in fig if k[0] == "2"} == {(T, m) for T in (5, 10) for m in (10, 20)}
    assert {k[2] for k in fig if k[0] == "3a"} == {2, 5, 10, 20}  # the scale's frame axis and the claims' T
    assert {k[1] for k in fig if k[0] == "4"} == {20, 50}  # Fig 4a and 4b
    assert {k[1] for k in fig if k[0] == "7"} == {0.5, 2.0, 8.0}
    assert fig[("3a", 3.0, 10)][5] == "uecr" and fig[("4", 50, 8.0)] == _pt(2, 8.0, 3.0, 50, 10, "uer")
    assert fig[("ms", 0.5)] == _pt(2, 0.5, 3.0, 20, 10, "s", NI) and set(k[1] for k in fig if k[0] == "ms") == {
        0.5,
        1.0,
    }
    assert fig[("w", 4.0)] == _pt(2, 4.0, 3.0, 20, 10, "uw1", NI) and {k[1] for k in fig if k[0] == "w"} == {
        1.0,
        2.0,
        4.0,
    }
    assert fig[("bic", 6.0)] == _pt(2, 6.0, 3.0, 20, 10, "b", NI) and {k[1] for k in fig if k[0] == "bic"} == set(D)
    assert fig[("head", 1.0)][5] == "ue" and fig[("good", 0.5)][5] == "ue"  # the bounds are drawn, not these
    wide = _points({**DEFAULT, "T pair of C002-6": "5 vs 50"}, figures=True)  # Fig 2's T = 5 and 10, and C002-6's
    assert {k[1] for k in wide if k[0] == "2"} == {(T, m) for T in (5, 10, 50) for m in (10, 20)}


SETTINGS = {  # register value -> the settings fields it sets (every other field canonical)
    ("two-stage", "designation start, labels by start"): dict(mark_init="designation", mark_association="designation"),
    ("two-stage", "previous start + assignment"): dict(mark_init="previous", mark_association="assignment"),
    ("two-stage", "designation start + line association"): dict(mark_init="designation", mark_association="lines"),
    ("two-stage", "no designation: moment start + line association"): dict(mark_init="moments", mark_association="lines"),
    ("EM stopping", "SQUAREM to 1e-6 sigma"): dict(accelerate="squarem", max_iter=5000, tol_sigma=1e-6, tol_loglik=None),
    ("EM stopping", "plain EM, cap 100"): dict(accelerate="none", max_iter=100, tol_sigma=1e-6, tol_loglik=None),
    ("EM stopping", "plain EM to a log-likelihood gap of 0.1"): dict(
        accelerate="none", max_iter=5000, tol_sigma=1e-6, tol_loglik=0.1
    ),
    ("velocity (sigma/frame)", "0, 0"): dict(velocity_sigma=(0.0, 0.0)),
    ("velocity (sigma/frame)", "0.5, 0.25"): dict(velocity_sigma=(0.5, 0.25)),
    ("noise (photons/sigma^2/frame)", 0.05): dict(noise_density=0.05),
    ("photon model", "poisson"): dict(photon_model="poisson"),
    ("designation error (sigma)", 1.0): dict(designation_sd_sigma=1.0),
    ("velocity knowledge", "designated"): dict(velocity_knowledge="designated"),
    ("tracks", "crossing"): dict(tracks="crossing"),
    ("tracks", "diverging"): dict(tracks="diverging"),
}  # fmt: skip
BASE = dict(
    seed=77, velocity_sigma=(0.2, 0.1), noise_density=0.01, photon_model="fixed", designation_sd_sigma=0.3,
    crb_phases=9, n_trials=12, n_bootstrap=2100,
)  # fmt: skip


@pytest.mark.parametrize("key", list(SETTINGS))
def test_each_register_value_sets_the_simulation_settings_it_names(key):
    s = study.settings_of({**DEFAULT, key[0]: key[1]}, 77, SCALE)
    want = replace(CANONICAL_SETTINGS, **{**BASE, **SETTINGS[key]})
    assert s == want
    assert type(s.seed) is int and isinstance(s.noise_density, float) and isinstance(s.designation_sd_sigma, float)


def test_the_default_settings_and_the_scales_iteration_cap():
    assert study.settings_of(DEFAULT, 77, SCALE) == replace(CANONICAL_SETTINGS, **BASE)
    capped = replace(SCALE, max_iter=30)
    assert study.settings_of(DEFAULT, 5, capped).max_iter == 30
    assert study.settings_of({**DEFAULT, "EM stopping": "plain EM, cap 100"}, 5, capped).max_iter == 30
    assert (
        study.settings_of({**DEFAULT, "EM stopping": "plain EM, cap 100"}, 5, replace(SCALE, max_iter=500)).max_iter
        == 100
    )
    assert study.settings_of({**DEFAULT, "seed": 1}, 5.0, SCALE).seed == 5


#: The settings each algorithm reads besides the scene (seed, velocity, noise, photon model, margin, bound phases,
#: tracks), from what each algorithm is (:data:`ALGORITHMS`): the EMs their stopping rule, the ULAs their merge
#: distance, the MAP-ULA the velocity knowledge, the iterative marks their start and association, the centre of
#: region its gate, the BIC fits their cap, the bounds nothing else.
READS = {
    "u": {"tol_sigma", "tol_loglik", "max_iter", "merge_sigma", "accelerate"},
    "p": {"tol_sigma", "tol_loglik"},
    "m": {"tol_sigma", "tol_loglik", "max_iter", "merge_sigma", "accelerate", "velocity_knowledge"},
    "e": {"tol_sigma", "tol_loglik", "max_iter", "accelerate", "mark_init", "mark_association"},
    "q": {"tol_sigma", "tol_loglik", "mark_init", "mark_association"},
    "c": {"gate_half_sigma"},
    "s": {"tol_sigma", "max_iter", "accelerate"},
    "w": {"tol_sigma", "max_iter"},
    "k": {"tol_sigma", "max_iter", "accelerate"},
    "1": {"tol_sigma", "max_iter", "accelerate"},
    "b": {"bic_max_iter"},
    "r": set(),
}
SCENE = {"seed", "velocity_sigma", "noise_density", "photon_model", "margin_sigma", "crb_phases", "tracks"}
#: Every field moved off its canonical value.
MOVED = dict(
    seed=9, velocity_sigma=(0.5, 0.25), noise_density=0.05, photon_model="poisson", margin_sigma=7.0,
    designation_sd_sigma=1.0, designation_velocity_sd=0.2, tol_sigma=1e-3, max_iter=77, merge_sigma=0.2,
    accelerate="none", mark_init="moments", mark_association="lines", gate_half_sigma=4.0, bic_max_iter=50,
    crb_phases=5, n_trials=3, n_bootstrap=500, velocity_knowledge="designated", tracks="crossing", tol_loglik=0.1,
)  # fmt: skip


def test_every_field_is_moved_by_the_probe():
    assert set(MOVED) == {f.name for f in fields(CANONICAL_SETTINGS)}
    assert all(getattr(CANONICAL_SETTINGS, k) != v for k, v in MOVED.items())
    assert set(READS) == set(ALGORITHMS)


@pytest.mark.parametrize("letter", sorted(ALGORITHMS))
def test_each_algorithm_keeps_the_settings_it_reads_and_the_others_are_canonical(letter):
    s = replace(CANONICAL_SETTINGS, **MOVED)
    out = study._job_settings(s, letter, SCALE, q=2)
    kept = SCENE | READS[letter]
    if letter in "pq":  # the iteration counts run to Fig 7's own tolerance whatever the stopping reading
        kept = kept - {"tol_sigma", "tol_loglik"}
    for f in fields(CANONICAL_SETTINGS):
        want = MOVED[f.name] if f.name in kept else getattr(CANONICAL_SETTINGS, f.name)
        assert getattr(out, f.name) == want, (letter, f.name)


def test_one_object_has_no_tracks_to_cross_and_the_scales_cap_bounds_the_iteration_counts():
    s = replace(CANONICAL_SETTINGS, **MOVED)
    assert study._job_settings(s, "u", SCALE, q=1).tracks == "parallel"
    assert study._job_settings(s, "u", SCALE, q=2).tracks == "crossing"
    assert study._job_settings(s, "u", SCALE).tracks == "crossing"  # two objects unless told
    capped = replace(SCALE, max_iter=30)
    for letter in "pq":
        assert study._job_settings(s, letter, capped).max_iter == 30  # canonical 5000 capped
        assert study._job_settings(s, letter, replace(SCALE, max_iter=9000)).max_iter == 5000
    assert study._job_settings(s, "u", capped).max_iter == 77  # the register's cap; settings_of applied the scale's


def test_jobs_are_one_per_point_and_letter_without_repeats():
    jobs = study.jobs_of(DEFAULT, 3, SCALE)
    assert len(jobs) == len(set(jobs))
    assert all(len(c.algs) == 1 for _, c in jobs)
    s = study.settings_of(DEFAULT, 3, SCALE)
    assert all(job == study._job_settings(s, c.algs, SCALE, c.q) for job, c in jobs)
    pts = _default_points()
    want = {(q, d, pix, m, T, a, n, var) for (q, d, pix, m, T, algs, n, var) in pts.values() for a in algs}
    # what no claim reads at the default: the centre of region off C002-9's order's pixel (3 sigma), the accelerated
    # ULA at Fig 7's points (C002-13 and C002-14 count plain-EM steps), the MAP-ULA unless the "ULA" reading is MAP
    unread = {_pt(1, 0.0, 1.0, 20, 10, "c"), _pt(1, 0.0, 5.0, 20, 10, "c"), _pt(2, 0.5, 3.0, 20, 10, "u", NI),
              _pt(2, 8.0, 3.0, 20, 10, "u", NI), _pt(2, 1.0, 3.0, 20, 50, "m"), _pt(2, 3.0, 3.0, 20, 50, "m")}  # fmt: skip
    assert {(c.q, c.d, c.pix, c.m, c.T, c.algs, c.n, c.variant) for _, c in jobs} == want - unread
    fig = study.jobs_of(DEFAULT, 3, SCALE, figures=True)
    assert set(jobs) < set(fig) and len(fig) == len(set(fig))
    every = {
        (c.q, c.d, c.pix, c.m, c.T, a, c.n, c.variant) for c in study._points(DEFAULT, SCALE, True)[1] for a in c.algs
    }
    assert {(c.q, c.d, c.pix, c.m, c.T, c.algs, c.n, c.variant) for _, c in fig} == every  # every letter of a figure
    assert {"b", "s", "w", "1", "r"} <= {c.algs for _, c in fig}
    some = study.jobs_of(DEFAULT, 3, SCALE, claims={"C002-15"})
    assert {c.algs for _, c in some} == {"u", "r"} and set(some) < set(jobs)


def test_one_object_s_jobs_run_on_parallel_tracks_whatever_the_tracks_reading():
    jobs = study.jobs_of({**DEFAULT, "tracks": "crossing"}, 3, SCALE)
    tracks = {(c.q, job.tracks) for job, c in jobs}
    assert tracks == {(1, "parallel"), (2, "crossing")}


def test_a_point_is_built_with_the_designation_error_and_the_scales_trials():
    P = study._Points({**DEFAULT, "designation error (sigma)": 1.0}, SCALE)
    c = P(2.0, 3, 1, 20.0, 10.0, "ue")
    assert c == Config(2, 3.0, 1.0, 20, 10, "ue", 1.0, None, None, 12, "explore", 0.0, ())
    assert [type(x) for x in c[:5]] == [int, float, float, int, int]
    assert P(1, 0, 3, 20, 5, "u", n=40, variant=[("tol_loglik", 0.1)]) == Config(
        1, 0.0, 3.0, 20, 5, "u", 1.0, None, None, 40, "explore", 0.0, (("tol_loglik", 0.1),)
    )
    assert P.asked == [c, P.asked[1]] and len(P.asked) == 2


def test_the_screen_is_a_quarter_of_every_size_with_floors():
    s = study.screen_scale(study.Scale(n_trials=100, n_iter_trials=40, n_bootstrap=2000, crb_phases=64))
    assert (s.n_trials, s.n_iter_trials, s.n_bootstrap, s.crb_phases) == (25, 10, 1000, 16)
    assert all(type(x) is int for x in (s.n_trials, s.n_iter_trials, s.n_bootstrap, s.crb_phases))
    s = study.screen_scale(study.Scale(n_trials=20, n_iter_trials=8, n_bootstrap=600, crb_phases=16), 0.5, 800)
    assert (s.n_trials, s.n_iter_trials, s.n_bootstrap, s.crb_phases) == (10, 4, 600, 8)
    s = study.screen_scale(study.Scale(n_trials=10, n_iter_trials=6, crb_phases=8), 0.25)
    assert (s.n_trials, s.n_iter_trials, s.crb_phases) == (8, 4, 8)
    assert study.screen_scale(SCALE, 1.0).n_trials == 12
    for bad in (0.0, -0.5, 1.5):
        with pytest.raises(ValueError, match="fraction"):
            study.screen_scale(SCALE, bad)


def test_an_entry_that_moves_a_claims_points_is_declared_by_that_claim():
    """Every register value that changes the points a claim reads (``claim_values.NEEDS``) is an entry the claim
    declares (``DEPENDS``): the measurement projects each claim onto its declared entries first, so an undeclared
    entry would never reach it and the exploration would silently never vary it for that claim."""
    from tvtrack.papers.p002_unified_location_em.claim_values import NEEDS
    from tvtrack.papers.p002_unified_location_em.register import DEPENDS

    D = list(SCALE.separations)
    g0, _ = study._points(DEFAULT, SCALE)
    moved = set()
    for name in REGISTER.names:
        for value in REGISTER[name].values:
            cfg = {**DEFAULT, name: value}
            g1, _ = study._points(cfg, SCALE)
            moved |= {(cid, name) for cid, need in NEEDS.items() if need(cfg, g1, D) != need(DEFAULT, g0, D)}
    assert ("C002-12", "T of Figs 4, 6, 7") in moved and ("C002-11", "m_k of Fig 5") in moved  # the check can see
    assert sorted((cid, name) for cid, name in moved if name not in DEPENDS[cid]) == []
