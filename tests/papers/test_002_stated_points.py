"""Paper 002: the values and directions the paper states, kept where the register and the rules file them.

- Fig 2 states its frame numbers (l. 105: «для разного числа кадров T=10,5»), as it states its photon counts
  (m_k = 20, 10) and its pixel (Delta / sigma = 1): an entry that moves any of them to another value is a world
  beyond the paper (an operating point), not a reading of its text.
- C002-13's sentence states a dependence and no direction (l. 131: «Зависимость числа итераций алгоритма от
  расстояния между объектами приведена на рис. 7»): fewer iterations for closer objects is that dependence too,
  so the measurement is the fold change either way and the same verdict follows from either direction.
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from tvtrack.estimate import Estimate
from tvtrack.measured import is_undecided
from tvtrack.montecarlo import ratio_ci
from tvtrack.papers.p002_unified_location_em import claim_values
from tvtrack.papers.p002_unified_location_em.claims import RULES
from tvtrack.papers.p002_unified_location_em.register import REGISTER

#: Fig 2's stated values (l. 105): frames T = 10, 5; photons m_k = 20, 10; pixel Delta / sigma = 1.
FIG2 = {"T pair of C002-6": "5 vs 10", "m_k pair of C002-6": "20 vs 10", "Delta of C002-6 (sigma)": 1.0}


@pytest.mark.parametrize("name", sorted(FIG2))
def test_every_entry_that_moves_a_value_fig_2_states_is_a_world_at_fig_2s_value(name):
    entry = REGISTER[name]
    assert (entry.kind, entry.side) == ("operating point", "world"), (name, entry.kind)
    assert entry.default == FIG2[name]  # the world is kept at the paper's stated point by default


def _iterations(near, far):
    """The two Fig 7 points C002-13 reads: plain-EM steps per trial at the smallest and the largest d."""
    return SimpleNamespace(
        g={"7": {0.5: "near", 8.0: "far"}}, res={"near": {"plain_iter": near}, "far": {"plain_iter": far}}
    )


STEPS = 60.0 + np.arange(40) % 7  # per-trial steps, 60-66


def test_c13_fewer_iterations_for_closer_objects_is_a_dependence_too():
    more_near, more_far = (
        claim_values._c13(_iterations(3 * STEPS, STEPS)),
        claim_values._c13(_iterations(STEPS, 3 * STEPS)),
    )
    signed = ratio_ci(STEPS, 3 * STEPS, paired=False)
    assert more_far.value == pytest.approx(1.0 / signed.value, rel=1e-12)  # the fold change, not the signed 1/3
    assert more_near.value == pytest.approx(more_far.value, rel=1e-12)
    for e in (more_near, more_far):
        assert RULES["C002-13"].decide(e) == "reproduced"


def test_c13_iterations_that_do_not_depend_on_the_distance_are_not_reproduced():
    flat = claim_values._c13(_iterations(STEPS, STEPS[::-1].copy()))
    assert 1.0 <= flat.ci_low <= flat.value <= flat.ci_high < 1.1
    assert RULES["C002-13"].decide(flat) == "not reproduced"


def test_fold_change_maps_the_interval_end_by_end_and_keeps_the_signed_ratio():
    below = Estimate(0.5, 0.05, 0.4, 0.625, 40, 0.95, "expanded percentile bootstrap; coverage 0.948 at n = 40")
    f = claim_values.fold_change(below)
    assert (f.value, f.ci_low, f.ci_high) == pytest.approx((2.0, 1.6, 2.5))
    assert f.stderr == pytest.approx(0.05 / 0.25)
    assert "q = 0.5 [0.4, 0.625]" in f.method and not is_undecided(f)
    straddles = claim_values.fold_change(Estimate(0.95, 0.05, 0.8, 1.1, 40, 0.95, "t"))
    assert (straddles.ci_low, straddles.ci_high) == pytest.approx((1.0, 1.25))  # no measurable dependence: from 1
    above = Estimate(2.0, 0.1, 1.8, 2.2, 40, 0.95, "t")
    assert (claim_values.fold_change(above).value, claim_values.fold_change(above).ci_low) == (2.0, 1.8)


def test_c13_compares_the_two_separations_as_unpaired_samples():
    """The plain-EM step counts at the nearest and the farthest separation come from different scenes, so their
    ratio's interval is the unpaired one (a paired interval would pretend the runs match)."""
    rng = np.random.default_rng(5)
    near = rng.integers(20, 60, 40).astype(float)
    far = rng.integers(5, 30, 40).astype(float)
    got = claim_values._c13(_iterations(near, far))
    unpaired = claim_values.fold_change(ratio_ci(near, far, paired=False))
    paired = claim_values.fold_change(ratio_ci(near, far))
    assert (got.value, got.ci_low, got.ci_high) == (unpaired.value, unpaired.ci_low, unpaired.ci_high)
    assert (paired.ci_low, paired.ci_high) != (unpaired.ci_low, unpaired.ci_high)  # the test can tell them apart
