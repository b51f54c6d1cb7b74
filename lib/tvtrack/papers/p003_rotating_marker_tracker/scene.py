"""TV scene of an object carrying a rotating-emitter marker, seen through interference: the experiment
(:class:`Scenario`) and its runner (:func:`run_scenario`, :func:`interference_runs`). The truth lives in
:mod:`.motion` and the image in :mod:`.imaging`.

Model (Yukhno 2025, eqs. (7)-(13), with this project's compensation model)::

    u_d(x, y, t) = s(x - x_m(t), y - y_m(t)) + kappa * f(x, y) + sum_q (d / SIR) * spot(x - x_q, y - y_q) + n

- ``s``: the marker spot (uniform disc of diameter ``D`` or square of side ``D``), brightness ``d``
  per fully covered pixel, centred on the marker ``x_m = x_r + r cos(theta)``,
  ``y_m = y_r + r sin(theta)``, ``theta = phi + int omega dt`` (eq. (8), exact phase integral).
- ``f``: zero-mean Gaussian random background with a Gaussian correlation function
  ``exp(-(tau / l_c)^2)`` (``l_c`` = correlation length, px); after compensation only
  ``kappa * f`` remains (``kappa`` = compensation residual factor; 1 = no compensation).
- stationary interferers, same spot as the marker, *residual* brightness ``d / SIR`` after
  compensation (SIR is defined after compensation; before it the ratio is ``SIR_0 = kappa SIR``).
- ``n``: white Gaussian sensor noise, ``noise_std`` per pixel per frame (eq. (U4)).

The static part (background residual and interferers) is rendered once per trial as a full
image; each frame only the gate crop is read out and the moving marker rendered into it, so
the per-frame cost is that of the gate (about 26 x 26 px), batched over trials.

Coordinates follow :mod:`tvtrack.render`: pixel centres at integers, ``x`` = column, ``y`` = row.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .ekf import EKFTracker, ekf_noise_from_bandwidths
from .loops import RotatingGateTracker, gains_realising, loop_gains, run_closed_loop
from .motion import (
    MOTIONS,
    MarkerTruth,
    marker_truth,
    object_motion,
)
from .draws import generator_blocks, tile_rows
from .draws import BlockNormal, CommonNormal
from .imaging import COMPENSATIONS, build_scene
from .backdrop import render_spot

__all__ = [
    "render_spot",
    "marker_truth",
    "MarkerTruth",
    "object_motion",
    "MOTIONS",
    "build_scene",
    "Scenario",
    "scenario_truth",
    "run_scenario",
    "state_errors",
    "interference_runs",
    "CommonNormal",
    "PLACEMENTS",
    "EXPOSURES",
    "COMPENSATIONS",
]


@dataclass(frozen=True)
class Scenario:
    """One tracking experiment (defaults: the paper's stated values, and this project's choices where it states none).

    Units: px, s, Hz; brightness in units of the marker brightness ``d``.
    ``kappa`` = compensation residual (1 = none); ``noise_std`` and ``background_std`` are
    per pixel (the background before compensation). ``omega_mod``/``radius_mod`` are relative
    sinusoidal modulation depths of the rotation rate and radius (Fig. 2). ``y_phase`` is the phase of the
    object's y sinusoid (rad; None = uniformly random per run, :func:`object_motion`). ``decoy_offset`` > 0
    adds an imitating interferer rotating like the marker about a centre displaced by that many px,
    at the phase offset ``decoy_phase`` (rad; None = uniformly random per trial); its brightness at the tracker is
    ``decoy_gain d / SIR`` with the SIR passed to :func:`run_scenario`. The paper defines SIR with the brightness an
    interferer keeps *after* compensation; a decoy moves, so no background compensation removes it: ``decoy_gain = 1``
    (the default) puts the decoy at the brightness a stationary interferer keeps at that SIR (the paper's SIR read
    for the decoy), ``1 / kappa`` at the brightness a stationary interferer *emits* there (equal emitters).
    ``exposure`` ``"instant"`` or ``"integrated"`` over the frame (:attr:`exposure_steps` sub-frame renders);
    ``compensation`` ``"kappa"`` (``kappa`` times the static scene left) or ``"median"`` (a per-pixel temporal median
    of the first ``median_revolutions`` revolutions, the marker masked out, subtracted, :func:`median_residual`; the
    interferers keep ``d / SIR`` either way). ``interferer_centre``
    (:data:`PLACEMENTS`): the interferers' circle about the object's start, about the image centre, or ``"trace"``,
    each interferer about the object's centre at its own random frame of the run (on the marker's trace).
    """

    fps: float = 500.0
    duration_s: float = 10.0
    image_size: int = 256
    spot: str = "disc"
    diameter: float = 8.0
    brightness: float = 1.0
    noise_std: float = 0.02
    background_std: float = 0.2
    corr_length: float = 8.0
    kappa: float = 0.1
    rotating: bool = True
    radius: float = 12.0
    rotation_hz: float = 8.0
    omega_mod: float = 0.0
    omega_mod_hz: float = 0.5
    radius_mod: float = 0.0
    radius_mod_hz: float = 0.05
    motion: str = "card"
    x_std: float = 10.0
    x_tau: float = 1.0
    x_smooth: float = 0.05
    y_amplitude: float = 20.0
    y_freq: float = 0.5
    y_phase: float | None = None
    n_interferers: int = 0
    interferer_jitter: float = 0.0
    interferer_diameter: float | None = None
    interferer_radius_offset: float = 0.0
    interferer_centre: str = "object"
    interferer_layout: str = "even"
    decoy_offset: float = 0.0
    decoy_phase: float | None = None
    decoy_gain: float = 1.0
    gate_half: float = 12.0
    b_xy: float = 10.0
    b_r: float = 0.2
    b_omega: float = 6.0
    variant: str = "S"
    realise_phase_bandwidth: bool = False
    form: str = "quadrant"
    edge_norm: str = "slope"
    exposure: str = "instant"
    compensation: str = "kappa"
    median_revolutions: float = 2.0
    init_offset: tuple = (3.0, -3.0)
    init_radius_factor: float = 0.85
    init_phase: float = 0.2

    def __post_init__(self):
        if not 0 < self.rotation_hz < self.fps / 2:
            raise ValueError(
                f"parameter 'rotation_hz' = {self.rotation_hz}; it must be > 0 and below the frame-rate "
                f"Nyquist fps / 2 = {self.fps / 2:g} Hz (the gate samples the rotation once a frame)"
            )
        if self.motion not in MOTIONS:
            raise ValueError(f"parameter 'motion' = {self.motion!r}; it must be one of {MOTIONS}")
        if self.edge_norm not in ("slope", "slew"):
            raise ValueError(f"parameter 'edge_norm' = {self.edge_norm!r}; it must be 'slope' or 'slew'")
        if self.compensation not in COMPENSATIONS:
            raise ValueError(f"parameter 'compensation' = {self.compensation!r}; it must be one of {COMPENSATIONS}")
        if self.exposure not in EXPOSURES:
            raise ValueError(f"parameter 'exposure' = {self.exposure!r}; it must be one of {EXPOSURES}")

    @property
    def n_frames(self) -> int:
        return int(round(self.duration_s * self.fps))

    @property
    def omega0(self) -> float:
        return 2 * np.pi * self.rotation_hz

    @property
    def exposure_steps(self) -> int:
        """Sub-frame renders of an integrated exposure: the marker's largest arc per frame in half-pixel steps
        (``ceil(2 omega_max r_max / fps) + 1``); 1 for an instant exposure."""
        if self.exposure == "instant":
            return 1
        arc = self.omega0 * (1 + self.omega_mod) * self.radius * (1 + self.radius_mod) / self.fps
        return int(np.ceil(2 * arc)) + 1

    def slope(self) -> float:
        """Discriminator slope ``S`` per px: ``2 d D`` for the quadrant form; for the edge form
        the numerical slope of its static characteristic at zero error."""
        if self.form == "quadrant":
            return 2 * self.brightness * self.diameter
        if self.form == "centroid":
            return 1.0
        from .discriminators import static_characteristic

        if self.edge_norm == "slew":
            # matched slew: the normalised edge output saturates where the quadrant form's does
            off = np.linspace(0.0, self.gate_half, 49)
            quad = static_characteristic(self.spot_renderer(), off, form="quadrant", half=self.gate_half)
            edge = static_characteristic(
                self.spot_renderer(), off, form="edge", half=self.gate_half, a=self.diameter / 2
            )
            return float(np.max(edge) / (np.max(quad) / (2 * self.brightness * self.diameter)))
        f = static_characteristic(
            self.spot_renderer(), [-0.25, 0.25], form="edge", half=self.gate_half, a=self.diameter / 2
        )
        return float((f[1] - f[0]) / 0.5)

    def gains(self):
        """Loop gains: the stated bandwidths as designed loop by loop (:func:`loop_gains`), or with
        ``realise_phase_bandwidth`` the PLL retuned so that the coupled loop realises ``b_omega``."""
        if self.realise_phase_bandwidth and self.rotating:
            return gains_realising(self.b_xy, self.b_r, self.b_omega, rotation_hz=self.rotation_hz, r=self.radius)
        return loop_gains(self.b_xy, self.b_r, self.b_omega, rotation_hz=self.rotation_hz)

    def spot_renderer(self):
        """``render(centers, shape, origin)`` for this scenario's spot."""
        return lambda c, shape, origin: render_spot(self.spot, c, shape, self.diameter, self.brightness, origin)


