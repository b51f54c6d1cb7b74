"""Paper 001: manoeuvre detection and prediction through occlusion.

V. T. Fisenko, L. D. Vilesov, V. I. Mozheiko, T. Yu. Fisenko, "Detection of an object's manoeuvre and prediction
of its trajectory in a television tracking system", 2008 (Izv. vuzov. Priborostroenie, unverified).

Modules: :mod:`.track_modes` (the per-channel TRACK2 / TRACK3 / COAST mode logic; its engines in
:mod:`._track_modes_kernel`, compiled, and :mod:`._track_modes_numpy`), :mod:`.maneuver_detector`
(the two-window manoeuvre detector of eqs. (3)-(14) and its thresholds), :mod:`.study` (the measurement functions
the explorer calls), :mod:`.register` (the notebook's register of unstated choices, its entries in
:mod:`.entries`), :mod:`.claims` (the claims and their rules), :mod:`.sizes` (the run sizes), :mod:`.params`
(parameter rules), :mod:`.plots` and :mod:`.recording` (Rerun layout).

The paper contract (:mod:`tvtrack.contract`): ``PAPER``, the paper declared in :mod:`.paper` and imported on first
use, and ``CITATION``, ``REGISTER``, ``DEPENDS``, ``RULES``, ``PARAMETERS``, ``CLAIMS``, ``Sizes`` and
``recording`` read from it.
"""

from ...contract import lazy_exports

CITATION = (
    "V. T. Fisenko, L. D. Vilesov, V. I. Mozheiko, T. Yu. Fisenko, \"Detection of an object's manoeuvre and "
    'prediction of its trajectory in a television tracking system", 2008 (Izv. vuzov. Priborostroenie, '
    "unverified)."
)

__getattr__, __dir__ = lazy_exports(__name__)  # PAPER from paper.py, and each name read from it
