"""Paper 004: laser-spot energy-centre prediction with a growing-memory polynomial ("Kalman") filter.

N. I. Kokryatska, R. M. Hrynchyshyn, "Modelling of signal generation and prediction of the coordinates of the
energy centres of laser-beam images using Kalman filters", Vinnytsia National Technical University, 2005.

Modules:

- :mod:`.beam_wander`: the synthetic beam-wander generator (the paper's recordings are not available),
  the camera that renders and measures the spot, and the optimal (true-model Kalman) predictor;
- :mod:`.traces`: the trace data set format and its loader (``data/laser_traces``);
- :mod:`.spot_centre`: the energy centre (windowed, thresholded centroid) and a Gaussian-fit MLE;
- :mod:`.predictors`: the paper's filter with its gain floor and every baseline (finite differences,
  spline, regression, MLP, RBF network, fading memory, constant-acceleration and Singer Kalman filters);
- :mod:`.prediction_study`: every method tuned the same way (cross-validation over paths) and scored;
- :mod:`.study`: the measurement functions the explorer calls; :mod:`.register`: the unstated choices;
  :mod:`.claims`: the claims and their rules; :mod:`.params`: parameter rules; :mod:`.recording`: Rerun layout.

The paper contract (:mod:`tvtrack.contract`): ``PAPER``, the paper declared in :mod:`.paper` and imported on first
use, and ``CITATION``, ``REGISTER``, ``DEPENDS``, ``RULES``, ``PARAMETERS``, ``CLAIMS``, ``Sizes`` and
``recording`` read from it.
"""

from ...contract import lazy_exports

CITATION = (
    'N. I. Kokryatska, R. M. Hrynchyshyn, "Modelling of signal generation and prediction of the coordinates of '
    'the energy centres of laser-beam images using Kalman filters", Vinnytsia National Technical University, '
    "2005."
)

__getattr__, __dir__ = lazy_exports(__name__)  # PAPER from paper.py, and each name read from it
