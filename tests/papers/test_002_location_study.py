"""Tests for the Monte Carlo machinery of notebook 002 (tvtrack.papers.p002_unified_location_em.simulation)."""

from dataclasses import replace

import numpy as np
import pytest

from tvtrack.papers.p002_unified_location_em.simulation import Config, run_config, seed_sequence
from tvtrack.papers.p002_unified_location_em.sim_config import CANONICAL_SETTINGS
from tvtrack.papers.p002_unified_location_em.summaries import (
    bootstrap_groups,
    position_errors,
    variance_ratio_ci,
    variance_sum,
)

SETTINGS = replace(
    CANONICAL_SETTINGS,
    seed=7,
    designation_sd_sigma=0.3,
    tol_sigma=1e-5,
    max_iter=500,
    bic_max_iter=20,
    crb_phases=2,
    n_trials=24,
)


def _config(q, d, pix, m, T, algs, variant=()) -> Config:
    """A configuration at the test settings' designation errors and trial count."""
    st = SETTINGS
    return Config(
        q,
        d,
        pix,
        m,
        T,
        algs,
        st.designation_sd_sigma,
        None,
        None,
        st.n_trials,
        "main",
        st.designation_velocity_sd,
        tuple(sorted(dict(variant).items())),
    )


def test_variance_ratio_ci_matches_closed_form_and_covers_truth():
    rng = np.random.default_rng(0)
    a = rng.normal(0, 2.0, (4000, 2))  # summed variance 8
    b = rng.normal(0, 1.0, (4000, 2))  # summed variance 2
    r = variance_ratio_ci(a, b, np.random.default_rng(1), 300, paired=False)
    assert r.value == pytest.approx(a.var(0, ddof=1).sum() / b.var(0, ddof=1).sum())
    assert r.ci_low < 4.0 < r.ci_high and r.ci_high - r.ci_low < 0.6
    mse = variance_ratio_ci(a + 1.0, b, np.random.default_rng(1), 300, mse=True)
    assert mse.value == pytest.approx(((a + 1) ** 2).mean(0).sum() / (b**2).mean(0).sum())
    sd = variance_ratio_ci(a, b, np.random.default_rng(1), 300, sqrt=True)
    assert sd.value == pytest.approx(np.sqrt(r.value))
    # paired resampling of identical samples gives exactly 1 in every resample
    same = variance_ratio_ci(a, a, np.random.default_rng(2), 50)
    assert same.value == same.ci_low == same.ci_high == pytest.approx(1.0)
    # robust spreads: one gross error moves the variance ratio a lot, the trimmed and median ones little
    a_gross = a.copy()
    a_gross[0] = 200.0
    plain = variance_ratio_ci(a_gross, b, np.random.default_rng(1), 300, paired=False)
    trimmed = variance_ratio_ci(a_gross, b, np.random.default_rng(1), 300, paired=False, spread="trimmed_variance")
    median = variance_ratio_ci(a_gross, b, np.random.default_rng(1), 300, paired=False, spread="median_square")
    assert plain.value > 8.0
    assert 3.0 < trimmed.value < 5.0 and 3.0 < median.value < 5.0  # scale ratio 4 of two normal samples


def test_bootstrap_groups_resamples_groups_independently_and_rows_jointly():
    rng = np.random.default_rng(3)
    x = rng.normal(size=(500, 2))
    # a statistic of one group's paired columns: identical columns give exactly 0 in every resample
    d = bootstrap_groups(
        [np.hstack([x, x])], lambda g: (g[..., :2] - g[..., 2:]).mean(axis=(1, 2)), np.random.default_rng(4), 2000
    )
    assert d.value == d.ci_low == d.ci_high == 0.0 and d.n == 500
    # two independent groups: the difference of means has the standard error sqrt(1/n1 + 1/n2)
    y = rng.normal(size=(300, 1)) + 1.0
    diff = bootstrap_groups(
        [x[:, :1], y], lambda a, b: b.mean(axis=(1, 2)) - a.mean(axis=(1, 2)), np.random.default_rng(5), 2000
    )
    assert diff.stderr == pytest.approx(np.sqrt(1 / 500 + 1 / 300), rel=0.15)
    assert diff.ci_low < 1.0 < diff.ci_high


def test_seed_sequence_depends_on_values_only():
    a = seed_sequence(5, (2, 1.0, "u", None)).generate_state(2)
    np.testing.assert_array_equal(a, seed_sequence(5, (2, 1.0, "u", None)).generate_state(2))
    assert not np.array_equal(a, seed_sequence(5, (2, 1.0, "e", None)).generate_state(2))
    assert not np.array_equal(a, seed_sequence(6, (2, 1.0, "u", None)).generate_state(2))


def test_a_configuration_shares_its_scenes_between_algorithms_and_is_reproducible():
    c_u = _config(2, 3.0, 1.0, 20, 4, "u")
    c_ue = _config(2, 3.0, 1.0, 20, 4, "ue")
    assert c_ue.n == 24 and c_ue.dsd == 0.3
    r = run_config(SETTINGS, c_ue)
    assert r["ula"].shape == (24, 2, 4) and r["em"].shape == (24, 2, 4)
    assert np.unique(r["seed"]).tolist() == [7]  # one seed: replicates are whole runs
    # the ULA alone sees the scenes it sees beside the marks
    np.testing.assert_array_equal(run_config(SETTINGS, c_u)["ula"], r["ula"])
    # epochs: the mid-frame error is the first-frame error plus (T-1)/2 velocity errors
    mid = position_errors(r, "ula", "mid")
    np.testing.assert_allclose(mid, (r["ula"][..., :2] + 1.5 * r["ula"][..., 2:]).reshape(24, -1))
    assert position_errors(r, "ula", "velocity", r["seed"] == 7).shape == (24, 4)
    # the ULA on well-separated objects is near its CRB (loose: 24 trials)
    r_crb = run_config(SETTINGS, _config(2, 3.0, 1.0, 20, 4, "ur"))
    assert np.isfinite(r_crb["crb_pos"]) and r_crb["crb_pos"] > 0
    v = variance_sum(position_errors(r, "ula"))
    assert 0.3 < v.value / r_crb["crb_pos"] < 3.0


def test_settings_variant_redraws_the_default_scenes_and_applies_its_settings():
    default = run_config(SETTINGS, _config(2, 1.0, 3.0, 20, 6, "ue"))
    capped = run_config(SETTINGS, _config(2, 1.0, 3.0, 20, 6, "ue", {"max_iter": 1, "accelerate": "none"}))
    same = run_config(SETTINGS, _config(2, 1.0, 3.0, 20, 6, "ue", {"max_iter": SETTINGS.max_iter}))
    # common random numbers: the same truth, and a variant equal to the settings gives the same estimates
    np.testing.assert_array_equal(capped["truth"], default["truth"])
    np.testing.assert_array_equal(same["ula"], default["ula"])
    # the cap applies: one plain EM step per ULA fit (and per frame for the marks), so the estimates differ
    assert capped["ula_iter"].max() == 1 and default["ula_iter"].max() > 1
    assert capped["em_iter"].max() <= 6
    assert not np.array_equal(capped["ula"], default["ula"])
