import pytest

from tvtrack.parameters import (
    Boolean,
    OneOf as Choice,
    OneOfList as ChoiceList,
    Integer,
    IntegerList,
    OutputDir,
    Real,
    RealList,
    validate_parameters,
)


def common(tmp_path, **extra):
    return {"seed": 3, "n_trials": 10, "output_dir": str(tmp_path / "out"), "rerun_mode": "off", **extra}


def test_valid_parameters_are_returned_normalised(tmp_path):
    ns = common(tmp_path, sigma=1, flag=True, sizes=[1, 2], widths=(0.5, 1))
    out = validate_parameters(
        ns, {"sigma": Real(0, 2), "flag": Boolean(), "sizes": IntegerList(1, 5), "widths": RealList(0, 2)}
    )
    assert out == {
        "seed": 3,
        "n_trials": 10,
        "output_dir": str(tmp_path / "out"),
        "rerun_mode": "off",
        "sigma": 1.0,
        "flag": True,
        "sizes": [1, 2],
        "widths": [0.5, 1.0],
    }
    assert isinstance(out["sigma"], float)
    assert (tmp_path / "out").is_dir()


@pytest.mark.parametrize(
    "name, value, rules, expected",
    [
        (
            "sigma",
            -0.1,
            {"sigma": Real(0, 2)},
            "parameter 'sigma' = -0.1 is out of range; it must be a real number in [0, 2]",
        ),
        ("sigma", 0.0, {"sigma": Real(0, 2, low_open=True)}, "must be a real number in (0, 2]"),
        ("sigma", float("nan"), {"sigma": Real(0, 2)}, "parameter 'sigma' = nan"),
        ("n", 2.5, {"n": Integer(1, 5)}, "parameter 'n' = 2.5 is out of range; it must be an integer in [1, 5]"),
        ("n", True, {"n": Integer(0, 5)}, "an integer in [0, 5]"),
        ("mode", "x", {"mode": Choice("a", "b")}, "parameter 'mode' = 'x' is out of range; it must be one of 'a', 'b'"),
        ("w", [0.5, 3.0], {"w": RealList(0, 2)}, "parameter 'w' = [0.5, 3.0]"),
        ("w", [], {"w": RealList(0, 2)}, "a list of 1..any real numbers"),
        ("figs", ["fig1", "fig9"], {"figs": ChoiceList("fig1", "fig2")}, "distinct values from 'fig1', 'fig2'"),
        ("figs", ["fig1", "fig1"], {"figs": ChoiceList("fig1", "fig2")}, "parameter 'figs' = ['fig1', 'fig1']"),
        ("figs", [], {"figs": ChoiceList("fig1")}, "at least 1 distinct"),
    ],
)
def test_bad_value_names_parameter_value_and_range(tmp_path, name, value, rules, expected):
    with pytest.raises(ValueError) as err:
        validate_parameters(common(tmp_path, **{name: value}), rules)
    assert expected in str(err.value)


def test_common_rules_apply_and_missing_parameter_is_named(tmp_path):
    with pytest.raises(ValueError, match="parameter 'rerun_mode' = 'web'"):
        validate_parameters(common(tmp_path, rerun_mode="web"), {})
    with pytest.raises(ValueError, match="parameter 'n_trials' = 0"):
        validate_parameters(common(tmp_path, n_trials=0), {})
    with pytest.raises(ValueError, match="parameter 'gain' is missing"):
        validate_parameters(common(tmp_path), {"gain": Real(0, 1)})


def test_output_dir_that_is_a_file_is_refused(tmp_path):
    f = tmp_path / "file"
    f.write_text("x")
    with pytest.raises(ValueError, match="parameter 'output_dir'"):
        validate_parameters({**common(tmp_path), "output_dir": str(f)}, {"output_dir": OutputDir()})
