"""C001-9 over the whole ±20° field: the paper's two rates from every start angle whose path stays within ±20°, not
only from the crossing point."""

import numpy as np
import pytest

from tvtrack.papers.p001_maneuver_occlusion_kf.register import build_register
from tvtrack.papers.p001_maneuver_occlusion_kf import spherical

REG = build_register()
RATE_10EL = 10 * 25 * 6 / 712  # 2.107°/s


@pytest.mark.parametrize("heading", [80.0, 105.0])
def test_a_start_off_the_crossing_matches_the_3d_geometry(heading):
    """A target at azimuth 0 with heading h is a crossing target seen 90 - h degrees past its closest approach; its
    angle rate there is V sin h / R. The closed form agrees with the finite-difference 3-D geometry."""
    R, V = 10e3, 200.0
    rate = np.degrees(V * np.sin(np.deg2rad(heading)) / R)
    row = spherical.spherical_deviations([R], [V], [heading], [0.0], horizon_s=10.0)[0]
    for col, ex in ((5, "linear"), (6, "quadratic")):
        dev, _ = spherical.start_deviation(rate, 90.0 - heading, 10.0, ex)  # (its ±20° is about another origin)
        assert dev == pytest.approx(row[col], rel=2e-3, abs=2e-3), ex


def test_c001_9_is_the_worst_start_within_the_field():
    """2.107°/s over the 10 s loss: from the crossing point the path leaves ±20° (104.3 el); the worst path that
    stays within it starts near -11° and deviates by 115 el. 0.5°/s, linear extrapolation, 4 s horizon: 0.096 el from
    the crossing, 2.95 el from -20°, where the angle accelerates most: a crossing-point check passes it at the
    1-element tolerance, the whole field does not (seen failing while the measurement looked at the crossing only)."""
    fast = spherical.field_deviation(RATE_10EL, 10.0, "quadratic")
    assert fast["deviation_el"] == pytest.approx(115.1, abs=0.3) and -12.0 <= fast["start_deg"] <= -10.0
    assert 0 < fast["starts_within"] < fast["starts"] == 81
    assert spherical.paper_rate_deviation(RATE_10EL, 10.0)["deviation_el"] == pytest.approx(104.33, abs=0.01)
    slow = spherical.field_deviation(0.5, 4.0, "linear")
    assert slow["deviation_el"] == pytest.approx(2.954, abs=0.01) and slow["start_deg"] == -20.0
    assert spherical.paper_rate_deviation(0.5, 4.0, "linear")["deviation_el"] == pytest.approx(0.0963, abs=1e-3)
    sz = dict(defaults=REG.default(), prediction_rms=7.6)
    m = spherical.measure_spherical({}, 0, sz)["C001-9"]
    assert m["2.107°/s (10 el/frame)"] == pytest.approx(fast["deviation_el"])
    lin4 = spherical.measure_spherical({"extrapolation": "linear", "horizon": "k_b3 filter memory"}, 0, sz)["C001-9"]
    assert lin4["0.5°/s (0.02°/frame)"] == pytest.approx(2.954, abs=0.01)  # > 1 tolerance: not reproduced
    # every start's deviation is at most the field's worst (the worst is a maximum over the starts within)
    for s in np.arange(-20.0, 20.5, 2.5):
        dev, inside = spherical.start_deviation(0.5, s, 4.0, "linear")
        assert not inside or dev <= slow["deviation_el"] + 1e-12
