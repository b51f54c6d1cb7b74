"""Rule pins of paper 003 (Yukhno 2025): each claim's rule decides synthetic values either side of the paper's
statement as the paper says (tests/rule_pins.py), for the default marker of diameter D = 8 px. Sentences and bands
from the paper's text and the acceptance bands set here; the values are written here, not read from claims.py. "No loss"
over a run count is read as a loss probability at most 0.1 (the project's reading of 0 of 20 runs)."""

from rule_pins import Band, Order, Trend, Unchecked, problems

GREATER = dict(yes=(1.3, 3.0), no=(0.7, 0.3))  # a ratio a / b: above 1 where the paper says a > b
UP, DOWN = ((1.0, 2.0, 4.0),), ((4.0, 2.0, 1.0),)
RARE = dict(low=None, high=0.1, inside=(0.0, 0.05), outside=(0.2, 0.8))  # "no loss": probability <= 0.1
OFTEN = dict(low=0.1, high=None, inside=(0.2, 0.8), outside=(0.0, 0.05))  # "losses occur": probability >= 0.1
FOLLOWS = Band(
    "the tracker follows x_r and y_r after a transient",
    "RMS error < D/2 = 4 px",
    None,
    4.0,
    (1.0, 3.5),
    (5.0, 20.0),
    unit="px",
)
LINEAR = Band(
    "the quadrant form restores a linear part",
    "slope / 2dD in [0.9, 1.1]",
    0.9,
    1.1,
    (1.0, 0.95, 1.05),
    (0.5, 0.85, 1.2),
)
EDGE_WORSE = Order(
    "edge discriminators become relay-like or lose function (no factor given; >= 2x suggested here; rule: > 1)",
    "edge / quadrant mean-square miss > 1",
    **GREATER,
)

PINS = {
    "C003-1": {
        "x_r": FOLLOWS,
        "y_r": FOLLOWS,
        "lost": Band("the tracker works (no loss in the runs)", "P(loss) <= 0.1", **RARE),
    },
    "C003-2": {
        "far": Order("the errors vary in step with the marker's rotation", "rotation-locked / control > 1", **GREATER),
        "near": Order("... in step with the rotation, not broadband", "rotation-locked / near control > 1", **GREATER),
        "wide_loops": Trend("because the loops are wide (10 Hz)", "locked share increasing in B_xy", UP, DOWN),
    },
    "C003-3": {
        "omega": Band("angular velocity is tracked", "RMS / mean rate < 5 %", None, 0.05, (0.01, 0.04), (0.1, 0.5)),
        "r": Band("radius is tracked", "RMS error < 1 px", None, 1.0, (0.2, 0.9), (1.5, 5.0), unit="px"),
    },
    "C003-4": {
        "spread": Band(
            "insensitive to the background", "RMS changes < 25 % across backgrounds", None, 1.25, (1.0, 1.2), (1.5, 3.0)
        ),
        "compensation": Order(
            "... thanks to compensation", "loss share without - with compensation > 0", (0.3, 0.9), (-0.3, -0.9)
        ),
    },
    "C003-5": {
        "no_loss": Band(
            "five interferers cause no loss", "P(loss) at SIR 3 <= 0.1", **RARE, says=("at SIR 3 with 5 interferer",)
        ),
        "no_capture": Band("... and no switch to an interferer", "P(capture) <= 0.1", **RARE),
    },
    "C003-6": {
        "finite": Band(
            "one interferer: a finite threshold",
            "P(loss) at SIR 0.5 >= 0.1",
            **OFTEN,
            says=("at SIR 0.5 with 1 interferer",),
        ),
        "loss_free": Band(
            "loss-free at SIR 2", "P(loss) at SIR 2 <= 0.1", **RARE, says=("at SIR 2 with 1 interferer",)
        ),
        "not_lower": Band(
            "the threshold is 2, not lower",
            "P(loss) a grid step below 2 >= 0.1",
            **OFTEN,
            says=("at SIR 1.33 with 1 interferer",),
        ),
    },
    "C003-7": {
        "loss_free": Band(
            "five interferers: loss-free at SIR 3",
            "P(loss) at SIR 3 <= 0.1",
            **RARE,
            says=("at SIR 3 with 5 interferer",),
        ),
        "not_lower": Band(
            "the threshold is 3, not lower",
            "P(loss) a grid step below 3 >= 0.1",
            **OFTEN,
            says=("at SIR 2 with 5 interferer",),
        ),
        "rise": Order("the threshold rises to 3 (from 2)", "threshold(5) / threshold(1) > 1", **GREATER),
    },
    "C003-8": {"": Unchecked("pre-compensation threshold 0.2-0.3", "SIR_0 = kappa SIR by construction here")},
    "C003-9": {
        "square_linear": LINEAR,
        "disc_linear": LINEAR,
        "edge_square": EDGE_WORSE,
        "edge_disc": EDGE_WORSE,
    },
    "C003-10": {
        "gate": Trend(
            "robustness comes mainly from the narrow gate",
            "threshold increasing in gate size",
            UP,
            DOWN,
            says=("five interferers", "gate side 12 -> 24 -> 40 px"),
        ),
        # the uncompensated scene at SIR_0 = x holds the compensated scene's interferers at SIR = x with 1/kappa
        # times its background: the ratio is at most kappa by construction (as C003-8)
        "compensation": Unchecked(
            "compensation a main factor (l. 208); 0.2-0.3 before compensation (l. 198)",
            "ratio <= kappa by construction in the kappa model",
        ),
    },
    "C003-11": {
        "dynamics": Band("small gates lose lock under dynamics", "P(loss) with a 1.5 D gate >= 0.1", **OFTEN),
        "selection": Order("large gates admit interferers", "threshold(5 D gate) / threshold(3 D gate) > 1", **GREATER),
        "bandwidth": Band(
            "errors depend substantially on the loop bandwidths",
            "fold change >= 1.25",
            1.25,
            None,
            (1.5, 4.0),
            (1.0, 1.1),
        ),
    },
    "C003-12": {
        "one": Order("modulation raises immunity (one interferer)", "static / rotating threshold > 1", **GREATER),
        "five": Order("... (five interferers)", "static / rotating threshold > 1", **GREATER),
        "imitator": Order("an imitator must move by the marker's law", "decoy / stationary threshold > 1", **GREATER),
    },
    "C003-13": {"": Unchecked("synthesis impossible with the traditional equation", "about the derivation")},
}


def test_every_rule_of_003_decides_as_the_paper_says():
    assert not problems("p003_rotating_marker_tracker", PINS), "\n".join(problems("p003_rotating_marker_tracker", PINS))


def test_the_tracking_bound_is_half_the_marker_diameter_at_any_diameter():
    """The acceptance set here: RMS error < D/2; gates in spot diameters (1.5, 3, 5 D)."""
    from tvtrack.papers.p003_rotating_marker_tracker.claims import claim_rules

    rules = claim_rules(10.0)
    assert [rules["C003-1"].parts[k].high for k in ("x_r", "y_r")] == [5.0, 5.0]
    assert "15 px gate" in rules["C003-11"].parts["dynamics"].quantity
    assert (
        "50 px gate" in rules["C003-11"].parts["selection"].a and "30 px gate" in rules["C003-11"].parts["selection"].b
    )
