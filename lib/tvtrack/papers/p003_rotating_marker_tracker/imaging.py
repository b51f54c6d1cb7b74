"""The compensated TV image of notebook 003: the scene object that renders each frame's gate crop (compiled where numba
is used: :mod:`._frame_kernels`), and its builder. The static parts it adds up live in :mod:`.backdrop` (spots, the
correlated background, interferers, the temporal-median residual), the common random numbers in :mod:`.draws`.

Model (Yukhno 2025, eqs. (9), (10), (19), with this project's compensation model)::

    u_d(x, y, t) = s(x - x_m(t), y - y_m(t)) + kappa * f(x, y) + sum_q (d / SIR) * spot(x - x_q, y - y_q) + n

Coordinates follow :mod:`tvtrack.render`: pixel centres at integers, ``x`` = column, ``y`` = row.
"""

from __future__ import annotations

import numpy as np
from numpy.lib.stride_tricks import sliding_window_view

from ... import jit
from ...render import disc_area, disc_spot
from ._frame_kernels import add_box_layers, crop_request, gather_windows
from .backdrop import add_spots, check_spot, correlated_background, median_residual, place_interferers, render_spot
from .draws import generator_blocks, tile_rows
from .motion import MarkerTruth

__all__ = [
    "render_spot",
    "correlated_background",
    "place_interferers",
    "add_spots",
    "RotatingMarkerScene",
    "median_residual",
    "build_scene",
    "COMPENSATIONS",
]


