"""004's operating point (``operating``): the bandwidth factor that keeps the paper's filter at the paper's 1-2 px
in every world, checked on a synthetic error model instead of simulated paths.

The paper's filter errs ``1.5 (b / 3)^s`` px per axis at bandwidth factor ``b`` in the default world (1.5 px at its
factor 3), with ``s`` the default world's exponent between the band's ends (:data:`operating.BAND_SLOPE`), and
``1.5 g (b / 3)^k`` in a joint world. Then
every step of :func:`operating.joint_factor` has a closed form: the power-law step lands on the target exactly when
``k = s``, and the secant step lands exactly for any other ``k`` (two points of a power law give its exponent).
"""

import pytest

from tvtrack.papers.p004_laser_spot_prediction import operating as op
from tvtrack.papers.p004_laser_spot_prediction.register import DEFAULT

S = op.BAND_SLOPE
JOINT = (("amplitude", 2.0), ("jitter", 1.0))  # two tabled values: a joint world
PRODUCT = 3.0 * 0.6037 * 0.5328  # the table's rows of the two values


@pytest.fixture(autouse=True)
def fresh(monkeypatch):
    """Each test starts with no joint world corrected and no reference measured."""
    for name in ("_JOINT", "_REFERENCE", "JOINT_OUTSIDE_BAND"):
        monkeypatch.setattr(op, name, {})


def _model(g, k, calls):
    """The error model: the default world (only the band position and a bandwidth given) errs ``1.5 (b / 3)^s``,
    any other configuration ``1.5 g (b / 3)^k``; every call recorded."""

    def rms(config):
        calls.append(dict(config))
        b = config["bandwidth"]
        if set(config) <= {op.BAND_POSITION, "bandwidth"}:
            return 1.5 * (b / 3.0) ** S
        return 1.5 * g * (b / 3.0) ** k

    return rms


def test_the_table_product_of_a_configuration():
    assert op.table_factors(DEFAULT) == (3.0, (), 0)
    assert op.table_factors({"amplitude": 2.0}) == (pytest.approx(3.0 * 0.6037, rel=1e-15), (("amplitude", 2.0),), 1)
    got, world, rows = op.table_factors({"jitter": 1.0, "amplitude": 2.0, op.BAND_POSITION: 2.0})
    assert got == pytest.approx(3.0 * 1.2464 * 0.6037 * 0.5328, rel=1e-15) and rows == 3
    assert world == (("error in the band", 2.0), ("amplitude", 2.0), ("jitter", 1.0))  # the register's order
    # a value with no row (a sweep's) keeps the default's factor and counts no row, the band position's too
    assert op.table_factors({"jitter": 2.0}) == (3.0, (("jitter", 2.0),), 0)
    assert op.table_factors({op.BAND_POSITION: 1.25}) == (3.0, (("error in the band", 1.25),), 0)
    # the bandwidth is the knob, not a world value of the key; entries outside the world are not in it, but the
    # horizon is: the paper's 1-2 px is its filter's error at the paper's (unstated) horizon
    assert op.table_factors({"bandwidth": 8.0, "network lags": 10}) == (3.0, (), 0)
    assert op.table_factors({"bandwidth": 8.0, "horizon": 3}) == (pytest.approx(3.0 * 0.3354), (("horizon", 3),), 1)
    got, world, rows = op.table_factors({"amplitude": 2.0, "horizon": 10})
    assert got == pytest.approx(3.0 * 0.6037 * 0.0971, rel=1e-15) and rows == 2  # a joint world: corrected
    assert world == (("amplitude", 2.0), ("horizon", 10))
    assert op.bandwidth_for({"bandwidth": 8.0, "horizon": 3}) == 8.0  # set by hand: used as it is