def scenario_truth(rng: np.random.Generator, n: int, sc: Scenario) -> MarkerTruth:
    """Truth of a scenario: Fig. 1 motion, rotation with optional Fig. 2 modulation, random phase."""
    T, dt = sc.n_frames, 1.0 / sc.fps
    t = np.arange(T) * dt
    c = sc.image_size / 2
    xr, yr = object_motion(
        rng,
        n,
        T,
        dt,
        center=(c, c),
        x_std=sc.x_std,
        x_tau=sc.x_tau,
        x_smooth=sc.x_smooth,
        y_amplitude=sc.y_amplitude,
        y_freq=sc.y_freq,
        kind=sc.motion,
        y_phase=sc.y_phase,
    )
    if not sc.rotating:
        return marker_truth(xr, yr, np.zeros((n, T)), np.zeros((n, T)), np.zeros(n), dt)
    omega = sc.omega0 * (1 + sc.omega_mod * np.sin(2 * np.pi * sc.omega_mod_hz * t)) * np.ones((n, 1))
    r = sc.radius * (1 + sc.radius_mod * np.sin(2 * np.pi * sc.radius_mod_hz * t)) * np.ones((n, 1))
    return marker_truth(xr, yr, r, omega, rng.uniform(0, 2 * np.pi, n), dt)


