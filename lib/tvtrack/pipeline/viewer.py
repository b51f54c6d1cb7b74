"""Open recordings in the real Rerun viewer, headless on the CPU, and look at what a user sees.

The native viewer (``rerun --headless``) renders through Vulkan; on a machine without a GPU it
runs on Mesa's software rasteriser (llvmpipe, package ``mesa-vulkan-drivers``). Without any
Vulkan driver it cannot start, and :class:`HeadlessViewer` raises :class:`ViewerUnavailable`
with the exact package to install.

The viewer is driven through ``rerun.experimental.ViewerClient`` (pinned rerun-sdk): open a
file, wait until it has loaded, move the time cursor, read the blueprint's views and their
reports, the recording's entity paths, and take per-view screenshots. What an overlay draws is
measured by *ablation*: the view is shot once as the blueprint has it and once with the
overlay's entities excluded from the view's query, and the pixels that differ are the overlay.
Counting the coloured ones among them (chroma above a threshold) is a coarse, colour-agnostic
check that the gate, the truth or the estimate is visible; no golden images are involved.

Pitfalls handled here (``shared/notes/rerun-viewer-check.md``): ``rerun`` defers silently to
whatever already listens on its port, so every viewer gets a fresh free port and its own
process is checked to be alive; ``rerun`` is a Python wrapper around the real binary, so the
viewer runs in its own process group and the whole group is ended.

Example
-------
>>> with HeadlessViewer() as viewer:                       # doctest: +SKIP
...     rec = viewer.open("run/recording.rrd")
...     viewer.set_time("frame", rec.timeline("frame").end // 2)
...     views = viewer.views()
...     shot = viewer.screenshot(views[0].view_id)
"""

from __future__ import annotations

import copy
import ctypes
import glob
import io
import os
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Iterable, Sequence

import numpy as np

__all__ = [
    "INSTALL_HINT",
    "ViewerUnavailable",
    "vulkan_problem",
    "rerun_executable",
    "verify_rrd",
    "free_port",
    "coloured_mask",
    "dominant_colours",
    "LoadedRecording",
    "OverlayPixels",
    "HeadlessViewer",
    "entities_under",
    "plays_role",
    "Expectation",
    "RecordingCheck",
    "check_recording",
]

INSTALL_HINT = "apt-get install -y mesa-vulkan-drivers"
"""What makes the viewer run on a machine without a GPU (Debian/Ubuntu: Mesa's llvmpipe Vulkan)."""

# Vulkan loader search path for installable client drivers (ICDs), Linux.
_ICD_DIRS = ("/usr/share/vulkan/icd.d", "/etc/vulkan/icd.d", "/usr/local/share/vulkan/icd.d")


class ViewerUnavailable(RuntimeError):
    """The headless viewer cannot run on this machine; the message says why and what to install."""


def vulkan_problem() -> str | None:
    """Why the headless viewer cannot render here, or ``None`` if a Vulkan driver is present.

    Checks the Vulkan loader (``libvulkan.so.1``) and at least one installable client driver
    (ICD manifest in the loader's search path, or named by ``VK_ICD_FILENAMES`` /
    ``VK_DRIVER_FILES``). Linux only; elsewhere returns ``None`` and lets the viewer decide.
    """
    if not sys.platform.startswith("linux"):
        return None
    try:
        ctypes.CDLL("libvulkan.so.1")
    except OSError:
        return f"no Vulkan loader (libvulkan.so.1); install a software Vulkan driver: {INSTALL_HINT}"
    named = os.environ.get("VK_DRIVER_FILES") or os.environ.get("VK_ICD_FILENAMES")
    if named:
        manifests = [p for p in named.split(os.pathsep) if p]
        if not any(Path(p).exists() for p in manifests):
            return (
                f"VK_DRIVER_FILES/VK_ICD_FILENAMES name no existing driver manifest ({named}); "
                f"unset it or install a software Vulkan driver: {INSTALL_HINT}"
            )
        return None
    if not any(glob.glob(os.path.join(d, "*.json")) for d in _ICD_DIRS):
        return (
            "the Vulkan loader is installed but no Vulkan driver is (no ICD manifest in "
            f"{', '.join(_ICD_DIRS)}); install a software Vulkan driver: {INSTALL_HINT}"
        )
    return None


def rerun_executable() -> str:
    """The ``rerun`` command of the running interpreter's environment (matches the SDK version)."""
    beside = Path(sys.executable).parent / "rerun"
    if beside.is_file():
        return str(beside)
    found = shutil.which("rerun")
    if found is None:
        raise FileNotFoundError("no 'rerun' command beside the Python interpreter or on PATH (it comes with rerun-sdk)")
    return found