class RotatingMarkerScene:
    """Static compensated scene per trial plus the moving marker, read out as gate crops.

    Parameters
    ----------
    truth : MarkerTruth
        Marker and object truth, shape (n, T) per state.
    image_shape : (int, int)
        Sensor size ``(rows, cols)``.
    spot : {"disc", "square"}
        Marker and interferer shape.
    diameter : float
        Spot diameter (disc) or side (square), px.
    brightness : float
        Marker brightness ``d`` per fully covered pixel.
    residual : ndarray, shape (n, rows, cols), optional
        Static residual after compensation, ``kappa f + interferers``; see :meth:`static_residual`.
    noise_std : float
        Sensor noise per pixel per frame (>= 0).
    interferers : ndarray, shape (n, q, 2), optional
        Interferer positions (kept for plotting and capture tagging).
    decoys : ndarray, shape (n, T, 2), optional
        Paths of a moving imitating interferer (e.g. an emitter rotating like the marker about
        another centre), rendered into every frame with the marker's spot.
    decoy_brightness : float or ndarray, shape (n,)
        Decoy brightness per fully covered pixel (one value per trial allowed).
    exposure_steps : int
        1: the sensor samples the scene at the frame time (instant exposure). ``m > 1``: it integrates over the
        frame interval centred on the frame time, rendered as the mean of ``m`` sub-frame renders at
        ``tau_j = ((j + 1/2)/m - 1/2) dt``: the object moves by its velocity (central differences of the truth),
        the marker turns by ``omega tau_j`` about it, the decoy about its own centre (``decoy_phase``). The spot
        energy per frame is the same either way; only its spread changes. :meth:`frame` (recordings) is instant.
    decoy_phase : ndarray, shape (n,), optional
        Phase offset of each decoy from the marker (needed to smear a decoy).
    """

    MARGIN = 40  # px of zero padding around the image so that gates may leave it

    def __init__(
        self,
        truth: MarkerTruth,
        image_shape,
        spot: str,
        diameter: float,
        brightness: float,
        residual=None,
        noise_std: float = 0.0,
        interferers=None,
        decoys=None,
        decoy_brightness=0.0,
        exposure_steps: int = 1,
        decoy_phase=None,
    ):
        check_spot(spot)
        if int(exposure_steps) < 1:
            raise ValueError(f"parameter 'exposure_steps' = {exposure_steps}; it must be >= 1")
        if noise_std < 0:
            raise ValueError(f"parameter 'noise_std' = {noise_std}; it must be >= 0")
        self.truth = truth
        self.n = truth.xr.shape[0]
        self.image_shape = tuple(image_shape)
        self.spot = spot
        self.diameter = float(diameter)
        self.brightness = float(brightness)
        self.noise_std = float(noise_std)
        self.interferers = np.zeros((self.n, 0, 2)) if interferers is None else np.asarray(interferers, float)
        self.decoys = None if decoys is None else np.asarray(decoys, dtype=float)
        self.decoy_brightness = np.broadcast_to(np.asarray(decoy_brightness, dtype=float), (self.n,))
        self._lit = np.flatnonzero(self.decoy_brightness != 0)  # trials whose decoy adds light
        self._box_cache: dict = {}  # spot boxes of the frames at hand (:meth:`_boxes`)
        m = self.MARGIN
        rows, cols = self.image_shape
        self._padded = np.zeros((self.n, rows + 2 * m, cols + 2 * m), dtype=np.float32)
        if residual is not None:
            self._padded[:, m : m + rows, m : m + cols] = residual
        self._base = np.arange(self.n) * self._padded.shape[1] * self._padded.shape[2]
        self._windows: dict = {}  # gate_crops' window views of the padded image by crop side
        self._trials = np.arange(self.n)
        self._marker = None  # gate_crops' marker positions (n, T, 2), made on first use
        self.exposure_steps = int(exposure_steps)
        if self.exposure_steps > 1:
            t = truth.t
            self._dt = float(t[1] - t[0]) if t.size > 1 else 1.0
            self._velocity = np.gradient(truth.center, self._dt, axis=1) if t.size > 1 else np.zeros_like(truth.center)
            if self.decoys is not None and decoy_phase is None:
                raise ValueError("an integrated exposure with a decoy needs 'decoy_phase'")
            self.decoy_phase = None if decoy_phase is None else np.asarray(decoy_phase, float).reshape(self.n)

    @classmethod
    def joined(cls, scenes) -> "RotatingMarkerScene":
        """One scene holding the trials of ``scenes`` one after the other (the same image, spot, brightness, sensor
        noise, exposure and frame times): each trial's crops are those its own scene gives, bit for bit. A scene
        without a decoy contributes a dark one (no light, :meth:`gate_crops` skips it). The static images are moved
        into the joined scene's and each scene keeps a view of its part, so no memory is doubled."""
        first = scenes[0]
        same = ("image_shape", "spot", "diameter", "brightness", "noise_std", "exposure_steps")
        if any(getattr(s, a) != getattr(first, a) for s in scenes for a in same) or any(
            not np.array_equal(s.truth.t, first.truth.t) for s in scenes
        ):
            raise ValueError(f"parameter 'scenes' must agree in {', '.join(same)} and frame times")
        out = cls.__new__(cls)
        out.__dict__.update({a: getattr(first, a) for a in same + ("truth",)})
        fields = ("xr", "yr", "r", "theta", "omega")
        out.truth = MarkerTruth(*(np.concatenate([getattr(s.truth, f) for s in scenes]) for f in fields), first.truth.t)
        out.n = sum(s.n for s in scenes)
        q = max(s.interferers.shape[1] for s in scenes)
        out.interferers = np.concatenate(
            [np.concatenate([s.interferers, np.full((s.n, q - s.interferers.shape[1], 2), -1e4)], 1) for s in scenes]
        )
        lit = any(s.decoys is not None for s in scenes)
        out.decoys = (
            np.concatenate([s.decoys if s.decoys is not None else s.truth.marker for s in scenes]) if lit else None
        )
        out.decoy_brightness = np.concatenate(
            [s.decoy_brightness if s.decoys is not None else np.zeros(s.n) for s in scenes]
        )
        out._lit = np.flatnonzero(out.decoy_brightness != 0)
        out._box_cache = {}
        out._padded = np.empty((out.n,) + first._padded.shape[1:], np.float32)
        start = 0
        for s in scenes:  # each scene's images moved into the joined ones (freed one by one); it reads its part
            out._padded[start : start + s.n] = s._padded
            s._padded, s._windows, start = out._padded[start : start + s.n], {}, start + s.n
        out._base = np.arange(out.n) * out._padded.shape[1] * out._padded.shape[2]
        out._windows, out._trials, out._marker = {}, np.arange(out.n), None
        if out.exposure_steps > 1:
            out._dt, out._velocity = first._dt, np.concatenate([s._velocity for s in scenes])
            out.decoy_phase = (
                np.concatenate([s.decoy_phase if s.decoys is not None else np.zeros(s.n) for s in scenes])
                if lit
                else None
            )
        return out

    def _sub_positions(self, k: int, k1: int) -> tuple[np.ndarray, np.ndarray | None]:
        """Marker (and decoy) positions at the ``m`` sub-frame times of frames ``k`` to ``k1 - 1``, shape
        (m, n, k1 - k, 2) each (elementwise: the numbers of each frame alone)."""
        tr, m, s = self.truth, self.exposure_steps, slice(k, k1)
        tau = ((np.arange(m) + 0.5) / m - 0.5) * self._dt
        shift = tau[:, None, None, None] * self._velocity[None, :, s]  # object motion within the frame
        ang = tr.theta[None, :, s] + tr.omega[None, :, s] * tau[:, None, None]
        r = tr.r[None, :, s]
        centre = np.stack([tr.xr[:, s], tr.yr[:, s]], axis=-1)[None]
        marker = centre + shift + r[..., None] * np.stack([np.cos(ang), np.sin(ang)], axis=-1)
        if self.decoys is None:
            return marker, None
        a0 = tr.theta[:, s] + self.decoy_phase[:, None]
        own = self.decoys[:, s] - r[0][..., None] * np.stack([np.cos(a0), np.sin(a0)], axis=-1)  # decoy's centre
        a = ang + self.decoy_phase[None, :, None]
        return marker, own[None] + shift + r[..., None] * np.stack([np.cos(a), np.sin(a)], axis=-1)

    def _sub_boxes(self, k: int) -> tuple[np.ndarray, np.ndarray]:
        """An integrated exposure's spot boxes at frame ``k``, layer by layer in the order they add up (marker and
        decoy interleaved, sub-step by sub-step): first pixels (L, n, 2) and renders (L, n, side, side), rendered
        :data:`SUB_CHUNK` frames at a time (the numbers of frame ``k`` alone, see :meth:`_boxes`)."""
        got = self._box_cache.get("sub")
        if got is None or not got[0] <= k < got[0] + got[1].shape[2]:
            k1 = min(k + self.SUB_CHUNK, self.truth.n_frames)
            sub_m, sub_d = self._sub_positions(k, k1)  # (steps, n, frames, 2) each
            steps = self.exposure_steps
            b = np.full(sub_m.shape[:3], self.brightness / steps)
            if sub_d is not None:  # marker and decoy interleaved, step by step, as they add up
                sub_m = np.stack([sub_m, sub_d], axis=1).reshape((2 * steps,) + sub_d.shape[1:])
                db = np.broadcast_to((self.decoy_brightness / steps)[:, None], b.shape[1:])
                b = np.stack([b, np.broadcast_to(db, b.shape)], axis=1).reshape((2 * steps,) + b.shape[1:])
            reach = self.diameter / 2 + 0.5
            box0 = np.floor(sub_m - reach).astype(np.int64) + 1
            got = self._box_cache["sub"] = (k, box0, self._spot(sub_m, int(np.ceil(2 * reach)), box0, b))
        return got[1][:, :, k - got[0]], got[2][:, :, k - got[0]]

    @staticmethod
    def static_residual(
        rng: np.random.Generator,
        n: int,
        image_shape,
        *,
        kappa: float,
        background_std: float,
        corr_length: float,
        interferers,
        interferer_brightness,
        spot: str,
        diameter: float,
    ) -> np.ndarray:
        """``kappa * f + sum_q b_q spot(. - x_q)``: what compensation leaves of the static scene.

        Parameters
        ----------
        kappa : float
            Compensation residual factor in [0, 1] (0 = perfect estimate of the background).
        background_std : float
            Standard deviation of ``f`` before compensation.
        interferers : ndarray, shape (n, q, 2)
        interferer_brightness : float or ndarray, shape (n,) or (n, q)
            Residual brightness (after compensation) of each interferer, ``d / SIR``.

        Returns
        -------
        ndarray, shape (n, rows, cols), float32
        """
        if not 0 <= kappa <= 1:
            raise ValueError(f"parameter 'kappa' = {kappa}; it must be in [0, 1]")
        out = kappa * correlated_background(rng, n, image_shape, corr_length, background_std)
        q = np.asarray(interferers, dtype=float)
        b = np.asarray(interferer_brightness, dtype=float)
        b = np.broadcast_to(b[:, None] if b.ndim == 1 else b, q.shape[:2])
        add_spots(out, q, b, spot, diameter)
        return out

    def gate_crops(self, k: int, centres, size: int, rng: np.random.Generator | None, trials=None):
        """Compensated signal ``u_d`` in square crops of side ``size`` around ``centres`` at frame ``k``.

        Parameters
        ----------
        k : int
            Frame index.
        centres : ndarray, shape (n, 2)
            Gate centres (px).
        size : int
            Crop side (px), e.g. :func:`tvtrack.measure.gate_crop_size`.
        rng : numpy.random.Generator or None
            Draws the sensor noise (None: noise-free).
        trials : ndarray of int, shape (n,), optional
            The trials whose crops are read (default: all, in order); ``centres`` are theirs.

        Returns
        -------
        crops : ndarray, shape (n, size, size), float32
        origin : ndarray of int, shape (n, 2)
            ``(x0, y0)`` of each crop's first pixel.
        inside : ndarray of bool, shape (n,)
            Whether the gate centre is inside the image.
        """
        m = self.MARGIN
        rows, cols = self.image_shape
        t, c = crop_request(self._padded.shape, self._trials, centres, size, trials)  # checked for both paths
        origin = np.floor(c - (size - 1) / 2.0).astype(np.int64)
        inside = ((c >= 0) & (c <= (cols - 1, rows - 1))).all(axis=1)
        o = np.minimum(np.maximum(origin + m, 0), (cols + 2 * m - size, rows + 2 * m - size))  # (x, y) in the padding
        origin = o - m
        ox, oy = o[:, 0], o[:, 1]
        if jit.enabled():  # the compiled twin (the same bits, see ._frame_kernels)
            crops = gather_windows(self._padded, t.astype(np.int64), oy.copy(), ox.copy(), size)
        else:
            if size not in self._windows:  # every size x size window of the padded image, a view (no copy), by side
                self._windows[size] = sliding_window_view(self._padded, (size, size), axis=(1, 2))
            crops = self._windows[size][t, oy, ox]  # (n, size, size), a copy
        if self._marker is None:  # eq. (8) for every frame at once (elementwise: the same numbers frame by frame)
            tr = self.truth
            self._marker = np.stack([tr.xr + tr.r * np.cos(tr.theta), tr.yr + tr.r * np.sin(tr.theta)], axis=-1)
        db = self.decoy_brightness if trials is None else self.decoy_brightness[t]
        if self.exposure_steps == 1:  # the spots' boxes rendered ahead (_boxes), added where they meet the crops
            box0, patch = self._boxes(k, False)
            self._add_boxes(crops, *((box0, patch) if trials is None else (box0[t], patch[t])), origin)
            if self.decoys is not None and self._lit.size:  # a dark decoy adds zeros: rendered only where it shines
                lit = self._lit if trials is None else np.flatnonzero(db != 0)
                box0, patch = self._boxes(k, True)  # the lit trials', in order
                if trials is not None:
                    rows = np.searchsorted(self._lit, t[lit])
                    box0, patch = box0[rows], patch[rows]
                if lit.size:
                    self._add_boxes(crops, box0, patch, origin[lit], None if lit.size == t.size else lit)
        else:
            box0, patch = self._sub_boxes(k)  # (layers, n, ...): added layer by layer
            self._add_boxes(crops, *((box0, patch) if trials is None else (box0[:, t], patch[:, t])), origin)
        if rng is not None and self.noise_std > 0:
            crops += self.noise_std * rng.standard_normal(crops.shape, dtype=np.float32)
        return crops, origin, inside

    CHUNK = 64  # frames whose spot boxes :meth:`_boxes` renders in one call
    SUB_CHUNK = 16  # frames whose sub-frame spot boxes :meth:`_sub_boxes` renders in one call

    def _boxes(self, k: int, decoy: bool) -> tuple[np.ndarray, np.ndarray]:
        """First pixels, shape (n, 2), and renders, shape (n, side, side) float32, of the boxes of pixels the marker's
        spots (``decoy``: the lit decoys', trials ``_lit``) reach at frame ``k`` (see :meth:`_add_spot`), rendered
        :data:`CHUNK` frames at a time: they follow the truth alone, and the spot functions work pixel by pixel, so
        these are the numbers a render of frame ``k`` alone gives."""
        got = self._box_cache.get(decoy)
        if got is None or not got[0] <= k < got[0] + got[1].shape[1]:
            k1 = min(k + self.CHUNK, self.truth.n_frames)
            if decoy:
                c = self.decoys[self._lit, k:k1]
                b = np.broadcast_to(self.decoy_brightness[self._lit, None], c.shape[:2])
            else:
                c, b = self._marker[:, k:k1], self.brightness
            reach = self.diameter / 2 + 0.5
            box0 = np.floor(c - reach).astype(np.int64) + 1
            got = self._box_cache[decoy] = (k, box0, self._spot(c, int(np.ceil(2 * reach)), box0, b))
        return got[1][:, k - got[0]], got[2][:, k - got[0]]

    def _add_boxes(self, crops, box0, patch, origin, trials=None) -> None:
        """Add the spot boxes ``patch`` (n, side, side) with first pixels ``box0`` (n, 2), or layers of them (shapes
        (L, n, ...), added one layer after the other), to the crops (first pixels ``origin``) of ``crops`` (the crops
        ``trials``, default all) where they overlap them, in place."""
        if box0.ndim == 2:
            box0, patch = box0[None], patch[None]
        if jit.enabled():  # the compiled twin (the same bits, see ._frame_kernels); contiguous: one compiled layout
            rows = np.arange(box0.shape[1]) if trials is None else np.asarray(trials, dtype=np.int64)
            return add_box_layers(crops, *map(np.ascontiguousarray, (box0, patch, origin)), rows)
        size, side = crops.shape[-1], patch.shape[-1]
        rel = box0 - origin  # each box's first pixel within its crop
        inside = ((rel >= 0) & (rel <= size - side)).all(axis=-1)
        # each trial writes its own crop's windows; a box larger than the crop is never wholly inside it (no windows)
        win = sliding_window_view(crops, (side, side), axis=(1, 2), writeable=True) if side <= size else None
        trials = np.arange(rel.shape[1]) if trials is None else np.asarray(trials)
        every = win is not None and inside.all()
        for j in range(rel.shape[0]):
            if every:
                win[trials, rel[j, :, 1], rel[j, :, 0]] += patch[j]
            else:
                self._place(crops, win, patch[j], rel[j], inside[j], side, trials)

    # crops holding more pixels than this get their spots rendered box by box: faster from about 48 disc or 96
    # square-spot crops of 26 x 26 px (measured: 84 against 121 us a frame for 96 discs, 90 against 95 for squares;
    # lower thresholds, faster per call with the 9-pixel box, made the tracking study's 24-30-run batches slower)
    BOX_MIN_PIXELS = {"disc": 30000, "square": 60000}

    def _add_spot(self, crops, centers, origin, brightness, trials=None) -> None:
        """Add spots centred at ``centers`` (n, 2) px, or (m, n, 2): ``m`` spots per crop added one after the other
        (``brightness`` then (m, n)), to ``crops`` (n, size, size), first pixels at ``origin``, in place; with
        ``trials`` (indices, shape (n,)) to those crops of ``crops`` only.

        All the spots are rendered in one call (the spot functions are pixel by pixel: the same numbers as one call
        each), then added in order. Large batches render only the box of pixels a spot can reach (centres within
        ``D/2 + 1/2`` of the spot's centre, for the disc and the square alike) and add it where it overlaps its crop:
        every pixel gets the same float32 number as rendering the whole crop (the other pixels get 0).
        """
        n, size = (crops.shape[0] if trials is None else len(trials)), crops.shape[-1]
        c = np.asarray(centers, dtype=float)
        m = 1 if c.ndim == 2 else c.shape[0]
        if m > 1:  # one render of every spot: centres, origins and brightnesses flattened to (m n, ...)
            c = c.reshape(m * n, 2)
            origin = np.tile(origin, (m, 1))
            brightness = np.broadcast_to(np.asarray(brightness, dtype=float), (m, n)).reshape(m * n)
        if crops.size <= self.BOX_MIN_PIXELS[self.spot]:
            spots = self._spot(c, size, origin, brightness)
            for j in range(m):
                if trials is None:
                    crops += spots[j * n : (j + 1) * n]
                else:
                    crops[trials] += spots[j * n : (j + 1) * n]
            return
        reach = self.diameter / 2 + 0.5
        # pixels up to c - reach and from c + reach get nothing: floor(c - reach) + 1 .. + side - 1 hold the rest
        side = int(np.ceil(2 * reach))
        box0 = np.floor(c - reach).astype(np.int64) + 1
        patch = self._spot(c, side, box0, brightness)
        rel = box0 - origin  # (m n, 2): each box's first pixel within its crop
        inside = ((rel >= 0) & (rel <= size - side)).all(axis=1)
        win = sliding_window_view(crops, (side, side), axis=(1, 2), writeable=True)  # each trial writes its own crop
        trials, every = (np.arange(n) if trials is None else np.asarray(trials)), inside.all()
        for j in range(m):
            sl = slice(j * n, (j + 1) * n)
            if every:
                win[trials, rel[sl, 1], rel[sl, 0]] += patch[sl]
            else:
                self._place(crops, win, patch[sl], rel[sl], inside[sl], side, trials)

    @staticmethod
    def _place(crops, win, patch, rel, inside, side: int, trials) -> None:
        """Add boxes ``patch`` (n, side, side) to the crops ``trials`` (n,) of ``crops`` (., size, size) with their
        first pixels at ``rel`` (n, 2) within the crops, where they overlap (``win``: the crops' side x side windows;
        ``inside``: the boxes wholly inside their crops)."""
        size = crops.shape[-1]
        t = np.flatnonzero(inside)
        if t.size:
            win[trials[t], rel[t, 1], rel[t, 0]] += patch[t]
        part = np.flatnonzero(~inside & ((rel > -side) & (rel < size)).all(axis=1))  # boxes across a crop's edge
        if part.size:  # boxes wholly outside add nothing
            ar = np.arange(side)
            cx, cy = rel[part, 0, None] + ar, rel[part, 1, None] + ar
            idx = (trials[part][:, None, None] * size + cy[:, :, None]) * size + cx[:, None, :]
            ok = ((cy >= 0) & (cy < size))[:, :, None] & ((cx >= 0) & (cx < size))[:, None, :]
            crops.reshape(-1)[idx[ok]] += patch[part][ok]  # indices unique: each box pixel inside is one crop pixel

    def _spot(self, centers, size, origin, brightness) -> np.ndarray:
        if self.spot == "disc":
            flux = np.asarray(brightness, dtype=float) * disc_area(self.diameter)
            return disc_spot(centers, (size, size), self.diameter, flux, origin, dtype=np.float32)
        return render_spot("square", centers, (size, size), self.diameter, brightness, origin).astype(np.float32)

    def frame(self, trial: int, k: int, rng: np.random.Generator | None = None) -> np.ndarray:
        """Full compensated frame ``u_d`` of one trial at frame ``k``, shape (rows, cols), float32."""
        m = self.MARGIN
        rows, cols = self.image_shape
        img = self._padded[trial, m : m + rows, m : m + cols].copy()
        img += render_spot(
            self.spot, self.truth.marker[trial, k], self.image_shape, self.diameter, self.brightness
        ).astype(np.float32)
        if self.decoys is not None:
            img += render_spot(
                self.spot, self.decoys[trial, k], self.image_shape, self.diameter, self.decoy_brightness[trial]
            ).astype(np.float32)
        if rng is not None and self.noise_std > 0:
            img += self.noise_std * rng.standard_normal(img.shape, dtype=np.float32)
        return img


