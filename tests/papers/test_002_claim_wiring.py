"""Paper 002: how each claim value is read from the simulation, pinned where the value pins' stand-in cannot tell.

The value pins give every algorithm at every point the same error sample times one scale, so a ratio of two
algorithms does not depend on the epoch, on which coordinate is read, or on which sample is resampled with which.
The stand-in here gives each algorithm at each point a sample of its own (or, where pairing is the question, one
shared sample), with its own scale per column (x, y, v_x, v_y), so that:

- the epoch the register names (the first frame, the middle, the last) moves every gain read at it;
- C002-7/-8/-9 read the x coordinate of the one object of Fig 3a, not x and y together;
- C002-11's MAP and known-velocity readings compare like with like at the epoch read, as a ratio of SDs where asked;
- C002-15 reads the initial positions and the velocities over the bound the register names, in the spread named;
- each claim's interval comes from its own seeded stream, the same whether it is measured alone or with the others;
- each claim reads exactly the simulation points it declares (so a subset runs only its own jobs).

Every expected value is computed here from the stand-in's arrays by the definitions of the paper's quantities
(positions at frame t are x + t v, summed variances over the trials with ddof 1), not through the module's helpers.
"""

from __future__ import annotations

import math
import zlib

import numpy as np
import pytest

from tvtrack.papers.p002_unified_location_em import claim_values as cv
from tvtrack.papers.p002_unified_location_em.register import REGISTER
from tvtrack.papers.p002_unified_location_em.sim_config import seed_sequence
from tvtrack.papers.p002_unified_location_em.study import Scale, _points
from tvtrack.papers.p002_unified_location_em.summaries import bootstrap_groups

DEFAULT = REGISTER.default()
D = (0.5, 1.0, 2.0, 3.0, 4.0, 6.0, 8.0)
SCALE = Scale(n_trials=40, n_iter_trials=12, separations=D, n_bootstrap=40)
B = 40
N = 40
ALGS = ("ula", "em", "cr", "map", "ula_vd", "em_vd")
#: One error sample (n, Q, 4) per object count, shared by every point and algorithm in the shared stand-in.
SHARED = {q: np.random.default_rng(21).standard_normal((N, q, 4)) for q in (1, 2)}


def _scales(c, alg: str, per_column: bool) -> np.ndarray:
    """The error scale of ``alg`` at point ``c`` per column (x, y, v_x, v_y): generic in the point and algorithm."""
    a = ALGS.index(alg)
    base = 1.3 * c.d + 0.7 * c.pix + 0.11 * c.m + 0.23 * c.T + 0.9 * a
    cols = np.arange(4) if per_column else np.zeros(4)
    return np.exp(0.4 * np.sin(base + 1.1 * cols)) * (0.5 + 0.1 * a if per_column else 1.0)


class Scenes:
    """``res[Config]``: each algorithm's errors (n, Q, 4) in sigma, plain-EM step counts and bounds; every point
    read is recorded in ``read``.

    ``shared``: every algorithm at every point is one sample times a scalar (a paired ratio is then the same in every
    resample, an unpaired one scatters); otherwise each has a sample of its own with a scale per column, plus
    ``bias`` (so that a mean square differs from a variance)."""

    def __init__(self, shared: bool = False, bias: float = 0.0):
        self.shared, self.bias, self.read, self._made = shared, bias, [], {}

    def __getitem__(self, c):
        self.read.append(c)
        if c not in self._made:
            self._made[c] = self._make(c)
        return self._made[c]

    def _make(self, c) -> dict:
        out = {"T": c.T}
        for i, a in enumerate(ALGS):
            if self.shared:
                out[a] = SHARED[c.q] * _scales(c, a, False)
            else:
                rng = np.random.default_rng([zlib.crc32(repr(c).encode()), i])
                out[a] = rng.standard_normal((N, c.q, 4)) * _scales(c, a, True) + self.bias
        k = np.arange(12)
        out.update(
            plain_iter=30.0 + 40.0 / (0.5 + c.d) + k % 3,
            em_plain_iter=55.0 + 7.0 * c.d + k % 5,
            crb_pos=0.2 + 0.05 * c.d,
            crb_vel=0.01 + 0.002 * c.d,
            bcrb_pos=0.13 + 0.04 * c.d,
            bcrb_vel=0.007 + 0.003 * c.d,
        )
        return out


