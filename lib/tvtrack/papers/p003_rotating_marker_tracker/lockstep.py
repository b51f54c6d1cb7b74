"""Several prepared batches of notebook 003's runs (:func:`.scene.prepare_scenario`) run side by side in one frame
loop, each with the numbers it gets alone, bit for bit.

A frame of :func:`.loops.run_closed_loop` costs a fixed ~130 us of NumPy calls plus a few us per run, so the
measurements' many batches of tens of runs (the loss curves of the rotating and static markers, the uncompensated
runs, the bandwidth pair; the Fig. 1 runs and the background sweep) pay mostly the fixed part. Here the batches
share one loop: their trackers become one (per-run gains and slopes), and the batches that crop and discriminate
alike (gate size, form, noise, spot, exposure) become one scene (:meth:`.imaging.RotatingMarkerScene.joined`) whose
frames are read in one call. Every step is elementwise or per run (per-run matrix products, per-row sums), so each
run's numbers do not depend on its neighbours; a static-marker tracker runs as a rotating one with zero radius and
zero radius and phase gains, which leaves its radius, phase and rate exactly as they are (tested).
"""

from __future__ import annotations

import numpy as np

from ...measure import gate_crop_size
from .imaging import RotatingMarkerScene
from .loops import LoopGains, RotatingGateTracker, TrackHistory, discriminate, run_closed_loop

__all__ = ["run_together"]

_GAINS = ("k_xy", "k_r", "k1", "k2", "k_phi", "k_om")


def run_together(batches) -> list:
    """Run prepared batches (:class:`.scene.Prepared`), those that can share a frame loop side by side.

    Batches share a loop when their trackers are :class:`.loops.RotatingGateTracker` of variant ``"S"`` and they
    have the same frame times and no crop callback; the others run alone.

    Returns
    -------
    list of tuple
        ``(truth, scene, history)`` per batch, as :func:`.scene.run_scenario` returns them.
    """
    batches = list(batches)
    hist: list = [None] * len(batches)
    loops: dict = {}  # frame times -> the batches sharing a loop
    for i, b in enumerate(batches):
        if _shareable(b):
            loops.setdefault(b.truth.t.tobytes(), []).append(i)
    for idx in loops.values():
        if len(idx) > 1:
            for i, h in zip(idx, _run_shared([batches[i] for i in idx])):
                hist[i] = h
    for i, b in enumerate(batches):
        if hist[i] is None:
            hist[i] = run_closed_loop(b.scene, b.tracker, b.rng, **b.loop)
    return [(b.truth, b.scene, h) for b, h in zip(batches, hist)]


def _shareable(b) -> bool:
    trk = b.tracker
    return (
        type(trk) is RotatingGateTracker
        and trk.variant == "S"
        and (trk.rotating or not np.any(trk.state[:, 2]))  # a static tracker's radius is 0 (see the module)
        and b.loop["crop_callback"] is None
    )


def _group_key(b):
    """What the batches of one joined scene share: how they crop and discriminate, and their image."""
    lp, sc = b.loop, b.scene
    edge = lp["form"] == "edge"
    return (
        lp["form"],
        lp["gate_half"],
        lp["edge_a"] if edge else None,
        lp["noise"],
        b.rng is None,
        (sc.image_shape, sc.spot, sc.diameter, sc.brightness, sc.noise_std, sc.exposure_steps),
    )


class _Stacked:
    """Standard normal draws of several sources (generators, :class:`.draws.CommonNormal`, ...), each drawing its
    own rows as it would alone, stacked along the leading axis."""

    def __init__(self, sources, rows):
        self.sources, self.rows = list(sources), list(rows)

    def standard_normal(self, shape, dtype=np.float64):
        shape = tuple(shape)
        return np.concatenate([g.standard_normal((m,) + shape[1:], dtype) for g, m in zip(self.sources, self.rows)])


