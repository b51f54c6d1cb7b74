"""The validation cell of notebook 000 (the cell after `parameters`): every bad value or cross-parameter
constraint raises one ValueError naming the parameter, before any work."""

import nbformat
import pytest

from tvtrack.pipeline.paths import NOTEBOOK_DIR


def _validate(tmp_path, **overrides):
    nb = nbformat.read(NOTEBOOK_DIR / "000_dissector_ekf.ipynb", as_version=4)
    parameters, validation = [c.source for c in nb.cells if c.cell_type == "code"][:2]
    namespace = {}
    exec(parameters, namespace)
    namespace.update(output_dir=str(tmp_path), **overrides)
    exec(validation, namespace)
    return namespace


def test_defaults_pass(tmp_path):
    assert _validate(tmp_path)["params"]["dt"] == 0.05


@pytest.mark.parametrize(
    "overrides, named",
    [
        ({"dt": 0}, "dt"),
        ({"steady_window_T": 40.0}, "steady_window_T"),
        ({"acquire_by_T": 25.0}, "acquire_by_T"),
        ({"contrast_grid": [0.0, 0.5]}, "contrast_grid"),
        ({"max_replicates": 3, "replicates": 4}, "max_replicates"),
        ({"dt_check_T": 1.0}, "dt_check_T"),
        ({"joint": -1}, "joint"),
        ({"offsets": [0.0, 0.5, 1.0]}, "offsets"),
        ({"offsets": [0.5, -0.5]}, "offsets"),
        ({"betas": [5.0, 25.0]}, "betas"),
        ({"screen_trials": 700}, "screen_trials"),
    ],
)
def test_bad_values_name_the_parameter(tmp_path, overrides, named):
    with pytest.raises(ValueError, match=named):
        _validate(tmp_path, **overrides)