def build_scene(
    rng: np.random.Generator,
    truth: MarkerTruth,
    *,
    image_shape=(256, 256),
    spot: str = "disc",
    diameter: float = 8.0,
    brightness: float = 1.0,
    noise_std: float = 0.02,
    kappa: float = 0.1,
    background_std: float = 0.2,
    corr_length: float = 8.0,
    n_interferers: int = 0,
    sir=np.inf,
    interferer_radius: float = 12.0,
    interferer_center=None,
    radial_jitter: float = 0.0,
    interferer_diameter: float | None = None,
    interferer_layout: str = "even",
    decoys=None,
    decoy_brightness=0.0,
    n_common: int | None = None,
    blocks=None,
    exposure_steps: int = 1,
    decoy_phase=None,
    compensation: str = "kappa",
    median_frames: int = 0,
):
    """A compensated scene with ``n_interferers`` stationary interferers of post-compensation
    ``SIR = d / b_q`` (scalar or one value per trial; ``b_q`` per fully covered pixel, like ``d``), placed by
    :func:`place_interferers` around ``interferer_center`` (default: the object's initial centre; ``"trace"``: each
    interferer about the object's centre at its own random frame of the run, :func:`_interferer_centres`) in
    ``interferer_layout``, with the marker's spot or one of ``interferer_diameter``.

    ``n_common``: draw the background and the interferer positions for ``n_common`` trials and
    repeat them over the ``n / n_common`` blocks (common random numbers; default: all trials
    independent). ``rng`` may be a list of generators: each draws for its own consecutive block
    of ``n / len(rng)`` trials (several seeds in one batch). ``blocks``, one dict per generator,
    overrides ``kappa``, ``background_std``, ``corr_length`` or ``n_interferers`` block by block
    (several scene settings in one batch; a block with fewer interferers is padded with dark ones
    far outside the image).

    ``compensation``: ``"kappa"`` leaves ``kappa`` times the static scene (:meth:`RotatingMarkerScene.
    static_residual`); ``"median"`` subtracts the temporal median of the first ``median_frames`` frames, the
    marker's own spot masked out (:func:`median_residual`: the background cancels), in every block with ``kappa < 1``
    (a block with ``kappa = 1`` stays uncompensated). Either way each interferer keeps ``d / SIR``: the paper's SIR is
    the brightness an interferer keeps after compensation (l. 198).

    Returns
    -------
    RotatingMarkerScene
    """
    n = truth.xr.shape[0]
    rngs, n_block, n_common = generator_blocks(rng, n, n_common)
    blocks = _check_blocks(blocks, len(rngs), compensation)
    q, residual = [], []
    for j, (g, b) in enumerate(zip(rngs, blocks)):
        first = j * n_block
        count = b.get("n_interferers", n_interferers)
        centre = _interferer_centres(g, truth, first, n_common, count, interferer_center)
        q.append(
            tile_rows(
                place_interferers(g, n_common, count, centre, interferer_radius, radial_jitter, interferer_layout),
                n_block,
            )
        )
        static = dict(kappa=kappa, background_std=background_std, corr_length=corr_length)
        res = _block_residual(
            g, {**static, **b}, truth, first, n_common, compensation, median_frames, image_shape, spot, diameter,
            brightness, noise_std,
        )  # fmt: skip
        residual.append(tile_rows(res, n_block))
    n_q = max(x.shape[1] for x in q)
    q = np.concatenate([np.concatenate([x, np.full((x.shape[0], n_q - x.shape[1], 2), -1e4)], axis=1) for x in q])
    residual = np.concatenate(residual) if len(residual) > 1 else residual[0]
    sir = np.broadcast_to(np.asarray(sir, dtype=float), (n,))
    if np.any(sir <= 0):
        raise ValueError(f"parameter 'sir' has values <= 0 ({sir.min()}); it must be > 0")
    # SIR is the marker's brightness over what each interferer keeps after compensation (l. 198), whatever the
    # compensation: d / SIR under the median too (one that removed them would leave no SIR to set)
    add_spots(
        residual,
        q,
        np.where(q[..., 0] > -1e3, (brightness / sir)[:, None], 0.0),
        spot,
        diameter if interferer_diameter is None else interferer_diameter,
    )
    return RotatingMarkerScene(
        truth,
        image_shape,
        spot,
        diameter,
        brightness,
        residual,
        noise_std,
        q,
        decoys,
        decoy_brightness,
        exposure_steps,
        decoy_phase,
    )


