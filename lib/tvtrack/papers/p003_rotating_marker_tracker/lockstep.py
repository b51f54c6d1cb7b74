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

A batch whose ``stop`` is a loss criterion (the loss curves: what they read of a run ends at its first loss of lock,
:func:`.lock.first_loss` and :func:`.lock.loss_criteria`) drops a run from the loop once the run has lost lock by that
criterion, looked for every :data:`CHECK_EVERY` frames over the frames since the last look (with the window before
them): about a third of the loss curves' run-frames come after a loss. A dropped run's later frames read as outside
the image (its gate and rate NaN); its first loss and everything before it are those of the full run, bit for bit.
"""

from __future__ import annotations

import numpy as np

from ...measure import gate_crop_size
from .draws import BlockNormal, CommonNormal
from .imaging import RotatingMarkerScene
from .lock import first_loss
from .loops import LoopGains, RotatingGateTracker, TrackHistory, discriminate, run_closed_loop

__all__ = ["run_together", "CHECK_EVERY"]

CHECK_EVERY = 25  # frames between looks for runs that have lost lock (batches with a ``stop`` criterion)

_GAINS = ("k_xy", "k_r", "k1", "k2", "k_phi", "k_om")


def run_together(batches) -> list:
    """Run prepared batches (:class:`.scene.Prepared`), those that can share a frame loop side by side.

    Batches share a loop when their trackers are :class:`.loops.RotatingGateTracker` of variant ``"S"`` and they
    have the same frame times and no crop callback; the others run alone (a batch with a ``stop`` criterion in a loop
    of its own, to drop its lost runs).

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
        if len(idx) > 1 or _stop(batches[idx[0]]) is not None:
            for i, h in zip(idx, _run_shared([batches[i] for i in idx])):
                hist[i] = h
    for i, b in enumerate(batches):
        if hist[i] is None:
            hist[i] = run_closed_loop(b.scene, b.tracker, b.rng, **b.loop)
    return [(b.truth, b.scene, h) for b, h in zip(batches, hist)]


