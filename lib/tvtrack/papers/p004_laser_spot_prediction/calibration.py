"""The calibrated world of paper 004: the wander's bandwidth at which the paper's own filter errs what the paper
says it errs.

The paper (Kokryatska and Hrynchyshyn 2005) reports its method's one-step error as "1...2 pixels" (abstract,
conclusions) on recordings that are not available. A synthetic world in which the filter errs a third of that is
an operating point the paper never saw, and comparisons made there (C004-3: a line against the filter's quadratic)
are made in the wrong regime. So the world is calibrated: one knob of the generator is searched until the paper's
filter, tuned as everywhere (floor cross-validated over paths), errs :data:`TARGET_PX` per axis on a data set of
the shipped size (15 paths x 1000 frames) at the paper's horizon (one frame).

**Which knob.** The wander's *bandwidth* (every corner frequency x a factor; the spectrum's shape and the paths'
range kept). The amplitude cannot reach the band: the error is nearly all motion (the energy centre errs 0.04 px),
so it grows linearly with the amplitude, and at the largest amplitude the generator allows with the spot inside the
128 px frame (RMS <= 128/6 px, amplitude 2.67) the filter errs 0.8 px. The bandwidth is also the least known
property of the world: the wander's time scale W0/V_perp is unknown within an order of magnitude (no range, beam
size or wind speed is given). The roll-off is a register reading (f^-2, f^-4, f^-6, G-tilt), not a scale.

**The search.** :func:`calibrate_bandwidth`: Brent's root finder (:func:`scipy.optimize.brentq`) on
``log(rms(b) / target)`` over ``log b`` in a bracket, every evaluation on the same seed (common random numbers:
the same paths, faster or slower), so ``rms(b)`` is a smooth increasing function of ``b`` up to the floor's
discrete choice.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
from scipy.optimize import brentq

from .beam_wander import BeamWanderConfig, scaled_config
from .register import DEFAULT
from .sizes import StudySize
from .study import paper_filter_rms

__all__ = [
    "TARGET_PX",
    "Calibration",
    "calibrate_bandwidth",
    "world_bracket",
    "calibrate_world",
    "world_table",
    "shipped_config_at",
]

#: The calibration's target: the middle of the band, px per axis.
TARGET_PX = 1.5


@dataclass(frozen=True)
class Calibration:
    """Result of :func:`calibrate_bandwidth`.

    Attributes
    ----------
    entry : str
        The register entry calibrated ("bandwidth": every corner frequency x ``scale``).
    scale : float
        The calibrated value (dimensionless factor on today's corners 0.02, 0.1, 0.5 Hz).
    rms_px : float
        The paper filter's per-axis RMS one-step error at ``scale``, px.
    target_px : float
        The target, px.
    evaluations : tuple of (float, float)
        Every (scale, rms px) the search evaluated, in order.
    """

    entry: str
    scale: float
    rms_px: float
    target_px: float
    evaluations: tuple


def calibrate_bandwidth(
    seed: int,
    size,
    target_px: float = TARGET_PX,
    bracket: tuple = (1.0, 8.0),
    config: dict | None = None,
    traces_seed: int | None = None,
    xtol: float = 0.005,
) -> Calibration:
    """The bandwidth factor at which the paper's filter errs ``target_px`` per axis (:func:`paper_filter_rms`).

    Brent's method on ``log(rms(b) / target)`` over ``log b`` in ``bracket``; ``xtol`` is the tolerance on
    ``log b`` (0.005: the factor to 0.5 %).

    Parameters
    ----------
    seed, size, traces_seed :
        As :func:`paper_filter_rms` (one seed for every evaluation: common random numbers).
    bracket : (float, float)
        Factors whose errors straddle the target (the fastest corner, 0.5 Hz x b, stays below the 12.5 Hz
        Nyquist frequency of 25 frames/s up to b = 25).
    config : dict, optional
        The rest of the world (default: the register's defaults, the bandwidth aside).

    Returns
    -------
    Calibration

    Raises
    ------
    ValueError
        If the bracket's errors do not straddle the target.
    """
    evals: dict = {}  # {scale: rms px}, in evaluation order

    def rms(b: float) -> float:
        if b not in evals:
            evals[b] = paper_filter_rms({**(config or {}), "bandwidth": b}, seed, size, traces_seed)
        return evals[b]

    gap = lambda log_b: float(np.log(rms(float(np.exp(log_b))) / target_px))  # noqa: E731
    lo, hi = (float(np.log(b)) for b in bracket)
    if gap(lo) * gap(hi) > 0:
        raise ValueError(
            f"parameter 'bracket' = {bracket}: the filter errs {rms(np.exp(lo)):.3g} and {rms(np.exp(hi)):.3g} px "
            f"there; both on one side of the target {target_px:g} px"
        )
    b = float(np.exp(brentq(gap, lo, hi, xtol=xtol)))
    r = rms(b)
    evaluations = tuple((float(k), float(v)) for k, v in evals.items())
    return Calibration("bandwidth", b, float(r), float(target_px), evaluations)


def world_bracket(
    config: dict, seed: int, size, target_px: float = TARGET_PX, start: float = 3.0, step: float = 2.0
) -> tuple | None:
    """Bandwidth factors ``(lo, hi)`` whose errors straddle ``target_px`` in the world ``config`` (its bandwidth
    aside), stepping from ``start`` by ``step`` towards the target; None where none is found before the fastest
    corner (0.5 Hz x b) reaches 0.4 x the frame rate or b falls below 0.05 (no bandwidth puts this world at the
    target: it leaves the paper's operating point).

    Returns
    -------
    (float, float) or None
    """
    fs = float({**DEFAULT, **config}["frame rate"])
    b_max, b_min = 0.8 * fs, 0.05
    b = float(start)
    r = paper_filter_rms({**config, "bandwidth": b}, seed, size)
    up = r < target_px
    while True:
        nxt = b * step if up else b / step
        nxt = min(nxt, b_max) if up else max(nxt, b_min)
        if nxt == b:
            return None
        rn = paper_filter_rms({**config, "bandwidth": nxt}, seed, size)
        if (rn >= target_px) == up:
            return (b, nxt) if up else (nxt, b)
        b = nxt


def calibrate_world(
    config: dict, seed: int, size, target_px: float = TARGET_PX, xtol: float = 0.01
) -> Calibration | None:
    """:func:`calibrate_bandwidth` in the world ``config`` (a register configuration, its bandwidth aside) from the
    bracket :func:`world_bracket` finds; None where no bandwidth puts the paper's filter at ``target_px``."""
    br = world_bracket(config, seed, size, target_px)
    if br is None:
        return None
    return calibrate_bandwidth(seed, size, target_px, br, config=config, xtol=xtol)


def world_table(seed: int = 2005, size=None, targets=(1.0, 2.0)) -> dict:
    """Recompute :mod:`.operating`'s table: per world value (every register world entry but the bandwidth and the
    band position, and every value of the readings that say where the paper's error applies, the horizon), the root of :func:`calibrate_world` over the default world's root at 1.5 px, and per band end
    in ``targets`` the default world's root there over it (one seed, common random numbers).

    Parameters
    ----------
    seed : int
    size : sizes.StudySize, optional
        Default: 15 paths x 500 frames (23 root finds).

    Returns
    -------
    dict
        ``{"world": {(entry, value): ratio}, "targets": {px: ratio}, "no_root": [(entry, value)], "at_default":
        {(entry, value): filter RMS px at the default world's factor}}``.
    """
    from .operating import BAND_POSITION, OPERATING_READINGS
    from .register import ROWS, WORLD

    size = size or StudySize(n_frames=500)
    base = calibrate_world({}, seed, size)
    out = {"world": {}, "targets": {}, "no_root": [], "at_default": {}}
    for t in targets:
        out["targets"][t] = calibrate_world({}, seed, size, t).scale / base.scale
    for name, _, default, values, *_ in ROWS:
        if (name not in WORLD and name not in OPERATING_READINGS) or name in ("bandwidth", BAND_POSITION):
            continue
        for v in values:
            if v == default:
                continue
            out["at_default"][(name, v)] = paper_filter_rms({name: v, "bandwidth": base.scale}, seed, size)
            cal = calibrate_world({name: v}, seed, size)
            if cal is None:
                out["no_root"].append((name, v))
            else:
                out["world"][(name, v)] = cal.scale / base.scale
    return out


def shipped_config_at(metadata: dict, bandwidth: float) -> BeamWanderConfig:
    """The shipped data set's generator configuration (its ``metadata``) with every corner x ``bandwidth``."""
    cfg = metadata["config"]
    base = BeamWanderConfig(**{**cfg, "corner_frequencies_hz": tuple(cfg["corner_frequencies_hz"])})
    return scaled_config(replace(base), bandwidth_scale=bandwidth)