def measure(config=DEFAULT, claims=None, res=None, seed=3):
    g, _ = _points(config, SCALE)
    res = Scenes() if res is None else res
    return cv.measure_claims(config, g, res, seed, B, D, claims), g, res


def positions(e, epoch: str, T: int) -> np.ndarray:
    """Per-trial position errors (n, 2Q) at the first frame, the middle or the last (x + t v), or the velocities."""
    if epoch == "velocity":
        return e[..., 2:].reshape(len(e), -1)
    t = {"first": 0.0, "mid": (T - 1) / 2, "last": T - 1.0}[epoch]
    return (e[..., :2] + t * e[..., 2:]).reshape(len(e), -1)


def var_sum(p) -> float:
    return float(np.var(p, axis=0, ddof=1).sum())


def V(res, c, alg="ula", epoch="first") -> float:
    """Summed variance of ``alg``'s position errors at point ``c`` and ``epoch`` (sigma^2)."""
    return var_sum(positions(res[c][alg], epoch, c.T))


def X(res, c, alg, epoch="first") -> float:
    """Variance of ``alg``'s x error of the one object at ``c`` (Fig 3a)."""
    return var_sum(positions(res[c][alg], epoch, c.T)[:, :1])


# -- the epoch and the coordinate read ----------------------------------------------------------------------------


@pytest.mark.parametrize("epoch", ["mid", "last"])
def test_the_two_stage_over_ula_gains_are_read_at_the_epoch_the_register_names(epoch):
    """rho = Sigma^2(two-stage) / Sigma^2(ULA) of both objects' positions at the frame read: C002-10 per separation
    and as geometric means over the close separations (Delta 5 over 3 sigma; 50 over 5 frames), C002-11 at T = 50,
    C002-12 at 8 sigma; each differs from the first frame's."""
    config = {**DEFAULT, "epoch": epoch}
    m, g, res = measure(config, {"C002-10", "C002-11", "C002-12"})

    def rho(c, ep=epoch):
        return V(res, c, "em", ep) / V(res, c, "ula", ep)

    closer = [e.value for e in m["C002-10"]["closer"]]
    np.testing.assert_allclose(closer, [rho(g["4"][20][d]) for d in D], rtol=1e-9)
    assert not np.allclose(closer, [rho(g["4"][20][d], "first") for d in D], rtol=1e-3)

    def lg(key, sub):
        return np.mean([np.log(rho(g[key][sub][d])) for d in (1.0, 2.0, 3.0)])

    assert m["C002-10"]["coarser pixels"].value == pytest.approx(np.exp(lg("6", 20) - lg("4", 20)), rel=1e-9)
    assert m["C002-10"]["more frames"].value == pytest.approx(np.exp(lg("5ab", 50) - lg("5ab", 5)), rel=1e-9)
    for d, part in ((1.0, "d = 1 sigma (paper x4.5)"), (3.0, "d = 3 sigma (paper x4)")):
        assert g["head"][d].T == 50 and m["C002-11"][part].value == pytest.approx(rho(g["head"][d]), rel=1e-9)
    for p, c in g["good"].items():
        assert c.d == 8.0 and m["C002-12"][f"Delta = {p:g} sigma"].value == pytest.approx(rho(c), rel=1e-9)


@pytest.mark.parametrize(
    "entry, value, num, den, key",
    [
        ("ULA", "MAP (designation prior)", "em", "map", "head_map"),
        ("velocity knowledge", "designated", "em_vd", "ula_vd", "head_known"),
    ],
)
@pytest.mark.parametrize("ratio", ["variance", "SD"])
def test_c11_under_the_map_and_known_velocity_readings_compares_at_the_epoch_read(entry, value, num, den, key, ratio):
    """C002-11 "x4 / x4.5" with the MAP-ULA (or the ULA that knows the velocity) as the denominator: both read at the
    last frame, and as the square root of the variance ratio when the ratio of SDs is asked."""
    config = {**DEFAULT, entry: value, "epoch": "last", "accuracy ratio of C002-11": ratio}
    m, g, res = measure(config, {"C002-11"})
    for d, part in ((1.0, "d = 1 sigma (paper x4.5)"), (3.0, "d = 3 sigma (paper x4)")):
        want = V(res, g["head"][d], num, "last") / V(res, g[key][d], den, "last")
        assert m["C002-11"][part].value == pytest.approx(math.sqrt(want) if ratio == "SD" else want, rel=1e-9)