# the interferers' circle about the object's start, about the image centre, or (the marker's trace) about the object's
# centre at each interferer's own random frame of the run
PLACEMENTS = ("object", "image", "trace")
EXPOSURES = ("instant", "integrated")


def run_scenario(
    rng: np.random.Generator,
    n: int,
    sc: Scenario,
    sir=np.inf,
    *,
    tracker: str = "loops",
    ekf_meas_var: float = 0.05,
    noise: str = "projected",
    keep_full: bool = True,
    crop_callback=None,
    n_common: int | None = None,
    gains=None,
    blocks=None,
):
    """Simulate ``n`` trials of a scenario end to end (truth, scene, tracker, closed loop).

    The truth, the decoy, the scene and the sensor noise draw from four generators spawned from
    ``rng``, so two scenarios that differ only in what a draw does not depend on (SIR, rotating or
    static marker, gate, loop gains) see the same object motion, background, interferer
    placement and noise.

    Parameters
    ----------
    sir : float or ndarray, shape (n,)
        Post-compensation signal-to-interference ratio of the stationary interferers and of the
        decoy (brightness ``d / SIR`` each).
    tracker : {"loops", "ekf"}
        Fixed-bandwidth loops (variant ``sc.variant``) or the discrete EKF of eqs. (16)-(17).
    noise : {"projected", "pixel"}
        See :func:`tvtrack.papers.p003_rotating_marker_tracker.loops.run_closed_loop` (the edge form always uses pixel noise).
    n_common : int, optional
        Common random numbers: within a generator's block, trial ``j n_common + i`` repeats every
        draw of trial ``i`` (e.g. ``n_common`` trials at each of several SIR values).
    blocks : list of dict, optional
        Scene settings per generator block (see :func:`build_scene`).
    gains : LoopGains, optional
        Loop gains instead of ``sc.gains()``; fields may be arrays of shape (n,) (per-trial gains, e.g. several
        bandwidths run as one batch on common draws).

    ``rng`` may be a list of generators (e.g. one per seed): each draws for its own consecutive
    block of ``n / len(rng)`` trials, exactly as it would alone, so seeds can share one batch.

    Returns
    -------
    truth : MarkerTruth
    scene : RotatingMarkerScene
    history : tvtrack.papers.p003_rotating_marker_tracker.loops.TrackHistory
    """
    p = prepare_scenario(
        rng,
        n,
        sc,
        sir,
        tracker=tracker,
        ekf_meas_var=ekf_meas_var,
        noise=noise,
        keep_full=keep_full,
        crop_callback=crop_callback,
        n_common=n_common,
        gains=gains,
        blocks=blocks,
    )
    return p.truth, p.scene, run_closed_loop(p.scene, p.tracker, p.rng, **p.loop)


