"""Fifth review of paper 002: the photon model the paper implies, C002-5's sizing, and the adversarial reading of
the unit of C002-11's "reduced distances 3 and 1".
"""

import pytest

from tvtrack.papers.p002_unified_location_em import study
from tvtrack.papers.p002_unified_location_em.register import DEPENDS, REGISTER

TINY = study.Scale(
    n_trials=4,
    n_iter_trials=4,
    separations=(1.0, 2.0, 3.0, 4.0, 6.0, 8.0),
    fig3_frames=(5, 10, 50),
    crb_phases=2,
    n_bootstrap=20,
    max_iter=40,
)
DEFAULT = REGISTER.default()
UNIT = "distance unit of C002-11"


def test_poisson_counts_are_a_world_beyond_the_paper():
    """Eq. (3) weighs every frame's relative frequencies equally: the paper's model is a fixed count per frame."""
    entry = REGISTER["photon model"]
    assert (entry.kind, entry.side, entry.default) == ("model", "world", "fixed")
    assert "likelihood (3)" in entry.why and "C002-12" in entry.why and "line fit" in entry.why


def test_c002_5_points_run_three_times_the_trials():
    jobs = study.jobs_of(DEFAULT, 7, TINY, claims=frozenset({"C002-5"}))
    assert study.C5_TRIALS >= 3
    assert len(jobs) == 6 and {c.n for _, c in jobs} == {study.C5_TRIALS * TINY.n_trials}
    assert {(c.pix, c.T) for _, c in jobs} == {(p, T) for p in (3.0, 1.0) for T in (5, 10, 50)}
    # the other claims' points keep the profile's trials
    assert {c.n for _, c in study.jobs_of(DEFAULT, 7, TINY, claims=frozenset({"C002-4"}))} == {TINY.n_trials}


def test_the_pixel_unit_of_c002_11_is_a_reading_of_c002_11_alone():
    entry = REGISTER[UNIT]
    assert (entry.kind, entry.origin, entry.default, entry.values) == (
        "reading",
        "adversarial",
        "sigma",
        ("sigma", "pixel"),
    )
    assert [c for c, names in DEPENDS.items() if UNIT in names] == ["C002-11"]


@pytest.mark.parametrize("pix", [3.0, 5.0])
def test_the_pixel_unit_reads_one_and_three_pixels(pix):
    config = {**DEFAULT, UNIT: "pixel", "Delta of Figs 4, 5, 7 (sigma)": pix}
    jobs = study.jobs_of(config, 7, TINY, claims=frozenset({"C002-11"}))
    assert {c.d for _, c in jobs} == {pix, 3 * pix} and {c.T for _, c in jobs} == {50}
    assert {c.pix for _, c in jobs} == {pix}
    sigma = study.jobs_of({**config, UNIT: "sigma"}, 7, TINY, claims=frozenset({"C002-11"}))
    assert {c.d for _, c in sigma} == {1.0, 3.0}


def test_with_one_sigma_pixels_the_two_units_agree_bit_for_bit():
    config = {**DEFAULT, "Delta of Figs 4, 5, 7 (sigma)": 1.0}
    a = study.measure(config, 7, TINY, claims=frozenset({"C002-11"}))["C002-11"]
    b = study.measure({**config, UNIT: "pixel"}, 7, TINY, claims=frozenset({"C002-11"}))["C002-11"]
    assert repr(a) == repr(b)
