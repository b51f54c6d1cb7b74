"""The named values of paper 000's register entries that the study branches on (:mod:`.study`) and the register
lists (:mod:`.register`): plain-word readings of the paper's words, each an entry's value.

They sit below both modules, so the study's measurement can project a configuration onto each claim's ``DEPENDS``
(reading the register) while the register names these values, without an import circle.
"""

from __future__ import annotations

__all__ = [
    "LOCK_DEFAULT",
    "WINDOW_DEFAULT",
    "JOINT_READING_C6",
    "LATE_SHARE",
    "ENSEMBLE_MEAN",
    "CONVERGENCE_READINGS",
    "AT_09",
    "EVERY_ABOVE",
    "DETERMINES_READINGS",
]

#: The default values of the register entries "lock threshold" (the run's lock_factor) and "steady window" (the run's
#: final window_T), named in plain words (the register table shows them).
LOCK_DEFAULT, WINDOW_DEFAULT = "the run's lock factor", "final window"
#: The adversarial pass's joint reading of C000-6 (the lost opening «Неучёт», ignoring, with the background current
#: held fixed as P varies); the explorer's one-at-a-time runs see it as one value of one register entry.
JOINT_READING_C6 = "ignoring the signal noise, fixed background current"
#: The two readings of "converge fairly quickly" (register entry "convergence criterion"; each has its own rule).
LATE_SHARE, ENSEMBLE_MEAN = "90 % of runs acquired", "ensemble mean within 10 %"
CONVERGENCE_READINGS = (LATE_SHARE, ENSEMBLE_MEAN)
#: The two readings of C000-5's "for P > 0.5 it substantially determines [the accuracy]" (register entry
#: "substantially determines"; each has its own rule): the paper's one example P = 0.9, or every contrast of Fig. 3
#: above 0.5 (the adversarial review, docs/adversarial/session4-000-review.md).
AT_09, EVERY_ABOVE = "at P = 0.9", "at every P > 0.5"
DETERMINES_READINGS = (AT_09, EVERY_ABOVE)