@dataclass
class Prepared:
    """A batch of runs set up and not yet run (:func:`prepare_scenario`): ``run_closed_loop(scene, tracker, rng,
    **loop)`` runs it; :func:`.lockstep.run_together` runs several side by side."""

    truth: MarkerTruth
    scene: object
    tracker: object
    rng: object
    loop: dict
    meta: dict | None = None
    stop: object = None  # a LossCriterion: runs may leave the loop once lost by it (:func:`.lockstep.run_together`)


def prepare_scenario(
    rng,
    n: int,
    sc: Scenario,
    sir=np.inf,
    *,
    tracker: str = "loops",
    ekf_meas_var: float = 0.05,
    noise: str = "projected",
    keep_full: bool = True,
    crop_callback=None,
    n_common: int | None = None,
    gains=None,
    blocks=None,
) -> Prepared:
    """The truth, scene, tracker and sensor-noise source of :func:`run_scenario` (same arguments), drawn exactly as
    it draws them, with the closed loop's settings; nothing is run."""
    rngs, n_block, n_common = generator_blocks(rng, n, n_common)
    if sc.interferer_centre not in PLACEMENTS:
        raise ValueError(f"parameter 'interferer_centre' = {sc.interferer_centre!r}; it must be one of {PLACEMENTS}")
    streams = [g.spawn(4) for g in rngs]  # truth, decoy, scene, noise
    bases = [scenario_truth(st[0], n_common, sc) for st in streams]
    truth = MarkerTruth(
        *(
            np.concatenate([tile_rows(getattr(b, f), n_block) for b in bases])
            for f in ("xr", "yr", "r", "theta", "omega")
        ),
        bases[0].t,
    )
    sir = np.broadcast_to(np.asarray(sir, dtype=float), (n,))
    decoys, dphi = _decoy_paths(streams, truth, sc, n, n_common, n_block, blocks)
    scene = _scene_of(streams, truth, sc, sir, decoys, dphi, n_common, blocks)
    trk = _tracker_of(sc, truth, tracker, gains, ekf_meas_var)
    noise_rng = (
        streams[0][3] if n_common == n else BlockNormal([CommonNormal(st[3], n_common) for st in streams], n_block)
    )
    loop = dict(
        gate_half=sc.gate_half,
        form=sc.form,
        edge_a=sc.diameter / 2,
        noise=noise if sc.form == "quadrant" else "pixel",
        keep_full=keep_full,
        crop_callback=crop_callback,
    )
    return Prepared(truth, scene, trk, noise_rng, loop)


