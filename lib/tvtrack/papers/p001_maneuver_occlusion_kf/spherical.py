"""C001-9 (Fisenko et al. 2008, text before Fig. 1): targets in uniform Cartesian motion seen in azimuth and
elevation, the paper's two angular rates first, then a grid of geometries.
"""

from __future__ import annotations

import itertools

import numpy as np

from .curves import prediction_error
from .scenario import FPS_REF, config_scenario, with_defaults
from .spherical_sets import HORIZONS, TARGET_SETS

__all__ = [
    "HORIZONS",
    "horizon_seconds",
    "spherical_deviations",
    "TARGET_SETS",
    "PAPER_RATES_PER_FRAME",
    "PAPER_RATES",
    "paper_rates",
    "paper_rate_deviation",
    "start_deviation",
    "field_deviation",
    "measure_spherical",
]


def horizon_seconds(config: dict) -> float:
    """C001-9's horizon in seconds under a complete configuration: 10 s for ``"10 s loss"``; ``k_bound3`` frames at
    ``frame_rate_hz`` for ``"k_b3 filter memory"``."""
    name = config["horizon"]
    if name not in HORIZONS:
        raise ValueError(f"horizon {name!r}; it must be one of {tuple(HORIZONS)}")
    return 10.0 if name == "10 s loss" else float(config["k_bound3"]) / float(config["frame_rate_hz"])


def spherical_deviations(
    ranges_m, speeds, headings_deg, elevations_deg, horizon_s: float = 10.0, deg_per_element: float = 6.0 / 712
) -> np.ndarray:
    """Targets in uniform Cartesian motion seen in azimuth/elevation: the largest deviation (elements) over
    ``horizon_s`` of a linear and of a quadratic extrapolation of the exact angular state at the start.

    Returns
    -------
    ndarray, shape (geometries, 7)
        range m, speed m/s, heading deg, initial elevation deg, stays within ±20° (1/0), linear, quadratic.
    """
    tt = np.linspace(0, horizon_s, 251)
    hd = 1e-3

    def angles(R, V, h, e0, t):
        p = R * np.array([np.cos(e0), 0.0, np.sin(e0)]) + V * np.asarray(t)[:, None] * np.array(
            [np.cos(h), np.sin(h), 0.0]
        )
        return np.degrees(np.arctan2(p[:, 1], p[:, 0])), np.degrees(np.arctan2(p[:, 2], np.hypot(p[:, 0], p[:, 1])))

    rows = []
    for R, V, h, e0 in itertools.product(ranges_m, speeds, np.deg2rad(headings_deg), np.deg2rad(elevations_deg)):
        az, el = angles(R, V, h, e0, tt)
        inside = np.all(np.abs(az) <= 20) and np.all(np.abs(el) <= 20)
        dev = []
        for order in (1, 2):
            worst = 0.0
            for ang, a3 in zip((az, el), angles(R, V, h, e0, [-hd, 0.0, hd])):
                v = (a3[2] - a3[0]) / (2 * hd)
                a = (a3[2] - 2 * a3[1] + a3[0]) / hd**2 if order == 2 else 0.0
                worst = max(worst, float(np.max(np.abs(a3[1] + v * tt + 0.5 * a * tt**2 - ang))) / deg_per_element)
            dev.append(worst)
        rows.append((R, V, np.degrees(h), np.degrees(e0), float(inside), *dev))
    return np.array(rows)


#: The paper's two angular rates as it states them, per frame (deg/frame): 10 elements/frame (6°/712 an element) and
#: 0.02°/frame (C001-10's two figures). The names give them in deg/s at the register's default 25 Hz.
PAPER_RATES_PER_FRAME = {
    "2.107°/s (10 el/frame)": 10.0 * 6.0 / 712,
    "0.5°/s (0.02°/frame)": 0.02,
}


def paper_rates(frame_rate_hz: float) -> dict:
    """The paper's two rates in deg/s at ``frame_rate_hz`` (its per-frame rates times the frame rate)."""
    return {name: r * float(frame_rate_hz) for name, r in PAPER_RATES_PER_FRAME.items()}


#: The paper's two rates, deg/s, at the register's default frame rate (the parts' names).
PAPER_RATES = paper_rates(FPS_REF)


def paper_rate_deviation(rate_deg_s: float, horizon_s: float = 10.0, extrapolation: str = "quadratic") -> dict:
    """C001-9 at one of the paper's angular rates: a target crossing at closest approach (azimuth 0, elevation 0,
    the rate ``rate_deg_s`` there), its angle extrapolated over ``horizon_s``; the largest deviation from the
    true angle, elements (closed form ``omega H - atan(omega H)`` at the crossing, where the angular acceleration
    is 0 so linear and quadratic coincide), and whether the angle stays within ±20°.
    """
    R = 10e3  # only the rate matters: the angle is atan(omega t)
    row = spherical_deviations([R], [np.deg2rad(rate_deg_s) * R], [90.0], [0.0], horizon_s=horizon_s)[0]
    return {
        "deviation_el": float(row[5] if extrapolation == "linear" else row[6]),
        "within_20deg": bool(row[4] > 0),
        "end_angle_deg": float(np.degrees(np.arctan(np.deg2rad(rate_deg_s) * horizon_s))),
    }


