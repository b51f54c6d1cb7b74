"""The world of one run of study 004 (Kokryatska and Hrynchyshyn 2005): the beam-wander generator and the camera at
a register configuration, the exposure readings, the mount vibration and the paths drawn until the spot stays on the
sensor. :mod:`.study` builds a run's scene from them.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from .operating import bandwidth_for
from .gtilt import GTILT
from .beam_wander import BeamWanderConfig, generate_traces
from .camera import SpotCamera
from .traces import TraceSet

__all__ = [
    "BASE_SCENE",
    "BASE_CAMERA",
    "EXPOSURE_SUBSAMPLES",
    "EXPOSURES",
    "VIBRATION_HZ",
    "MAX_DRAWS",
    "scene_config",
    "camera_for",
    "exposure_weights",
    "exposed_traces",
    "vibration",
    "traces_on_sensor",
]

#: Sub-frame samples per exposure of the "full frame" exposure reading.
EXPOSURE_SUBSAMPLES = 4


#: The shipped data set's generator configuration and this project's default camera (21 px centroid window).
BASE_SCENE = BeamWanderConfig()
BASE_CAMERA = SpotCamera(centroid_window_px=21.0)


def scene_config(config: dict, size, base: BeamWanderConfig = BASE_SCENE) -> BeamWanderConfig:
    """The generator's configuration at a register configuration (``size``: a :class:`.sizes.StudySize`).

    ``bandwidth`` scales every corner frequency (``"calibrated"``: the factor that keeps the paper's filter at
    the paper's operating point in this world, :func:`.operating.bandwidth_for`), ``amplitude`` the wander RMS
    range; ``frame rate``
    changes the sampling at ``n_frames`` images per path (the paper: "up to 1000 images"), the drift
    kept in px/s.
    """
    fs = float(config["frame rate"])
    return replace(
        base,
        n_paths=size.n_paths,
        n_frames=size.n_frames,
        frame_rate_hz=fs,
        corner_frequencies_hz=tuple(f * bandwidth_for(config) for f in base.corner_frequencies_hz),
        spectral_index=float(config["spectral index"]),
        rolloff=config["roll-off"],
        rms_min_px=base.rms_min_px * config["amplitude"],
        rms_max_px=base.rms_max_px * config["amplitude"],
        drift_max_px_per_frame=base.drift_max_px_per_frame * base.frame_rate_hz / fs,
        scintillation_sigma_ln=float(config["scintillation"]),
    )


def camera_for(config: dict, base: SpotCamera = BASE_CAMERA) -> SpotCamera:
    """The camera at a register configuration: read noise, saturation (8-bit full scale or none), the
    energy-centre algorithm and the spot size (Gaussian sigma, px)."""
    return replace(
        base,
        read_noise_dn=float(config["read noise"]),
        bit_depth=8 if config["saturation"] == "8-bit" else 16,
        centroid_mode="windowed" if config["energy centre"] == "windowed" else "gate",
        spot_sigma_px=float(config.get("spot size", base.spot_sigma_px)),
    )


#: Exposure readings: sub-frame weights (newest first, one sub-sample = 1/EXPOSURE_SUBSAMPLES frame).
EXPOSURES = ("instant", "full frame", "interlaced, frame integration")


def exposure_weights(exposure: str, k: int = EXPOSURE_SUBSAMPLES) -> np.ndarray:
    """Weights of the path's sub-samples in one frame's spot, newest (the frame time) first.

    "instant": the centre at the frame time. "full frame": a boxcar over the frame interval.
    "interlaced, frame integration": a TV camera's two fields, each integrating one frame interval, the
    second half a frame earlier; the frame is their mean (triangle-topped over 1.5 frame intervals).
    """
    if exposure == "instant":
        return np.ones(1)
    if exposure == "full frame":
        return np.full(k, 1.0 / k)
    if exposure == "interlaced, frame integration":
        w = np.zeros(k + k // 2)
        w[:k] += 0.5 / k
        w[k // 2 :] += 0.5 / k
        return w
    raise ValueError(f"parameter 'exposure' = {exposure!r}; it must be one of {EXPOSURES}")


def exposed_traces(scene: BeamWanderConfig, seed: int, exposure: str, k: int = EXPOSURE_SUBSAMPLES) -> TraceSet:
    """Traces at ``scene`` as the camera sees them (:func:`exposure_weights`): "instant" is the
    generator itself; under the G-tilt spectrum the exposure is exact (the spectrum times the exposure's
    power gain: a boxcar of one frame interval, and for the interlaced reading two such fields half a
    frame apart); otherwise the path is drawn at ``k`` sub-samples per frame and each frame's
    centre and intensity are the weighted means of the sub-samples up to the frame time (the start
    padded with the first sub-sample).

    Returns
    -------
    TraceSet
        ``centres_px`` (n_paths, n_frames, 2) px, ``intensity`` (n_paths, n_frames); the metadata's
        ``wander_rms_px`` are the path draws (before averaging).
    """
    w = exposure_weights(exposure, k)
    if scene.rolloff == GTILT:  # exact: the exposure multiplies the spectrum (gtilt.exposure_gain)
        dt = 1.0 / scene.frame_rate_hz
        tau, delta = {"instant": (0.0, 0.0), "full frame": (dt, 0.0), EXPOSURES[2]: (dt, dt / 2)}[exposure]
        tr = generate_traces(replace(scene, exposure_s=tau, field_offset_s=delta), seed)
        return TraceSet(
            tr.centres_px, tr.intensity, tr.frame_rate_hz, tr.image_size_px, dict(tr.metadata, exposure=exposure)
        )
    if exposure == "instant":
        return generate_traces(scene, seed)
    fine = replace(
        scene,
        frame_rate_hz=scene.frame_rate_hz * k,
        n_frames=scene.n_frames * k,
        drift_max_px_per_frame=scene.drift_max_px_per_frame / k,
    )
    tr = generate_traces(fine, seed)
    at = k * np.arange(scene.n_frames) + k - 1  # sub-sample at each frame time
    idx = np.maximum(at[:, None] - np.arange(w.size)[None, :], 0)  # (T, len(w))
    xy = np.einsum("ptjc,j->ptc", tr.centres_px[:, idx], w)
    inten = np.einsum("ptj,j->pt", tr.intensity[:, idx], w)
    return TraceSet(xy, inten, scene.frame_rate_hz, scene.image_size_px, dict(tr.metadata, exposure=exposure))


#: Frequency of the "vibration" regime's sinusoid, Hz (below the 12.5 Hz Nyquist of 25 frames/s).
VIBRATION_HZ = 8.0


def vibration(amplitude_px: float, frame_rate_hz: float, shape, rng: np.random.Generator) -> np.ndarray:
    """Mount vibration: ``amplitude_px * sin(2 pi f n / fs + phi)`` per path and axis, ``f`` =
    :data:`VIBRATION_HZ`, phases uniform from ``rng`` (drawn whatever the amplitude: common random
    numbers).

    Parameters
    ----------
    shape : tuple (P, T, 2)
        Paths, frames, axes.

    Returns
    -------
    ndarray, shape (P, T, 2), px
    """
    P, T, A = shape
    t = np.arange(T)[None, :, None] / frame_rate_hz
    return amplitude_px * np.sin(2 * np.pi * VIBRATION_HZ * t + rng.uniform(0, 2 * np.pi, (P, 1, A)))


#: Most draws of a run's paths (:func:`traces_on_sensor`) before the run gives up.
MAX_DRAWS = 50


def traces_on_sensor(scene: BeamWanderConfig, stream: np.random.SeedSequence, exposure: str) -> tuple[TraceSet, int]:
    """The run's paths (:func:`exposed_traces`), drawn again until the spot stays on the sensor on every path.

    The paper's recordings kept the spot in the 128 px frame (it measures the spot in every image). A large wander
    (amplitude 2: 6-16 px RMS per axis) with the drift reaches the edge on some draws, which the generator
    refuses. Such a set is drawn again, so the world is conditioned on the spot staying on the sensor, as the
    recordings were. The first draw uses the seed every earlier version used, so a set that stays on the sensor
    is unchanged; later draws take children of ``stream``.

    Returns
    -------
    traces : TraceSet
    draws : int
        Sets drawn (1: the first stayed on the sensor).
    """
    seed = int(stream.generate_state(1)[0])
    for k in range(1, MAX_DRAWS + 1):
        try:
            return exposed_traces(scene, seed, exposure), k
        except ValueError as err:
            if "leave the sensor" not in str(err):
                raise
        seed = int(stream.spawn(1)[0].generate_state(1)[0])
    raise ValueError(
        f"the spot left the {scene.image_size_px} px sensor on every one of {MAX_DRAWS} draws of the paths: the "
        "wander is too large for the frame"
    )
