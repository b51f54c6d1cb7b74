"""Every reading a claim of paper 002 declares can change that claim's value, and each reading's band follows its
statistic.

A reading (kinds reading, statistic, comparator) that a claim's measurement never uses is not a reading of that
claim: the explorer would count its conditions as agreeing configurations that could not have disagreed. The test
over the register measures every claim at the default and at each other value of each reading it declares (small
sizes, one seed, the same scenes), and asks that some part's point value moves. It caught the "MSE" and "SD ratio"
statistics in the log-gain claims (C002-2's "weakens", C002-3, C002-4, C002-6, C002-10's pixel and frame gains),
which read variances whatever the statistic, and the "SD ratio" of C002-1, whose spreads are variance sums.
"""

import math

import numpy as np
import pytest

from tvtrack.papers.p002_unified_location_em import claim_values, study
from tvtrack.papers.p002_unified_location_em.claims import RULES
from tvtrack.papers.p002_unified_location_em.register import DEPENDS, REGISTER
from tvtrack.verdicts import synthetic

SMALL = study.Scale(
    n_trials=8,
    n_iter_trials=4,
    separations=(1.0, 2.0, 3.0, 4.0, 6.0, 8.0),
    fig3_frames=(5, 10, 50),
    crb_phases=2,
    n_bootstrap=20,
    max_iter=40,
)
DEFAULT = REGISTER.default()
SEED = 5


def _values(measured) -> list[float]:
    """Every point value of a claim's measurement (an Estimate, a list of them, a dict of parts)."""
    if isinstance(measured, dict):
        return [v for k in sorted(measured) for v in _values(measured[k])]
    if isinstance(measured, list):
        return [v for m in measured for v in _values(m)]
    return [float(getattr(measured, "value", measured))]


_LINES = "designation start + line association"
#: Values of a declared reading that cannot move one claim, and why (``DEPENDS`` is per entry: the entry's other
#: values act). The test checks that each is indeed inert, so the list stays true; the explorer counts these
#: conditions as agreeing configurations that could not have disagreed.
INERT = {
    ("C002-7", "two-stage", _LINES): "one object: nothing to associate, the lines label the marks as their starts do",
    ("C002-8", "two-stage", _LINES): "one object: nothing to associate",
    ("C002-9", "two-stage", _LINES): "one object: nothing to associate",
    ("C002-12", "two-stage", _LINES): "objects 8 sigma apart: the lines label the marks as their starts do",
    ("C002-14", "two-stage", _LINES): "the association costs no EM iteration: the marks' counts are the same",
}


def _readings():
    for cid, names in DEPENDS.items():
        for name in names:
            entry = REGISTER[name]
            if entry.side == "reading":
                for value in entry.alternatives:
                    yield pytest.param(cid, name, value, id=f"{cid}:{name}={value}")


def _moves(cid, name, value) -> tuple[bool, list]:
    base = _values(study.measure(DEFAULT, SEED, SMALL, claims=frozenset({cid}))[cid])
    moved = _values(study.measure({**DEFAULT, name: value}, SEED, SMALL, claims=frozenset({cid}))[cid])
    return len(base) != len(moved) or not np.allclose(base, moved, rtol=1e-12, atol=0.0), base


@pytest.mark.parametrize("cid,name,value", list(_readings()))
def test_every_declared_reading_moves_its_claims_value(cid, name, value):
    moves, base = _moves(cid, name, value)
    if (cid, name, value) in INERT:
        assert not moves, f"{cid} moves under {name} = {value!r}: drop it from INERT"
    else:
        assert moves, f"{cid} declares {name!r} but its value is the same under {value!r}: {base}"


def test_every_declared_reading_has_a_value_that_acts():
    for cid, names in DEPENDS.items():
        for name in names:
            entry = REGISTER[name]
            if entry.side == "reading":
                assert any((cid, name, v) not in INERT for v in entry.alternatives), (cid, name)


def test_the_ratio_of_standard_deviations_is_a_reading_of_c002_11_alone():
    entry = REGISTER["accuracy ratio of C002-11"]
    assert entry.kind == "statistic" and entry.values == ("variance", "SD")
    assert [c for c, names in DEPENDS.items() if entry.name in names] == ["C002-11"]
    assert "SD ratio" not in REGISTER["statistic"].values
    # under the SD reading C002-11 is the square root of its variance reading, on the same scenes and resamples
    var = study.measure(DEFAULT, SEED, SMALL, claims=frozenset({"C002-11"}))["C002-11"]
    sd = study.measure({**DEFAULT, entry.name: "SD"}, SEED, SMALL, claims=frozenset({"C002-11"}))["C002-11"]
    for part, est in var.items():
        assert sd[part].value == pytest.approx(math.sqrt(est.value), rel=1e-12)
        assert sd[part].ci_high == pytest.approx(math.sqrt(est.ci_high), rel=1e-12)
    # the paper's x4 read as an SD ratio is judged by the same band [3, 6]: a value of 4 reproduces either way
    assert RULES["C002-11"].judge(synthetic(RULES["C002-11"], "reproduced")).verdict == "reproduced"


def test_mse_reaches_the_log_gains():
    """Under "MSE" C002-2's "weakens" is the ratio of MSE photon gains: squared bias counts (a value the variance
    reading cannot give: with every error shifted by one sigma the variance gains stay and the MSE gains move)."""
    rng = np.random.default_rng(0)
    far = [rng.normal(size=(40, 4)), rng.normal(size=(40, 4))]
    near = [rng.normal(size=(40, 4)), rng.normal(size=(40, 4))]
    shifted = [near[0] + 1.0, near[1]]
    args = (np.random.default_rng(1), 200)

    def weakens(n, spread):
        return claim_values.mean_log_gain([np.hstack(far)], [np.hstack(n)], *args, spread=spread).value

    assert weakens(shifted, "variance") == pytest.approx(weakens(near, "variance"), rel=1e-12)
    v_far = [(x**2).mean(0).sum() for x in far]
    v_near = [(x**2).mean(0).sum() for x in shifted]
    assert weakens(shifted, "mse") == pytest.approx((v_far[0] / v_far[1]) / (v_near[0] / v_near[1]), rel=1e-12)
