"""The EKF trackers of notebook 003: the discrete EKF form of
eqs. (16)-(17) (Riccati sign corrected here) on the quadrant discriminator, and the velocity-state EKF
of the seven-state model (beyond the paper) with its process model and measurement Jacobian.

Both update in the information form of the paper's corrected (17), ``P = (P^-1 + H^T H / s^2)^-1``, not through
:func:`tvtrack.filters.kf_update`: the two are equal in exact arithmetic but not to the bit, and the claims'
pinned numbers are this form's.
"""

from __future__ import annotations

import numpy as np

from .discriminators import polar_errors

__all__ = ["ekf_noise_from_bandwidths", "EKFTracker", "velocity_model", "marker_jacobian", "VelocityEKFTracker"]


def ekf_noise_from_bandwidths(
    meas_var: float, dt: float, r: float, b_xy: float, b_r: float, b_omega: float
) -> np.ndarray:
    """Process-noise densities ``N_0`` (diagonal, per second) giving the EKF the stated bandwidths.

    A random-walk state measured every ``dt`` with variance ``meas_var`` (information rate
    ``J = 1 / (meas_var dt)``) has the steady-state Kalman-Bucy bandwidth ``sqrt(q J)``; a double
    integrator (phase, rate) has ``w_n = (q J_th)^(1/4)``, ``zeta = 0.707``, with the phase
    information ``J_th = r^2 J``.

    Returns
    -------
    ndarray, shape (5,)
        ``(q_x, q_y, q_r, q_theta, q_omega)``.
    """
    info = 1.0 / (meas_var * dt)
    wxy, wr, wn = 2 * np.pi * b_xy, 2 * np.pi * b_r, 2 * np.pi * b_omega / 2.058
    return np.array([wxy**2 / info, wxy**2 / info, wr**2 / info, 0.0, wn**4 / (info * r**2)])


class EKFTracker:
    """Discrete EKF form of eqs. (16)-(17) (Riccati sign corrected here) on the
    quadrant discriminator.

    State ``(x_r, y_r, r, theta, omega)`` with ``theta' = omega``. The measurement is the marker
    offset from the gate read by the normalised quadrant discriminator,
    ``z = (Delta_x, Delta_y) / S ~= m(lambda) - m(lambda_hat)``, with ``m`` the marker position
    of eq. (8); ``H = dm/dlambda`` (rows ``[1, 0, cos th, -r sin th, 0]`` and
    ``[0, 1, sin th, r cos th, 0]``). The update is the information form of the corrected (17),
    ``R = (R^-^-1 + H^T H / s^2)^-1``, and the estimate moves by ``R H^T z / s^2`` (eq. (16)).
    (The pixel-level form, ``sum_p H_p^T H_p``, is dominated by the spot's sharp edge and its
    linearisation holds only within a pixel of the truth, so it diverges from the paper's
    initial errors; the discriminator form keeps the quadrant form's +-D/2 linear range.)

    Parameters
    ----------
    x0 : ndarray, shape (n, 5)
    P0 : ndarray, shape (5, 5)
    q : ndarray, shape (5,)
        Process-noise densities (per second), e.g. from :func:`ekf_noise_from_bandwidths`.
    meas_var : float
        Variance (px^2) of each normalised discriminator output.
    slope : float
        Discriminator slope ``S``.
    """

    def __init__(self, x0, P0, q, meas_var: float, slope: float):
        if not meas_var > 0:
            raise ValueError(f"parameter 'meas_var' = {meas_var}; it must be > 0")
        if not slope > 0:
            raise ValueError(f"parameter 'slope' = {slope}; it must be > 0")
        self.state = np.array(x0, dtype=float, copy=True)
        n = self.state.shape[0]
        self.P = np.broadcast_to(np.asarray(P0, dtype=float), (n, 5, 5)).copy()
        self.q = np.asarray(q, dtype=float)
        self.meas_var, self.slope = float(meas_var), float(slope)

    def gate_center(self) -> np.ndarray:
        """Predicted marker position, shape (n, 2)."""
        x = self.state
        return np.stack([x[:, 0] + x[:, 2] * np.cos(x[:, 3]), x[:, 1] + x[:, 2] * np.sin(x[:, 3])], axis=1)

    def update(self, dx, dy, dt: float) -> tuple[np.ndarray, np.ndarray]:
        """Update with frame k's discriminator outputs, then predict to k+1; returns ``(e_r, e_th)``."""
        x, P = self.state, self.P
        n = x.shape[0]
        polar = polar_errors(dx, dy, x[:, 3])
        cs, sn, r = np.cos(x[:, 3]), np.sin(x[:, 3]), x[:, 2]
        z = np.stack([dx, dy], axis=1) / self.slope
        H = np.zeros((n, 2, 5))
        H[:, 0, 0] = H[:, 1, 1] = 1.0
        H[:, 0, 2], H[:, 1, 2] = cs, sn
        H[:, 0, 3], H[:, 1, 3] = -r * sn, r * cs
        info = np.einsum("nki,nkj->nij", H, H) / self.meas_var
        P_new = np.linalg.inv(np.linalg.inv(P) + info)  # corrected (17)
        x += np.einsum("nij,nkj,nk->ni", P_new, H, z) / self.meas_var  # (16)
        F = np.eye(5)
        F[3, 4] = dt
        x[:, 3] += dt * x[:, 4]
        self.P = F @ P_new @ F.T + np.diag(self.q * dt)
        return polar


