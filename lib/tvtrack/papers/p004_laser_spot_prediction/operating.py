"""The paper's operating point in every world of study 004: the wander's bandwidth each register world needs so
that the paper's filter errs what the paper says it errs.

The paper states its filter's one-step error, "1...2 pixels" (abstract, conclusions), and the default world is
calibrated to it (:mod:`.calibration`: the wander's bandwidth factor at which the filter errs 1.5 px per axis).
A world entry that changes the spectrum, the size of the wander, the camera or the frame rate moves that error:
at the default world's factor 9 of the register's 18 other world values put the filter outside 1-2 px (seed 2005,
15 x 500 frames: f^-6 0.49 px, f^-5/3 between the corners 0.65, half the amplitude 0.81, 200 frames/s 0.13; f^-2
4.2, double amplitude 3.2, jitter 1x and 4x 2.9 and 6.5, vibration 2.3), so a flip there compared methods at an
operating point the paper never saw. So each world value is re-calibrated: the register's ``bandwidth`` defaults
to ``"calibrated"``, which :func:`bandwidth_for` resolves to the factor at which the filter errs the register's
``error in the band`` in that world.

**The table.** :data:`WORLD_FACTORS` holds, per world value, the root of :func:`.calibration.calibrate_world`
(Brent's method, 1 % in the factor) divided by the default world's root, both on the same paths (seed 2005, 15
paths x 500 frames, common random numbers: the seed's own error in the root cancels in the ratio); the factor
applied is :data:`DEFAULT_BANDWIDTH` x that ratio. :data:`TARGET_FACTORS` does the same for the band's ends (the
default world at 1.0 and 2.0 px). :func:`.calibration.world_table` recomputes both (21 root finds, about 30 CPU
minutes on a loaded core: so the table is kept, not recomputed per run; the explorer pays nothing for it); a test
checks three rows on other paths. A configuration that changes several world entries at once gets the product of
their ratios (the filter's error is close to separable in them: amplitude x a function of the spectrum's shape and time
scale). Checked on three joint worlds (same seed and size): f^-6 with double amplitude errs 1.12 px, a flat
spectrum with jitter 1.64 px, 200 frames/s with 64 DN read noise and half the amplitude 1.50 px: inside the
paper's band, not at its middle. A value with no row (a default moved by a sweep) keeps the default's factor.

**Where re-calibration is not meaningful** the register marks the value ``off_operating_point``: the bandwidth's
own other values (the knob itself set by hand: the slow world, 0.33 px, and the fast one, 3.9 px), and any world in
which no bandwidth up to 0.4 x the frame rate puts the filter at 1.5 px (:data:`NO_ROOT`; none of today's).
"""

from __future__ import annotations

from .register import DEFAULT, WORLD

__all__ = [
    "CALIBRATED",
    "DEFAULT_BANDWIDTH",
    "BAND_POSITION",
    "WORLD_FACTORS",
    "TARGET_FACTORS",
    "NO_ROOT",
    "bandwidth_for",
]

#: The bandwidth entry's default: re-calibrated in every world (:func:`bandwidth_for`).
CALIBRATED = "calibrated"
#: The default world's factor (the calibration's root on the shipped-size data set, rounded).
DEFAULT_BANDWIDTH = 3.0
#: The register entry that places the world in the paper's 1-2 px (px per axis; an unreported setting).
BAND_POSITION = "error in the band"

#: {(entry, value): root in that world / root in the default world} (seed 2005, 15 x 500 frames, target 1.5 px).
WORLD_FACTORS: dict = {
    ("spectral index", 0.0): 0.8485,
    ("spectral index", 5 / 3): 2.2050,
    ("roll-off", "f^-2"): 0.1071,
    ("roll-off", "f^-6"): 1.8223,
    ("roll-off", "G-tilt"): 1.0730,
    ("amplitude", 0.5): 1.7641,
    ("amplitude", 2.0): 0.6037,
    ("jitter", 1.0): 0.5328,
    ("jitter", 4.0): 0.1981,
    ("frame rate", 200.0): 7.9949,
    ("read noise", 16.0): 0.9812,
    ("read noise", 64.0): 0.7874,
    ("saturation", "none"): 1.0001,
    ("scintillation", 0.8): 0.9933,
    ("energy centre", "whole gate"): 1.0025,
    ("exposure", "interlaced, frame integration"): 1.1820,
    ("spot size", 0.6): 0.8823,
    ("vibration", 1.0): 0.5027,
}
#: {target px: root at that target / root at 1.5 px}, both in the default world.
TARGET_FACTORS: dict = {1.0: 0.7382, 1.5: 1.0, 2.0: 1.2464}
#: World values in which no bandwidth puts the paper's filter at 1.5 px (marked off the operating point).
NO_ROOT: tuple = ()


def bandwidth_for(config: dict) -> float:
    """The wander's bandwidth factor of a register configuration (entries left out at their defaults).

    A number is used as it is (the bandwidth entry's uncalibrated worlds, or a factor set by hand).
    :data:`CALIBRATED` gives :data:`DEFAULT_BANDWIDTH` x the band position's ratio x the ratio of every world
    entry changed from its default that has a row in :data:`WORLD_FACTORS`.

    Returns
    -------
    float
        Factor on every corner frequency (dimensionless).
    """
    cfg = {**DEFAULT, **config}
    b = cfg["bandwidth"]
    if b != CALIBRATED:
        return float(b)
    out = DEFAULT_BANDWIDTH * TARGET_FACTORS.get(cfg.get(BAND_POSITION, 1.5), 1.0)
    for name in WORLD:
        if name != BAND_POSITION and cfg[name] != DEFAULT[name]:
            out *= WORLD_FACTORS.get((name, cfg[name]), 1.0)
    return float(out)
