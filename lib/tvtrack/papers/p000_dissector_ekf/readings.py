"""The named values of paper 000's register entries that the study branches on (:mod:`.study`) and the register
lists (:mod:`.register`): plain-word readings of the paper's words, each an entry's value.

They sit below both modules, so the study's measurement can project a configuration onto each claim's ``DEPENDS``
(reading the register) while the register names these values, without an import circle.
"""

from __future__ import annotations

__all__ = [
    "LOCK_DEFAULT",
    "WINDOW_DEFAULT",
    "LATE_SHARE",
    "ENSEMBLE_MEAN",
    "CONVERGENCE_READINGS",
    "AT_09",
    "EVERY_ABOVE",
    "DETERMINES_READINGS",
    "NOISE_EFFECT",
    "ACCOUNTING",
    "C5_COMPARISONS",
    "C2_CARD",
    "C2_EVERY",
    "C2_READINGS",
    "CS_CONSISTENT",
    "CS_LITERAL",
    "CS_READINGS",
]

#: The default values of the register entries "lock threshold" (the run's lock_factor) and "steady window" (the run's
#: final window_T), named in plain words (the register table shows them).
LOCK_DEFAULT, WINDOW_DEFAULT = "the run's lock factor", "final window"
#: The two readings of "converge fairly quickly" (register entry "convergence criterion"; each has its own rule).
LATE_SHARE, ENSEMBLE_MEAN = "90 % of runs acquired", "ensemble mean within 10 %"
CONVERGENCE_READINGS = (LATE_SHARE, ENSEMBLE_MEAN)
#: The two readings of C000-5's "for P > 0.5 it substantially determines [the accuracy]" (register entry
#: "substantially determines"; each has its own rule): the paper's one example P = 0.9, or every contrast of Fig. 3
#: above 0.5 (the adversarial review, docs/validity/000.md).
AT_09, EVERY_ABOVE = "at P = 0.9", "at every P > 0.5"
DETERMINES_READINGS = (AT_09, EVERY_ABOVE)
#: The two readings of what C000-5 compares (register entry "C000-5 comparison"): the accuracy with the signal noise
#: over the accuracy without it (Fig. 3's sigma_x^2 / sigma_x^2*), or the Conclusions' "accounting for" the noise:
#: a filter that ignores it over variant 2, which accounts for it, on the same data.
NOISE_EFFECT, ACCOUNTING = "with the signal noise / without it", "ignoring the signal noise / accounting for it"
C5_COMPARISONS = (NOISE_EFFECT, ACCOUNTING)
#: The two readings of the contrasts at which C000-2's "at psi_A = 20 the error was 2 %" holds (register entry
#: "C000-2 contrasts"; each has its own rule): P = 0 and 0.5 (this project's default), or every contrast of Fig. 3.
C2_CARD, C2_EVERY = "P = 0 and 0.5", "every Fig. 3 contrast"
C2_READINGS = (C2_CARD, C2_EVERY)
#: The two readings of variant 1's signal-noise term (register entry "signal-noise scale"): sqrt(c_s S) X2 with
#: c_s = N0 P/(1-P), consistent with eq. (2) (this project's default), or sqrt(A S) X2 as eq. (6) prints it.
CS_CONSISTENT, CS_LITERAL = "c_s = N0 P/(1-P)", "c_s = A, as printed"
CS_READINGS = (CS_CONSISTENT, CS_LITERAL)
