"""Rule pins of paper 000 (Martyshevsky 1995): each claim's rule decides synthetic values either side of the paper's
statement as the paper says (tests/rule_pins.py). Sentences and bands from the paper's conclusions and its card's
claims table; the values are written here, not read from claims.py."""

from rule_pins import Band, Order, Trend, Unchecked, problems

RATIO_UP = "error variance over sigma_x^2* rises with P"
SAME = Band(
    "the two algorithms give approximately the same potential accuracy",
    "v1 / v2 in [0.8, 1.25]",
    0.8,
    1.25,
    (1.0, 0.85, 1.2),
    (0.7, 1.4),
)
DT = Band(
    "dt = 0.05 keeps discretisation errors within 3 %",
    "|relative change| <= 0.03",
    -0.03,
    0.03,
    (0.0, 0.02, -0.02),
    (0.05, -0.05, 0.3),
)
SHARE = Band(
    "both algorithms converge fairly quickly (default reading: 90 % of runs in lock)",
    "share not in lock <= 0.1",
    None,
    0.1,
    (0.0, 0.05),
    (0.2, 0.5),
)
WITHIN_10 = Band(
    "converge: sigma_x^2 within 10 % of its steady state",
    "ratio in [0.9, 1.1]",
    0.9,
    1.1,
    (1.0, 0.95, 1.05),
    (0.8, 1.2),
)
LOW_P = Band(
    "for P < 0.5 the non-stationary noise does not substantially affect accuracy",
    "ratio <= 1.3",
    None,
    1.3,
    (1.0, 1.2),
    (1.5, 3.0),
)
HIGH_P = Band("for P > 0.5 it substantially determines accuracy", "ratio >= 2", 2.0, None, (2.5, 10.0), (1.5, 1.0))

PINS = {
    "C000-1": {
        "convergence criterion=90 % of runs acquired / variant *": SHARE,
        "convergence criterion=*default* / variant *": SHARE,
        "convergence criterion=ensemble mean within 10 % / variant *": WITHIN_10,
    },
    "C000-2": {
        "P=*": Band(
            "at psi_A = 20 the coordinate error is 2 % of the micro-raster size",
            "sigma_x / T in [0.01, 0.03]",
            0.01,
            0.03,
            (0.02, 0.015, 0.028),
            (0.005, 0.04, 0.2),
        ),
    },
    "C000-3": {
        "P=0": Unchecked("same potential accuracy", "at P = 0 the two variants are one filter"),
        "P=0.*": SAME,
        "psi_A=*": SAME,
    },
    "C000-4": {"": Order("variant 1 needs more computation", "cost v1 / cost v2 > 1", (1.5, 4.0), (0.67, 0.25))},
    "C000-5": {
        "substantially determines=* / P=0.25": LOW_P,
        "substantially determines=* / P=0.5": LOW_P,
        "substantially determines=* / P=0.7": HIGH_P,
        "substantially determines=* / P=0.9": HIGH_P,
    },
    "C000-6": {
        "": Band(
            "at P = 0.9 the variance exceeds the achievable one by more than 20 times",
            "ratio > 20",
            20.0,
            None,
            (25.0, 100.0),
            (15.0, 2.0),
        ),
    },
    "C000-7": {
        "trend": Trend(
            "sigma_x^2 grows with P relative to sigma_x^2*",
            RATIO_UP + " (increasing in P)",
            ((1.0, 1.5, 3.0, 30.0),),
            ((30.0, 3.0, 1.5, 1.0), (1.0, 5.0, 2.0, 30.0)),
        ),
        "measurement vs estimate": Order(
            "the measurement variance grows faster than the estimate variance",
            "measurement ratio - estimate ratio > 0",
            (1.0, 20.0),
            (-1.0, -20.0),
        ),
    },
    "C000-8": {"variant * at psi_A=*, P=*": DT},
    "C000-9": {
        "variant *": Trend(
            "sigma_x^2 decreases with psi_A (Fig. 2)",
            "decreasing in psi_A",
            ((1e-2, 1e-3, 1e-4),),
            ((1e-4, 1e-3, 1e-2),),
        ),
    },
    "C000-10": {"": Unchecked("experiment agrees with the model", "no experimental data in the paper")},
}


def test_every_rule_of_000_decides_as_the_paper_says():
    assert not problems("p000_dissector_ekf", PINS), "\n".join(problems("p000_dissector_ekf", PINS))
