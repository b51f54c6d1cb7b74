"""The figure studies of paper 000 (studies.py): acquisition against the signed offset and its pull-in range."""

import numpy as np

from tvtrack.montecarlo import proportion_ci
from tvtrack.papers.p000_dissector_ekf import studies, study
from tvtrack.papers.p000_dissector_ekf.register import REGISTER

DEFAULT = REGISTER.default()
SMALL = study.Sizes(n_trials=40, duration_T=8.0, window_T=3.0, substeps=2, acquire_by_T=3.0)


def test_pull_in_range_walks_out_from_zero_on_each_side():
    ok, late = proportion_ci(0, 400), proportion_ci(200, 400)
    offsets = [-1.0, -0.6, -0.3, 0.0, 0.3, 0.6, 1.0]
    acq = {"v2": {"late": [ok, late, ok, ok, ok, ok, late]}}  # -1.0 is fine again, past a failing -0.6
    assert studies.pull_in_range(offsets, acq) == {"v2": {"negative": -0.3, "positive": 0.6}}
    acq = {"v1": {"late": [ok, ok, ok, late, ok, ok, ok]}}  # from 0 itself not acquired
    assert studies.pull_in_range(offsets, acq) == {"v1": {"negative": None, "positive": None}}


def test_a_negative_offset_starts_the_truth_on_the_other_side_and_acquisition_is_not_symmetric():
    """The truth starts at -0.3 T in every run; from +-0.3 T (inside the micro-raster) both variants acquire; from
    -1 T most runs do not, while from +1 T they do (issue 37's finding: the pull-in range is not symmetric)."""
    acq = studies.acquisition_vs_offset(DEFAULT, 4, SMALL, [-1.0, -0.3, 0.3, 1.0])
    x, *_ = study._path(DEFAULT, 4, SMALL, -0.3)
    np.testing.assert_allclose(x[:, 0], -0.3)
    for a in acq.values():
        late = [e.value for e in a["late"]]
        assert late[1] < 0.2 and late[2] < 0.2
        assert late[0] > 0.5 and late[3] < 0.2