def _interferer_centres(g: np.random.Generator, truth: MarkerTruth, first: int, n_common: int, count: int, where):
    """The centres of the interferers' circles for the trials ``first .. first + n_common - 1`` (px): the object's
    initial centre (``where`` None), a fixed point, or with ``"trace"`` the object's centre at a frame drawn uniformly
    from the run for each interferer (shape (n_common, count, 2)), so that every interferer lies on the marker's trace:
    the marker passes over it within half a revolution of that frame, off it by at most the object's travel in that
    time (Fig. 3: the marker "sweeps the area where the interferers are placed")."""
    if where is None:
        return truth.center[first : first + n_common, 0]
    if isinstance(where, str):
        if where != "trace":
            raise ValueError(f"parameter 'interferer_center' = {where!r}; it must be None, a point or 'trace'")
        k = g.integers(0, truth.n_frames, size=(n_common, count))
        rows = first + np.arange(n_common)[:, None]
        return np.stack([truth.xr[rows, k], truth.yr[rows, k]], axis=-1)
    return where


def _check_blocks(blocks, n_generators: int, compensation: str) -> list:
    """The per-generator scene settings of :func:`build_scene` (one dict per generator), checked."""
    blocks = [{}] * n_generators if blocks is None else list(blocks)
    if len(blocks) != n_generators or any(
        set(b) - {"kappa", "background_std", "corr_length", "n_interferers", "decoy_offset"} for b in blocks
    ):
        raise ValueError(
            "parameter 'blocks' needs one dict per generator with keys among kappa, background_std, "
            "corr_length, n_interferers, decoy_offset"
        )
    if compensation not in COMPENSATIONS:
        raise ValueError(f"parameter 'compensation' = {compensation!r}; it must be one of {COMPENSATIONS}")
    return blocks


def _block_residual(
    g, b: dict, truth, first: int, n_common: int, compensation: str, median_frames: int, image_shape, spot: str,
    diameter: float, brightness: float, noise_std: float,
):  # fmt: skip
    """One generator block's static residual without its interferers, shape (n_common, rows, cols): what the median of
    the first ``median_frames`` frames leaves (:func:`median_residual`) when ``compensation`` is ``"median"`` and the
    block compensates (``kappa < 1``), else ``kappa`` times the background (``b``'s settings)."""
    if compensation == "median" and b["kappa"] < 1:
        part = MarkerTruth(
            *(getattr(truth, f)[first : first + n_common] for f in ("xr", "yr", "r", "theta", "omega")), truth.t
        )
        return median_residual(g, part, median_frames, image_shape, spot, diameter, brightness, noise_std)
    res = RotatingMarkerScene.static_residual(
        g,
        n_common,
        image_shape,
        kappa=b["kappa"],
        background_std=b["background_std"],
        corr_length=b["corr_length"],
        interferers=np.zeros((n_common, 0, 2)),
        interferer_brightness=np.zeros(n_common),
        spot=spot,
        diameter=diameter,
    )
    return res


COMPENSATIONS = ("kappa", "median")
