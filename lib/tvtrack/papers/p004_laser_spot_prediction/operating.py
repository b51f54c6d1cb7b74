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
default world at 1.0 and 2.0 px). :func:`.calibration.world_table` recomputes both (23 root finds, about 30 CPU
minutes on a loaded core: so the table is kept, not recomputed per run; the explorer pays nothing for it); a test
checks three rows on other paths. A value with no row (a default moved by a sweep) keeps the default's factor.

**Joint worlds.** The product of the ratios is only a first guess where a configuration changes two or more
tabled values (the band position counts as one): the error is not separable where a source that does not scale
with the wander (jitter, mount vibration, the camera's noise) meets one that changes the wander's speed or the
sampling. At the product, 200 frames/s with the f^-5/3 spectrum, 16 DN read noise, no saturation, the whole gate's
energy centre and 1 px vibration errs 0.49 x the default world (about 0.7 px at the paper profile, below the
paper's 1-2 px; each value alone is inside it). So :func:`joint_factor` corrects the product on the table's own
paths (seed 2005, the first :data:`JOINT_PATHS` of its 15 x 500 frames: within 2 % of all 15 in the error's
ratio): it measures the error at the product; if that is more than :data:`JOINT_TOL` from the default world's at
the band position (same paths), one power-law step with the default world's exponent (:data:`BAND_SLOPE`, from
:data:`TARGET_FACTORS`' band ends) and, if still outside, one secant step on the two measured points, measured
where it ends; the measured factor nearest the target is kept (a secant step may overshoot). At most three
evaluations per distinct world combination (about 0.5 CPU s each), cached per combination, the same for every
replicate and seed. A world whose error hardly moves with the bandwidth (secant exponent below
:data:`MIN_SLOPE`: a noise floor above the band, or jitter below it) takes no secant step. A joint world whose
filter, at the factor kept, errs outside the paper's 1-2 px by more than :data:`JOINT_TOL` (read on the table's
scale) is listed in :data:`JOINT_OUTSIDE_BAND`: the explorer counts its configurations beside the labels
(docs/validity/004.md).

**The horizon.** The paper does not state its prediction horizon (the register reads one frame, and 3 and 10 as
other readings of "prediction mode"), so its "1...2 pixels" is its filter's error at that unstated horizon. Under
another horizon reading the world is therefore calibrated at that horizon: the horizon is tabled like a world value
(:data:`OPERATING_READINGS`; at the default world's factor 3 the filter errs 1.6 px at one frame, 4.9 px at 3
and 7.1 px at 10 on the table's paths), and a horizon read with a world value changed is corrected as a joint world. Without
it the horizon's flips compared methods where the paper's filter errs three to five times the paper's band.

**Where re-calibration is not meaningful** the register marks the value ``off_operating_point``: the bandwidth's
own other values (the knob itself set by hand: the slow world, 0.33 px, and the fast one, 3.9 px), and any world in
which no bandwidth up to 0.4 x the frame rate puts the filter at 1.5 px (:data:`NO_ROOT`; none of today's).
"""

from __future__ import annotations

import math

from .register import DEFAULT, NAMES, WORLD

__all__ = [
    "CALIBRATED",
    "DEFAULT_BANDWIDTH",
    "BAND_POSITION",
    "WORLD_FACTORS",
    "TARGET_FACTORS",
    "NO_ROOT",
    "bandwidth_for",
    "joint_factor",
    "table_factors",
    "BAND_SLOPE",
    "JOINT_TOL",
    "JOINT_PATHS",
    "MIN_SLOPE",
    "JOINT_OUTSIDE_BAND",
    "BAND_PX",
    "OPERATING_READINGS",
]

#: The bandwidth entry's default: re-calibrated in every world (:func:`bandwidth_for`).
CALIBRATED = "calibrated"
#: The default world's factor (the calibration's root on the shipped-size data set, rounded).
DEFAULT_BANDWIDTH = 3.0
#: The register entry that places the world in the paper's 1-2 px (px per axis; an unreported setting).
BAND_POSITION = "error in the band"

#: Readings of the paper's text that say where its stated error applies: the world is calibrated at them too.
OPERATING_READINGS = ("horizon",)

#: {(entry, value): root in that world / root in the default world} (seed 2005, 15 x 500 frames, target 1.5 px);
#: the horizon's rows: the root at that horizon in the default world over the root at one frame.
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
    ("horizon", 3): 0.3354,
    ("horizon", 10): 0.0971,
}
#: {target px: root at that target / root at 1.5 px}, both in the default world.
TARGET_FACTORS: dict = {1.0: 0.7382, 1.5: 1.0, 2.0: 1.2464}
#: World values in which no bandwidth puts the paper's filter at 1.5 px (marked off the operating point).
NO_ROOT: tuple = ()


#: The default world's exponent of the error in the bandwidth (error ~ b^k) between the band's ends: log 2 over
#: log of the ratio of their roots (about 1.32).
BAND_SLOPE = math.log(2.0) / math.log(TARGET_FACTORS[2.0] / TARGET_FACTORS[1.0])
#: A joint world's error may differ from the default world's at the band position by this share (same paths).
JOINT_TOL = 0.05
#: Paths of the table's 15 x 500 frames a joint world's correction is measured on.
JOINT_PATHS = 8
#: Below this secant exponent the bandwidth hardly moves the error: no bandwidth puts the world in the band.
MIN_SLOPE = 0.25
#: Bandwidth factors of a joint world: [lowest, highest x frame rate] (as :func:`.calibration.world_bracket`).
FACTOR_RANGE = (0.05, 0.8)
#: {world combination: factor} of :func:`joint_factor` (this process; the explorer's workers inherit it).
_JOINT: dict = {}
_REFERENCE: dict = {}  # {band position: the default world's error there on the joint worlds' paths}
#: The paper's own error band, px per axis ("1...2 pixels", abstract and conclusions): its operating point.
BAND_PX = (1.0, 2.0)
#: {world combination: (factor, the paper's filter's error there, px per axis on the table's scale)} of the joint
#: worlds whose corrected filter still errs outside :data:`BAND_PX` (by more than :data:`JOINT_TOL`): outside the
#: paper's operating point.
JOINT_OUTSIDE_BAND: dict = {}


def table_factors(config: dict) -> tuple:
    """``(product, world, rows)``: :data:`DEFAULT_BANDWIDTH` x the band position's ratio x the ratio of every
    world entry (or :data:`OPERATING_READINGS` entry) changed from its default that has a row in
    :data:`WORLD_FACTORS`; the configuration's changed world entries (bandwidth aside) and operating readings as a
    tuple of (entry, value) in the register's order, the key of :func:`joint_factor`; and how many of them have a
    row (the band position's in :data:`TARGET_FACTORS`)."""
    cfg = {**DEFAULT, **config}
    band = cfg.get(BAND_POSITION, 1.5)
    out = DEFAULT_BANDWIDTH * TARGET_FACTORS.get(band, 1.0)
    tabled = [n for n in NAMES if (n in WORLD and n != "bandwidth") or n in OPERATING_READINGS]
    world = tuple((n, cfg[n]) for n in tabled if cfg[n] != DEFAULT[n])
    rows = sum((n, v) in WORLD_FACTORS or (n == BAND_POSITION and v in TARGET_FACTORS) for n, v in world)
    for name, v in world:
        if name != BAND_POSITION:
            out *= WORLD_FACTORS.get((name, v), 1.0)
    return float(out), world, int(rows)


def bandwidth_for(config: dict) -> float:
    """The wander's bandwidth factor of a register configuration (entries left out at their defaults).

    A number is used as it is (the bandwidth entry's uncalibrated worlds, or a factor set by hand).
    :data:`CALIBRATED` gives :func:`table_factors`' product where at most one tabled value is changed (a table
    row, exactly), and :func:`joint_factor` where two or more are.

    Returns
    -------
    float
        Factor on every corner frequency (dimensionless).
    """
    cfg = {**DEFAULT, **config}
    if cfg["bandwidth"] != CALIBRATED:
        return float(cfg["bandwidth"])
    product, world, rows = table_factors(cfg)
    if rows < 2:
        return product
    if world not in _JOINT:
        raise LookupError(
            f"the joint world {dict(world)} has no corrected bandwidth yet: "
            "study.resolve_operating_point(config) corrects it before its scene is drawn"
        )
    return _JOINT[world]


def _within(r: float, ref: float) -> bool:
    return abs(math.log(r / ref)) <= math.log1p(JOINT_TOL)


def joint_factor(world: tuple, rms) -> float:
    """The bandwidth factor of a joint world ``world`` ((entry, value) pairs, :func:`table_factors`): the
    product of its rows, corrected with ``rms`` (a configuration with a numeric bandwidth -> the paper's filter's
    per-axis error on the table's paths, px: :func:`.study.table_paths_rms` on the first :data:`JOINT_PATHS`)
    towards the default world's error at the band position on the same paths: kept if within
    :data:`JOINT_TOL`; else one power-law step (:data:`BAND_SLOPE`); if still outside, one secant step on the two
    measured points (exponent at least :data:`MIN_SLOPE`; below it the bandwidth hardly moves the error), its error
    measured there; the measured factor nearest the target is kept (a secant step may overshoot). A world whose
    filter at the factor kept errs outside the paper's :data:`BAND_PX` by more than :data:`JOINT_TOL` is outside the
    paper's operating point (:data:`JOINT_OUTSIDE_BAND`); its error is read on the table's scale (times the band
    position over the default world's error there on the same paths, since those paths err a few per cent off the
    table's 15). One that misses the band position but stays in the band is kept. Cached per ``world``."""
    if world in _JOINT:
        return _JOINT[world]
    config = {**dict(world), "bandwidth": CALIBRATED}
    band = config.get(BAND_POSITION, DEFAULT[BAND_POSITION])
    lo, hi = FACTOR_RANGE[0], FACTOR_RANGE[1] * float({**DEFAULT, **config}["frame rate"])
    clip = lambda b: min(max(b, lo), hi)  # noqa: E731
    if band not in _REFERENCE:  # the default world at the band position, on the same paths
        b_ref = table_factors({BAND_POSITION: band})[0]
        _REFERENCE[band] = rms({BAND_POSITION: band, "bandwidth": b_ref})
    ref = _REFERENCE[band]
    at = lambda b: rms({**config, "bandwidth": b})  # noqa: E731
    b0 = table_factors(config)[0]
    tried = [(b0, at(b0))]
    if not _within(tried[-1][1], ref):
        r0 = tried[0][1]
        b1 = clip(b0 * (ref / r0) ** (1.0 / BAND_SLOPE))
        tried.append((b1, at(b1) if b1 != b0 else r0))
        r1 = tried[-1][1]
        k = math.log(r1 / r0) / math.log(b1 / b0) if b1 != b0 else 0.0
        if not _within(r1, ref) and k >= MIN_SLOPE:  # below MIN_SLOPE the bandwidth hardly moves the error
            b2 = clip(b1 * (ref / r1) ** (1.0 / k))
            tried.append((b2, at(b2) if b2 != b1 else r1))  # measured where it ends: a secant may overshoot
    out, err = min(tried, key=lambda p: abs(math.log(p[1] / ref)))  # the measured point nearest the target
    scaled = err * band / ref  # px on the table's scale: the default world errs ``band`` px there
    lo, hi = BAND_PX[0] / (1.0 + JOINT_TOL), BAND_PX[1] * (1.0 + JOINT_TOL)  # the band, give the correction's tolerance
    if not lo <= scaled <= hi:
        JOINT_OUTSIDE_BAND[world] = (float(out), float(scaled))
    _JOINT[world] = float(out)
    return _JOINT[world]