class _Group:
    """Batches discriminated alike: their joined scene, trial slice of the shared tracker and settings."""

    def __init__(self, batches, start: int):
        lp = batches[0].loop
        self.scene = batches[0].scene if len(batches) == 1 else RotatingMarkerScene.joined([b.scene for b in batches])
        self.sl = slice(start, start + self.scene.n)
        self.gate_half, self.form, self.edge_a, self.noise = lp["gate_half"], lp["form"], lp["edge_a"], lp["noise"]
        self.size = gate_crop_size(max(self.edge_a or 0.0, self.gate_half) if self.form == "edge" else self.gate_half)
        self.rng = None if batches[0].rng is None else _Stacked([b.rng for b in batches], [b.scene.n for b in batches])


def _joined_tracker(trackers) -> RotatingGateTracker:
    """One variant-S tracker of the runs of ``trackers``: per-run gains and slopes; a static tracker's runs get zero
    radius and phase gains (its radius is 0, so its gate stays on ``(x_r, y_r)`` and its other states do not move)."""
    rows = [t.state.shape[0] for t in trackers]
    gains = {}
    for f in _GAINS:
        parts = [np.broadcast_to(np.asarray(getattr(t.g, f), float), (m,)) for t, m in zip(trackers, rows)]
        if f in ("k_r", "k1", "k2"):
            parts = [p if t.rotating else np.zeros(m) for p, t, m in zip(parts, trackers, rows)]
        gains[f] = np.concatenate(parts)
    joint = RotatingGateTracker(np.concatenate([t.state for t in trackers]), LoopGains(**gains), 1.0, "S", True)
    joint.slope = np.concatenate([np.full(m, t.slope) for t, m in zip(trackers, rows)])
    joint.still = np.flatnonzero(np.concatenate([np.full(m, not t.rotating) for t, m in zip(trackers, rows)]))
    return joint


def _run_shared(batches) -> list:
    """:func:`.loops.run_closed_loop` of each batch, run side by side (see the module); histories in batch order."""
    keys = [_group_key(b) for b in batches]
    order = sorted(range(len(batches)), key=lambda i: list(dict.fromkeys(keys)).index(keys[i]))  # stable by group
    groups, start = [], 0
    for key in dict.fromkeys(keys):
        members = [batches[i] for i in order if keys[i] == key]
        groups.append(_Group(members, start))
        start += groups[-1].scene.n
    trk = _joined_tracker([batches[i].tracker for i in order])
    full = any(b.loop["keep_full"] for b in batches)
    n, T = start, batches[0].truth.t.size
    t = batches[0].truth.t
    dt = float(t[1] - t[0]) if T > 1 else 1.0
    est = np.empty((n, T, 5), np.float32) if full else None
    disc = np.empty((n, T, 4), np.float32) if full else None
    gate, inside, omega = np.empty((n, T, 2), np.float32), np.empty((n, T), bool), np.empty((n, T), np.float32)
    dx, dy = np.empty(n), np.empty(n)
    for k in range(T):
        c = trk.gate_center()
        omega[:, k] = trk.state[:, 4]
        if full:
            est[:, k] = trk.state
        for g in groups:
            dx[g.sl], dy[g.sl], inside[g.sl, k] = discriminate(
                g.scene, k, c[g.sl], g.size, g.gate_half, g.form, g.edge_a, g.noise, g.rng
            )
        e_r, e_th = trk.update(dx, dy, dt)
        gate[:, k] = c
        if full:
            e_r[trk.still], e_th[trk.still] = 0.0, 0.0  # what a static tracker reports
            disc[:, k] = np.stack([dx, dy, e_r, e_th], axis=1) / trk.slope[:, None]
    out, at = [None] * len(batches), 0
    for i in order:
        b = batches[i]
        sl = slice(at, at + b.scene.n)
        at = sl.stop
        keep = b.loop["keep_full"]
        g = gate[sl]
        miss = np.linalg.norm(g - b.truth.marker, axis=-1).astype(np.float32)
        out[i] = TrackHistory(est[sl] if keep else None, g, disc[sl] if keep else None, miss, inside[sl], omega[sl])
    return out
