"""C000-4 ("variant 1 is two-dimensional and needs more computation"): the arithmetic of one filter step, counted.

Each variant's step is written here once as straight-line scalar code, the paper's unnumbered filter equations
(labelled (E1)-(E8) here, in the order printed) with the corrected (E5), (E6) for variant 1 and the scalar EKF of
eq. (9) for variant 2, with every constant of the model (``Phi``, ``G``, ``R``'s coefficients, the scan's timing
table) computed before the step. Run on :class:`Counted` numbers, the step counts its own multiplications, additions
(subtractions included), divisions and function evaluations (exp, sqrt); ``tests/papers/test_000_cost.py`` checks
that the straight-line steps give the estimates and variances of the vectorised filters of :mod:`.ekf` (which use
the Joseph form of the covariance update, algebraically the same). The counts are deterministic, so C000-4's verdict
and number are too; the CPU-time ratio of the same steps compiled (:mod:`._kernels`, timed by
:func:`.study.cost_ratio`) is the register's other reading.
"""

from __future__ import annotations

import math
from collections import Counter as _Tally

import numpy as np

from ... import jit
from . import _kernels
from .ekf import g22_variance
from .model import DissectorScan, GaussMarkovMessage

__all__ = [
    "Counted",
    "variant1_step",
    "variant2_step",
    "operation_counts",
    "operation_ratio",
    "run_steps_variant1",
    "run_steps_variant2",
]

#: The operations counted as arithmetic (a function evaluation is reported beside them).
ARITHMETIC = ("mul", "add", "div")


class Counted:
    """A float that tallies every arithmetic operation it takes part in (into a shared :class:`collections.Counter`).

    Operations between plain floats (the model's constants) are not counted: they are computed once, not per step.
    """

    __slots__ = ("v", "tally")

    def __init__(self, v: float, tally: _Tally):
        self.v, self.tally = float(v), tally

    def _op(self, kind: str, v: float) -> "Counted":
        self.tally[kind] += 1
        return Counted(v, self.tally)

    @staticmethod
    def _v(o):
        return o.v if isinstance(o, Counted) else float(o)

    def __add__(self, o):
        return self._op("add", self.v + self._v(o))

    __radd__ = __add__

    def __sub__(self, o):
        return self._op("add", self.v - self._v(o))

    def __rsub__(self, o):
        return self._op("add", self._v(o) - self.v)

    def __mul__(self, o):
        return self._op("mul", self.v * self._v(o))

    __rmul__ = __mul__

    def __truediv__(self, o):
        return self._op("div", self.v / self._v(o))

    def __rtruediv__(self, o):
        return self._op("div", self._v(o) / self.v)

    def __float__(self):
        return self.v


def _fn(name: str, f, array_f):
    def apply(x):
        if isinstance(x, Counted):
            return x._op(name, f(x.v))
        return array_f(x)  # plain numbers and arrays of trials (the runners below)

    return apply


_exp, _sqrt = _fn("exp", math.exp, np.exp), _fn("sqrt", math.sqrt, np.sqrt)


def _timing(scan: DissectorScan, k: int, start=0.0):
    """The scan's timing table: ``tau_k - tau_c`` of sample ``k`` with the sweep at phase ``start`` (T, a number or
    one per trial) at switch-on (a constant of the scan, not arithmetic of the step)."""
    tau = scan.phase(k, start) - scan.pulse_centre
    return float(tau) if np.ndim(tau) == 0 else tau


def _sqrt_c(scan: DissectorScan, signal_noise_scale: str) -> float:
    """``sqrt(c_s)`` of variant 1's ``sqrt(c_s S) X2``: ``c_s = N0 P/(1-P)`` (consistent with eq. (2)) or ``A``
    (eq. (6) as printed, ``"literal"``)."""
    return math.sqrt(scan.amplitude if signal_noise_scale == "literal" else scan.n0 * scan.signal_noise_ratio)


