"""Trace data sets: true spot-centre trajectories saved as ``.npz`` (no pickles).

A :class:`TraceSet` holds ``n_paths`` trajectories of ``n_frames`` frames: the true centre
``(x, y)`` in pixels (pixel centres at integers, x = column, y = row, as in
:mod:`tvtrack.render`), a per-frame total-intensity factor (scintillation, mean about 1), the
frame rate, the sensor size and the parameters that generated them (JSON).

File layout (a deflated ``.npz`` with a fixed time stamp, so equal data give equal bytes; every array plain numeric or a 0-d unicode string)::

    centres_px    float64 (n_paths, n_frames, 2)
    intensity     float64 (n_paths, n_frames)      > 0
    frame_rate_hz float64 ()                       > 0
    image_size_px int64   ()                       > 0
    metadata_json <U      ()                       JSON object (generator, seed, per-path draws)
    format        <U      ()                       "tvtrack-traces-v1"

:func:`load_traces` opens with ``allow_pickle=False`` and checks names, dtypes, shapes and
values; any mismatch raises ``ValueError`` naming the file and the offending entry.
"""

from __future__ import annotations

import hashlib
import io
import json
import zipfile
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

__all__ = ["TraceSet", "save_traces", "load_traces", "sha256_file", "FORMAT_TAG", "DATA_DIR"]

FORMAT_TAG = "tvtrack-traces-v1"

#: The repository's ``data/`` folder with the shipped data sets (the package is installed editable from ``lib/``).
DATA_DIR = Path(__file__).resolve().parents[4] / "data"

_REQUIRED = ("centres_px", "intensity", "frame_rate_hz", "image_size_px", "metadata_json", "format")


@dataclass
class TraceSet:
    """True spot-centre trajectories.

    Attributes
    ----------
    centres_px : ndarray, float64, shape (n_paths, n_frames, 2)
        True centre ``(x, y)`` per frame, pixels.
    intensity : ndarray, float64, shape (n_paths, n_frames)
        Total-intensity factor per frame (dimensionless, > 0; scintillation).
    frame_rate_hz : float
        Frames per second.
    image_size_px : int
        Side of the square sensor, pixels.
    metadata : dict
        JSON-serialisable description (generator parameters with units, seed, per-path draws).
    """

    centres_px: np.ndarray
    intensity: np.ndarray
    frame_rate_hz: float
    image_size_px: int
    metadata: dict = field(default_factory=dict)

    def __post_init__(self):
        _validate(self.centres_px, self.intensity, self.frame_rate_hz, self.image_size_px, where="TraceSet")

    @property
    def n_paths(self) -> int:
        return self.centres_px.shape[0]

    @property
    def n_frames(self) -> int:
        return self.centres_px.shape[1]

    @property
    def time_s(self) -> np.ndarray:
        """Frame times, seconds, shape (n_frames,)."""
        return np.arange(self.n_frames) / self.frame_rate_hz


def _validate(centres, intensity, frame_rate_hz, image_size_px, where: str) -> None:
    c = np.asarray(centres)
    i = np.asarray(intensity)
    if c.dtype != np.float64 or c.ndim != 3 or c.shape[-1] != 2 or c.shape[0] < 1 or c.shape[1] < 1:
        raise ValueError(
            f"{where}: 'centres_px' must be float64 of shape (n_paths>=1, n_frames>=1, 2); got {c.dtype} {c.shape}"
        )
    if i.dtype != np.float64 or i.shape != c.shape[:2]:
        raise ValueError(f"{where}: 'intensity' must be float64 of shape {c.shape[:2]}; got {i.dtype} {i.shape}")
    if not np.all(np.isfinite(c)):
        raise ValueError(f"{where}: 'centres_px' holds non-finite values")
    if not (np.all(np.isfinite(i)) and np.all(i > 0)):
        raise ValueError(f"{where}: 'intensity' must be finite and > 0")
    if not (np.isfinite(frame_rate_hz) and frame_rate_hz > 0):
        raise ValueError(f"{where}: 'frame_rate_hz' = {frame_rate_hz!r}; it must be a finite number > 0")
    if int(image_size_px) != image_size_px or image_size_px < 1:
        raise ValueError(f"{where}: 'image_size_px' = {image_size_px!r}; it must be an integer >= 1")
    if np.any(c < -0.5) or np.any(c > image_size_px - 0.5):
        raise ValueError(
            f"{where}: 'centres_px' leave the sensor [-0.5, {image_size_px - 0.5}] px "
            f"(range {c.min():.2f}..{c.max():.2f})"
        )