def _stop(b):
    """The batch's loss criterion for dropping lost runs (the sliding-window kind only), or None."""
    crit = getattr(b, "stop", None)
    return crit if crit is not None and crit.kind == "window" else None


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
    own rows as it would alone, stacked along the leading axis; of those only the rows ``active`` (None: all).

    The loop asks one draw of one shape a frame, for ``frames`` frames: the draws of :data:`CHECK_EVERY` frames are
    made in one call per generator (a generator's draws in one call are those of successive calls, in order)."""

    def __init__(self, sources, rows, frames: int):
        self.sources, self.rows, self.active, self.left = list(sources), list(rows), None, int(frames)
        self._ahead, self._at, self._kind = None, 0, None

    def standard_normal(self, shape, dtype=np.float64):
        kind = (tuple(shape)[1:], np.dtype(dtype))
        if self._ahead is None or self._at == len(self._ahead):
            if self._kind not in (None, kind) or self.left < 1:
                raise ValueError("the stacked draws serve one shape a frame, for the frames given")
            m, self._kind, self._at = min(CHECK_EVERY, self.left), kind, 0
            self._ahead = np.concatenate([_ahead(g, r, kind[0], dtype, m) for g, r in zip(self.sources, self.rows)], 1)
            self.left -= m
        elif kind != self._kind:
            raise ValueError("the stacked draws serve one shape a frame, for the frames given")
        z, self._at = self._ahead[self._at], self._at + 1
        return z if self.active is None else z[self.active]


def _ahead(g, rows: int, rest: tuple, dtype, m: int) -> np.ndarray:
    """``m`` successive draws ``g.standard_normal((rows,) + rest, dtype)`` of a source, shape (m, rows, *rest)."""
    if isinstance(g, np.random.Generator):
        return g.standard_normal((m, rows) + rest, dtype)
    if isinstance(g, CommonNormal):
        z = g.rng.standard_normal((m, g.n_common) + rest, dtype)
        return np.tile(z, (1, rows // g.n_common) + (1,) * len(rest))
    if isinstance(g, BlockNormal):
        return np.concatenate([_ahead(s, g.block, rest, dtype, m) for s in g.sources], axis=1)
    return np.stack([g.standard_normal((rows,) + rest, dtype) for _ in range(m)])


class _Group:
    """Batches discriminated alike: their joined scene, trial slice of the shared tracker and settings; ``act`` the
    scene's trials still run (None: all) at ``a:b`` of the loop's running trials."""

    def __init__(self, batches, start: int):
        lp = batches[0].loop
        self.scene = batches[0].scene if len(batches) == 1 else RotatingMarkerScene.joined([b.scene for b in batches])
        self.sl = slice(start, start + self.scene.n)
        self.gate_half, self.form, self.edge_a, self.noise = lp["gate_half"], lp["form"], lp["edge_a"], lp["noise"]
        self.size = gate_crop_size(max(self.edge_a or 0.0, self.gate_half) if self.form == "edge" else self.gate_half)
        sources, rows = [b.rng for b in batches], [b.scene.n for b in batches]
        self.rng = None if batches[0].rng is None else _Stacked(sources, rows, batches[0].truth.t.size)
        self.act, self.a, self.b = None, start, start + self.scene.n

    def keep(self, active) -> None:
        """Run only the trials ``active`` (sorted indices into the loop's trials) from now on."""
        self.a, self.b = np.searchsorted(active, [self.sl.start, self.sl.stop])
        self.act = active[self.a : self.b] - self.sl.start
        if self.rng is not None:
            self.rng.active = self.act


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
    joint.is_still = np.concatenate([np.full(m, not t.rotating) for t, m in zip(trackers, rows)])
    joint.still = np.flatnonzero(joint.is_still)
    return joint


def _kept_runs(trk: RotatingGateTracker, keep) -> RotatingGateTracker:
    """The joined tracker ``trk`` of the runs ``keep`` (boolean mask) only, their states as they are."""
    out = RotatingGateTracker(trk.state[keep], LoopGains(*(getattr(trk.g, f)[keep] for f in _GAINS)), 1.0, "S", True)
    out.slope, out.is_still = trk.slope[keep], trk.is_still[keep]
    out.still = np.flatnonzero(out.is_still)
    return out


def _lost(watch, gate, inside, active, checked: int, k: int) -> np.ndarray:
    """The running trials of the watched batches (``(trials slice, criterion, marker positions)``) that have lost lock
    by frame ``k``, judged on the frames from ``checked`` (and the window before them: the same loss frames as
    :func:`.lock.first_loss` over the whole run; a window cut at the chunk's start can only miss a loss)."""
    out = []
    for sl, crit, marker in watch:
        rows = active[(active >= sl.start) & (active < sl.stop)]
        if rows.size:
            s = max(0, checked - (crit.window - 1))
            miss = np.linalg.norm(gate[rows, s : k + 1] - marker[rows - sl.start, s : k + 1], axis=-1)
            out.append(rows[first_loss(miss.astype(np.float32), crit, inside[rows, s : k + 1]) >= 0])
    return np.concatenate(out) if out else np.zeros(0, int)


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
    n, t = start, batches[0].truth.t
    T, at, watch = t.size, 0, []
    for i in order:
        if _stop(batches[i]) is not None:
            watch.append((slice(at, at + batches[i].scene.n), _stop(batches[i]), batches[i].truth.marker))
        at += batches[i].scene.n
    dt = float(t[1] - t[0]) if T > 1 else 1.0
    est = np.empty((n, T, 5), np.float32) if full else None
    disc = np.empty((n, T, 4), np.float32) if full else None
    gate, inside, omega = (
        np.full((n, T, 2), np.nan, np.float32),
        np.zeros((n, T), bool),
        np.full((n, T), np.nan, np.float32),
    )
    active, rows, checked = np.arange(n), slice(None), 0
    for k in range(T):
        c = trk.gate_center()
        omega[rows, k] = trk.state[:, 4]
        if full:
            est[rows, k] = trk.state
        dx, dy, ins = np.empty(active.size), np.empty(active.size), np.empty(active.size, bool)
        for g in groups:
            if g.b > g.a:
                dx[g.a : g.b], dy[g.a : g.b], ins[g.a : g.b] = discriminate(
                    g.scene, k, c[g.a : g.b], g.size, g.gate_half, g.form, g.edge_a, g.noise, g.rng, None, g.act
                )
        e_r, e_th = trk.update(dx, dy, dt)
        gate[rows, k], inside[rows, k] = c, ins
        if full:
            e_r[trk.still], e_th[trk.still] = 0.0, 0.0  # what a static tracker reports
            disc[rows, k] = np.stack([dx, dy, e_r, e_th], axis=1) / trk.slope[:, None]
        if watch and (k + 1) % CHECK_EVERY == 0 and k + 1 < T:
            lost = _lost(watch, gate, inside, active, checked, k)
            checked = k + 1
            if lost.size:  # the runs that lost lock leave the loop
                keep = ~np.isin(active, lost)
                active, trk = active[keep], _kept_runs(trk, keep)
                rows = active
                for g in groups:
                    g.keep(active)
    return _split(batches, order, gate, inside, omega, est, disc)


def _split(batches, order, gate, inside, omega, est, disc) -> list:
    """The joined loop's histories, one :class:`.loops.TrackHistory` per batch (in batch order)."""
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
