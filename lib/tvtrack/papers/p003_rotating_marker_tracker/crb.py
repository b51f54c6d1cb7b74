"""Posterior Cramer-Rao bound of the rotating-marker tracker and the trackers measured against it (beyond the paper).

The bound is for the seven-state model of :func:`.loops.velocity_model` (object position and velocity, radius,
phase, rate; linear-Gaussian dynamics) observed through every pixel of the rendered marker spot in white sensor noise
(Tichavsky, Muravchik & Nehorai 1998, through :func:`tvtrack.bounds.pcrlb.pcrlb_recursion`). Per frame the pixels
carry the information ``J_z = M^T G M`` about the state, with ``G = sum_p grad s_p grad s_p^T / sigma^2`` the
information of the spot's position (the rendered spot's gradient by central differences, averaged over sub-pixel
positions) and ``M = dm/dlambda`` the Jacobian of the marker position of eq. (8), averaged over the uniformly
distributed phase (the expectation the bound takes). The spot can be rendered supersampled (each pixel the mean of
``s x s`` sub-pixel renders): ``s = 1`` is the scene's own renderer (the data the simulated trackers see), larger
``s`` tends to exact pixel-area integration (derived here: sharp edges make the information resolution-dependent).

:func:`compare_with_bound` runs the fixed-gain loops (over a bandwidth grid, the best reported), the five-state EKF
and the velocity EKF on truths drawn from that model, on the same draws, and compares their RMS errors with the
bound on the one-step prediction (what the gate is placed with).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ...bounds.pcrlb import pcrlb_recursion
from ...montecarlo import rms_ci
from .ekf import EKFTracker, VelocityEKFTracker, ekf_noise_from_bandwidths, marker_jacobian, velocity_model
from .loops import RotatingGateTracker, run_closed_loop
from .motion import MarkerTruth
from .scene import Scenario
from .imaging import build_scene
from .backdrop import render_spot

__all__ = [
    "MODEL",
    "quadrant_noise_var",
    "spot_position_information",
    "marker_information",
    "prediction_bound",
    "model_truth",
    "compare_with_bound",
]

#: The world of the comparison (this project's choice; the paper has none): noise densities of
#: :func:`.loops.velocity_model` and the prior standard deviations of ``(x_r, y_r, r, theta, omega, v_x, v_y)``. Speeds
#: of 10-20 px/s (this project's Fig. 1 motion moves at up to 60 px/s) keep a 3 s run inside the image; the rate wanders
#: by ~2 % over 3 s.
MODEL = dict(q_acc=100.0, q_r=0.05, q_omega=1.0, prior_std=(2.0, 2.0, 1.0, 0.2, 1.0, 10.0, 10.0))


def quadrant_noise_var(gate_half: float, noise_std: float, slope: float) -> float:
    """Variance (px^2) of each normalised quadrant output from white pixel noise: ``(2A)^2 sigma^2 / S^2``
    (every pixel of the ``2A x 2A`` gate enters one of the two half-gate sums with weight +-1)."""
    return (2 * gate_half) ** 2 * noise_std**2 / slope**2


def _render(spot, centre, size, diameter, brightness, s):
    """The spot at ``centre`` on a ``size x size`` grid of unit pixels (centres 0..size-1), each pixel the mean of
    ``s x s`` sub-pixel renders."""
    o = -s / 2 + 0.5  # first sub-pixel centre, in sub-pixel units
    img = render_spot(spot, np.asarray(centre) * s, (size * s, size * s), diameter * s, brightness, (o, o))
    return img.reshape(size, s, size, s).mean(axis=(1, 3))


def spot_position_information(
    spot: str,
    diameter: float,
    brightness: float,
    noise_std: float,
    supersample: int = 1,
    offsets: int = 7,
    h: float = 1e-3,
) -> np.ndarray:
    """Fisher information of one frame's pixels about the spot's position, ``sum_p grad s_p grad s_p^T / sigma^2``.

    The gradient by central differences (step ``h`` px) of the rendered spot, averaged over ``offsets x offsets``
    sub-pixel positions of its centre (the bound's expectation over the position).

    Parameters
    ----------
    spot : {"disc", "square"}
    diameter, brightness : float
        Spot diameter (side) ``D`` (px) and brightness ``d`` per fully covered pixel.
    noise_std : float
        White sensor-noise standard deviation per pixel.
    supersample : int
        Sub-pixel renders per pixel and axis (1: the scene's renderer).

    Returns
    -------
    ndarray, shape (2, 2)
        px^-2.
    """
    if not (noise_std > 0 and supersample >= 1 and offsets >= 1):
        raise ValueError("need noise_std > 0, supersample >= 1 and offsets >= 1")
    size = int(np.ceil(diameter)) + 6
    G = np.zeros((2, 2))
    for i in range(offsets):
        for j in range(offsets):
            c = np.array([size / 2 + i / offsets, size / 2 + j / offsets])
            g = [
                (
                    _render(spot, c + h * e, size, diameter, brightness, supersample)
                    - _render(spot, c - h * e, size, diameter, brightness, supersample)
                ).ravel()
                / (2 * h)
                for e in np.eye(2)
            ]
            G += np.array([[a @ b for b in g] for a in g])
    return G / (offsets**2 * noise_std**2)


def marker_information(G, r: float, n_states: int = 7, n_phase: int = 64) -> np.ndarray:
    """Expected information ``E_theta[M^T G M]`` of one frame about the state, the phase uniform on the circle.

    Parameters
    ----------
    G : array_like, shape (2, 2)
        Information about the marker position (:func:`spot_position_information`).
    r : float
        Rotation radius (px).
    n_states : int
        5 (the paper's state) or 7 (with velocity; its velocity columns are zero).

    Returns
    -------
    ndarray, shape (n_states, n_states)
    """
    s = np.zeros((n_phase, n_states))
    s[:, 2], s[:, 3] = r, 2 * np.pi * np.arange(n_phase) / n_phase
    M = marker_jacobian(s)
    return np.einsum("nki,kl,nlj->ij", M, np.asarray(G, float), M) / n_phase


def prediction_bound(F, Q, P0, info, n_frames: int) -> np.ndarray:
    """Posterior CRB of the one-step prediction: ``B^-_0 = P0``, ``B^-_k = F B_{k-1} F^T + Q`` with ``B_k`` the
    filtered bound of :func:`tvtrack.bounds.pcrlb.pcrlb_recursion` (the measurement information ``info`` every
    frame).

    Returns
    -------
    ndarray, shape (n_frames, k, k)
    """
    P0 = np.asarray(P0, float)
    filt = pcrlb_recursion(F, Q, np.linalg.inv(P0), np.broadcast_to(info, (n_frames,) + P0.shape))
    pred = np.einsum("ij,kjl,ml->kim", F, filt[:-1], F) + Q
    return np.concatenate([P0[None], pred])


def model_truth(rng: np.random.Generator, n: int, sc: Scenario, F, Q, P0) -> tuple[MarkerTruth, np.ndarray]:
    """Truths drawn from the seven-state model and the prior means the trackers start from.

    The prior mean of trial ``i`` is ``(c, c, r_0, phi_i, omega_0, 0, 0)`` (``c`` the image centre, ``phi_i``
    uniform); the initial state is the mean plus a draw from ``N(0, P0)``, then ``x_{k+1} = F x_k + w_k``,
    ``w_k ~ N(0, Q)``.

    Returns
    -------
    truth : MarkerTruth
    mean0 : ndarray, shape (n, 7)
    """
    T, dt = sc.n_frames, 1.0 / sc.fps
    c = sc.image_size / 2
    mean0 = np.zeros((n, 7))
    mean0[:, :5] = [c, c, sc.radius, 0.0, sc.omega0]
    mean0[:, 3] = rng.uniform(0, 2 * np.pi, n)
    x = mean0 + rng.standard_normal((n, 7)) @ np.linalg.cholesky(P0).T
    w = rng.standard_normal((T, n, 7)) @ np.linalg.cholesky(Q).T
    states = np.empty((n, T, 7))
    for k in range(T):
        states[:, k] = x
        x = x @ F.T + w[k]
    truth = MarkerTruth(*(states[:, :, j].copy() for j in range(5)), np.arange(T) * dt)
    return truth, mean0


def compare_with_bound(
    seed: int,
    n: int,
    duration_s: float,
    transient_s: float,
    sc: Scenario | None = None,
    bxy_grid=(2.5, 5.0, 10.0, 20.0, 40.0),
    supersample=(1, 8),
    model: dict = MODEL,
) -> dict:
    """RMS object-position errors of the trackers on the model's truths against the posterior CRB.

    Every tracker runs on the same truths, scene and sensor noise (white noise only: no residual background, no
    interferers, so the bound's observation model is the scene's). The loops run at each bandwidth of ``bxy_grid``
    (the paper's other loops as designed); the five-state EKF at the stated bandwidths (:func:`.loops.
    ekf_noise_from_bandwidths`); the velocity EKF with the model's own noise densities; both EKFs with the
    quadrant outputs' true noise variance (:func:`quadrant_noise_var`) and the prior ``P0``.

    Returns
    -------
    dict
        ``"rms"``: ``{"loops B Hz": Estimate, ..., "EKF (5 states)", "EKF (velocity)"}`` (px, both axes pooled,
        frames after ``transient_s``); ``"bound"``: the PCRB's RMS (px) over the same frames for each supersampling
        factor ``{s: float}`` (the first, ``s = 1``, is the scene's renderer, the bound of these runs);
        ``"best_loops"``: the grid bandwidth with the smallest RMS and whether it is a grid edge; ``"lost"``: runs
        whose error exceeded the gate half-size; ``"info_ratio"``: the pixels' information about the marker
        position over the quadrant outputs' (``G_xx`` times their noise variance).
    """
    sc = replace(sc or Scenario(), duration_s=duration_s, background_std=0.0, n_interferers=0)
    dt, T = 1.0 / sc.fps, sc.n_frames
    k0 = int(round(transient_s * sc.fps))
    F, Q = velocity_model(dt, model["q_acc"], model["q_r"], model["q_omega"])
    P0 = np.diag(np.square(model["prior_std"]))
    truth, mean0 = model_truth(np.random.default_rng([40, seed]), n, sc, F, Q, P0)
    scene = build_scene(
        np.random.default_rng([41, seed]),
        truth,
        image_shape=(sc.image_size, sc.image_size),
        spot=sc.spot,
        diameter=sc.diameter,
        brightness=sc.brightness,
        noise_std=sc.noise_std,
        kappa=sc.kappa,
        background_std=0.0,
    )
    slope = sc.slope()
    mv = quadrant_noise_var(sc.gate_half, sc.noise_std, slope)
    trackers = {
        f"loops {b:g} Hz": lambda b=b: RotatingGateTracker(mean0[:, :5], replace(sc, b_xy=b).gains(), slope)
        for b in bxy_grid
    }
    q5 = ekf_noise_from_bandwidths(mv, dt, sc.radius, sc.b_xy, sc.b_r, sc.b_omega)
    trackers["EKF (5 states)"] = lambda: EKFTracker(mean0[:, :5], P0[:5, :5], q5, mv, slope)
    trackers["EKF (velocity)"] = lambda: VelocityEKFTracker(
        mean0, P0, model["q_acc"], model["q_r"], model["q_omega"], mv, slope
    )
    rms, lost = {}, {}
    tr = np.stack([truth.xr, truth.yr], axis=-1)
    for name, make in trackers.items():
        h = run_closed_loop(scene, make(), np.random.default_rng([42, seed]), gate_half=sc.gate_half, noise="projected")
        rms[name] = rms_ci(h.estimate[:, k0:, :2] - tr[:, k0:])
        lost[name] = int((h.miss[:, k0:].max(axis=1) > sc.gate_half).sum())
    bound, info = {}, {}
    for s in supersample:
        G = spot_position_information(sc.spot, sc.diameter, sc.brightness, sc.noise_std, supersample=s)
        B = prediction_bound(F, Q, P0, marker_information(G, sc.radius), T)
        bound[s] = float(np.sqrt(np.mean(B[k0:, 0, 0] + B[k0:, 1, 1]) / 2))
        info[s] = float(G[0, 0])
    loops = {b: rms[f"loops {b:g} Hz"].value for b in bxy_grid}
    best = min(loops, key=loops.get)
    return dict(
        rms=rms,
        bound=bound,
        lost=lost,
        best_loops=dict(bandwidth_hz=best, edge=best in (bxy_grid[0], bxy_grid[-1])),
        info_ratio=info[supersample[0]] * mv,
    )