def verify_rrd(path: str | Path, timeout_s: float = 60.0) -> str:
    """Run ``rerun rrd verify`` on a file; returns its report, raises ``ValueError`` if it fails."""
    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"no recording at {path}")
    with path.open("rb") as fh:
        head = fh.read(4)
    if len(head) < 4 or not (head[:3] == b"RRF" and head[3:4].isdigit()):
        # `rerun rrd verify` passes a file too short to hold a message ("0 files verified without error")
        raise ValueError(f"rerun rrd verify {path} failed (exit 0): Not an RRD file: no RRF header, got {head!r}")
    proc = subprocess.run(
        [rerun_executable(), "rrd", "verify", str(path)], capture_output=True, text=True, timeout=timeout_s
    )
    report = (proc.stdout + proc.stderr).strip()
    if proc.returncode != 0 or "0 files verified" in report:
        raise ValueError(f"rerun rrd verify {path} failed (exit {proc.returncode}): {report}")
    return report


def free_port() -> int:
    """A TCP port on 127.0.0.1 that nothing listens on right now."""
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def coloured_mask(image: np.ndarray, min_chroma: int = 60) -> np.ndarray:
    """Pixels whose colour is clearly not grey.

    Parameters
    ----------
    image : ndarray, shape (H, W, 3), uint8
        RGB screenshot.
    min_chroma : int
        Threshold on ``max(R,G,B) - min(R,G,B)``, in 8-bit levels (0..255). Grey images,
        text, axes and grid lines stay below ~20; the viewer's palette colours are above 80.

    Returns
    -------
    ndarray of bool, shape (H, W)
    """
    rgb = np.asarray(image, dtype=np.int16)[..., :3]
    return (rgb.max(axis=-1) - rgb.min(axis=-1)) >= min_chroma


