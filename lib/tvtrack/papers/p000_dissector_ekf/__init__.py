"""Paper 000: coordinate accuracy of an image-dissector tracker under signal-dependent noise.

Yu. V. Martyshevsky, "Analysis of the accuracy of determining the coordinates of a light object by a television
tracking system based on an image dissector", Avtometriya, 1995, No. 3.

Modules: :mod:`.model` (the scan, the message, the data generators), :mod:`.ekf` (the paper's two EKFs),
:mod:`.reference` (grid filter, PCRLB), :mod:`.baseline` (centroid + fixed-gain tracker), :mod:`.settling`
(per-scan errors, acquisition times, the median ratio), :mod:`.study` (measurement functions), :mod:`.cpu_time`
(C000-4's paired timings), :mod:`.register` (unstated choices), :mod:`.claims` (the claims and their rules),
:mod:`.params` (parameter rules), :mod:`.plots`, :mod:`.findings` and :mod:`.recording` (Rerun layout).

The paper contract (:mod:`tvtrack.contract`): ``PAPER``, the paper declared in :mod:`.paper` and imported on first
use, and ``CITATION``, ``REGISTER``, ``DEPENDS``, ``RULES``, ``PARAMETERS``, ``CLAIMS``, ``Sizes`` and
``recording`` read from it.
"""

from ...contract import lazy_exports

CITATION = (
    'Yu. V. Martyshevsky, "Analysis of the accuracy of determining the coordinates of a light object by a '
    'television tracking system based on an image dissector", Avtometriya, 1995, No. 3.'
)

__getattr__, __dir__ = lazy_exports(__name__)  # PAPER from paper.py, and each name read from it