def test_c11_asked_as_a_ratio_of_sds_is_the_root_of_the_ula_gain():
    m, g, res = measure({**DEFAULT, "accuracy ratio of C002-11": "SD"}, {"C002-11"})
    c = g["head"][3.0]
    want = math.sqrt(V(res, c, "em") / V(res, c, "ula"))
    assert m["C002-11"]["d = 3 sigma (paper x4)"].value == pytest.approx(want, rel=1e-9)


@pytest.mark.parametrize("epoch", ["first", "last"])
def test_fig_3a_claims_read_the_x_coordinate_of_the_one_object(epoch):
    """C002-7/-8/-9 compare Var x_o (Fig 3a: one object, 10 frames): the two-stage marks over the ULA at Delta = 1
    and 5 sigma, the ULA at 5 over 1 sigma and over the marks, the centres of region over the marks and the marks
    over the ULA at 3 sigma; the y coordinate, read too, would move every one."""
    m, g, res = measure({**DEFAULT, "epoch": epoch}, {"C002-7", "C002-8", "C002-9"})
    fig = {p: g["3a"][p][10] for p in (1.0, 3.0, 5.0)}
    assert all(c.q == 1 for c in fig.values())

    def x(p, alg):
        return X(res, fig[p], alg, epoch)

    def both(p, alg):
        return V(res, fig[p], alg, epoch)

    c7, c8, c9 = m["C002-7"], m["C002-8"], m["C002-9"]
    assert c7["fine pixels"].value == pytest.approx(x(1.0, "em") / x(1.0, "ula"), rel=1e-9)
    assert c7["coarse pixels"].value == pytest.approx(x(5.0, "em") / x(5.0, "ula"), rel=1e-9)
    assert c8["worse than fine pixels"].value == pytest.approx(x(5.0, "ula") / x(1.0, "ula"), rel=1e-9)
    assert c8["better than the marks"].value == pytest.approx(x(5.0, "ula") / x(5.0, "em"), rel=1e-9)
    assert c9["centre-of-region >= iterative marks"].value == pytest.approx(x(3.0, "cr") / x(3.0, "em"), rel=1e-9)
    assert c9["iterative marks >= ULA"].value == pytest.approx(x(3.0, "em") / x(3.0, "ula"), rel=1e-9)
    assert c7["coarse pixels"].value != pytest.approx(both(5.0, "em") / both(5.0, "ula"), rel=1e-3)


# -- the photon and pixel reference points ------------------------------------------------------------------------


def test_c2_weakening_is_the_photon_ratio_at_six_sigma_over_that_at_one_sigma():
    """r_m(d) = Sigma^2(m_k = 10) / Sigma^2(m_k = 20) of the ULA at Fig 1a (Delta 3 sigma, T 5); "weakens" reads
    r_m(6 sigma) / r_m(1 sigma), "far apart" r_m(6 sigma)."""
    m, g, res = measure(claims={"C002-2"})
    assert all(g["1a"][mk][d].pix == 3.0 and g["1a"][mk][d].T == 5 for mk in (10, 20) for d in (1.0, 6.0))

    def r_m(d):
        return V(res, g["1a"][10][d]) / V(res, g["1a"][20][d])

    assert m["C002-2"]["far apart"].value == pytest.approx(r_m(6.0), rel=1e-9)
    assert m["C002-2"]["weakens"].value == pytest.approx(r_m(6.0) / r_m(1.0), rel=1e-9)
    assert m["C002-2"]["weakens"].value != pytest.approx(r_m(6.0) / r_m(2.0), rel=1e-3)