def variant1_step(
    scan: DissectorScan,
    message: GaussMarkovMessage,
    x,
    d,
    y,
    k: int,
    beta: float = 15.0,
    g22="paper",
    signal_noise_scale: str = "consistent",
    start=0.0,
):
    """One step of variant 1 (2-state EKF, eqs. (7), (8), (E1)-(E8), corrected (E5), (E6), ``c_s = N0 P/(1-P)``, or
    ``c_s = A`` with ``signal_noise_scale="literal"``).

    Parameters
    ----------
    x : (x1, x2)            the estimate ``X(k/k)`` (x1 in T)
    d : (d11, d12, d22)     its covariance ``D(k)`` (symmetric)
    y : float               the sample ``Y(k+1)``
    k : int                 the index ``k + 1`` of that sample
    start : float or ndarray   the sweep's phase at switch-on (T; one per trial with arrays over trials)

    Returns
    -------
    (x1, x2), (d11, d12, d22)   ``X(k+1)`` and ``D(k+1)``
    """
    f1, q1 = message.euler(scan.dt)
    f2, q2 = 1.0 - beta * scan.dt, g22_variance(g22, beta, scan.dt)
    f11, f12, f22 = f1 * f1, f1 * f2, f2 * f2  # constants of (E7)
    a, sig2 = scan.amplitude, scan.pulse_sigma**2
    sqrt_c = _sqrt_c(scan, signal_noise_scale)
    c_exp, c_h1, c_h2, r = -0.5 / sig2, a / sig2, 0.5 / sig2, scan.n0 / scan.dt
    xp1, xp2 = f1 * x[0], f2 * x[1]  # (E1), (E4)
    p11, p12, p22 = f11 * d[0] + q1, f12 * d[1], f22 * d[2] + q2  # (E7), (E8)
    u = _timing(scan, k, start) - xp1
    s = _exp(c_exp * (u * u))
    root = sqrt_c * _sqrt(s)  # sqrt(c_s S)
    h = a * s + root * xp2  # (E3)
    h1, h2 = c_h1 * (s * u) + c_h2 * (root * u) * xp2, root  # the gradient of (E3)
    b1, b2 = p11 * h1 + p12 * h2, p12 * h1 + p22 * h2  # D(k+1/k) h^T
    v = h1 * b1 + h2 * b2 + r  # innovation variance
    k1, k2 = b1 / v, b2 / v  # (E5)
    nu = y - h
    x_new = (xp1 + k1 * nu, xp2 + k2 * nu)  # (E2)
    d_new = (p11 - k1 * b1, p12 - k1 * b2, p22 - k2 * b2)  # corrected (E6)
    return x_new, d_new


def variant2_step(
    scan: DissectorScan,
    message: GaussMarkovMessage,
    x,
    d,
    y,
    k: int,
    noise_iterations: int = 0,
    assumed_contrast: float | None = None,
    start=0.0,
):
    """One step of variant 2 (scalar EKF, eq. (9): the noise intensity at the predicted estimate, re-evaluated
    ``noise_iterations`` times at the updated one; ``assumed_contrast`` 0 is the filter ignoring the signal noise).
    Arguments as :func:`variant1_step` with scalar ``x``, ``d`` (or arrays over trials)."""
    p = scan.contrast if assumed_contrast is None else assumed_contrast
    f1, q1 = message.euler(scan.dt)
    f11, a, sig2 = f1 * f1, scan.amplitude, scan.pulse_sigma**2
    c_exp, c_h, r0, r1 = -0.5 / sig2, a / sig2, scan.n0 / scan.dt, scan.n0 * p / (1.0 - p) / scan.dt
    xp, p = f1 * x, f11 * d + q1
    tk = _timing(scan, k, start)
    u = tk - xp
    s = _exp(c_exp * (u * u))
    h, dh = a * s, c_h * (s * u)
    ph = p * dh
    dh_ph, nu = dh * ph, y - h

    def update(r):  # gain and update with the noise variance r (the linearisation stays at the prediction)
        v = dh_ph + r
        return xp + (ph / v) * nu, p * r / v

    x_new, d_new = update(r0 + r1 * s)
    for _ in range(noise_iterations):  # eq. (9)'s intensity re-evaluated at the updated estimate
        u1 = tk - x_new
        x_new, d_new = update(r0 + r1 * _exp(c_exp * (u1 * u1)))
    return x_new, d_new


