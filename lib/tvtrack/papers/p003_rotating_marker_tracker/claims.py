"""The claims of paper 003 (Yukhno 2025) and the rules that decide them.

``CLAIMS`` holds what the paper says (statement and the paper's value); :func:`claim_rules` builds each claim's
rule for a marker of diameter ``D`` (px; the scenario's), and ``RULES`` is that for the default scenario.
"""

from __future__ import annotations

from ...verdicts import AllOf, InBand, Monotone, NotCheckable, Ordering, Rule
from .scene import Scenario
from .study import BXY_GRID, LINEAR_BAND, SIR_GRID

__all__ = ["CLAIMS", "RULES", "claim_rules"]


def _claim(statement: str, paper_value: str) -> dict[str, str]:
    return {"statement": statement, "paper_value": paper_value}


CLAIMS = {
    "C003-1": _claim(
        "The derived tracker follows x_r (random) and y_r (sinusoid) after a transient (Fig. 1).",
        "qualitative (Fig. 1)",
    ),
    "C003-2": _claim(
        "Because the coordinate loops are wide (10 Hz), the errors vary in step with the marker's rotation.",
        "qualitative (Fig. 1 text)",
    ),
    "C003-3": _claim(
        "Angular velocity and radius are tracked while they vary sinusoidally (Fig. 2).", "qualitative (Fig. 2)"
    ),
    "C003-4": _claim("The tracker is insensitive to the background thanks to compensation.", "qualitative"),
    "C003-5": _claim(
        "Five powerful stationary interferers in the swept area cause no loss and no switch to an interferer.",
        "no loss at SIR 3 (Fig. 3)",
    ),
    "C003-6": _claim("One interferer: loss-free SIR threshold 2 after compensation.", "2"),
    "C003-7": _claim("Five interferers: the threshold rises to 3.", "3"),
    "C003-8": _claim(
        "With compensation equal to a 10x background reduction the pre-compensation threshold is 0.2-0.3 (five "
        "interferers need >= 0.3).",
        "SIR_0 0.2 (one), 0.3 (five)",
    ),
    "C003-9": _claim(
        "Edge discriminators become relay-like or lose function for a round spot; the quadrant form restores a "
        "linear part and shape insensitivity.",
        "qualitative",
    ),
    "C003-10": _claim(
        "Robustness comes mainly from the narrow rotating gate following the emitter, plus compensation.",
        "qualitative; compensation a main factor (l. 208)",
    ),
    "C003-11": _claim(
        "Gate size trades loss of lock under dynamics against spatial selection of interferers; errors depend on "
        "loop bandwidths.",
        "qualitative",
    ),
    "C003-12": _claim(
        "Spatio-temporal modulation should raise immunity to interference imitating the marker, since an imitator "
        "must move by the marker's law.",
        "supposition (introduction)",
    ),
    "C003-13": _claim(
        "The synthesis is impossible with the traditional Stratonovich equation; the generalised form allows it.",
        "theoretical",
    ),
}


def _tracking_rules(D: float) -> dict[str, Rule]:
    """C003-1..4 and 9: the tracking claims, for a marker of diameter ``D`` (px)."""
    ratio = dict(measure="ratio")
    return {
        "C003-1": AllOf(
            {
                "x_r": InBand("post-transient RMS x_r error", high=D / 2, unit="px"),
                "y_r": InBand("post-transient RMS y_r error", high=D / 2, unit="px"),
                "lost": InBand("share of runs that lost lock", high=0.1),
            }
        ),
        "C003-2": AllOf(
            {
                "far": Ordering("rotation-locked x_r error amplitude", "amplitude locked to 1.5 f_rot", ">", **ratio),
                "near": Ordering(
                    "rotation-locked x_r error amplitude", "amplitude locked to f_rot + 1 Hz", ">", **ratio
                ),
                "wide_loops": Monotone(
                    "rotation-locked / near-control amplitude",
                    "B_xy " + " -> ".join(f"{b:g}" for b in BXY_GRID) + " Hz",
                ),
            }
        ),
        "C003-3": AllOf(
            {
                "omega": InBand("post-transient RMS (omega_hat - omega) / omega0", high=0.05),
                "r": InBand("post-transient RMS r error", high=1.0, unit="px"),
            }
        ),
        "C003-4": AllOf(
            {
                "spread": InBand(
                    "max / min compensated RMS miss over d/(kappa sigma_f) in {50, 100} and corr. length {4, 8, 16} px",
                    high=1.25,
                ),
                "compensation": Ordering(
                    "share of runs lost without compensation (d/sigma_f = 5)", "with compensation", ">"
                ),
            }
        ),
        "C003-9": AllOf(
            {
                "square_linear": InBand("quadrant slope (slope_range) / 2dD, square", *LINEAR_BAND),
                "disc_linear": InBand("quadrant slope (slope_range) / 2dD, disc", *LINEAR_BAND),
                "edge_square": Ordering("edge-form mean-square miss", "quadrant form's (square)", ">", **ratio),
                "edge_disc": Ordering("edge-form mean-square miss", "quadrant form's (disc)", ">", **ratio),
            }
        ),
    }


