"""Paper 000: the register entries each claim declares (``DEPENDS``), pinned to what the paper and the register's
reasons give the claim, and each declared entry read by the claim's measurement.

An entry a claim declares but never reads makes the explorer count a condition for a claim it cannot move; one it
drops leaves that claim measured at the entry's default only. So each list is written out here with its reason,
and a small run of each claim's measurement records which entries it reads.
"""

from __future__ import annotations

import pytest

from tvtrack.papers.p000_dissector_ekf import study
from tvtrack.papers.p000_dissector_ekf.register import DEPENDS, REGISTER
from tvtrack.register import project

#: How every filter run's data are made: the sampler, where the error is scored, the SNR's noise and the photon law.
DATA = ["sample model", "scoring time", "sigma_sh", "photon model"]
#: Variant 1's readings ((E8)'s G22, eq. (6)'s signal-noise scale) and variant 2's (eq. (9)'s noise point).
BOTH_VARIANTS = ["G22", "signal-noise scale", "v2 noise at"]
#: The worlds beyond the paper's stationary model that every filter run carries: the object's manoeuvre (the truth
#: path and the pulse that follows it) and the drifting background (the photon samples). A claim computed from
#: those runs is measured in them, so it declares both (their defaults are the paper's: eq. (2)'s constant N0 and
#: eqs. (3), (4)'s Gauss-Markov message alone).
WORLDS = ["manoeuvre", "background"]

EXPECTED = {
    # "Variant 1 is two-dimensional and needs more computation": the cost measure, its batch, variant 2's eq. (9) work.
    "C000-4": ["C000-4 cost measure", "C000-4 batch", "v2 noise at"],
    # "converge fairly quickly" (Fig. 1 from D11(0) = 0.2): both variants from the paper's start (estimate, position),
    # the criterion and its lock threshold, at Fig. 1's operating point (psi_A, P, sigma_1), in the runs' worlds;
    # the steady window gives the steady error both criteria refer to (the lock reference, the ensemble-mean ratio).
    "C000-1": DATA
    + BOTH_VARIANTS
    + ["initial estimate", "initial position", "convergence criterion", "lock threshold"]
    + ["psi_A", "contrast", "sigma_1", "steady window"]
    + WORLDS,
    # "at psi_A = 20 the coordinate error is 2 % of the micro-raster size": psi_A fixed by the sentence, its P by the
    # reading "C000-2 contrasts"; the raster's length, the steady window, the message, in the runs' worlds.
    "C000-2": DATA + BOTH_VARIANTS + ["micro-raster size", "C000-2 contrasts", "steady window", "sigma_1"] + WORLDS,
    # "approximately the same estimate of potential accuracy": v1 / v2 over Fig. 3 (psi_A, its contrast convention)
    # and Fig. 2 (its P), by the statistic and the reading of "accuracy", in the steady window and the runs' worlds.
    "C000-3": DATA
    + BOTH_VARIANTS
    + ["psi_A", "contrast", "contrast convention", "statistic", "C000-3 accuracy"]
    + ["steady window", "sigma_1"]
    + WORLDS,
    # "for P < 0.5 ... does not substantially affect ... for P > 0.5 substantially determines": Fig. 3's variant 2
    # over sigma_x^2* (no variant 1), with its two readings of "substantially determines" and of the comparison.
    "C000-5": DATA
    + ["v2 noise at", "psi_A", "contrast convention", "statistic", "steady window", "sigma_1", "background"]
    + ["manoeuvre", "substantially determines", "C000-5 comparison"],
    # "at P = 0.9 ... exceeds the potentially achievable ... by more than 20 times": the sentence's filter (either
    # variant or the one ignoring the noise) over its reference, at P = 0.9 (psi_A by the contrast convention), in the
    # steady window and the runs' worlds (sigma_1 held at the paper's 0.1 T: tests/test_declared_entries.py says why).
    "C000-6": DATA
    + BOTH_VARIANTS
    + ["C000-6 filter", "potentially achievable", "psi_A", "contrast convention", "statistic", "steady window"]
    + WORLDS,
    # "sigma_x^2 grows with P relative to sigma_x^2*": Fig. 3's ratio (C000-5's without its two readings).
    "C000-7": DATA
    + ["v2 noise at", "psi_A", "contrast convention", "statistic", "steady window", "sigma_1", "background"]
    + ["manoeuvre"],
    # "dt = 0.05 keeps discretisation errors <= 3 %": both variants at dt and dt / factor at the check's own
    # (psi_A, P) points, so no operating point of the figures (no psi_A, contrast or contrast convention).
    "C000-8": ["sigma_sh"] + BOTH_VARIANTS,
    # "sigma_x^2 decreases with psi_A" (Fig. 2): both variants over the psi_A grid at Fig. 2's P, by the statistic,
    # in the steady window and the runs' worlds.
    "C000-9": DATA + BOTH_VARIANTS + ["contrast", "statistic", "steady window", "sigma_1"] + WORLDS,
}


@pytest.mark.parametrize("claim", sorted(EXPECTED))
def test_each_claim_declares_the_entries_its_sentence_reads(claim):
    got = DEPENDS[claim]
    assert len(got) == len(set(got)), f"{claim} declares an entry twice: {got}"
    assert set(got) == set(EXPECTED[claim]), (
        f"{claim}: declared but not expected {sorted(set(got) - set(EXPECTED[claim]))}, "
        f"expected but not declared {sorted(set(EXPECTED[claim]) - set(got))}"
    )
    assert set(DEPENDS) == set(EXPECTED)


class _Reads(dict):
    """A configuration that records the entries a measurement reads."""

    def __init__(self, *args):
        super().__init__(*args)
        self.read = set()

    def __getitem__(self, name):
        self.read.add(name)
        return super().__getitem__(name)

    def get(self, name, default=None):
        self.read.add(name)
        return super().get(name, default)


TINY = study.Sizes(
    n_trials=4,
    duration_T=6.0,
    window_T=1.0,
    substeps=1,
    psi_grid=(5.0, 50.0),
    contrast_grid=(0.0, 0.5, 0.9),
    dt_points=((20.0, 0.5),),
    dt_factor=2,
    dt_trials=4,
    dt_duration_T=2.0,
    grid_trials=2,
    grid_points=21,
    acquire_by_T=2.0,
)
#: Each measured claim's function, and the readings beyond the default under which an entry it declares is read
#: (C000-6 reads variant 1's G22 and signal-noise scale only when its sentence's filter is variant 1).
MEASUREMENTS = {
    "C000-1": (study._c1, []),
    "C000-2": (study._c2, []),
    "C000-3": (study._c3, []),
    "C000-5": (study._c5_c7, []),
    "C000-6": (study._c6, [{"C000-6 filter": "variant 1"}]),
    "C000-7": (study._c5_c7, []),
    "C000-8": (study._c8, []),
    "C000-9": (study._c9, []),
}


@pytest.mark.parametrize("claim", sorted(MEASUREMENTS))
def test_each_declared_entry_is_read_by_its_claims_measurement(claim):
    fn, readings = MEASUREMENTS[claim]
    default = REGISTER.default()
    read = set()
    for change in [{}, *readings]:
        cfg = _Reads(project({**default, **change}, DEPENDS[claim], default))
        study._MEMO.clear()
        fn(cfg, 1, TINY)
        read |= cfg.read
    assert set(DEPENDS[claim]) <= read, f"{claim} declares entries its measurement never reads: " + str(
        sorted(set(DEPENDS[claim]) - read)
    )