def start_deviation(
    rate_deg_s: float, start_deg: float, horizon_s: float = 10.0, extrapolation: str = "quadratic"
) -> tuple[float, bool]:
    """A target in uniform straight motion seen at ``start_deg`` from its closest approach, its angle moving at
    ``rate_deg_s`` there (away from the closest approach for a positive start): the largest deviation (elements)
    over ``horizon_s`` of the angle extrapolated from its exact rate (``"linear"``) and acceleration
    (``"quadratic"``), and whether the angle stays within ±20° over the horizon.

    Closed form: ``theta(t) = atan(tan theta0 + k t)`` with ``k = omega / cos² theta0`` (speed over the closest
    distance, 1/s) and ``theta''(0) = -2 k² cos³ theta0 sin theta0``.
    """
    a, w = np.deg2rad(start_deg), np.deg2rad(rate_deg_s)
    k = w / np.cos(a) ** 2
    t = np.linspace(0.0, horizon_s, 1001)
    theta = np.arctan(np.tan(a) + k * t)
    acc = -2.0 * k**2 * np.cos(a) ** 3 * np.sin(a) if extrapolation == "quadratic" else 0.0
    dev = float(np.degrees(np.max(np.abs(a + w * t + 0.5 * acc * t**2 - theta)))) / (6.0 / 712)
    return dev, bool(np.all(np.abs(np.degrees(theta)) <= 20.0 + 1e-9))


def field_deviation(
    rate_deg_s: float, horizon_s: float = 10.0, extrapolation: str = "quadratic", step_deg: float = 0.5
) -> dict:
    """C001-9 at one of the paper's rates over the whole ±20° field: every start angle from -20° to 20° (step
    ``step_deg``; a negative start approaches the closest point first) whose path stays within ±20° over the horizon
    (the claim says nothing of a path that leaves it), the largest deviation (elements) and where it starts.

    Returns
    -------
    dict
        ``deviation_el`` (NaN when no path stays within ±20°), ``start_deg``, ``starts_within`` and ``starts``.
    """
    starts = np.arange(-20.0, 20.0 + step_deg / 2, step_deg)
    rows = [(s, *start_deviation(rate_deg_s, s, horizon_s, extrapolation)) for s in starts]
    inside = [r for r in rows if r[2]]
    worst = max(inside, key=lambda r: r[1]) if inside else (float("nan"), float("nan"), False)
    return {
        "deviation_el": float(worst[1]),
        "start_deg": float(worst[0]),
        "starts_within": len(inside),
        "starts": len(rows),
    }


def prediction_rms(config: dict, sizes: dict) -> float:
    """C001-9's "prediction RMS at k_b3" tolerance (elements) at the configuration's frame rate and k_b3 (the entries
    it declares; every other entry at the register's default): the random prediction error at reappearance after the
    scenario's loss (:func:`.curves.prediction_error`). At the default frame rate and k_b3 it is the run's
    ``sizes["prediction_rms"]``, the same computation the notebook makes once."""
    d = sizes["defaults"]
    fps, kb3 = config["frame_rate_hz"], config["k_bound3"]
    if (fps, kb3) == (d["frame_rate_hz"], d["k_bound3"]):
        return float(sizes["prediction_rms"])
    at = with_defaults({"frame_rate_hz": fps, "k_bound3": kb3}, sizes)
    sc = config_scenario(at)
    return float(prediction_error(sc, at, sizes, int(kb3), sc.f_loss, sc.f_back)[1])


def measure_spherical(config: dict, seed: int, sizes: dict, claims=None) -> dict:
    """C001-9 in parts: at each of the paper's two rates (:data:`PAPER_RATES`) the largest deviation over the ±20°
    field in multiples of the tolerance (:func:`field_deviation`: every start angle whose path stays within ±20°,
    not only the crossing point), then over the register's grid of geometries the fraction within
    ±20° whose extrapolation stays within the tolerance (``extrapolation``: quadratic/linear; ``tolerance``:
    "1 element" or "prediction RMS at k_b3", :func:`prediction_rms` at the configuration; ``targets``: a key of :data:`TARGET_SETS`; ``horizon``: a key of
    :data:`HORIZONS`, with ``k_bound3`` and ``frame_rate_hz`` (:func:`horizon_seconds`); NaN when no geometry stays
    within ±20°); the paper's rates are per frame, so in deg/s they are read at ``frame_rate_hz``
    (:func:`paper_rates`); ``{}`` when ``claims`` does not ask for C001-9."""
    if claims is not None and "C001-9" not in claims:
        return {}
    config = with_defaults(config, sizes)
    H = horizon_seconds(config)
    tol = 1.0 if config["tolerance"] == "1 element" else prediction_rms(config, sizes)
    parts = {
        name: field_deviation(rate, H, config["extrapolation"])["deviation_el"] / tol
        for name, rate in paper_rates(config["frame_rate_hz"]).items()
    }
    rows = spherical_deviations(*TARGET_SETS[config["targets"]], horizon_s=H)
    inside = rows[rows[:, 4] > 0]
    col = 5 if config["extrapolation"] == "linear" else 6
    parts["geometries"] = float(np.mean(inside[:, col] < tol)) if inside.size else float("nan")
    return {"C001-9": parts}
