"""Tests of paper 002's cap study (:mod:`.cap_check`): the larger cap reruns the same scenes, changes only the trials
that reached the default cap, measures nothing where the cap does not bind, and its paragraph's words follow the
intervals."""

import numpy as np
import pytest

from tvtrack.counts import proportion_ci
from tvtrack.estimate import Estimate
from tvtrack.papers.p002_unified_location_em import cap_check as cc
from tvtrack.papers.p002_unified_location_em import claim_values, study
from tvtrack.papers.p002_unified_location_em.register import REGISTER

DEFAULT = REGISTER.default()
#: 6 trials a point with the smoke profile's cap of 100 EM steps: at seed 5 Fig 6b's marks reach it in most trials,
#: Fig 4a's in one trial (d = 2 sigma) and none at d = 1 and 3 sigma.
SCALE = study.Scale(n_trials=6, separations=(1.0, 2.0, 3.0, 4.0, 6.0, 8.0), crb_phases=2, max_iter=100)
CLOSE = (1.0, 2.0, 3.0)


class _Res(dict):
    """``res[c]`` of the points run, with the settings and scale they ran under (as :func:`.study.figure_data`'s)."""

    def __init__(self, items, settings, scale):
        super().__init__(items)
        self.settings, self.scale = settings, scale


@pytest.fixture(scope="module")
def setup():
    g, _ = study._points(DEFAULT, SCALE, figures=True)
    settings = study.settings_of(DEFAULT, 5, SCALE)
    pts = [g[k][20][d] for k in ("6", "4") for d in CLOSE]
    jobs = [(study._job_settings(settings, a, SCALE, c.q), c._replace(algs=a)) for c in pts for a in "ue"]
    study.run_jobs(jobs)
    res = study._Results(settings, SCALE)
    return g, _Res({c: res[c] for c in pts}, settings, SCALE)


def _capped(r, alg):
    return r[f"{alg}_flags"][:, 2]


def test_a_larger_cap_reaches_the_stopping_rule_and_changes_only_the_capped_trials(setup):
    g, res = setup
    hits = {}
    for k in ("6", "4"):
        for d in CLOSE:
            c = g[k][20][d]
            r, big = res[c], cc.at_larger_cap(res, c, "ue", 10**6)
            for alg, name in (("em", "two-stage"), ("ula", "ULA")):
                cap = _capped(r, alg)
                hits[(k, d, name)] = int(cap.sum())
                assert not _capped(big, alg).any()  # the stopping rule is reached by every EM
                assert np.array_equal(r[alg][~cap], big[alg][~cap])  # bit for bit where the cap did not bind
                assert not np.all(r[alg][cap] == big[alg][cap], axis=(1, 2)).any()  # every capped trial moves on
    assert [hits[("6", d, "two-stage")] for d in CLOSE] == [6, 5, 6]
    assert [hits[("4", d, "two-stage")] for d in CLOSE] == [0, 1, 0]


def test_paired_change_is_exactly_zero_without_a_change_and_measures_a_known_one():
    e = np.random.default_rng(1).normal(size=(30, 4))
    var = claim_values.spread_total
    same = cc.paired_change([e], [e.copy()], var, np.random.default_rng(2), 2000)
    assert (same.value, same.ci_low, same.ci_high) == (0.0, 0.0, 0.0)
    assert cc._signed(same) == "exactly 0"
    doubled = cc.paired_change([e], [2 * e], var, np.random.default_rng(2), 2000)
    assert doubled.value == pytest.approx(3 * var(e[None])[0], rel=1e-12)  # Var(2e) - Var(e) = 3 Var(e)
    halved = cc.paired_change([2 * e], [e], var, np.random.default_rng(2), 2000)
    assert (cc._side(doubled), cc._side(halved), cc._side(same)) == ("up", "down", "none")


def test_the_same_cap_changes_nothing_and_the_paragraph_says_so(setup):
    g, res = setup
    keys = set(study._CACHE)
    out = cc.cap_check(DEFAULT, g, res, 1999, 2000, factor=1)
    assert set(study._CACHE) == keys  # the reruns are not cached: what the claims read stays as it was
    assert out["cap"] == out["larger cap"] == 100 and out["claims"] == ["C002-10"]
    for p in out["points"].values():
        for key in ("two-stage variance change", "rho change"):
            assert (p[key].value, p[key].ci_low, p[key].ci_high) == (0.0, 0.0, 0.0)
        assert p["changed trials"] == 0 and p["rho"][0] == p["rho"][1]
    part = out["part"]
    assert part["default"] == part["larger"] and part["change"].value == 0.0
    text = cc.cap_paragraph(out)
    assert "the estimates change in 0 of the 18 trials." in text
    assert "So the default cap leaves the gain rho without a measurable change at d = 1, 2 and 3 sigma." in text
    assert (
        f'its rule gives "{part["verdicts"][0]}" at the default cap and "{part["verdicts"][0]}" at the larger' in text
    )
    assert text.endswith("so on this replicate that verdict does not depend on the cap.")