def operation_counts(variant: int, noise_iterations: int = 0) -> dict:
    """Arithmetic of one filter step of ``variant`` (1 or 2) at psi_A = 20, P = 0.5 (the counts do not depend on
    the operating point): ``{"mul", "add", "div", "exp", "sqrt", "arithmetic"}`` (arithmetic = mul + add + div)."""
    from .model import scan_at_snr

    scan, message, tally = scan_at_snr(20.0, 0.5, 0.05), GaussMarkovMessage(0.1, 0.15), _Tally()
    c = lambda v: Counted(v, tally)  # noqa: E731
    if variant == 1:
        variant1_step(scan, message, (c(0.01), c(0.2)), (c(0.2), c(0.0), c(1.0)), c(0.4), 10)
    elif variant == 2:
        variant2_step(scan, message, c(0.01), c(0.2), c(0.4), 10, noise_iterations)
    else:
        raise ValueError(f"parameter 'variant' = {variant!r}; it must be 1 or 2")
    out = {key: tally.get(key, 0) for key in (*ARITHMETIC, "exp", "sqrt")}
    out["arithmetic"] = sum(out[key] for key in ARITHMETIC)
    return out


def operation_ratio(noise_iterations: int = 0) -> float:
    """Arithmetic operations per step of variant 1 over variant 2 (C000-4's default reading)."""
    return operation_counts(1)["arithmetic"] / operation_counts(2, noise_iterations)["arithmetic"]


def _run_steps(step, y, x, d):
    """Run ``step(x, d, y_k, k)`` over the columns ``k = 1..K-1`` of ``y`` (n_trials, K); column 0 holds the prior
    (no sample at k = 0). Returns the X1 estimates and their variances D11, each (n_trials, K)."""
    n, K = y.shape
    est, var = np.empty((n, K)), np.empty((n, K))
    est[:, 0], var[:, 0] = x[0] if isinstance(x, tuple) else x, d[0] if isinstance(d, tuple) else d
    for k in range(1, K):
        x, d = step(x, d, y[:, k], k)
        est[:, k], var[:, k] = (x[0], d[0]) if isinstance(x, tuple) else (x, d)
    return est, var


def _timing_table(scan: DissectorScan, n_columns: int, start, n_trials: int) -> np.ndarray:
    """:func:`_timing` of the samples ``k = 0..n_columns-1`` of each trial (the same values, computed at once),
    shape (n_trials, n_columns)."""
    start = np.broadcast_to(np.asarray(start, dtype=float), (n_trials,))[:, None]
    return np.ascontiguousarray(scan.phase(np.arange(n_columns), start) - scan.pulse_centre)


def _start(start, n: int):
    """Switch-on phases as a number or an array of ``n`` (one per trial); None is 0."""
    if start is None:
        return 0.0
    start = np.asarray(start, dtype=float)
    if start.shape not in ((), (n,)) or not np.all(np.isfinite(start)):
        raise ValueError(f"parameter 'start' has shape {start.shape}; it must be finite, a number or ({n},)")
    return start


def _runner_inputs(y, init, start, width: int | None):
    """The inputs of :func:`run_steps_variant1` (``width`` 2) or :func:`run_steps_variant2` (``width`` None), checked
    and shaped for both paths: the compiled loops index ``y[i, 0]`` and ``init[i]`` of every trial ``i`` unchecked,
    so what the NumPy path refuses is refused here (``ValueError``) and an ``init`` of one row is broadcast to one
    row per trial here, the same numbers both ways.

    Returns
    -------
    n : int                    the number of trials, ``y.shape[0]``
    x0 : ndarray               initial estimates, (n,) or (n, width), a C-contiguous copy
    start : float or ndarray   as :func:`_start`
    """
    if y.ndim != 2 or y.shape[1] < 1:
        raise ValueError(f"parameter 'y' has shape {y.shape}; it must be (n_trials, K), K >= 1 (column 0: the prior)")
    n = y.shape[0]
    start = _start(start, n)
    want = (n,) if width is None else (n, width)
    if init is None:
        return n, np.zeros(want), start
    x0 = np.asarray(init, dtype=float)
    allowed = ((), (1,), want) if width is None else ((1, width), want)
    if x0.shape not in allowed:
        shapes = " or ".join(map(str, allowed))
        raise ValueError(f"parameter 'init' has shape {x0.shape}; it must be {shapes} (one row: the same for all)")
    return n, (x0 if x0.shape == want else np.broadcast_to(x0, want)).copy(), start


def _count(name: str, value) -> int:
    """Refuse a count that is not an integer >= 0 (a float with an integer value is one): ``ValueError`` naming
    the parameter."""
    try:
        ok = not isinstance(value, bool) and int(value) == value and value >= 0
    except (TypeError, ValueError, OverflowError):
        ok = False
    if not ok:
        raise ValueError(f"parameter {name!r} = {value!r}; it must be an integer >= 0")
    return int(value)


