"""The adversarial reading of eq. (6) as printed: variant 1's signal-noise term sqrt(A S) X2 (c_s = A) instead of
this project's default sqrt(c_s S) X2 with c_s = N0 P / (1 - P), which makes (6) agree with eq. (2) (register entry
"signal-noise scale")."""

import numpy as np
import pytest

from tvtrack.montecarlo import ratio_ci
from tvtrack.papers.p000_dissector_ekf import study
from tvtrack.papers.p000_dissector_ekf.claims import claim_rules
from tvtrack.papers.p000_dissector_ekf.cost import run_steps_variant1
from tvtrack.papers.p000_dissector_ekf.ekf import run_variant1, variant1_filter
from tvtrack.papers.p000_dissector_ekf.register import DEPENDS, REGISTER

SIZES = study.Sizes(
    n_trials=120, duration_T=16.0, window_T=6.0, substeps=3, contrast_grid=(0.0, 0.5, 0.9), psi_grid=(5.0, 20.0)
)
DEFAULT = REGISTER.default()
LITERAL = {**DEFAULT, "signal-noise scale": study.CS_LITERAL}


def test_the_entry_is_an_adversarial_reading_read_by_every_claim_that_runs_variant_1():
    entry = REGISTER["signal-noise scale"]
    assert entry.side == "reading" and entry.origin == "adversarial" and entry.default == study.CS_CONSISTENT
    readers = {c for c, names in DEPENDS.items() if "signal-noise scale" in names}
    assert readers == {"C000-1", "C000-2", "C000-3", "C000-6", "C000-8", "C000-9"}


@pytest.mark.parametrize("compiled", [False, True])
def test_the_literal_scale_is_the_core_filter_with_c_s_equal_to_a(compiled):
    """The straight-line steps under c_s = A give the core EKF's estimates (ekf.variant1_filter, 'literal')."""
    from tvtrack import jit

    if compiled and not jit.available():
        pytest.skip("numba is not installed")
    cfg = DEFAULT
    x, pulse, xi, _ = study.truth_paths(cfg, 2, SIZES)
    scan = study.operating_scan(cfg, 20.0, 0.5, SIZES)
    y = study.photon_samples(cfg, 2, scan, pulse, xi)[:20]
    want, want_d = run_variant1(variant1_filter(scan, study.MESSAGE, signal_noise_scale="literal"), y)
    got, got_d = run_steps_variant1(scan, study.MESSAGE, y, compiled=compiled, signal_noise_scale="literal")
    np.testing.assert_allclose(got, want, rtol=1e-7, atol=1e-10)
    np.testing.assert_allclose(got_d, want_d, rtol=1e-7, atol=1e-12)


def test_under_the_literal_scale_variant_1_is_several_times_worse_and_c000_3_fails():
    """Measured (200 runs, psi_A = 20): variant 1 / variant 2 = 9.4, 7.7, 4.4 at P = 0, 0.5, 0.9; variant 1's RMS
    error 6 % of T. Planting 'the entry is ignored' (variant 1 at c_s = N0 P/(1-P) under both) fails here."""
    lit = study.steady_runs(LITERAL, 2, SIZES, 20.0, 0.5, "v1")
    v2 = study.steady_runs(LITERAL, 2, SIZES, 20.0, 0.5, "v2")
    assert np.array_equal(v2, study.steady_runs(DEFAULT, 2, SIZES, 20.0, 0.5, "v2"))  # variant 2 untouched
    assert ratio_ci(lit, v2).ci_low > 3.0
    rule = claim_rules(SIZES)["C000-3"]
    assert rule.judge(study._c3(LITERAL, 2, SIZES)).verdict == "not reproduced"
    assert rule.judge(study._c3(DEFAULT, 2, SIZES)).verdict != "not reproduced"  # partly at this size


def test_under_the_literal_scale_c000_3_judges_p_0_where_the_variants_are_two_filters():
    """Eq. (6) as printed gives variant 1 the signal-noise term sqrt(A S) X2 whatever the contrast; at P = 0 the data
    (eq. (2): N0 P/(1-P) S = 0) hold no signal noise, yet variant 1 still models one, so the two variants are two
    filters and «примерно одинаковую оценку потенциальной точности» is a comparison there too. Only with c_s = N0
    P/(1-P), where the term vanishes at P = 0, is the ratio 1 by construction (not checkable). At the register's
    contrast 0 (Fig. 2 read at P = 0) the literal scale measures the Fig. 2 parts as well."""
    from tvtrack import verdicts as vd

    rule = claim_rules(SIZES)["C000-3"]
    for contrast in (0.0, 0.5):
        literal = vd.for_config(rule, {**LITERAL, "contrast": contrast})
        assert isinstance(literal.parts["P=0"], vd.InBand)
        assert (literal.parts["P=0"].low, literal.parts["P=0"].high) == (0.8, 1.25)
        assert "psi_A=5" in literal.parts
        consistent = vd.for_config(rule, {**DEFAULT, "contrast": contrast})
        assert isinstance(consistent.parts["P=0"], vd.NotCheckable)
        assert ("psi_A=5" in consistent.parts) == (contrast != 0.0)
    got = study._c3({**LITERAL, "contrast": 0.0}, 2, SIZES)
    assert got["reading"] == 0.0 and got["measured"]["reading"] == study.CS_LITERAL
    parts = got["measured"]["measured"]
    assert set(parts) == {"P=0", "P=0.5", "P=0.9", "psi_A=5"}
    assert parts["P=0"].ci_low > 1.25  # variant 1 models a signal noise the data lack: worse, not 1 by construction
    assert rule.judge(got).why.count("(P=0) not reproduced") == 1
    same = study._c3({**DEFAULT, "contrast": 0.0}, 2, SIZES)["measured"]["measured"]
    assert set(same) == {"P=0", "P=0.5", "P=0.9"} and same["P=0"].value == 1.0