def test_a_larger_cap_is_measured_on_the_same_trials(setup):
    g, res = setup
    out = cc.cap_check(DEFAULT, g, res, 1999, 2000, factor=10**4)
    assert out["larger cap"] == 10**6
    for d, p in out["points"].items():
        r, big = res[g["6"][20][d]], cc.at_larger_cap(res, g["6"][20][d], "ue", 10**6)
        capped = _capped(r, "em") | _capped(r, "ula")
        assert p["changed trials"] == capped.sum() and p["changed trials not capped"] == 0
        assert p["two-stage cap hit, larger cap"].value == p["ULA cap hit, larger cap"].value == 0.0
        e0, e1 = (claim_values.errors(x, "em") for x in (r, big))
        var = claim_values.spread_total
        assert p["two-stage variance change"].value == pytest.approx(var(e1[None])[0] - var(e0[None])[0], abs=1e-12)
        u0, u1 = (claim_values.errors(x, "ula") for x in (r, big))
        rho = (var(e0[None])[0] / var(u0[None])[0], var(e1[None])[0] / var(u1[None])[0])
        assert p["rho"] == pytest.approx(rho, rel=1e-12)
        assert p["rho change"].value == pytest.approx(rho[1] - rho[0], rel=1e-9)
    m = cc.cap_metrics(out)
    assert m["cap_check/d2/two-stage cap hit"].value == pytest.approx(5 / 6)
    assert m["cap_check/C002-10 coarser pixels/change"].value == pytest.approx(
        out["part"]["larger"].value - out["part"]["default"].value
    )


# -- the paragraph's words --------------------------------------------------------------------------------------


def _e(v, lo, hi):
    return Estimate(v, 0.0, lo, hi, 80, 0.95, "test")


def _point(rho_change):
    return {
        "two-stage cap hit": proportion_ci(30, 80),
        "ULA cap hit": proportion_ci(0, 80),
        "two-stage cap hit, larger cap": proportion_ci(0, 80),
        "ULA cap hit, larger cap": proportion_ci(0, 80),
        "changed trials": 30,
        "changed trials not capped": 0,
        "two-stage variance": (1.5, 1.6),
        "two-stage variance change": _e(0.1, 0.01, 0.2),
        "rho": (0.5, 0.6),
        "rho change": rho_change,
    }


def _out(changes, verdicts=("not reproduced", "not reproduced"), part_change=None):
    return {
        "cap": 5000,
        "larger cap": 1000000,
        "n": 80,
        "T": 10,
        "pix": 5.0,
        "m": 20,
        "close": list(changes),
        "points": {d: _point(e) for d, e in changes.items()},
        "claims": ["C002-10"],
        "part": {
            "default": _e(0.66, 0.55, 0.81),
            "larger": _e(0.74, 0.61, 0.91),
            "change": part_change or _e(0.08, 0.04, 0.13),
            "verdicts": verdicts,
        },
        "cpu_s": 1.0,
    }


UP, DOWN, NONE = _e(0.1, 0.02, 0.2), _e(-0.1, -0.2, -0.02), _e(0.1, -0.02, 0.2)


def test_the_whole_paragraph_reads_the_numbers_it_is_given():
    assert cc.cap_paragraph(_out({1.0: UP})) == (
        "**The EM iteration cap.** At Fig 6b's configuration (Delta = 5 sigma, m_k = 20, T = 10; the figures' "
        "replicate, 80 trials a point) the two-stage's per-frame marks reach the cap of 5000 EM iterations in some "
        "frame in 37.5% [26.9%, 49.0%] of the trials at d = 1 sigma; the ULA reaches it in 0.0% [0.0%, 4.5%] of the "
        "trials at d = 1 sigma. Rerun on the same scenes with a cap of 1000000 iterations, the marks reach it in "
        "0.0% [0.0%, 4.5%] of the trials at d = 1 sigma, the ULA in 0.0% [0.0%, 4.5%] of the trials at d = 1 sigma; "
        "the estimates change in 30 of the 80 trials, every one of them among those that reached the default cap. "
        "Paired on the same trials (95 % intervals, widened where a simulation test found the bootstrap interval of "
        "a ratio of variance sums to cover less than 95 % at this number of trials), the larger cap changes the "
        "two-stage's variance sum Sigma^2 of "
        "the initial positions by +0.1 [+0.01, +0.2] sigma^2 at d = 1 sigma (1.5 -> 1.6: up), and the gain rho = "
        "Sigma^2_two-stage / Sigma^2_ULA by +0.1 [+0.02, +0.2] at d = 1 sigma (0.5 -> 0.6: up). So the default cap "
        "understates the ULA's gain rho (rho rises when the EMs run further) at d = 1 sigma. Of the claims at the "
        'register default, C002-10 reads these points (part "coarser pixels": rho at Delta = 5 sigma over rho at Fig 4a\'s pixels, geometric '
        "mean over d = 1 sigma): on this replicate (intervals from this study's own resamples, as its rule reads "
        "them) it is 0.66 [0.55, 0.81] at the default cap and 0.74 [0.61, 0.91] "
        'at the larger one, a paired change of +0.08 [+0.04, +0.13] (a measurable change); its rule gives "not '
        'reproduced" at the default cap and "not reproduced" at the larger one, so on this replicate that verdict '
        "does not depend on the cap."
    )