@pytest.mark.parametrize("T4", [10, 20])
def test_c14_ula_work_is_its_steps_times_the_frames_over_the_marks_steps(T4):
    """The ULA iterates over all T frames at once (a step costs T frame passes); the marks' step counts are already
    summed over the frames: work ratio = mean(steps_ULA x T) / mean(marks' steps), the closest and farthest pooled."""
    m, g, res = measure({**DEFAULT, "T of Figs 4, 6, 7": T4}, {"C002-14"})
    near, far = res[g["7"][min(D)]], res[g["7"][max(D)]]
    ula = np.concatenate([near["plain_iter"], far["plain_iter"]]) * T4
    marks = np.concatenate([near["em_plain_iter"], far["em_plain_iter"]])
    assert m["C002-14"].value == pytest.approx(ula.mean() / marks.mean(), rel=1e-12)


# -- C002-15: the bound, the statistic, the epoch -----------------------------------------------------------------


@pytest.mark.parametrize(
    "bound, pos, vel", [("CRB", "crb_pos", "crb_vel"), ("van Trees (designation prior)", "bcrb_pos", "bcrb_vel")]
)
@pytest.mark.parametrize("statistic", ["variance", "MSE"])
def test_c15_is_the_ulas_spread_of_the_initial_positions_and_velocities_over_the_bound_named(
    bound, pos, vel, statistic
):
    """The paper's "practically potential accuracy": the ULA's summed variance (or mean square) of the first frame's
    positions over the position bound at the very close (1 sigma), 2 and 4 sigma points, and of the velocities over
    the velocity bound, whatever epoch the gains read; the van Trees bound where the designation prior is named."""
    config = {**DEFAULT, "bound": bound, "statistic": statistic, "epoch": "last"}
    res = Scenes(bias=0.4)  # biased errors: the mean square exceeds the variance
    m, g, _ = measure(config, {"C002-15"}, res)
    spread = var_sum if statistic == "variance" else (lambda p: float((p**2).mean(axis=0).sum()))
    c15 = m["C002-15"]
    for d, part in ((1.0, "very close"), (2.0, "d = 2 sigma"), (4.0, "d = 4 sigma")):
        r = res[g["c15"][d]]
        assert c15[part].value == pytest.approx(spread(positions(r["ula"], "first", 10)) / r[pos], rel=1e-9)
    r = res[g["c15"][1.0]]
    assert c15["velocities, very close"].value == pytest.approx(spread(positions(r["ula"], "velocity", 10)) / r[vel])
    if statistic == "MSE":
        assert c15["very close"].value > var_sum(positions(r["ula"], "first", 10)) / r[pos] * 1.05


# -- pairing and the bootstrap streams ----------------------------------------------------------------------------


def _width(e) -> float:
    return (e.ci_high - e.ci_low) / abs(e.value)


def test_ratios_between_independent_configurations_are_resampled_apart_and_same_scene_ratios_in_pairs():
    """With one error sample shared by every point, a ratio resampled in pairs is the same in every resample (no
    width), one resampled apart scatters: C002-2's photon ratio, C002-5's pixel ratio at each T and C002-8's ULA at
    5 over 1 sigma compare different configurations (apart); C002-8's ULA over the marks the same scenes (pairs)."""
    m, _, _ = measure(claims={"C002-2", "C002-5", "C002-8"}, res=Scenes(shared=True))
    apart = [m["C002-2"]["far apart"], *m["C002-5"], m["C002-8"]["worse than fine pixels"]]
    assert min(_width(e) for e in apart) > 0.1
    assert _width(m["C002-8"]["better than the marks"]) < 1e-9


def _intervals(m) -> list:
    out = []
    for v in m.values():
        for e in v.values() if isinstance(v, dict) else v if isinstance(v, list) else [v]:
            for x in e if isinstance(e, list) else [e]:
                out.append((x.value, x.ci_low, x.ci_high))
    return out


BOOTSTRAPPED = ["C002-2", "C002-3", "C002-4", "C002-5", "C002-6", "C002-10"]


