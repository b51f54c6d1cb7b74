"""Each register entry's kind, with the line of the paper that decides it (:func:`tvtrack.register.with_kinds` applies
them; the three kinds are explained there)."""

from __future__ import annotations

#: {entry name: (kind, the line of the paper that decides it)}.
KINDS = {
    "motion": (
        "unreported setting",
        "an unreported setting: Fig. 1's 'x random, y a sinusoid' and nothing for the interference runs; the laws are never printed",
    ),
    "motion_scale": (
        "unreported setting",
        "an unreported setting: Fig. 1's 'Y: sinusoid, X: random' at amplitudes never printed (it was filed as a "
        "reading, with a hovering object that Fig. 1's moving object rules out; that is now the entry on whether the object moves in the interference runs)",
    ),
    "interference_motion": (
        "reading",
        "a reading of Fig. 3 (l. 198): the marker sweeps the interferers, and nothing says the object moved in the "
        "interference runs",
    ),
    "sinusoid_hz": (
        "unreported setting",
        "an unreported setting: Fig. 1's 'Y moves along a sinusoid' at a frequency never printed",
    ),
    "rotation_rate": (
        "unreported setting",
        "an unreported setting: l. 185 gives the mean rotation frequency; the law of the paper's own runs is never printed",
    ),
    "fig2_law": (
        "unreported setting",
        "an unreported setting: Fig. 2's omega and r 'vary sinusoidally' at a depth and rate never printed",
    ),
    "bandwidth_reading": ("reading", "a reading of 'bandwidths 10; 0.2 and 6 Hz'"),
    "slope_range": ("reading", "a reading of 'the quadrant form restores a linear part'"),
    "phase_loop": ("reading", "a reading of '6 Hz for omega' (l. 192)"),
    "noise": (
        "unreported setting",
        "an unreported setting: the sensor noise 'white, intensity N' has a value never printed",
    ),
    "fps": ("unreported setting", "an unreported setting: the frame rate of the paper's 'TV sensor' is never printed"),
    "exposure": ("unreported setting", "an unreported setting: the exposure of the paper's sensor is never printed"),
    "spot": ("reading", "a reading of the spot: a 'diameter' in the simulation, a square spot in eq. (9)"),
    "compensation": (
        "model",
        "a world beyond the paper: its compensation is a hypothesis ('equivalent to reducing the background by an order of magnitude'), the temporal median a method it does not name",
    ),
    "residual_background": (
        "reading",
        "a reading of 'marker brightness over the background std after compensation 50-100' (it was filed as a regime)",
    ),
    "interferer_radius": ("reading", "a reading of Fig. 3's interferers"),
    "interferer_layout": (
        "reading",
        "a reading of l. 198's 'the area where the five powerful stationary interferers are placed'",
    ),
    "interferer_size": (
        "unreported setting",
        "an unreported setting: the interferers' spots are never printed; what 2D changes is the flux, four times the marker's at the same SIR, so a flip under it comes from the brighter interferer, not from its size",
    ),
    "placement": (
        "reading",
        "a reading of l. 198: Fig. 3 shows 'the trace of the marker's emitter, which in its rotation sweeps the area "
        "where the five powerful stationary interferers are placed'; with the object moving, the area the marker "
        "sweeps is a band along the object's path ('trace', the paper's own description), of which the default circle "
        "about the start is one part",
    ),
    "loss_window_s": ("statistic", "a reading of 'loss of tracking', which the paper does not define"),
    "loss_radius": ("statistic", "a reading of 'loss of tracking': leaving the gate or the spot"),
    "horizon": (
        "unreported setting",
        "an unreported setting: the length of the paper's interference runs is never printed",
    ),
    "static_gate": ("comparator", "a reading of the static baseline at its own optimum"),
    "static_form": ("comparator", "a reading of 'the non-modulated' baseline"),
    "edge_norm": ("comparator", "a reading of the edge form's slope"),
    "decoy_brightness": ("comparator", "a reading of SIR (l. 198) for a decoy that is not compensated"),
}