def _interference_rules() -> dict[str, Rule]:
    """C003-5, 6, 7, 10, 11 and 12: the interference claims."""

    def p_at(s, n):
        return f"P(loss within T) at SIR {s:.3g}, {n} interferer(s)"

    ratio = dict(measure="ratio")
    return {
        "C003-5": AllOf(
            {
                "no_loss": InBand(p_at(3, 5), high=0.1),
                "no_capture": InBand("P(capture by an interferer) at SIR 3, five interferers", high=0.1),
            }
        ),
        "C003-6": AllOf(
            {
                "finite": InBand(p_at(0.5, 1), low=0.1),
                "loss_free": InBand(p_at(2, 1), high=0.1),
                "not_lower": InBand(p_at(4 / 3, 1) + " (a grid step below 2)", low=0.1, better="lower"),
            }
        ),
        "C003-7": AllOf(
            {
                "loss_free": InBand(p_at(3, 5), high=0.1),
                "not_lower": InBand(p_at(2, 5) + " (a grid step below 3)", low=0.1, better="lower"),
                "rise": Ordering("threshold with five interferers", "with one", ">", **ratio),
            }
        ),
        "C003-10": AllOf(
            {
                "gate": Monotone("threshold, five interferers", "gate side 1.5D -> 3D -> 5D", "increasing"),
                # the paper's order of magnitude, factor 2
                "compensation": InBand("compensated / uncompensated SIR_0 threshold (see note)", high=2 * 0.1),
            }
        ),
        "C003-11": AllOf(
            {
                "dynamics": InBand(f"P(loss within T) of the 1.5D gate at SIR {SIR_GRID[-1]:g}", low=0.1),
                "selection": Ordering("threshold of the 5D gate", "of the 3D gate", ">", **ratio),
                "bandwidth": Ordering("mean-square miss with B_xy = 20 Hz", "with 5 Hz", "<", **ratio),
            }
        ),
        "C003-12": AllOf(
            {
                "one": Ordering("static marker's threshold", "rotating marker's (one interferer)", ">", **ratio),
                "five": Ordering("static marker's threshold", "rotating marker's (five interferers)", ">", **ratio),
                "imitator": Ordering(
                    "threshold against a decoy that follows the marker's law",
                    "against one stationary emitter",
                    ">",
                    **ratio,
                ),
            }
        ),
    }


def claim_rules(diameter: float | None = None) -> dict[str, Rule]:
    """``{claim id: rule}`` for a marker of ``diameter`` px (the default scenario's if None), in claim order."""
    D = Scenario().diameter if diameter is None else diameter
    rules = _tracking_rules(D) | _interference_rules()
    rules["C003-8"] = NotCheckable(
        "In this compensation model SIR_0 = kappa SIR by construction (compensation scales the whole static scene, "
        "interferers included), so the pre-compensation thresholds are kappa times C003-6/7's and carry no "
        "separate evidence."
    )
    rules["C003-13"] = NotCheckable("A statement about the derivation, not about tracker behaviour.")
    return {cid: rules[cid] for cid in CLAIMS}


RULES = claim_rules()