def save_traces(path, traces: TraceSet) -> Path:
    """Write ``traces`` to ``path`` (``.npz`` added if missing) and return the path."""
    path = Path(path)
    if path.suffix != ".npz":
        path = path.with_suffix(".npz")
    path.parent.mkdir(parents=True, exist_ok=True)
    arrays = {
        "centres_px": np.asarray(traces.centres_px, dtype=np.float64),
        "intensity": np.asarray(traces.intensity, dtype=np.float64),
        "frame_rate_hz": np.asarray(traces.frame_rate_hz, dtype=np.float64),
        "image_size_px": np.asarray(traces.image_size_px, dtype=np.int64),
        "metadata_json": np.asarray(json.dumps(traces.metadata, sort_keys=True)),
        "format": np.asarray(FORMAT_TAG),
    }
    # like np.savez_compressed, but with a fixed time stamp so equal data give equal bytes
    # (the data set's checksums are then reproducible)
    with zipfile.ZipFile(path, "w", compression=zipfile.ZIP_DEFLATED) as zf:
        for name, a in arrays.items():
            info = zipfile.ZipInfo(f"{name}.npy", date_time=(1980, 1, 1, 0, 0, 0))
            info.compress_type = zipfile.ZIP_DEFLATED
            buf = io.BytesIO()
            np.lib.format.write_array(buf, a, allow_pickle=False)
            zf.writestr(info, buf.getvalue())
    return path


def load_traces(path) -> TraceSet:
    """Read and validate a trace file written by :func:`save_traces`.

    Raises
    ------
    FileNotFoundError
        If ``path`` does not exist.
    ValueError
        If the file is not a readable ``.npz`` without pickles, or an entry is missing, of the
        wrong dtype or shape, or out of range.
    """
    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"trace file {str(path)!r} does not exist")
    where = f"trace file {str(path)!r}"
    try:
        with np.load(path, allow_pickle=False) as z:
            if not hasattr(z, "files"):
                raise ValueError(f"{where}: not an .npz archive (a single .npy array)")
            missing = [k for k in _REQUIRED if k not in z.files]
            if missing:
                raise ValueError(f"{where}: missing entries {missing}; expected {list(_REQUIRED)}")
            arrays = {k: z[k] for k in _REQUIRED}
    except (zipfile.BadZipFile, OSError, EOFError) as exc:
        raise ValueError(f"{where}: not a readable .npz archive ({exc})") from None
    except ValueError as exc:
        if "pickle" in str(exc).lower():
            raise ValueError(f"{where}: holds pickled objects, which are refused") from None
        raise
    for key in ("metadata_json", "format"):
        a = arrays[key]
        if a.dtype.kind != "U" or a.shape != ():
            raise ValueError(f"{where}: '{key}' must be a 0-d unicode string; got {a.dtype} {a.shape}")
    if str(arrays["format"]) != FORMAT_TAG:
        raise ValueError(f"{where}: format {str(arrays['format'])!r}; expected {FORMAT_TAG!r}")
    for key, kind in (("frame_rate_hz", "f"), ("image_size_px", "i")):
        a = arrays[key]
        if a.shape != () or a.dtype.kind != kind:
            raise ValueError(
                f"{where}: '{key}' must be a 0-d {'float' if kind == 'f' else 'integer'}; got {a.dtype} {a.shape}"
            )
    try:
        metadata = json.loads(str(arrays["metadata_json"]))
    except json.JSONDecodeError as exc:
        raise ValueError(f"{where}: 'metadata_json' is not valid JSON ({exc})") from None
    if not isinstance(metadata, dict):
        raise ValueError(f"{where}: 'metadata_json' must hold a JSON object")
    _validate(
        arrays["centres_px"], arrays["intensity"], float(arrays["frame_rate_hz"]), int(arrays["image_size_px"]), where
    )
    return TraceSet(
        arrays["centres_px"],
        arrays["intensity"],
        float(arrays["frame_rate_hz"]),
        int(arrays["image_size_px"]),
        metadata,
    )


def sha256_file(path) -> str:
    """Hex SHA-256 of a file's bytes."""
    h = hashlib.sha256()
    with open(path, "rb") as fh:
        for block in iter(lambda: fh.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()
