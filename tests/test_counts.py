"""Exact rates of rare events (:mod:`tvtrack.counts`) against closed forms computed here, independently.

Clopper-Pearson ends are the beta quantiles ``B(alpha/2; k, n-k+1)`` and ``B(1-alpha/2; k+1, n-k)``
(scipy.stats.beta, not the binomial test the module calls); the bound zero events certify is
``1 - alpha^(1/n)`` (about 3/n at 95 %, the rule of three); the words are compared whole.
"""

import math

import pytest
from scipy import stats

from tvtrack.counts import events_statement, mark_extrapolated, proportion_ci, rate_from_counts, zero_events_bound
from tvtrack.estimate import Estimate


def _cp(k, n, confidence=0.95):
    """Clopper-Pearson's ends from the beta quantiles."""
    a = 1 - confidence
    low = 0.0 if k == 0 else stats.beta.ppf(a / 2, k, n - k + 1)
    high = 1.0 if k == n else stats.beta.ppf(1 - a / 2, k + 1, n - k)
    return low, high


def _bound(n, confidence=0.95):
    return 1 - (1 - confidence) ** (1 / n)


# --------------------------------------------------------------------------- proportion_ci


@pytest.mark.parametrize("k, n, confidence", [(3, 40, 0.95), (1, 1, 0.95), (0, 1, 0.95), (7, 10, 0.8), (12, 60, 0.5)])
def test_proportion_ci_is_the_beta_quantile_interval_with_its_fields(k, n, confidence):
    e = proportion_ci(k, n, confidence)
    low, high = _cp(k, n, confidence)
    p = k / n
    assert e.value == p
    assert e.ci_low == pytest.approx(low, abs=1e-10) and e.ci_high == pytest.approx(high, abs=1e-10)
    assert e.stderr == pytest.approx(math.sqrt(p * (1 - p) / n), rel=1e-12, abs=0.0)
    assert (e.n, e.confidence, e.method, e.extrapolated) == (n, confidence, "Clopper-Pearson", False)


def test_proportion_ci_stderr_is_the_binomial_one():
    # 12 of 60: sqrt(0.2 * 0.8 / 60) = 0.05163977794943222
    assert proportion_ci(12, 60).stderr == pytest.approx(0.05163977794943222, rel=1e-12)
    assert proportion_ci(1, 1).stderr == 0.0 and proportion_ci(0, 5).stderr == 0.0


def test_proportion_ci_of_one_run_and_no_run():
    one = proportion_ci(1, 1)  # k = n = 1: [(alpha/2)^(1/n), 1] = [0.025, 1]
    assert (one.value, one.ci_high, one.n) == (1.0, 1.0, 1) and one.ci_low == pytest.approx(0.025, rel=1e-9)
    none = proportion_ci(0, 1)  # k = 0 of 1: [0, 1 - (alpha/2)^(1/n)] = [0, 0.975]
    assert (none.value, none.ci_low) == (0.0, 0.0) and none.ci_high == pytest.approx(0.975, rel=1e-9)
    for n in (0, -3):
        with pytest.raises(ValueError, match=f"proportion_ci needs n >= 1, got n={n}"):
            proportion_ci(0, n)


# --------------------------------------------------------------------------- zero_events_bound


@pytest.mark.parametrize("n, confidence", [(1, 0.95), (2, 0.95), (300, 0.95), (30, 0.9), (30, 0.99)])
def test_zero_events_bound_is_one_minus_alpha_to_the_one_over_n(n, confidence):
    assert zero_events_bound(n, confidence) == pytest.approx(1 - (1 - confidence) ** (1 / n), rel=1e-12)


def test_zero_events_bound_limits():
    assert zero_events_bound(1) == pytest.approx(0.95, rel=1e-12)  # one run certifies little
    assert zero_events_bound(1000) == pytest.approx(-math.log(0.05) / 1000, rel=2e-3)  # the rule of three
    assert 2.99 / 1000 < zero_events_bound(1000) < 3.0 / 1000
    assert stats.binom.pmf(0, 300, zero_events_bound(300)) == pytest.approx(0.05, rel=1e-9)  # what "certify" means
    for n in (0, -1):
        with pytest.raises(ValueError, match=f"zero_events_bound needs n >= 1, got n={n}"):
            zero_events_bound(n)


# --------------------------------------------------------------------------- rate_from_counts


@pytest.mark.parametrize("k, n, confidence", [(1, 48, 0.95), (3, 40, 0.9), (48, 48, 0.95)])
def test_rate_from_counts_with_events_is_clopper_pearson_at_its_confidence(k, n, confidence):
    e = rate_from_counts(k, n, confidence)
    low, high = _cp(k, n, confidence)
    assert e.value == k / n and e.n == n and e.confidence == confidence and e.method == "Clopper-Pearson"
    assert e.ci_low == pytest.approx(low, abs=1e-10) and e.ci_high == pytest.approx(high, abs=1e-10)


def test_rate_from_counts_at_its_default_confidence():
    e = rate_from_counts(3, 40)
    assert (e.ci_low, e.ci_high) == pytest.approx(_cp(3, 40, 0.95), abs=1e-10) and e.confidence == 0.95


