"""Paper 003: tracking a marker whose emitter rotates about the object, through interference.

P. M. Yukhno, "Synthesis of algorithms for tracking objects with spatio-temporal modulation of their emission",
Avtometriya, 2025, No. 3, doi:10.15372/AUT20250302.

Modules: :mod:`.scene` (the rotating-marker scene, interferers, decoy and the scenario runner), :mod:`.discriminators`
(quadrant and edge discriminators, S-curves), :mod:`.loops` (the rotating-gate tracking loops, their coupled
frequency response, the EKF trackers (five states, and with velocity), the 1-D two-emitter tracker), :mod:`.crb`
(the posterior CRB and the trackers against it), :mod:`.lock` (loss-of-lock criterion and the
criteria a loss meets), :mod:`.study` (the measurement functions
the explorer calls, on direct counts; :mod:`.memo` keeps their parts by what they read), :mod:`.beyond` (frame-rate smear,
the temporal median), :mod:`.register` (what the paper left unstated), :mod:`.claims` (the claims
and their rules), :mod:`.params` (parameter rules), :mod:`.plots`, :mod:`.prose` (generated sentences) and
:mod:`.recording` (Rerun layout).

The paper contract (:mod:`tvtrack.contract`): ``PAPER``, the paper declared in :mod:`.paper` and imported on first
use, and ``CITATION``, ``REGISTER``, ``DEPENDS``, ``RULES``, ``PARAMETERS``, ``CLAIMS``, ``Sizes`` and
``recording`` read from it.
"""

from ...contract import lazy_exports

CITATION = (
    'P. M. Yukhno, "Synthesis of algorithms for tracking objects with spatio-temporal modulation of their '
    'emission", Avtometriya, 2025, No. 3, doi:10.15372/AUT20250302.'
)

__getattr__, __dir__ = lazy_exports(__name__)  # PAPER from paper.py, and each name read from it