def _use_kernel(compiled: bool | None) -> bool:
    return jit.enabled() if compiled is None else bool(compiled)


def run_steps_variant1(
    scan,
    message,
    y,
    d0=(0.2, 1.0),
    init=None,
    beta: float = 15.0,
    g22: str = "paper",
    compiled: bool | None = None,
    signal_noise_scale: str = "consistent",
    start=None,
):
    """Variant 1 over samples ``y`` (n_trials, K): :func:`variant1_step` vectorised over the trials, or its compiled
    loop (:func:`._kernels.variant1_loop`, where numba is enabled; ``compiled`` forces either). The same estimates
    and D11 as :func:`.ekf.run_variant1` (which uses the Joseph form; ``tests/papers/test_000_cost.py`` checks that
    they agree), several times faster. ``init`` (n_trials, 2) initial estimates, or (1, 2) for every trial (default
    0); ``y`` needs K >= 1; ``signal_noise_scale`` as :func:`variant1_step`; ``start`` (n_trials,) each trial's sweep
    phase at switch-on (T; None: 0)."""
    n, x0, start = _runner_inputs(y, init, start, 2)
    if _use_kernel(compiled):
        f1, q1 = message.euler(scan.dt)
        f2, q2 = 1.0 - beta * scan.dt, g22_variance(g22, beta, scan.dt)
        sig2, sqrt_c = scan.pulse_sigma**2, _sqrt_c(scan, signal_noise_scale)
        consts = (f1, f2, f1 * f1, f1 * f2, f2 * f2, q1, q2, -0.5 / sig2, scan.amplitude / sig2, 0.5 / sig2)
        tk = _timing_table(scan, y.shape[1], start, n)
        return _kernels.variant1_loop(
            np.ascontiguousarray(y, dtype=float),
            np.ascontiguousarray(x0),
            (float(d0[0]), float(d0[1])),
            tk,
            *consts,
            scan.amplitude,
            sqrt_c,
            scan.n0 / scan.dt,
        )
    x = (x0[:, 0].copy(), x0[:, 1].copy())
    d = (np.full(n, float(d0[0])), np.zeros(n), np.full(n, float(d0[1])))
    return _run_steps(
        lambda x, d, yk, k: variant1_step(scan, message, x, d, yk, k, beta, g22, signal_noise_scale, start), y, x, d
    )


def run_steps_variant2(
    scan, message, y, d0: float = 0.2, init=None, assumed_contrast=None, noise_iterations=0, compiled=None, start=None
):
    """Variant 2 (or, with ``assumed_contrast`` 0, the filter ignoring the signal noise) over samples ``y``
    (n_trials, K): :func:`variant2_step` vectorised over the trials, or its compiled loop
    (:func:`._kernels.variant2_loop`); the same estimates and D11 as :func:`.ekf.run_variant2`. ``init``
    (n_trials,) initial estimates, or a number for every trial (default 0); ``y`` needs K >= 1;
    ``noise_iterations`` an integer >= 0; ``start`` (n_trials,) each trial's sweep phase at switch-on (T; None:
    0)."""
    n, x, start = _runner_inputs(y, init, start, None)
    noise_iterations = _count("noise_iterations", noise_iterations)
    if _use_kernel(compiled):
        p = scan.contrast if assumed_contrast is None else assumed_contrast
        f1, q1 = message.euler(scan.dt)
        sig2 = scan.pulse_sigma**2
        r0, r1 = scan.n0 / scan.dt, scan.n0 * p / (1.0 - p) / scan.dt
        tk = _timing_table(scan, y.shape[1], start, n)
        return _kernels.variant2_loop(
            np.ascontiguousarray(y, dtype=float),
            np.ascontiguousarray(x),
            float(d0),
            tk,
            f1,
            f1 * f1,
            q1,
            -0.5 / sig2,
            scan.amplitude / sig2,
            scan.amplitude,
            r0,
            r1,
            noise_iterations,
        )

    def step(x, d, yk, k):
        return variant2_step(scan, message, x, d, yk, k, noise_iterations, assumed_contrast, start)

    return _run_steps(step, y, x, np.full(n, float(d0)))