@pytest.mark.parametrize("n, confidence", [(48, 0.95), (20, 0.9), (1, 0.5)])
def test_rate_from_counts_without_events_is_the_one_sided_bound(n, confidence):
    e = rate_from_counts(0, n, confidence)
    b = _bound(n, confidence)
    assert (e.value, e.ci_low, e.n, e.confidence, e.extrapolated) == (0.0, 0.0, n, confidence, False)
    assert e.ci_high == pytest.approx(b, rel=1e-12)
    assert isinstance(e.stderr, float) and math.isnan(e.stderr)
    assert e.method == f"count: 0 of {n} runs, rate < {b:.3g} (one-sided bound 1 - (1 - confidence)^(1/n))"


def test_rate_from_counts_of_zero_in_48_reads_below_0_0605():
    assert (
        rate_from_counts(0, 48).method
        == "count: 0 of 48 runs, rate < 0.0605 (one-sided bound 1 - (1 - confidence)^(1/n))"
    )


# --------------------------------------------------------------------------- mark_extrapolated


def _fit(value, method="logistic fit"):
    return Estimate(value, 0.01, value / 2, value * 2, 48, 0.95, method)


def test_a_fit_the_counts_resolve_is_returned_untouched():
    fit = _fit(0.3)
    assert mark_extrapolated(fit, 14, 48) is fit  # default confidence: bound 0.0605 < 0.3
    assert mark_extrapolated(fit, 1, 48, 0.95) is fit  # one event is enough when the value is above the bound
    # exactly at the bound zero events would certify: resolved (>=)
    at = _fit(1 - (1 - 0.95) ** (1 / 48))
    assert at.value == zero_events_bound(48)
    assert mark_extrapolated(at, 2, 48) is at


def test_a_fit_below_the_bound_at_its_own_confidence_is_extrapolated():
    # at 50 % the bound of 48 runs is 1 - 0.5^(1/48) = 0.0143; at 95 % it would be 0.0605
    fit = _fit(0.03)
    assert mark_extrapolated(fit, 1, 48, 0.5) is fit
    low = mark_extrapolated(fit, 1, 48, 0.95)
    assert low.extrapolated is True and low.value == 0.03
    b50 = _bound(48, 0.5)
    below = mark_extrapolated(_fit(0.01), 1, 48, 0.5)
    lo, hi = _cp(1, 48, 0.5)
    assert b50 == pytest.approx(0.014337, abs=1e-6)
    assert below.method == (
        f"logistic fit; extrapolated: 1 of 48 runs: rate {1 / 48:.3g} [{lo:.3g}, {hi:.3g}] (50% Clopper-Pearson)"
    )


def test_zero_events_always_extrapolate_a_fit_however_large():
    fit = _fit(0.3)
    out = mark_extrapolated(fit, 0, 48)
    assert out is not fit and out.extrapolated is True
    assert (out.value, out.stderr, out.ci_low, out.ci_high, out.n, out.confidence) == (0.3, 0.01, 0.15, 0.6, 48, 0.95)
    assert out.method == "logistic fit; extrapolated: 0 of 48 runs: rate < 0.0605 (95% one-sided)"
    assert fit.extrapolated is False and fit.method == "logistic fit"  # the fit itself is not changed


def test_extrapolated_words_without_a_fitted_method_and_with_one_that_starts_oddly():
    assert (
        mark_extrapolated(_fit(1e-9, ""), 0, 48).method == "extrapolated: 0 of 48 runs: rate < 0.0605 (95% one-sided)"
    )
    # the fitted method's own leading characters are kept: only the separator of an empty method goes
    out = mark_extrapolated(_fit(1e-9, "Xu's logistic tail"), 0, 20, 0.9)
    assert out.method == f"Xu's logistic tail; extrapolated: 0 of 20 runs: rate < {_bound(20, 0.9):.3g} (90% one-sided)"


# --------------------------------------------------------------------------- events_statement


def test_events_statement_of_zero_events_is_the_bound_in_words():
    assert events_statement(0, 60) == "0 of 60 runs: rate < 0.0487 (95% one-sided)"
    assert events_statement(0, 1000, 0.99) == f"0 of 1000 runs: rate < {_bound(1000, 0.99):.3g} (99% one-sided)"
    assert events_statement(0, 1000, 0.99) == "0 of 1000 runs: rate < 0.00459 (99% one-sided)"


@pytest.mark.parametrize("k, n, confidence", [(1, 60, 0.95), (3, 60, 0.95), (9, 20, 0.8)])
def test_events_statement_with_events_is_the_rate_and_its_interval(k, n, confidence):
    lo, hi = _cp(k, n, confidence)
    pct = f"{confidence:.0%}"
    assert (
        events_statement(k, n, confidence)
        == f"{k} of {n} runs: rate {k / n:.3g} [{lo:.3g}, {hi:.3g}] ({pct} Clopper-Pearson)"
    )


def test_events_statement_at_the_default_confidence():
    lo, hi = _cp(3, 60)
    assert (round(lo, 5), round(hi, 4)) == (0.01043, 0.1392)
    assert events_statement(3, 60) == "3 of 60 runs: rate 0.05 [0.0104, 0.139] (95% Clopper-Pearson)"
    assert (
        events_statement(1, 60)
        == f"1 of 60 runs: rate 0.0167 [{_cp(1, 60)[0]:.3g}, {_cp(1, 60)[1]:.3g}] (95% Clopper-Pearson)"
    )