def test_each_claims_interval_is_drawn_from_its_own_seeded_stream():
    """Measured twice at one seed, alone or with the others, a claim's interval is the same; at another seed every
    part's interval moves, C002-10's geometric means and C002-6's contrast included (a part resampled from a fixed
    generator of its own would keep its interval whatever the seed; the data have spread, so the intervals have
    width)."""
    res = Scenes()
    together, _, _ = measure(claims=set(BOOTSTRAPPED), res=res)
    again, _, _ = measure(claims=set(BOOTSTRAPPED), res=res)
    assert _intervals(together) == _intervals(again)
    for cid in BOOTSTRAPPED:
        alone, _, _ = measure(claims={cid}, res=res)
        assert _intervals(alone) == _intervals({cid: together[cid]}), cid
    other, _, _ = measure(claims=set(BOOTSTRAPPED), res=res, seed=4)
    for a, b in zip(_intervals(together), _intervals(other), strict=True):
        assert a[0] == b[0] and (a[1], a[2]) != (b[1], b[2])  # the same value, another interval
    assert min(x[2] - x[1] for x in _intervals(together)) > 0


def _log_gain_stat(k):
    """exp(mean log rho over the first k groups - over the rest): rho a group's [num | den] variance-sum ratio."""

    def mlog(groups):
        vs = []
        for a in groups:
            h = a.shape[-1] // 2
            num = a[..., :h].var(axis=-2, ddof=1).sum(axis=-1)
            vs.append(np.log(num / a[..., h:].var(axis=-2, ddof=1).sum(axis=-1)))
        return np.mean(vs, axis=0)

    return lambda *g: mlog(g[:k]) - mlog(g[k:])


def test_c4_interval_is_the_log_gain_bootstrap_of_its_own_stream():
    """C002-4: the growth Sigma^2(d = 1) / Sigma^2(d = 6) at Delta 5 over that at Delta 3 sigma (Fig 1c), its interval
    the percentile bootstrap of the log ratio drawn from the stream ("bootstrap", "C002-4") of the seed, mapped back."""
    m, g, res = measure(claims={"C002-4"}, seed=7)
    pair = {p: np.hstack([positions(res[g["1c"][p][d]]["ula"], "first", 5) for d in (1.0, 6.0)]) for p in (5.0, 3.0)}
    rng = np.random.default_rng(seed_sequence(7, ("bootstrap", "C002-4")))
    ref = bootstrap_groups([pair[5.0], pair[3.0]], _log_gain_stat(1), rng, B)
    got = m["C002-4"]
    assert (got.value, got.ci_low, got.ci_high) == pytest.approx(
        (math.exp(ref.value), math.exp(ref.ci_low), math.exp(ref.ci_high)), rel=1e-9
    )


def test_a_mean_log_gain_uses_the_resamples_and_spread_asked():
    rng = np.random.default_rng(31)
    hi = [np.hstack([1.5 * rng.standard_normal((30, 2)), rng.standard_normal((30, 2))]) for _ in range(2)]
    lo = [np.hstack([rng.standard_normal((30, 2)), rng.standard_normal((30, 2))]) for _ in range(2)]
    got = cv.mean_log_gain(hi, lo, np.random.default_rng(5), 150)
    ref = bootstrap_groups(hi + lo, _log_gain_stat(2), np.random.default_rng(5), 150)
    assert (got.ci_low, got.ci_high) == pytest.approx((math.exp(ref.ci_low), math.exp(ref.ci_high)), rel=1e-9)
    mse = cv.mean_log_gain(hi, lo, np.random.default_rng(5), 150, spread="mse")

    def ms(a):
        return (a**2).mean(axis=0).sum()

    want = np.mean([np.log(ms(a[:, :2]) / ms(a[:, 2:])) for a in hi]) - np.mean(
        [np.log(ms(a[:, :2]) / ms(a[:, 2:])) for a in lo]
    )
    assert mse.value == pytest.approx(math.exp(want), rel=1e-9)


