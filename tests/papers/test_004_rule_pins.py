"""Rule pins of paper 004 (Kokryatska and Hrynchyshyn 2005): each claim's rule decides synthetic values either side
of the paper's statement as the paper says (tests/rule_pins.py). Sentences from the paper's text, bands from this
project's acceptance rules; the values are written here, not read from claims.py."""

from rule_pins import Band, Order, Unchecked, problems

BEATS = Order(
    "the filter is more accurate than the other methods on the same data",
    "baseline MSE / filter MSE > 1",
    (1.3, 4.0),
    (0.7, 0.25),
)
PINS = {
    "C004-1": {
        "": Band(
            "the prediction error does not exceed 2 pixels",
            "95th percentile of |e| <= 2 px",
            None,
            2.0,
            (1.0, 1.9),
            (2.5, 10.0),
            unit="px",
        )
    },
    "C004-2": {"": Unchecked("accuracy improved to 1...2 pixels", "the simulated world is calibrated to 1.5 px")},
    # the paper's Table: finite differences and splines (2-10 px), linear regression (3-10 px); networks 2-3, 2-4 px
    "C004-3": {
        b: BEATS
        for b in (
            "finite differences, 2 points",
            "finite differences, 3 points",
            "cubic spline",
            "linear regression deg 1",
            "linear regression deg 2",
        )
    },
    "C004-3b": {"MLP back-prop": BEATS, "RBF network": BEATS},
    "C004-4": {
        "": Band(
            "the recursion reproduces the growing-memory least-squares estimate",
            "relative deviation <= 1e-9",
            None,
            1e-9,
            (0.0, 1e-12),
            (1e-6, 1e-3),
            unit="relative",
        )
    },
    # the paper reads it off eq. (6) ("from formula (6) it is obvious"): the closed-form gain falls as 9/N and the
    # variance sigma^2 g_N1 is an identity of least squares under the white noise of eq. (1)
    "C004-5": {
        "": Unchecked(
            "the correction is large for small n, tends to 0, and smoothing improves with n",
            "an identity of the derivation: the closed-form gain and the least-squares variance",
        )
    },
    "C004-6": {
        "": Band(
            "without a floor the accuracy degrades; the floor prevents it",
            "error without / with the floor >= 2",
            2.0,
            None,
            (2.5, 10.0),
            (1.0, 1.6),
            unit="ratio",
        )
    },
    "C004-7": {"": Unchecked("estimates exist from n = 3", "the quadratic through three samples, by construction")},
    "C004-8": {
        "": Band(
            "the algorithm works in real time",
            "time per frame / frame interval <= 1",
            None,
            1.0,
            (0.01, 0.5),
            (1.5, 10.0),
            unit="ratio",
        )
    },
}


def test_every_rule_of_004_decides_as_the_paper_says():
    assert not problems("p004_laser_spot_prediction", PINS), "\n".join(problems("p004_laser_spot_prediction", PINS))
