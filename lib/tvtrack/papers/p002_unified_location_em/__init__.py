"""Paper 002: a unified location algorithm (ULA) for the linear motion of closely spaced objects.

V. E. Savanevich, "A unified location algorithm for determining the motion parameters of closely spaced objects",
Kharkiv Military University, 1999 (journal probably Radioelectronics and Informatics; unverified).

Modules: ``model`` (the linear-motion scene: geometry, truth, designation, photon counts), ``em`` (the ULA: EM
over all frames, eqs. (10)-(11), with SQUAREM and the MAP variant; its E- and M-steps in ``em_steps``, its
iteration and stopping rules in ``em_loop``),
``two_stage`` (per-frame marks and line fits, the paper's comparator), ``sim_config`` (a simulation's settings,
point and seeds), ``simulation`` (one configuration's Monte Carlo: every algorithm on the same scenes, errors,
bounds), ``study`` (the measurement functions the
explorer calls and the figure data), ``readings`` (which points and statistics a configuration's claims
compare), ``claim_values`` (what each claim computes from the points, and the sentences' statistics),
``register`` (the unstated choices and which claim reads which), ``claims`` (the claims and their rules),
``params`` (the notebook's parameter rules), ``plots`` (one function per figure), ``recording`` (the Rerun
layout of one trial) and ``cap_check`` (whether the EM iteration cap matters where it is reached, Fig 6b).

The paper contract (:mod:`tvtrack.contract`): ``PAPER``, the paper declared in :mod:`.paper` and imported on first
use, and ``CITATION``, ``REGISTER``, ``DEPENDS``, ``RULES``, ``PARAMETERS``, ``CLAIMS``, ``Sizes`` and
``recording`` read from it.
"""

from ...contract import lazy_exports

CITATION = (
    'V. E. Savanevich, "A unified location algorithm for determining the motion parameters of closely spaced '
    'objects", Kharkiv Military University, 1999 (journal probably Radioelectronics and Informatics; unverified).'
)

__getattr__, __dir__ = lazy_exports(__name__)  # PAPER from paper.py, and each name read from it