@pytest.mark.parametrize("gap", [False, True])
def test_the_frame_dependence_reads_both_halves_in_the_spread_asked(gap):
    """C002-6's dependence with the mean square as the spread: |ln(u / v)| (or |u - v|) of the fewer and the more
    frames' mean squares, both halves read in the same spread."""
    rng = np.random.default_rng(41)
    hi = [np.hstack([2.0 * rng.standard_normal((30, 2)) + 0.5, rng.standard_normal((30, 2)) - 0.3]) for _ in range(2)]
    lo = [np.hstack([rng.standard_normal((30, 2)) + 0.2, 1.1 * rng.standard_normal((30, 2))]) for _ in range(2)]

    def dep(a):
        u, v = (a[:, :2] ** 2).mean(axis=0).sum(), (a[:, 2:] ** 2).mean(axis=0).sum()
        return abs(u - v) if gap else abs(math.log(u / v))

    got = cv.frame_dependence(hi, lo, np.random.default_rng(2), 100, "mse", gap)
    assert got.value == pytest.approx(np.mean([dep(a) for a in hi]) - np.mean([dep(a) for a in lo]), rel=1e-9)


# -- C002-6's readings and a configuration without them -----------------------------------------------------------


def _c6_want(res, g, cols=slice(None), gap=False):
    """Fig 2 (Delta 1 sigma): the mean over d <= 2 sigma of the ULA's |ln Sigma^2(T 5) / Sigma^2(T 10)| (or the
    absolute gap) at 20 photons minus that at 10."""

    def s(c):
        return var_sum(positions(res[c]["ula"], "first", c.T)[:, cols])

    def dep(mk):
        vals = []
        for d in (0.5, 1.0, 2.0):
            u, v = s(g["2"][(5, mk)][d]), s(g["2"][(10, mk)][d])
            vals.append(abs(u - v) if gap else abs(math.log(u / v)))
        return np.mean(vals)

    return dep(20) - dep(10)


def test_c6_is_the_relative_frame_dependence_at_twenty_photons_minus_ten_over_both_coordinates():
    m, g, res = measure(claims={"C002-6"})
    assert m["C002-6"].value == pytest.approx(_c6_want(res, g), rel=1e-9)
    gap, _, _ = measure({**DEFAULT, "T dependence of C002-6": "absolute (variance gap)"}, {"C002-6"}, res)
    assert gap["C002-6"].value == pytest.approx(_c6_want(res, g, gap=True), rel=1e-9)
    across, _, _ = measure({**DEFAULT, "coordinate of C002-6": "across the separation"}, {"C002-6"}, res)
    assert across["C002-6"].value == pytest.approx(_c6_want(res, g, slice(0, None, 2)), rel=1e-9)


def test_a_configuration_without_the_later_readings_reads_the_papers():
    """A configuration stored before C002-6's coordinate and frame-dependence entries, or the gross-error entry,
    existed reads both coordinates, the relative dependence and the statistic as named: the default's values."""
    later = ("coordinate of C002-6", "T dependence of C002-6", "gross errors")
    old = {k: v for k, v in DEFAULT.items() if k not in later}
    res = Scenes()
    now, _, _ = measure(claims={"C002-6", "C002-1"}, res=res)
    before, _, _ = measure(old, {"C002-6", "C002-1"}, res)
    assert _intervals(before) == _intervals(now)
    assert cv.epoch_and_spread(old) == ("first", "variance")


@pytest.mark.parametrize(
    "entries, want",
    [
        ({"epoch": "mid", "statistic": "MSE", "gross errors": "kept"}, ("mid", "mse")),
        ({"epoch": "last", "statistic": "variance", "gross errors": "trimmed 10 %"}, ("last", "trimmed_variance")),
        ({"epoch": "velocity", "statistic": "MSE"}, ("velocity", "mse")),
    ],
)
def test_the_gains_read_the_epoch_and_spread_the_register_names(entries, want):
    assert cv.epoch_and_spread({**DEFAULT, **entries}) == want


def test_errors_read_the_first_frame_unless_told():
    """The paper's "initial position" is the first frame's (t = 0): without an epoch, errors are x and y there."""
    res = Scenes()
    c = _points(DEFAULT, SCALE)[0]["head"][1.0]
    np.testing.assert_array_equal(cv.errors(res[c], "ula"), res[c]["ula"][..., :2].reshape(N, -1))
    assert not np.allclose(cv.errors(res[c], "ula", "last"), cv.errors(res[c], "ula"))


# -- the points each claim reads ----------------------------------------------------------------------------------

READINGS = [
    {},
    {"ULA": "MAP (designation prior)"},
    {"velocity knowledge": "designated"},
    {"ULA": "MAP (designation prior)", "velocity knowledge": "designated"},
]