def dominant_colours(image: np.ndarray, mask: np.ndarray, n: int = 3, quantum: int = 32) -> list[tuple]:
    """The ``n`` most frequent colours among ``image[mask]``, each channel rounded to the middle
    of a ``quantum``-wide bin, as ``((r, g, b), count)`` (for messages, not for asserting)."""
    pixels = np.asarray(image)[..., :3][mask].astype(np.int32)
    if pixels.size == 0:
        return []
    binned = (pixels // quantum) * quantum + quantum // 2
    colours, counts = np.unique(binned, axis=0, return_counts=True)
    order = np.argsort(-counts)[:n]
    return [(tuple(int(c) for c in colours[i]), int(counts[i])) for i in order]


def _decode_png(png: bytes) -> np.ndarray:
    from PIL import Image

    with Image.open(io.BytesIO(png)) as im:
        return np.asarray(im.convert("RGB"))


@dataclass
class LoadedRecording:
    """A recording open in the viewer (the active one)."""

    path: Path
    store_id: str
    timelines: dict = field(default_factory=dict)  # name -> rerun Timeline (start, end)
    load_s: float = 0.0

    def timeline(self, name: str):
        if name not in self.timelines:
            raise KeyError(f"recording {self.path} has no timeline {name!r}; it has {sorted(self.timelines)}")
        return self.timelines[name]


@dataclass
class OverlayPixels:
    """What excluding some entities from a view changed in its screenshot."""

    view_name: str
    entities: list[str]
    changed: int  # pixels that differ between shown and hidden
    coloured: int  # of those, pixels whose shown colour is not grey
    colours: list[tuple]  # dominant shown colours among the changed coloured pixels


class HeadlessViewer:
    """A native Rerun viewer running headless, in its own process group, on a fresh port.

    Parameters
    ----------
    window_size : (int, int)
        Viewer window in logical pixels (width, height); screenshots of views are cut from it.
    startup_timeout_s : float
        How long to wait for the viewer to answer after launch.
    log_path : str or Path, optional
        Where the viewer's own stdout/stderr go (default: a temporary file, removed on close).

    Use as a context manager; :meth:`close` ends the whole process group.
    """

    def __init__(
        self,
        window_size: tuple[int, int] = (1200, 700),
        startup_timeout_s: float = 30.0,
        log_path: str | Path | None = None,
    ):
        w, h = (int(v) for v in window_size)
        if not (200 <= w <= 4000 and 200 <= h <= 4000):
            raise ValueError(f"parameter 'window_size' = {window_size!r}; both sides must be in [200, 4000] px")
        if not startup_timeout_s > 0:
            raise ValueError(f"parameter 'startup_timeout_s' = {startup_timeout_s!r}; it must be > 0 s")
        self.window_size = (w, h)
        self.startup_timeout_s = float(startup_timeout_s)
        self._own_log = log_path is None
        self.log_path = Path(log_path) if log_path else Path(tempfile.mkstemp(prefix="rerun-viewer-", suffix=".log")[1])
        self.port: int | None = None
        self.started_at: float | None = None
        self._proc: subprocess.Popen | None = None
        self._client = None
        self.recording: LoadedRecording | None = None

    # -- life cycle -------------------------------------------------------------------------
    def __enter__(self) -> "HeadlessViewer":
        self.start()
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def start(self) -> None:
        """Launch the viewer and connect; raises :class:`ViewerUnavailable` if it cannot render."""
        import rerun as rr
        from rerun.experimental import ViewerClient

        problem = vulkan_problem()
        if problem:
            raise ViewerUnavailable(problem)
        self.port = free_port()
        w, h = self.window_size
        cmd = [
            rerun_executable(),
            "--headless",
            "--bind",
            "127.0.0.1",
            "--port",
            str(self.port),
            "--window-size",
            f"{w}x{h}",
            "--hide-welcome-screen",
        ]
        with open(self.log_path, "wb") as log:
            self._proc = subprocess.Popen(
                cmd, stdout=log, stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL, start_new_session=True
            )
        self.started_at = time.monotonic()
        url = f"rerun+http://127.0.0.1:{self.port}/proxy"
        deadline = self.started_at + self.startup_timeout_s
        last_error: Exception | None = None
        while time.monotonic() < deadline:
            if self._proc.poll() is not None:
                self._raise_start_failure(f"the viewer exited with code {self._proc.returncode} while starting")
            try:
                client = ViewerClient.connect(url)
                state = client.get_state()
            except (ConnectionError, RuntimeError, OSError) as exc:
                last_error = exc
                time.sleep(0.1)
                continue
            self._client = client
            break
        if self._client is None:
            self.close()
            raise RuntimeError(
                f"the headless viewer did not answer on {url} within {self.startup_timeout_s:.0f} s "
                f"(last error: {last_error}); log: {self._log_tail()}"
            )
        # the gRPC server answers before the renderer exists: paint one small frame to be sure it
        # renders, then check that our own process is the one answering (rerun defers silently
        # to an existing listener on its port and exits)
        try:
            self._client.take_screenshot(max_size=64)
        except (ConnectionError, RuntimeError, OSError) as exc:
            try:  # a viewer that cannot render panics; give it a moment to exit
                self._proc.wait(timeout=5)
            except subprocess.TimeoutExpired:
                pass
            if self._proc.poll() is not None:
                self._raise_start_failure(f"the viewer exited with code {self._proc.returncode} on its first frame")
            tail = self._log_tail()
            self.close()
            raise RuntimeError(f"the headless viewer cannot take a screenshot ({exc}); log: {tail}") from exc
        if self._proc.poll() is not None:
            self._raise_start_failure("the viewer process exited although something answers on its port")
        if state.viewer_version and state.viewer_version.split("+")[0] != rr.__version__:
            self.close()
            raise RuntimeError(f"viewer {state.viewer_version} answers but rerun-sdk is {rr.__version__}")

    def _raise_start_failure(self, what: str):
        try:
            log = self.log_path.read_text(errors="replace")
        except OSError:
            log = ""
        panic = next((line.strip() for line in log.splitlines() if "panicked" in line), "")
        tail = self._log_tail()
        self.close()
        # without Vulkan, wgpu falls back to GL, which lacks a render target the viewer needs
        no_renderer = ("graphics adapter", "render context", "backend: gl", "no suitable adapter")
        if any(sign in log.lower() for sign in no_renderer):
            raise ViewerUnavailable(
                f"{what} ({panic or 'no usable graphics adapter'}); install a software Vulkan driver: {INSTALL_HINT}"
            )
        raise RuntimeError(f"{what}. Viewer log: {tail}")

    def _log_tail(self, n_chars: int = 1500) -> str:
        try:
            return self.log_path.read_text(errors="replace")[-n_chars:]
        except OSError:
            return "(no log)"

    @property
    def alive(self) -> bool:
        return self._proc is not None and self._proc.poll() is None

    def close(self) -> None:
        """End the viewer's whole process group (wrapper and binary) and wait until every
        process of it has exited."""
        import psutil  # a dependency of rerun-sdk

        self._client = None
        proc, self._proc = self._proc, None
        if proc is not None and proc.poll() is None:
            try:
                group = psutil.Process(proc.pid).children(recursive=True)
            except psutil.NoSuchProcess:
                group = []
            try:
                os.killpg(proc.pid, signal.SIGTERM)
            except ProcessLookupError:
                pass
            try:
                proc.wait(timeout=5)
            except subprocess.TimeoutExpired:
                proc.kill()
                proc.wait(timeout=5)
            _, alive = psutil.wait_procs(group, timeout=5)
            for child in alive:
                child.kill()
            psutil.wait_procs(alive, timeout=5)
        if self._own_log:
            self.log_path.unlink(missing_ok=True)

    @property
    def client(self):
        """The connected ``rerun.experimental.ViewerClient``."""
        if self._client is None or not self.alive:
            raise RuntimeError(
                "the headless viewer is not running" + (f"; log: {self._log_tail()}" if self._proc is not None else "")
            )
        return self._client

    # -- recordings -------------------------------------------------------------------------
    def open(self, path: str | Path, timeout_s: float = 60.0) -> LoadedRecording:
        """Open an ``.rrd`` file (closing whatever was open), wait until it has fully loaded
        (nothing loading, timeline ranges unchanged over two consecutive polls) and show it on
        its own default blueprint."""
        path = Path(path).resolve()
        if not path.is_file():
            raise FileNotFoundError(f"no recording at {path}")
        client = self.client
        if client.get_state().recordings:
            client.close("all")
        t0 = time.monotonic()
        opened = client.open(str(path))
        if not opened.store_ids:
            raise RuntimeError(f"the viewer opened no recording from {path}")
        store_id = opened.store_ids[0]
        previous = None
        while True:
            state = client.get_state()
            rec = next((r for r in state.recordings if r.store_id == store_id), None)
            ranges = None if rec is None else tuple((t.name, t.start, t.end) for t in rec.timelines)
            if not state.loading and ranges and all(t[2] is not None for t in ranges) and ranges == previous:
                break
            if time.monotonic() - t0 > timeout_s:
                raise TimeoutError(
                    f"{path} did not finish loading in {timeout_s:.0f} s "
                    f"(still loading: {[s.status for s in state.loading]})"
                )
            previous = ranges
            time.sleep(0.1)
        # the viewer keeps a blueprint per application id across files: show this file's own
        # default blueprint, as a user opening it for the first time sees it
        client.run_command("recording.reset_blueprint_to_default", store_id=store_id)
        client.take_screenshot(max_size=64)  # one painted frame applies the queued command
        self.recording = LoadedRecording(
            path=path, store_id=store_id, timelines={t.name: t for t in rec.timelines}, load_s=time.monotonic() - t0
        )
        return self.recording

    def set_time(self, timeline: str, sequence: int) -> None:
        """Pause the active recording at ``sequence`` on a sequence timeline (e.g. ``frame``)."""
        self.client.set_time(timeline, sequence=int(sequence), play_state="paused")

    def state(self):
        """``ViewerState`` of the viewer (views with their reports, recordings, loading)."""
        return self.client.get_state()

    def views(self):
        """The active blueprint's views (``view_id``, ``view_class``, ``name``, ``origin``, ``reports``)."""
        return self.client.get_state().views

    def entity_paths(self) -> list[str]:
        """Entity paths of the active recording (``/camera/image`` ...), without ``/__properties``."""
        schema = self.client.get_recording_schema(paths_only=True, max_entities=10_000)
        return [e.entity_path for e in schema.entities if not e.entity_path.startswith("/__")]

    def archetypes(self) -> dict[str, set[str]]:
        """Archetype short names logged per entity path, e.g. ``{"/camera/image": {"Image"}}``."""
        schema = self.client.get_recording_schema(max_entities=10_000)
        return {
            e.entity_path: {c.archetype.rsplit(".", 1)[-1] for c in e.components if c.archetype}
            for e in schema.entities
            if not e.entity_path.startswith("/__")
        }

    def blueprint(self) -> dict:
        """The active recording's blueprint, keyed by blueprint entity path, archetype, field."""
        return self.client.get_blueprint(store_id=self._store_id()).blueprint

    def _store_id(self) -> str:
        if self.recording is None:
            raise RuntimeError("no recording is open; call open() first")
        return self.recording.store_id

    # -- pixels -----------------------------------------------------------------------------
    def screenshot_png(self, view_id: str | None = None, max_size: int | None = None) -> bytes:
        """PNG of one view (by ``view_id``) or of the whole viewer."""
        return self.client.take_screenshot(view_id=view_id, max_size=max_size)

    def screenshot(self, view_id: str | None = None) -> np.ndarray:
        """RGB array (H, W, 3) uint8 of one view or of the whole viewer."""
        return _decode_png(self.screenshot_png(view_id))

    def overlay_pixels(
        self, view, entities: Sequence[str], shown: np.ndarray | None = None, min_chroma: int = 60
    ) -> OverlayPixels:
        """Pixels that ``entities`` (and everything below them) draw in ``view``.

        The view is shot as the blueprint has it (or ``shown`` is used) and again with the
        entities excluded from its query; the blueprint is restored afterwards.
        """
        if not entities:
            raise ValueError("parameter 'entities' is empty; name at least one entity path")
        if shown is None:
            shown = self.screenshot(view.view_id)
        original = self.blueprint()
        hidden_bp = copy.deepcopy(original)
        key = f"/view/{view.view_id}/ViewContents"
        contents = hidden_bp.setdefault(key, {}).setdefault("ViewContents", {})
        query = contents.get("query", "$origin/**")
        rules = [query] if isinstance(query, str) else list(query)
        # a multi-rule query must be a list of expressions (a newline-joined string matches nothing)
        rules = [r for rule in rules for r in rule.splitlines() if r.strip()]
        contents["query"] = rules + [f"- {e.rstrip('/')}/**" for e in entities]
        store_id = self._store_id()
        try:
            self.client.set_blueprint(hidden_bp, store_id=store_id)
            hidden = self.screenshot(view.view_id)
        finally:
            self.client.set_blueprint(original, store_id=store_id)
        if hidden.shape != shown.shape:
            raise RuntimeError(f"view {view.name!r} changed size between screenshots: {shown.shape} vs {hidden.shape}")
        changed = (shown != hidden).any(axis=-1)
        coloured = changed & coloured_mask(shown, min_chroma)
        return OverlayPixels(
            view_name=view.name,
            entities=list(entities),
            changed=int(changed.sum()),
            coloured=int(coloured.sum()),
            colours=dominant_colours(shown, coloured),
        )

    def seconds_since_start(self) -> float:
        return 0.0 if self.started_at is None else time.monotonic() - self.started_at


def entities_under(paths: Iterable[str], origin: str) -> list[str]:
    """Entity paths at or below ``origin`` (both with a leading ``/``)."""
    root = "/" + origin.strip("/")
    return [p for p in paths if p == root or p.startswith(root + "/")]


def plays_role(path: str, origin: str, role: str) -> bool:
    """Whether an entity below ``origin`` plays ``role``: one of its path parts below the origin
    starts with the role's name (``/camera/gate``, ``/camera/gate_rotated``, ``/camera/estimates/obj1``
    all play ``gate`` or ``estimate`` under origin ``/camera``)."""
    below = path[len("/" + origin.strip("/")) :].strip("/").split("/")
    return any(part.startswith(role) for part in below if part)


IMAGE_ARCHETYPES = frozenset({"Image", "EncodedImage", "DepthImage", "SegmentationImage"})
REPORT_SEVERITIES = frozenset({"error", "warning"})


@dataclass(frozen=True)
class Expectation:
    """What a tracking recording must show in the viewer.

    Attributes
    ----------
    image : bool
        Whether a 2-D view must show an image (``Image``, ``EncodedImage`` ... archetype).
    overlays : tuple of str
        Roles drawn over the image in a 2-D view (see :func:`plays_role`).
    series_root : str
        Entity root of the error series (``errors`` for ``errors/x`` ...), which must be plotted
        in a time-series view.
    timeline : str
        Sequence timeline; the screenshots are taken at the middle of its range.
    min_overlay_px : int
        Coloured pixels each overlay role must change in its view (a small dot is ~5).
    min_line_px : int
        Coloured pixels the series must draw in each time-series view showing them.
    min_image_fraction : float
        Fraction of its view's pixels the image must change.
    labels_when_overlapping : bool
        Whether point markers of two entities that overlap must carry labels (:func:`layout_problems`).
    other_timelines : tuple of str
        Timelines a view may hold all its data on although the recording opens on another (an iterative
        estimator's history on ``iteration``): that view is shown once the user picks its timeline.
    """

    image: bool = True
    overlays: tuple[str, ...] = ("gate", "truth", "estimate")
    series_root: str = "errors"
    timeline: str = "frame"
    min_overlay_px: int = 3
    min_line_px: int = 150
    min_image_fraction: float = 0.01
    labels_when_overlapping: bool = True
    other_timelines: tuple[str, ...] = ()


@dataclass
class RecordingCheck:
    """What :func:`check_recording` saw; ``problems`` is empty when the recording looks right."""

    path: Path
    frame: int | None = None
    views: list = field(default_factory=list)
    entity_paths: list[str] = field(default_factory=list)
    pixels: dict[str, OverlayPixels] = field(default_factory=dict)  # role or view name -> pixels
    problems: list[str] = field(default_factory=list)
    load_s: float = 0.0
    check_s: float = 0.0


def check_recording(viewer: HeadlessViewer, path: str | Path, expect: Expectation = Expectation()) -> RecordingCheck:
    """Open ``path`` in ``viewer`` and check what a user looks for.

    At the middle frame: the blueprint has a 2-D view and a time-series view, all visible; an
    image and every overlay role of ``expect`` are under a 2-D view's origin and draw pixels
    there (coloured ones for the overlays); scalar series under ``expect.series_root`` are in a
    time-series view and draw coloured lines in the first such view; after painting the whole
    viewer, no view reports an error or a warning. Problems are collected, not raised, so one run lists them all.
    """
    t0 = time.monotonic()
    rec = viewer.open(path)
    check = RecordingCheck(path=Path(path), load_s=rec.load_s)
    problems = check.problems
    if expect.timeline not in rec.timelines:
        problems.append(f"no {expect.timeline!r} timeline; timelines: {sorted(rec.timelines)}")
        return check
    line = rec.timeline(expect.timeline)
    check.frame = frame = (line.start + line.end) // 2
    viewer.set_time(expect.timeline, frame)

    views = check.views = viewer.views()
    spatial = [v for v in views if v.view_class == "2D"]
    series_views = [v for v in views if v.view_class == "TimeSeries"]
    if not spatial or not series_views:
        problems.append(
            f"blueprint views {sorted(v.view_class for v in views)}: need a 2-D image view "
            "('2D') and a time series ('TimeSeries')"
        )
    problems += [f"view {v.name!r} ({v.view_class}) is not visible" for v in views if not v.visible]
    paths = check.entity_paths = viewer.entity_paths()
    archetypes = viewer.archetypes()
    shots: dict[str, np.ndarray] = {}  # each screenshot paints a whole frame: take only the needed ones

    def shot(view) -> np.ndarray:
        if view.view_id not in shots:
            shots[view.view_id] = viewer.screenshot(view.view_id)
        return shots[view.view_id]

    images = [
        (v, p) for v in spatial for p in entities_under(paths, v.origin) if archetypes.get(p, set()) & IMAGE_ARCHETYPES
    ]
    # the view's main image first (an entity named ".../image"), not a small overlay such as a gate crop
    images.sort(key=lambda vp: not vp[1].rstrip("/").endswith("/image"))
    if expect.image and not images:
        problems.append(f"no image entity in the 2-D views {[v.origin for v in spatial]}; entities: {paths}")
    for view, image_path in images[:1] if expect.image else []:
        shown = shot(view)
        px = check.pixels["image"] = viewer.overlay_pixels(view, [image_path], shown=shown)
        area = shown.shape[0] * shown.shape[1]
        if px.changed < expect.min_image_fraction * area:
            problems.append(f"image {image_path} covers only {px.changed} of {area} px of view {view.name!r}")
    for role in expect.overlays:
        found = [(v, [p for p in entities_under(paths, v.origin) if plays_role(p, v.origin, role)]) for v in spatial]
        found = [(v, ps) for v, ps in found if ps]
        if not found:
            problems.append(f"no {role!r} entity in the 2-D views {[v.origin for v in spatial]}; entities: {paths}")
            continue
        view, role_paths = found[0]
        px = check.pixels[role] = viewer.overlay_pixels(view, role_paths, shown=shot(view))
        if px.coloured < expect.min_overlay_px:
            problems.append(
                f"{role} {role_paths} draws {px.coloured} coloured px in view {view.name!r} at "
                f"{expect.timeline} {frame} ({px.changed} changed); need >= {expect.min_overlay_px}"
            )

    series = [p for p in entities_under(paths, expect.series_root) if "Scalars" in archetypes.get(p, set())]
    if not series:
        problems.append(f"no scalar series under /{expect.series_root}; entities: {paths}")
    plotting = [v for v in series_views if entities_under(series, v.origin)]
    if series and not plotting:
        problems.append(f"series {series} are in no time-series view (origins {[v.origin for v in series_views]})")
    for view in plotting[:1]:
        in_view = entities_under(series, view.origin)
        total = int(coloured_mask(shot(view)).sum())
        px = check.pixels[f"series:{view.name}"] = viewer.overlay_pixels(view, in_view, shown=shot(view))
        if min(total, px.coloured) < expect.min_line_px:
            problems.append(
                f"time-series view {view.name!r}: {total} coloured px, {px.coloured} of them from "
                f"{in_view}; need >= {expect.min_line_px} (a plotted line)"
            )

    viewer.screenshot_png(max_size=64)  # paint every view once more, as the blueprint has them
    for view in viewer.views():  # reports describe the last paint
        problems += [
            f"view {view.name!r} reports {r.severity}: {r.summary} {r.details or ''}".strip()
            for r in view.reports
            if r.severity.lower() in REPORT_SEVERITIES
        ]
    check.check_s = time.monotonic() - t0
    return check


# --- the recording's layout, read from the file (no viewer needed) ---------------------------------------------

_NOT_TIMELINES = {"rerun.controls.RowId"}
_COLOUR_COMPONENTS = (
    "Points2D:colors",
    "Boxes2D:colors",
    "LineStrips2D:colors",
    "SeriesLines:colors",
    "SeriesPoints:colors",
)


@dataclass
class RecordingLayout:
    """What a recording file says about how it opens (:func:`read_layout`).

    Attributes
    ----------
    opening_timeline : str or None
        The timeline the blueprint's time panel opens on (``None``: the viewer chooses).
    views : list of dict
        ``{"name", "kind", "origin"}`` of each view in the blueprint (kind ``"2D"``, ``"TimeSeries"`` ...).
    timelines : dict
        Entity path -> the timelines it has data on (empty for static-only entities).
    colours : dict
        Entity path -> the packed RGBA colours it was logged with (points, boxes, lines, series styles).
    labels : set
        Entity paths logged with text labels (``Points2D:labels`` ...).
    positions : dict
        Entity path -> (frame, (N, 2) positions) of points, box centres and line vertices, in logging order.
    images : dict
        Entity path -> (width, height) of its images.
    markers : set
        Entity paths logged as points (``Points2D``): markers that can hide one another.
    bounds : dict
        View origin -> ``(x_min, x_max, y_min, y_max)`` of the blueprint's visual bounds, where it sets them.
    """

    opening_timeline: str | None = None
    views: list = field(default_factory=list)
    timelines: dict = field(default_factory=dict)
    colours: dict = field(default_factory=dict)
    labels: set = field(default_factory=set)
    positions: dict = field(default_factory=dict)
    images: dict = field(default_factory=dict)
    markers: set = field(default_factory=set)
    bounds: dict = field(default_factory=dict)


def _column(batch, name):
    return batch.column(name).to_pylist() if name in batch.schema.names else None


def _first_string(value):
    while isinstance(value, list) and value:
        value = value[0]
    return value if isinstance(value, str) else None


def read_layout(path: str | Path) -> RecordingLayout:
    """Read the blueprint (views, opening timeline, visual bounds) and the recording's entities (timelines with
    data, colours, labels, positions, image sizes) from an ``.rrd`` file."""
    from rerun.chunk import RrdReader

    reader = RrdReader(Path(path))
    layout = RecordingLayout()
    blueprints = reader.blueprints()
    views: dict[str, dict] = {}
    if blueprints:
        for chunk in reader.stream(store=blueprints[0]).to_chunks():
            batch, entity = chunk.to_record_batch(), str(chunk.entity_path)
            timeline = _column(batch, "TimePanelBlueprint:timeline")
            if timeline:
                layout.opening_timeline = _first_string(timeline[-1]) or layout.opening_timeline
            if entity.startswith("/view/") and entity.count("/") == 2:
                view = views.setdefault(entity, {})
                for key, column in (
                    ("kind", "ViewBlueprint:class_identifier"),
                    ("name", "ViewBlueprint:display_name"),
                    ("origin", "ViewBlueprint:space_origin"),
                ):
                    values = _column(batch, column)
                    if values:
                        view[key] = _first_string(values[-1])
            for name in batch.schema.names:
                if name.startswith("VisualBounds2D:"):
                    ranges = batch.column(name).to_pylist()[-1]
                    while isinstance(ranges, list) and len(ranges) == 1:
                        ranges = ranges[0]
                    if isinstance(ranges, dict):  # {"x_range": [x0, x1], "y_range": [y0, y1]}
                        ranges = [ranges.get("x_range"), ranges.get("y_range")]
                    try:
                        flat = np.asarray(ranges, dtype=float).ravel()
                    except (TypeError, ValueError):
                        continue
                    if flat.size == 4:
                        views.setdefault("/".join(entity.split("/")[:3]), {})["bounds"] = tuple(flat)
    for view in views.values():
        if "origin" in view:
            origin = "/" + view["origin"].strip("/")
            layout.views.append({"name": view.get("name") or origin, "kind": view.get("kind"), "origin": origin})
            if "bounds" in view:
                layout.bounds[origin] = view["bounds"]
    for chunk in reader.stream().to_chunks():
        batch, entity = chunk.to_record_batch(), str(chunk.entity_path)
        if entity.startswith("/__"):
            continue
        names = batch.schema.names
        timelines = {
            n
            for n in names
            if ":" not in n
            and n not in _NOT_TIMELINES
            and n != "log_time"
            and batch.num_rows
            and batch.column(n).null_count < batch.num_rows
        }
        layout.timelines.setdefault(entity, set()).update(timelines)
        for name in _COLOUR_COMPONENTS:
            for row in _column(batch, name) or []:
                if row:
                    layout.colours.setdefault(entity, set()).add(int(row[0]))
        if any(n.endswith(":labels") and any(_column(batch, n) or []) for n in names):
            layout.labels.add(entity)
        frames = _column(batch, "frame") or [None] * batch.num_rows
        for name in ("Points2D:positions", "Boxes2D:centers", "LineStrips2D:strips"):
            for frame, row in zip(frames, _column(batch, name) or []):
                if row and name.startswith("Points2D"):
                    layout.markers.add(entity)
                if row:
                    xy = np.asarray(
                        [p for item in row for p in (item if name.startswith("Line") else [item])], dtype=float
                    ).reshape(-1, 2)
                    layout.positions.setdefault(entity, []).append((frame, xy))
        for fmt in _column(batch, "Image:format") or []:
            if fmt:
                layout.images[entity] = (fmt[0].get("width"), fmt[0].get("height"))
    return layout


def _under(entity: str, origin: str) -> bool:
    origin = origin.rstrip("/") or "/"
    return origin == "/" or entity == origin or entity.startswith(origin + "/")


_BAND_EDGES = {"minus", "plus", "lo", "hi", "low", "high", "lower", "upper"}
_ROLES = {
    "truth",
    "estimate",
    "estimated",
    "measured",
    "measurement",
    "predicted",
    "prediction",
    "gate",
    "detection",
    "detected",
    "interferer",
    "decoy",
}


def _leaf_tokens(entity: str) -> list[str]:
    return [t for t in entity.rstrip("/").rsplit("/", 1)[-1].lower().split("_") if t]


def _compared_series(a: str, b: str) -> bool:
    """Two series of one time-series view are compared unless they are the two edges of one band
    (``estimate_minus_sigma`` / ``estimate_plus_sigma``), which share their colour on purpose."""
    strip = lambda e: [t for t in _leaf_tokens(e) if t not in _BAND_EDGES]
    return strip(a) != strip(b)


def _compared_overlays(a: str, b: str) -> bool:
    """Two overlays of a 2-D view are compared when they play different roles (truth and estimate); parts of one
    thing (``gate``, ``gate_path``) or the same role of two objects (``center/truth``, ``marker/truth``) may share."""
    ra, rb = _leaf_tokens(a)[:1], _leaf_tokens(b)[:1]
    return bool(ra and rb) and ra != rb and ra[0] in _ROLES and rb[0] in _ROLES


def _hex(rgba: int) -> str:
    return f"#{rgba >> 8:06x}"


def layout_problems(layout: RecordingLayout, expectation: Expectation | None = None) -> list[str]:
    """What a user would see wrong on opening the recording, before any pixel is drawn:

    - the viewer opens on a timeline on which a view has no data ("No data available": 002 opened on
      ``iteration`` with its images on ``frame``), or the blueprint leaves the timeline to chance;
    - compared things in one view share a colour (two series, or two overlays of a 2-D view);
    - markers of two entities lie on top of each other (closer than 2 % of the view) with no labels to tell
      them apart;
    - a 2-D view's visual bounds cut off the data, or frame it so loosely that it fills under a tenth of the view.
    """
    expectation = expectation or Expectation()
    problems = []
    timeline = layout.opening_timeline
    if timeline is None:
        problems.append("the blueprint does not choose the timeline the viewer opens on (TimePanel(timeline=...))")
    for view in layout.views:
        entities = [e for e in layout.timelines if _under(e, view["origin"])]
        timed = {e: layout.timelines[e] for e in entities if layout.timelines[e]}
        on_other = set().union(*timed.values()) <= set(expectation.other_timelines) if timed else False
        if timeline and timed and not on_other and not any(timeline in t for t in timed.values()):
            elsewhere = sorted(set().union(*timed.values()))
            problems.append(
                f"view {view['name']!r} has no data on the opening timeline {timeline!r} "
                f"(its data is on {', '.join(elsewhere)}): it opens on 'No data available'"
            )
        single = {e: next(iter(layout.colours[e])) for e in entities if len(layout.colours.get(e, ())) == 1}
        compared = _compared_series if view.get("kind") == "TimeSeries" else _compared_overlays
        items = sorted(single.items())
        for i, (a, rgba) in enumerate(items):
            for b, other in items[i + 1 :]:
                if rgba == other and compared(a, b):
                    problems.append(f"view {view['name']!r}: {a} and {b} share the colour {_hex(rgba)}")
        if view.get("kind") == "2D":
            problems += _framing_problems(layout, view, entities, expectation)
    return problems


def _framing_problems(layout: RecordingLayout, view: dict, entities: list[str], expectation: Expectation) -> list[str]:
    problems = []
    drawn = [np.concatenate([xy for _, xy in layout.positions[e]]) for e in entities if e in layout.positions]
    images = [layout.images[e] for e in entities if e in layout.images]
    points = np.concatenate(drawn) if drawn else np.empty((0, 2))
    points = points[np.all(np.isfinite(points), axis=1)]
    if view["origin"] in layout.bounds:
        x0, x1, y0, y1 = layout.bounds[view["origin"]]
    elif images:
        x0, y0, x1, y1 = 0.0, 0.0, float(max(w for w, _ in images)), float(max(h for _, h in images))
    elif len(points):
        (x0, y0), (x1, y1) = points.min(axis=0), points.max(axis=0)
    else:
        return problems
    span = max(x1 - x0, y1 - y0, 1e-12)
    if len(points) and view["origin"] in layout.bounds:
        (px0, py0), (px1, py1) = points.min(axis=0), points.max(axis=0)
        margin = 0.02 * span
        if px0 < x0 - margin or px1 > x1 + margin or py0 < y0 - margin or py1 > y1 + margin:
            problems.append(
                f"view {view['name']!r}: its visual bounds [{x0:.4g}, {x1:.4g}] x [{y0:.4g}, {y1:.4g}] "
                f"cut off data spanning [{px0:.4g}, {px1:.4g}] x [{py0:.4g}, {py1:.4g}]"
            )
        elif not images and max(px1 - px0, py1 - py0) < 0.1 * span:
            problems.append(f"view {view['name']!r}: the data fills under a tenth of its visual bounds")
    if expectation.labels_when_overlapping:
        problems += _overlap_problems(layout, view, entities, 0.02 * span)
    return problems


def _overlap_problems(layout: RecordingLayout, view: dict, entities: list[str], distance: float) -> list[str]:
    """Pairs of point entities in a 2-D view whose markers overlap in most frames, with neither labelled."""
    problems = []
    points = [e for e in entities if e in layout.markers and e not in layout.labels]
    by_frame = {e: {f: xy.mean(axis=0) for f, xy in layout.positions[e] if len(xy) == 1} for e in points}
    for i, a in enumerate(points):
        for b in points[i + 1 :]:
            common = sorted(set(by_frame[a]) & set(by_frame[b]))
            if len(common) < 2:
                continue
            gaps = np.array([np.linalg.norm(by_frame[a][f] - by_frame[b][f]) for f in common])
            if np.median(gaps) < distance:
                problems.append(
                    f"view {view['name']!r}: {a} and {b} overlap (median {np.median(gaps):.3g} apart) "
                    f"with no labels to tell them apart"
                )
    return problems