def test_a_number_is_the_bandwidth_and_a_single_world_its_table_row():
    assert op.bandwidth_for({"bandwidth": 8.0, "amplitude": 2.0}) == 8.0
    assert op.bandwidth_for({"amplitude": 2.0}) == pytest.approx(3.0 * 0.6037, rel=1e-15)
    with pytest.raises(LookupError, match="has no corrected bandwidth yet"):
        op.bandwidth_for(dict(JOINT))
    op._JOINT[JOINT] = 4.2
    assert op.bandwidth_for(dict(JOINT)) == 4.2


def test_a_joint_world_within_the_tolerance_keeps_the_product():
    calls = []
    g = 1.04 / (PRODUCT / 3.0) ** S  # 4 % above the target at the product
    assert op.joint_factor(JOINT, _model(g, S, calls)) == pytest.approx(PRODUCT, rel=1e-15)
    assert calls == [{op.BAND_POSITION: 1.5, "bandwidth": 3.0}, {**dict(JOINT), "bandwidth": PRODUCT}]
    assert op._JOINT[JOINT] == pytest.approx(PRODUCT, rel=1e-15) and op.JOINT_OUTSIDE_BAND == {}
    assert op.joint_factor(JOINT, None) == op._JOINT[JOINT]  # cached: not measured again


def test_the_power_law_step_lands_where_the_world_shares_the_default_exponent():
    calls = []
    g = 1.3  # 30 % above the default world at any factor
    got = op.joint_factor(JOINT, _model(g, S, calls))
    want = 3.0 * g ** (-1.0 / S)  # 1.5 g (b / 3)^s = 1.5
    assert got == pytest.approx(want, rel=1e-12) and len(calls) == 3
    assert calls[2] == {**dict(JOINT), "bandwidth": pytest.approx(want, rel=1e-12)}


@pytest.mark.parametrize("k", [0.6, 2.0, 3.5])
def test_the_secant_step_lands_for_any_other_exponent(k):
    calls = []
    g = 1.5
    got = op.joint_factor(JOINT, _model(g, k, calls))
    want = 3.0 * g ** (-1.0 / k)  # 1.5 g (b / 3)^k = 1.5
    b1 = PRODUCT * (1.0 / (g * (PRODUCT / 3.0) ** k)) ** (1.0 / S)
    assert [c["bandwidth"] for c in calls[1:]] == pytest.approx([PRODUCT, b1, want], rel=1e-12)
    assert got == pytest.approx(want, rel=1e-10)


def test_a_world_whose_error_hardly_moves_takes_no_secant_step_and_is_outside_the_band():
    calls = []
    g, k = 0.3, 0.1  # below MIN_SLOPE: no bandwidth reaches 1.5 px within the range
    got = op.joint_factor(JOINT, _model(g, k, calls))
    assert len(calls) == 3  # the reference, the product, the power-law step
    b1 = calls[2]["bandwidth"]
    assert got == b1 and b1 > PRODUCT  # the nearer of the two measured points
    err = 1.5 * g * (b1 / 3.0) ** k
    assert op.JOINT_OUTSIDE_BAND[JOINT] == (pytest.approx(b1, rel=1e-12), pytest.approx(err, rel=1e-12))
    assert err < 1.0 / 1.05  # below the band, beyond the correction's tolerance


def test_the_steps_stay_in_the_factor_range_of_the_worlds_frame_rate():
    calls = []
    world = (("frame rate", 200.0), ("jitter", 1.0))
    product = 3.0 * 7.9949 * 0.5328
    got = op.joint_factor(world, _model(1e-3, S, calls))  # far too small an error: the step wants a huge factor
    assert len(calls) == 3 and calls[2]["bandwidth"] == 0.8 * 200.0 == got  # clipped at 0.8 x the frame rate
    assert product < 160.0 and op.JOINT_OUTSIDE_BAND[world][0] == 160.0
    calls = []
    got = op.joint_factor(JOINT, _model(1e3, S, calls))  # far too large: the step wants a tiny factor
    assert len(calls) == 2 and calls[1]["bandwidth"] == 0.05 == got  # the reference is measured already


