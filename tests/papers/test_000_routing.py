"""Paper 000: the cost helpers that feed C000-4 (variant 1 needs more computation than variant 2).

The default reading counts the arithmetic of one filter step: each variant's straight-line step runs on
:class:`cost.Counted` numbers, which tally every multiplication, addition (subtractions included), division and
function evaluation they take part in, and the claim's value is variant 1's arithmetic over variant 2's. Here the
counting numbers are checked operation by operation against plain arithmetic, the counts against the hand-derived
ones at another operating point (straight-line code: the counts cannot depend on it), and the CPU-time reading's
routing (the operating point psi_A = 20, P = 0.5, the draws of the seed, one trial or a batch, the compiled steps
with the register's initial estimate and variances, eq. (9)'s re-evaluations) against fakes of the timed steps.
"""

from __future__ import annotations

import math
from collections import Counter

import numpy as np
import pytest

from tvtrack.papers.p000_dissector_ekf import cost, study
from tvtrack.papers.p000_dissector_ekf.model import GaussMarkovMessage, scan_at_snr

C = cost.Counted


def test_counted_numbers_do_the_arithmetic_and_tally_each_operation_once():
    t = Counter()
    a, b = C(6.0, t), C(1.5, t)
    got = [a + b, a + 2, 2 + a, a - b, a - 2, 10 - a, a * b, a * 2, 2 * a, a / b, a / 4, 3 / b]
    assert [g.v for g in got] == [7.5, 8.0, 8.0, 4.5, 4.0, 4.0, 9.0, 12.0, 12.0, 4.0, 1.5, 2.0]
    assert all(type(g) is C and g.tally is t for g in got)
    assert t == Counter(add=6, mul=3, div=3)
    assert float(a) == 6.0 and type(float(C(2, t))) is float and C(2, t).v == 2.0 and type(C(2, t).v) is float
    assert 1.0 + 2.0 == 3.0 and t == Counter(add=6, mul=3, div=3)  # plain numbers are not counted
    e, r = cost._exp(C(0.5, t)), cost._sqrt(C(2.25, t))
    assert (e.v, r.v) == (pytest.approx(math.exp(0.5)), 1.5) and (t["exp"], t["sqrt"]) == (1, 1)
    np.testing.assert_allclose(cost._exp(np.array([0.0, 1.0])), [1.0, math.e])  # arrays of trials: NumPy's
    assert cost._sqrt(4.0) == 2.0 and (t["exp"], t["sqrt"]) == (1, 1)


def test_the_operation_counts_are_those_of_one_step_at_any_operating_point(monkeypatch):
    one, two, again = cost.operation_counts(1), cost.operation_counts(2), cost.operation_counts(2, 1)
    assert (one["arithmetic"], two["arithmetic"], again["arithmetic"]) == (43, 20, 31)
    assert all(c["arithmetic"] == c["mul"] + c["add"] + c["div"] for c in (one, two, again))
    assert list(one) == ["mul", "add", "div", "exp", "sqrt", "arithmetic"]
    assert cost.operation_counts(2, 2)["exp"] == 3  # each re-evaluation of eq. (9) one more exponential
    assert cost.operation_ratio() == 43 / 20 and cost.operation_ratio(1) == 43 / 31
    with pytest.raises(ValueError, match="parameter 'variant' = 3; it must be 1 or 2"):
        cost.operation_counts(3)
    seen = []
    monkeypatch.setattr(cost, "variant1_step", lambda *a: seen.append(("v1", a)))
    monkeypatch.setattr(cost, "variant2_step", lambda *a: seen.append(("v2", a)))
    assert cost.operation_counts(1)["arithmetic"] == 0 and cost.operation_counts(2, 4)["exp"] == 0
    (v1, (scan, msg, x, d, y, k)), (v2, (scan2, msg2, x2, d2, y2, k2, its)) = seen
    assert scan == scan2 == scan_at_snr(20.0, 0.5, 0.05) and msg == msg2 == GaussMarkovMessage(0.1, 0.15)
    assert [type(v) for v in (*x, *d, y, x2, d2, y2)] == [C] * 9 and (k, k2, its) == (10, 10, 4)
    assert len({id(v.tally) for v in (*x, *d, y)}) == 1  # one tally for the whole step


@pytest.fixture
def timed(monkeypatch):
    """The compiled steps, their samples and the paired timing replaced by recorders."""
    seen = {}
    monkeypatch.setattr(study.jit, "enabled", lambda: True)
    monkeypatch.setattr(study, "scan_at_snr", lambda *a: seen.setdefault("scan", a) and "scan")
    monkeypatch.setattr(
        study, "draw_noises", lambda rng, n, k, m: seen.setdefault("draws", (rng.random(), n, k, m)) and {"xi": "xi"}
    )
    monkeypatch.setattr(
        study,
        "truth_and_pulse",
        lambda scan, msg, noises: seen.setdefault("pulse", (scan, msg, noises)) and ("x", "pulse"),
    )
    monkeypatch.setattr(
        study, "samples_from_pulse", lambda scan, pulse, xi: seen.setdefault("y", (scan, pulse, xi)) and "y"
    )
    monkeypatch.setattr(study, "run_steps_variant1", lambda *a, **k: seen.setdefault("v1", (a, k)) and 1)
    monkeypatch.setattr(study, "run_steps_variant2", lambda *a, **k: seen.setdefault("v2", (a, k)) and 2)

    def paired(v1, v2, y, repeats):
        seen["timed"] = (v1("y1"), v2("y2"), y, repeats)
        return "ratio"

    monkeypatch.setattr(study, "paired_time_ratio", paired)
    return seen


@pytest.mark.parametrize("one_trial, shape", [(False, (30, 40)), (True, (1, 1200))])
def test_the_cpu_reading_times_both_compiled_steps_on_the_same_samples(timed, one_trial, shape):
    assert study.cost_ratio(30, 40, 9, repeats=5, noise_iterations=2, one_trial=one_trial) == "ratio"
    assert timed["scan"] == (20.0, 0.5, 0.05, study.PULSE_DURATION) and study.PULSE_DURATION == 0.5
    assert timed["draws"] == (np.random.default_rng(9).random(), *shape, 1)
    assert timed["pulse"] == ("scan", study.MESSAGE, {"xi": "xi"}) and timed["y"] == ("scan", "pulse", "xi")
    assert timed["timed"] == (1, 2, "y", 5)
    assert timed["v1"] == (("scan", study.MESSAGE, "y1", (0.2, 1.0), None, 15.0), {"compiled": True})
    assert timed["v2"] == (("scan", study.MESSAGE, "y2", 0.2, None, None, 2), {"compiled": True})
    assert (study.D11_0, study.D22_0, study.BETA_0) == (0.2, 1.0, 15.0)


def test_the_cpu_reading_repeats_eleven_paired_timings_by_default_and_no_re_evaluation(timed):
    study.cost_ratio(3, 4, 1)
    assert timed["timed"][3] == 11 and timed["v2"][0][-1] == 0 and timed["draws"][1:] == (3, 4, 1)


def test_without_compiled_steps_the_cpu_reading_is_nan_with_its_reason(monkeypatch):
    monkeypatch.setattr(study.jit, "enabled", lambda: False)
    e = study.cost_ratio(3, 4, 1)
    assert all(math.isnan(v) for v in (e.value, e.stderr, e.ci_low, e.ci_high)) and (e.n, e.confidence) == (0, 0.95)
    assert e.method == "none (no compiled steps: the interpreter would be timed)"
