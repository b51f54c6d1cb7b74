"""The real Rerun viewer, headless on the CPU, driven through ``rerun.experimental.ViewerClient``
(pinned rerun-sdk): open a file, wait until it has loaded, move the time cursor, read the blueprint's
views and their reports, the recording's entity paths, take per-view screenshots, and measure what
some entities draw by ablation (:meth:`HeadlessViewer.overlay_pixels`).

Pitfalls handled here (``shared/notes/rerun-viewer-check.md``): ``rerun`` defers silently to
whatever already listens on its port, so every viewer gets a fresh free port and its own
process is checked to be alive; ``rerun`` is a Python wrapper around the real binary, so the
viewer runs in its own process group and the whole group is ended. Re-exported by
:mod:`tvtrack.pipeline.viewer`.
"""

from __future__ import annotations

import copy
import os
import signal
import subprocess
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Sequence

import numpy as np

from .pixels import OverlayPixels, decode_png, coloured_mask, dominant_colours
from .environment import INSTALL_HINT, ViewerUnavailable, free_port, rerun_executable, vulkan_problem

__all__ = ["LoadedRecording", "HeadlessViewer"]


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

    def set_time(self, timeline: str, sequence: int, timeout_s: float = 30.0) -> None:
        """Pause the active recording at ``sequence`` on a sequence timeline (e.g. ``frame``), and return once the
        viewer reports its cursor there and has painted a frame at it.

        The viewer applies the command at its next frame: a view's screenshot taken before then shows the time the
        file opened on (frame 0, where a view whose entities start at frame 1 is blank).
        """
        self.client.set_time(timeline, sequence=int(sequence), play_state="paused")
        store_id, t0 = self._store_id(), time.monotonic()
        while True:
            self.client.take_screenshot(max_size=64)  # one painted frame applies the queued command
            rec = next((r for r in self.client.get_state().recordings if r.store_id == store_id), None)
            if rec is not None and (rec.current_timeline, rec.current_time) == (timeline, int(sequence)):
                return
            if time.monotonic() - t0 > timeout_s:
                raise TimeoutError(
                    f"the viewer's time cursor did not reach {timeline} {sequence} in {timeout_s:.0f} s (at "
                    f"{None if rec is None else (rec.current_timeline, rec.current_time)})"
                )
            time.sleep(0.05)

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
        return decode_png(self.screenshot_png(view_id))

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