def _decoy_paths(streams, truth: MarkerTruth, sc: Scenario, n: int, n_common: int, n_block: int, blocks=None):
    """The law-following decoy's image positions, shape (n, frames, 2), and its phase offsets, shape (n, 1): it
    rotates like the marker about a centre ``sc.decoy_offset`` px from the object's (a block's ``decoy_offset``
    where ``blocks`` sets one), at a random angle and (unless ``sc.decoy_phase``) a random phase, both drawn from each
    generator's decoy stream. Trials of a block without a decoy get zeros (and no decoy brightness, see
    :func:`_scene_of`). ``(None, None)`` without any decoy."""
    offsets = [float((blocks[j] if blocks else {}).get("decoy_offset", sc.decoy_offset)) for j in range(len(streams))]
    if max(offsets) <= 0:
        return None, None
    zero = np.zeros(n_common)
    ang = np.concatenate(
        [
            tile_rows(st[1].uniform(0, 2 * np.pi, n_common) if o > 0 else zero, n_block)
            for st, o in zip(streams, offsets)
        ]
    )[:, None]
    dphi = (
        np.concatenate(
            [
                tile_rows(st[1].uniform(0, 2 * np.pi, n_common) if o > 0 else zero, n_block)
                for st, o in zip(streams, offsets)
            ]
        )[:, None]
        if sc.decoy_phase is None
        else np.full((n, 1), float(sc.decoy_phase))
    )
    off = np.repeat(offsets, n_block)[:, None] if len(set(offsets)) > 1 else offsets[0]
    decoys = np.stack(
        [
            truth.xr + off * np.cos(ang) + truth.r * np.cos(truth.theta + dphi),
            truth.yr + off * np.sin(ang) + truth.r * np.sin(truth.theta + dphi),
        ],
        axis=-1,
    )
    return decoys, dphi


def _scene_of(streams, truth: MarkerTruth, sc: Scenario, sir, decoys, dphi, n_common: int, blocks):
    """The compensated scene of a scenario (:func:`build_scene` with the scenario's settings; the decoy at
    ``sc.decoy_gain d / SIR``)."""
    c = sc.image_size / 2
    return build_scene(
        [st[2] for st in streams],
        truth,
        image_shape=(sc.image_size, sc.image_size),
        spot=sc.spot,
        diameter=sc.diameter,
        brightness=sc.brightness,
        noise_std=sc.noise_std,
        kappa=sc.kappa,
        background_std=sc.background_std,
        corr_length=sc.corr_length,
        n_interferers=sc.n_interferers,
        sir=sir,
        interferer_radius=sc.radius + sc.interferer_radius_offset,
        interferer_center={"object": None, "trace": "trace"}.get(sc.interferer_centre, np.array([c, c])),
        radial_jitter=sc.interferer_jitter,
        interferer_layout=sc.interferer_layout,
        interferer_diameter=sc.interferer_diameter,
        decoys=decoys,
        decoy_brightness=_decoy_brightness(sc, sir, blocks, len(streams)),
        n_common=n_common,
        blocks=blocks,
        exposure_steps=sc.exposure_steps,
        decoy_phase=None if decoys is None else dphi[:, 0],
        compensation=sc.compensation,
        median_frames=int(np.ceil(sc.median_revolutions * sc.fps / sc.rotation_hz)),
    )


