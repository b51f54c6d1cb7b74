"""Each register entry's kind, with the line of the paper that decides it (:func:`tvtrack.register.with_kinds` applies
them; the three kinds are explained there)."""

from __future__ import annotations

#: {entry name: (kind, the line of the paper that decides it)}.
KINDS = {
    "spectral index": (
        "unreported setting",
        "an unreported setting: the spectrum of the paper's own laser paths is never printed",
    ),
    "roll-off": (
        "unreported setting",
        "an unreported setting: the spectrum of the paper's own laser paths is never printed",
    ),
    "bandwidth": (
        "operating point",
        "a world beyond the paper: its default re-calibrates every world to the paper's operating point ('1...2 "
        "pixels'; where in that band is the entry 'error in the band'), and its only other values, 1 and 8, set the "
        "wander's speed by hand outside it (the paper's filter errs 0.33 and 3.9 px there)",
    ),
    "error in the band": (
        "unreported setting",
        "an unreported setting: where in its own '1...2 pixels' the paper's filter erred is never printed",
    ),
    "amplitude": (
        "unreported setting",
        "an unreported setting: the wander of the paper's own paths is never printed (no trace, only that the spot stays in 128 px)",
    ),
    "jitter": ("regime", "a world beyond the paper: frame-uncorrelated tilt its shipped-like paths do not carry"),
    "frame rate": ("reading", "a reading of '25 frames/s' against 'every 5 ms'"),
    "read noise": ("model", "a world beyond the paper: its camera's noise is not stated, 64 DN a spot barely above it"),
    "saturation": ("model", "a world beyond the paper: an 8-bit sensor or none"),
    "scintillation": ("regime", "a world beyond the paper: turbulence strengths it does not state"),
    "energy centre": ("reading", "a reading of the paper's energy-centre algorithm (its ref. [1])"),
    "horizon": ("reading", "a reading of 'prediction mode', which gives no horizon"),
    "network lags": ("comparator", "a reading of the MLP and RBF inputs, which the paper does not give"),
    "network inputs": ("comparator", "a reading of what the MLP and RBF network are fed"),
    "tuning": ("reading", "a reading of the floor and windows, which the paper does not give"),
    "reference": ("statistic", "a reading of the error the paper could score"),
    "C004-1 statistic": ("statistic", "a reading of 'does not exceed 2 pixels'"),
    "spline": ("comparator", "a reading of 'spline extrapolation' [5]"),
    "exposure": ("regime", "a world beyond the paper: its camera's exposure is not stated"),
    "spot size": ("model", "a world beyond the paper: a focused, undersampled spot"),
    "C004-3 statistic": ("statistic", "a reading of 'more accurate'"),
    "vibration": ("regime", "a world beyond the paper: a mount vibration it shows no spectrum of"),
    "C004-8 pipeline": ("reading", "a reading of 'functions in real time'"),
    "C004-8 statistic": ("statistic", "a reading of 'real time' as a deadline"),
    "C004-8 frame": (
        "unreported setting",
        "an unreported setting: the image area the paper's own program measured each frame over (the whole 128 x 128 "
        "image or a cut of it, its Fig. 2 'cut' option; the algorithm is its ref. [1]) is never printed",
    ),
    "C004-8 clock": ("statistic", "a reading of the time per frame"),
    "lost frames": ("model", "a world beyond the paper: its recursion counts samples on an even grid"),
    "frame loss": ("regime", "a world beyond the paper: frames lost to obscuration or deep fades"),
    "C004-5 noise": ("regime", "a world beyond the paper: heavy-tailed noise for the model's variance"),
    "C004-2 statistic": ("reading", "a reading of '1...2 pixels' (abstract, conclusions)"),
    "floor form": ("reading", "a reading of 'forbid further decrease of the correction term' (after eq. (6))"),
}