@pytest.mark.parametrize(
    "changes, sentence",
    [
        (
            {1.0: UP},
            "So the default cap understates the ULA's gain rho (rho rises when the EMs run further) at d = 1 sigma.",
        ),
        (
            {1.0: DOWN},
            "So the default cap overstates the ULA's gain rho (rho falls when the EMs run further) at d = 1 sigma.",
        ),
        ({1.0: NONE}, "So the default cap leaves the gain rho without a measurable change at d = 1 sigma."),
        (
            {1.0: UP, 2.0: NONE, 3.0: UP},
            "So the default cap understates the ULA's gain rho (rho rises when the EMs run further) at d = 1 and 3 "
            "sigma and leaves the gain rho without a measurable change at d = 2 sigma.",
        ),
    ],
)
def test_the_gain_sentence_follows_each_interval(changes, sentence):
    assert cc._gain_sentence(_out(changes)["points"]) == sentence


def test_the_verdict_sentence_follows_the_rule_at_each_cap():
    head = (
        'Of the claims at the register default, C002-10 reads these points (part "coarser pixels": rho at Delta = 5 '
        "sigma over rho at Fig 4a's pixels, geometric mean over d = 1 sigma): on this replicate (intervals from this "
        "study's own "
        "resamples, as its rule reads them) it is 0.66 [0.55, 0.81] at the default "
        "cap and 0.74 [0.61, 0.91] at the larger one, a paired change of "
    )
    moved = _out({1.0: UP}, ("undecided", "not reproduced"))
    assert cc._claims_sentence(moved) == head + (
        '+0.08 [+0.04, +0.13] (a measurable change); its rule gives "undecided" at the default cap and "not '
        'reproduced" at the larger one, so on this replicate that verdict depends on the cap.'
    )
    still = _out({1.0: UP}, ("undecided", "undecided"), _e(0.08, -0.01, 0.13))
    assert cc._claims_sentence(still) == head + (
        '+0.08 [-0.01, +0.13] (no measurable change); its rule gives "undecided" at the default cap and '
        '"undecided" at the larger one, so on this replicate that verdict does not depend on the cap.'
    )
    assert cc._claims_sentence({**still, "claims": []}) == "No claim reads these points at the register default."


def test_a_paired_change_is_read_widened_by_the_measured_coverage_and_an_unmeasured_one_decides_nothing():
    """The paired changes state the coverage measured for the package's bootstrap of a variance ratio at their size
    (0.895 at n = 80: short of 95 %), so the interval the words read is the widened one; below the smallest size
    measured nothing is decided; an interval of no width (nothing changed) stays exactly 0."""
    from tvtrack.papers.p002_unified_location_em.ratio_coverage import ratio_coverage_note

    raw = Estimate(0.04, 0.02, 0.004, 0.088, 80, 0.95, "cluster percentile bootstrap (2000 resamples of 80 clusters)")
    wide = cc.proxied(raw, ratio_coverage_note(80))
    assert wide.ci_low < raw.ci_low and wide.ci_high > raw.ci_high and "taken for this paired change" in wide.method
    assert cc._side(raw) == "up" and cc._side(wide) == "none"  # a lower end of +0.004 does not survive the widening
    small = cc.proxied(Estimate(0.5, 0.1, 0.3, 0.7, 2, 0.95, "cluster percentile bootstrap"), ratio_coverage_note(2))
    assert "coverage unmeasured" in small.method and cc._side(small) == "none"
    zero = Estimate(0.0, 0.0, 0.0, 0.0, 80, 0.95, "cluster percentile bootstrap")
    assert cc.proxied(zero, ratio_coverage_note(80)) == zero


def test_a_rerun_keeps_the_points_own_settings_variant(monkeypatch):
    """``study.rerun`` adds the cap to a point's variant (e.g. Fig 7's tolerance), never replaces it."""
    seen = []
    monkeypatch.setattr(study, "run_config", lambda job, c: seen.append(dict(c.variant)) or {})
    monkeypatch.setattr(study, "_job_settings", lambda *a: None)

    class Res:
        settings, scale = None, None

    from tvtrack.papers.p002_unified_location_em.sim_config import Config

    point = Config(2, 1.0, 3.0, 20, 10, "u", 0.3, None, None, 8, "", 0.0, variant=(("tol_px", 1e-3),))
    study.rerun(Res(), point, "u", max_iter=10**6)
    assert seen == [{"tol_px": 1e-3, "max_iter": 10**6}]