def velocity_model(dt: float, q_acc: float, q_r: float, q_omega: float) -> tuple[np.ndarray, np.ndarray]:
    """Transition and process-noise covariance of the seven-state model with object velocity.

    State ``(x_r, y_r, r, theta, omega, v_x, v_y)`` (px, px, px, rad, rad/s, px/s, px/s): the five states of eqs.
    (7), (11), (12) with ``g_1 = v_x``, ``g_2 = v_y`` and white accelerations (nearly constant velocity), the radius
    a random walk, the phase driven by a random-walk rate (``theta' = omega``, ``omega' = n_04``). Exact
    discretisation of the continuous white-noise densities over ``dt``: each integrated pair (position, velocity)
    gets ``q [[dt^3/3, dt^2/2], [dt^2/2, dt]]``.

    Parameters
    ----------
    dt : float
        Frame interval (s).
    q_acc : float
        Acceleration noise density (px^2/s^3), per axis.
    q_r : float
        Radius random-walk density (px^2/s).
    q_omega : float
        Rate random-walk density (rad^2/s^3).

    Returns
    -------
    F, Q : ndarray, shape (7, 7)
    """
    F = np.eye(7)
    Q = np.zeros((7, 7))
    block = np.array([[dt**3 / 3, dt**2 / 2], [dt**2 / 2, dt]])
    for pos, rate, q in ((0, 5, q_acc), (1, 6, q_acc), (3, 4, q_omega)):
        F[pos, rate] = dt
        Q[np.ix_([pos, rate], [pos, rate])] = q * block
    Q[2, 2] = q_r * dt
    return F, Q


def marker_jacobian(state) -> np.ndarray:
    """``dm / dlambda`` of the marker position of eq. (8) for five- or seven-state vectors.

    Parameters
    ----------
    state : ndarray, shape (n, k), k >= 5
        ``(x_r, y_r, r, theta, ...)``.

    Returns
    -------
    ndarray, shape (n, 2, k)
        Rows ``[1, 0, cos th, -r sin th, 0, ...]`` and ``[0, 1, sin th, r cos th, 0, ...]``.
    """
    s = np.asarray(state, dtype=float)
    H = np.zeros((s.shape[0], 2, s.shape[1]))
    cs, sn, r = np.cos(s[:, 3]), np.sin(s[:, 3]), s[:, 2]
    H[:, 0, 0] = H[:, 1, 1] = 1.0
    H[:, 0, 2], H[:, 1, 2] = cs, sn
    H[:, 0, 3], H[:, 1, 3] = -r * sn, r * cs
    return H


class VelocityEKFTracker:
    """Discrete EKF of eqs. (16)-(17) on the seven-state model of :func:`velocity_model` (object velocity added).

    The same measurement as :class:`EKFTracker` (the normalised quadrant outputs read as the marker's offset from the
    gate, ``H = dm/dlambda`` with zero velocity columns) and the same information-form update (corrected (17)); the
    prediction uses the model's ``F`` and ``Q`` for the frame interval. ``state`` is the five-state view ``(x_r, y_r,
    r, theta, omega)`` the closed-loop runner records; ``velocity`` the last two states.

    Parameters
    ----------
    x0 : ndarray, shape (n, 7)
        Initial estimates ``(x_r, y_r, r, theta, omega, v_x, v_y)``.
    P0 : ndarray, shape (7, 7)
    q_acc, q_r, q_omega : float
        Noise densities of :func:`velocity_model`.
    meas_var : float
        Variance (px^2) of each normalised discriminator output.
    slope : float
        Discriminator slope ``S``.
    """

    def __init__(self, x0, P0, q_acc: float, q_r: float, q_omega: float, meas_var: float, slope: float):
        if not meas_var > 0:
            raise ValueError(f"parameter 'meas_var' = {meas_var}; it must be > 0")
        if not slope > 0:
            raise ValueError(f"parameter 'slope' = {slope}; it must be > 0")
        self.lam = np.array(x0, dtype=float, copy=True)
        if self.lam.ndim != 2 or self.lam.shape[1] != 7:
            raise ValueError(f"parameter 'x0' has shape {self.lam.shape}; it must be (n, 7)")
        self.P = np.broadcast_to(np.asarray(P0, dtype=float), (self.lam.shape[0], 7, 7)).copy()
        self.q = (float(q_acc), float(q_r), float(q_omega))
        self.meas_var, self.slope = float(meas_var), float(slope)

    @property
    def state(self) -> np.ndarray:
        """The five-state part ``(x_r, y_r, r, theta, omega)``, shape (n, 5) (a view)."""
        return self.lam[:, :5]

    @property
    def velocity(self) -> np.ndarray:
        """``(v_x, v_y)`` (px/s), shape (n, 2)."""
        return self.lam[:, 5:]

    def gate_center(self) -> np.ndarray:
        """Predicted marker position, shape (n, 2)."""
        x = self.lam
        return np.stack([x[:, 0] + x[:, 2] * np.cos(x[:, 3]), x[:, 1] + x[:, 2] * np.sin(x[:, 3])], axis=1)

    def update(self, dx, dy, dt: float) -> tuple[np.ndarray, np.ndarray]:
        """Update with frame k's discriminator outputs, then predict to k+1; returns ``(e_r, e_th)``."""
        x = self.lam
        polar = polar_errors(dx, dy, x[:, 3])
        H = marker_jacobian(x)
        z = np.stack([dx, dy], axis=1) / self.slope
        info = np.einsum("nki,nkj->nij", H, H) / self.meas_var
        P_new = np.linalg.inv(np.linalg.inv(self.P) + info)  # corrected (17)
        x += np.einsum("nij,nkj,nk->ni", P_new, H, z) / self.meas_var  # (16)
        F, Q = velocity_model(dt, *self.q)
        x[:] = x @ F.T
        self.P = F @ P_new @ F.T + Q
        return polar