@pytest.mark.parametrize("reading", READINGS, ids=["default", "MAP", "designated", "MAP and designated"])
def test_c11_reads_exactly_the_points_it_declares(reading):
    """C002-11's headline points (T = 50, d = 1 and 3 sigma) and, under the MAP reading, the MAP-ULA's twins (the MAP
    reading wins over the known velocity), or under the known velocity alone, those of the ULA that knows it."""
    config = {**DEFAULT, **reading}
    m, g, res = measure(config, {"C002-11"})
    want = list(g["head"].values())
    if "ULA" in reading:
        want += list(g["head_map"].values())
    elif reading:
        want += list(g["head_known"].values())
    assert set(res.read) == set(want) and len(want) == len(set(want))
    assert cv.NEEDS["C002-11"](config, g, list(D)) == want


@pytest.mark.parametrize("cid", list(cv.NEEDS))
def test_each_claim_reads_exactly_the_points_it_declares(cid):
    m, g, res = measure(claims={cid})
    assert set(res.read) == set(cv.NEEDS[cid](DEFAULT, g, list(D))) and set(m) == {cid}


def test_a_subset_of_claims_runs_only_its_own_points_in_the_claims_order():
    """C002-2 reads Fig 1a's four points (10 and 20 photons, 6 and 1 sigma; Delta 3 sigma, 5 frames); with C002-4
    its points come first, then Fig 1c's at Delta 5 sigma (1 and 6 sigma; those at 3 sigma are Fig 1a's), none repeated."""
    g, _ = _points(DEFAULT, SCALE)
    two = cv.needed_points(DEFAULT, g, D, claims={"C002-2"})
    assert [(c.m, c.d, c.pix, c.T) for c in two] == [
        (10, 6.0, 3.0, 5),
        (10, 1.0, 3.0, 5),
        (20, 6.0, 3.0, 5),
        (20, 1.0, 3.0, 5),
    ]
    both = cv.needed_points(DEFAULT, g, D, claims={"C002-4", "C002-2"})
    assert both[:4] == two and [(c.m, c.pix, c.d) for c in both[4:]] == [(10, 5.0, 1.0), (10, 5.0, 6.0)]
    assert g["1c"][3.0][1.0] == g["1a"][10][1.0]  # Fig 1c at Delta 3 sigma is Fig 1a at 10 photons: read once
    assert len(cv.needed_points(DEFAULT, g, D)) == len(set(cv.needed_points(DEFAULT, g, D)))


# -- the coverage table's experiments -----------------------------------------------------------------------------


def test_the_coverage_of_a_statistic_counts_intervals_that_hold_the_truth_ends_included(monkeypatch):
    """:func:`gain_interval_coverage` draws experiment r's groups without correlation, resamples them from the
    generator seeded by (the table's seed, n, groups, r), and counts an interval holding the true value, an end
    equal to it included."""
    from tvtrack.estimate import Estimate
    from tvtrack.papers.p002_unified_location_em import gain_coverage as gc
    from tvtrack.papers.p002_unified_location_em import ratio_coverage as rc

    truth = gc.STATISTICS["log gain"]
    ends = [(truth, truth + 1.0), (truth - 1.0, truth), (truth + 0.5, truth + 1.0), (truth - 2.0, truth - 1.0)]
    draws, seen = [], []

    def draw(case, n, r, groups, correlation):
        draws.append((case, n, r, groups, correlation))
        return [r], [r]

    def interval(hi, lo, rng, n_bootstrap):
        seen.append((rng.random(), n_bootstrap))
        lo_, hi_ = ends[hi[0]]
        return Estimate(1.0, 0.1, lo_, hi_, 10, 0.95, "stub")

    monkeypatch.setattr(gc, "draw_groups", draw)
    monkeypatch.setattr(cv, "mean_log_gain", interval)
    share = cv.gain_interval_coverage("log gain", "case", 30, 2, experiments=4, n_bootstrap=77)
    assert share == 0.5
    assert draws == [("case", 30, r, 2, 0.0) for r in range(4)]
    assert seen == [(np.random.default_rng([rc.SEED, 30, 2, r]).random(), 77) for r in range(4)]