def _decoy_brightness(sc: Scenario, sir, blocks, n_generators: int):
    """The decoy's brightness per trial, ``sc.decoy_gain d / SIR``; 0 in a block whose ``decoy_offset`` is 0."""
    b = sc.decoy_gain * sc.brightness / sir
    if not blocks or all("decoy_offset" not in x for x in blocks):
        return b
    on = np.repeat([float(x.get("decoy_offset", sc.decoy_offset)) > 0 for x in blocks], len(sir) // n_generators)
    return np.where(on, b, 0.0)


def _tracker_of(sc: Scenario, truth: MarkerTruth, tracker: str, gains, ekf_meas_var: float):
    """The tracker of a scenario, started off the truth by the scenario's initial errors: the fixed-bandwidth loops
    (``gains`` or the scenario's) or the discrete EKF of eqs. (16)-(17)."""
    n = truth.xr.shape[0]
    x0 = np.stack(
        [
            truth.xr[:, 0] + sc.init_offset[0],
            truth.yr[:, 0] + sc.init_offset[1],
            sc.init_radius_factor * truth.r[:, 0],
            truth.theta[:, 0] + sc.init_phase,
            np.full(n, sc.omega0 if sc.rotating else 0.0),
        ],
        axis=1,
    )
    slope = sc.slope()
    if tracker == "loops":
        return RotatingGateTracker(x0, sc.gains() if gains is None else gains, slope, sc.variant, sc.rotating)
    if tracker == "ekf":
        q = ekf_noise_from_bandwidths(ekf_meas_var, 1.0 / sc.fps, sc.radius, sc.b_xy, sc.b_r, sc.b_omega)
        P0 = np.diag([9.0, 9.0, 4.0, 0.04, 1.0])
        return EKFTracker(x0, P0, q, ekf_meas_var, slope)
    raise ValueError(f"parameter 'tracker' = {tracker!r}; it must be 'loops' or 'ekf'")


def state_errors(truth: MarkerTruth, history) -> np.ndarray:
    """Estimate minus truth of a closed-loop run, phase wrapped to ``(-pi, pi]``.

    Parameters
    ----------
    truth : MarkerTruth
        Per-trial truth, arrays of shape (n, T).
    history : tvtrack.papers.p003_rotating_marker_tracker.loops.TrackHistory
        Run with ``keep_full=True`` (``history.estimate`` of shape (n, T, 5)).

    Returns
    -------
    ndarray, shape (n, T, 5)
        Errors of ``x_r, y_r, r`` (px), ``theta`` (rad) and ``omega`` (rad/s).
    """
    tr = np.stack([truth.xr, truth.yr, truth.r, truth.theta, truth.omega], axis=-1)
    e = history.estimate - tr
    e[..., 3] = np.angle(np.exp(1j * e[..., 3]))
    return e


def interference_runs(rng: np.random.Generator, n: int, sc: Scenario, sir_values, blocks=None) -> dict:
    """Batched interference runs, ``n`` trials per SIR, keeping only what loss detection needs.

    The ``n`` trials are the same at every SIR (common random numbers: motion, background,
    interferer placement, decoy and noise), so loss curves against SIR are paired, and two
    scenarios run from the same ``rng`` state (e.g. rotating and static markers) share them too.

    Parameters
    ----------
    n : int
        Trials per SIR value.
    sc : Scenario
    sir_values : array_like, shape (m,)
        Post-compensation signal-to-interference ratios.

    Returns
    -------
    dict
        ``sir`` (m n,) per-trial SIR (trials of one SIR contiguous), ``miss`` (m n, T) px,
        ``inside`` (m n, T) bool, ``gate`` (m n, T, 2) px, ``interferers`` (m n, q, 2) px,
        ``trial`` (m n,) index of the common draws (0..n-1), ``dt`` frame interval (s),
        ``omega_hat`` (m n, T) the tracker's angular-velocity estimate (rad/s), ``omega_error``
        (m n, T) its relative error against the truth (NaN for a static marker). With a list
        of generators the blocks follow each other: ``block`` (k m n,) says which generator
        (``blocks``: scene settings per generator, see :func:`build_scene`).
    """
    p = prepare_interference(rng, n, sc, sir_values, blocks)
    return interference_outcome(p, run_closed_loop(p.scene, p.tracker, p.rng, **p.loop))


def prepare_interference(rng, n: int, sc: Scenario, sir_values, blocks=None) -> Prepared:
    """The batch of :func:`interference_runs` set up (:func:`prepare_scenario`), not run; with ``sir``, ``n``,
    ``generators`` and ``fps`` in its ``meta`` for :func:`interference_outcome`."""
    rngs = list(rng) if isinstance(rng, (list, tuple)) else [rng]
    sir = np.tile(np.repeat(np.asarray(sir_values, float), n), len(rngs))
    p = prepare_scenario(rngs, sir.size, sc, sir, keep_full=False, n_common=n, blocks=blocks)
    p.meta = dict(sir=sir, n=n, generators=len(rngs), fps=sc.fps)
    return p


def interference_outcome(p: Prepared, h) -> dict:
    """:func:`interference_runs`' dict from its prepared batch ``p`` (:func:`prepare_interference`) and the batch's
    closed-loop history ``h``."""
    truth, scene, sir, n, k = p.truth, p.scene, p.meta["sir"], p.meta["n"], p.meta["generators"]
    m = sir.size // (n * k)
    with np.errstate(divide="ignore", invalid="ignore"):
        omega_error = np.where(truth.omega != 0, h.omega / truth.omega - 1, np.nan).astype(np.float32)
    return dict(
        sir=sir,
        miss=h.miss,
        inside=h.inside,
        gate=h.gate,
        interferers=scene.interferers,
        omega_hat=h.omega,
        omega_error=omega_error,
        trial=np.tile(np.arange(n), m * k),
        block=np.repeat(np.arange(k), m * n),
        dt=1.0 / p.meta["fps"],
    )