def test_a_step_clipped_to_where_it_started_measures_nothing_again(monkeypatch):
    calls = []
    monkeypatch.setattr(op, "FACTOR_RANGE", (PRODUCT, 0.8))  # the product is the range's lowest factor
    got = op.joint_factor(JOINT, _model(30.0, 2.0, calls))  # too large: every step wants a lower factor
    assert got == PRODUCT and len(calls) == 2


def test_a_secant_step_clipped_to_where_it_started_measures_nothing_again(monkeypatch):
    calls = []
    g, k = 30.0, 0.6  # flatter than the default world: the power-law step falls short, the secant wants lower
    b0 = op.table_factors(dict(JOINT))[0]
    b1 = b0 * (1.5 / (1.5 * g * (b0 / 3.0) ** k)) ** (1.0 / S)  # the power-law step, as the model's numbers give it
    monkeypatch.setattr(op, "FACTOR_RANGE", (b1, 0.8))  # the power-law step ends at the lowest factor
    got = op.joint_factor(JOINT, _model(g, k, calls))
    assert len(calls) == 3 and got == pytest.approx(b1, rel=1e-15)


def test_a_joint_world_at_another_band_position_aims_at_that_position():
    calls = []
    world = (("error in the band", 2.0), ("amplitude", 2.0))
    got = op.joint_factor(world, _model(1.0, 2.0, calls))
    b_ref = 3.0 * 1.2464
    assert calls[0] == {op.BAND_POSITION: 2.0, "bandwidth": pytest.approx(b_ref, rel=1e-15)}
    ref = 1.5 * (b_ref / 3.0) ** S
    assert ref == pytest.approx(2.0, rel=0.01)  # about the band's upper end
    assert got == pytest.approx(3.0 * (ref / 1.5) ** 0.5, rel=1e-10)  # 1.5 (b / 3)^2 = the default world's error
    assert world not in op.JOINT_OUTSIDE_BAND  # 2 px on the table's scale: in the band
    other = (("error in the band", 2.0), ("jitter", 1.0))
    op.joint_factor(other, _model(1.0, 2.0, calls))
    assert sum(set(c) == {op.BAND_POSITION, "bandwidth"} for c in calls) == 1  # the reference measured once


def test_a_world_kept_in_the_band_off_its_position_is_not_outside():
    calls = []
    g, k = 1.2, 0.2  # hardly moves: stays about 20 % above 1.5 px, inside 1-2 px
    op.joint_factor(JOINT, _model(g, k, calls))
    assert JOINT not in op.JOINT_OUTSIDE_BAND
    calls = []
    op._JOINT.clear()
    op.joint_factor(JOINT, _model(2.0, 0.1, calls))  # about 3 px: outside
    assert op.JOINT_OUTSIDE_BAND[JOINT][1] > 2.0 * 1.05


def test_a_joint_world_is_corrected_on_the_first_eight_of_the_tables_paths(monkeypatch):
    from tvtrack.papers.p004_laser_spot_prediction import study

    seen = []
    calls = []
    model = _model(1.3, S, calls)

    def table_paths_rms(config, n_paths=None):
        seen.append(n_paths)
        return model(config)

    monkeypatch.setattr(study, "table_paths_rms", table_paths_rms)
    assert study.resolve_operating_point(dict(JOINT)) is None  # corrected, inside the band
    assert seen == [8, 8, 8] == [op.JOINT_PATHS] * 3
    assert op._JOINT[JOINT] == pytest.approx(3.0 * 1.3 ** (-1.0 / S), rel=1e-12)
    assert study.resolve_operating_point({"amplitude": 2.0}) is None and len(seen) == 3  # one world: its row
    assert study.resolve_operating_point({**dict(JOINT), "bandwidth": 8.0}) is None and len(seen) == 3  # by hand
