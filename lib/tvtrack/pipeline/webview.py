"""``python -m tvtrack view RUN``: a run's recording in the Rerun web viewer, served from this machine.

``rerun --web-viewer`` (from the pinned rerun-sdk) serves the viewer's wasm app on one port and the
recording over gRPC on another; the browser opens ``http://HOST:WEB/?url=rerun+http://HOST:GRPC/proxy``.
Both listen on loopback unless told otherwise. Facts measured on this project's machines
(``shared/notes/web-viewer-in-browser.md``): if a port is taken, ``rerun`` silently defers to whatever
listens there, so both ports are checked free first and the child is checked alive; ``rerun`` is a
Python wrapper around the real binary, so it runs in its own process group and the whole group is ended.

Fixed default ports (:data:`DEFAULT_WEB_PORT`, :data:`DEFAULT_GRPC_PORT`, Rerun's own defaults) make
the URL predictable, so the static site can link to it: run the command, then follow the link.
"""

from __future__ import annotations

import os
import signal
import socket
import subprocess
import time
import webbrowser
from pathlib import Path
from urllib.parse import quote

from .preflight import UsageError
from .viewer import rerun_executable

__all__ = [
    "DEFAULT_HOST",
    "DEFAULT_WEB_PORT",
    "DEFAULT_GRPC_PORT",
    "find_recording",
    "viewer_url",
    "port_free",
    "WebViewer",
    "serve",
]

DEFAULT_HOST = "127.0.0.1"
DEFAULT_WEB_PORT = 9090
DEFAULT_GRPC_PORT = 9876
START_TIMEOUT_S = 60.0


def find_recording(target: str | Path) -> Path:
    """The ``.rrd`` named by ``target``: the file itself, or ``recording.rrd`` in a run directory."""
    path = Path(target)
    if path.is_dir():
        path = path / "recording.rrd"
    if path.suffix != ".rrd" or not path.is_file():
        raise UsageError(f"no recording at {target}: give a run directory holding recording.rrd, or an .rrd file")
    return path.resolve()


def viewer_url(host: str, web_port: int, grpc_port: int) -> str:
    """The URL that opens the web viewer on the recording served at ``grpc_port``."""
    return f"http://{host}:{web_port}/?url=" + quote(f"rerun+http://{host}:{grpc_port}/proxy", safe="")


def port_free(host: str, port: int) -> bool:
    """Whether ``port`` on ``host`` can be bound now (nothing else listens there)."""
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        try:
            s.bind((host, port))
        except OSError:
            return False
    return True


def _listening(host: str, port: int) -> bool:
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.settimeout(0.5)
        return s.connect_ex((host, port)) == 0


class WebViewer:
    """``rerun --web-viewer`` serving one recording, as a context manager.

    Parameters
    ----------
    recording : Path
        The ``.rrd`` file.
    host : str
        Address both servers bind to (loopback by default).
    web_port, grpc_port : int
        Ports of the viewer app and of the recording; both must be free.
    """

    def __init__(
        self,
        recording: str | Path,
        host: str = DEFAULT_HOST,
        web_port: int = DEFAULT_WEB_PORT,
        grpc_port: int = DEFAULT_GRPC_PORT,
    ):
        self.recording = find_recording(recording)
        self.host, self.web_port, self.grpc_port = host, web_port, grpc_port
        self.process: subprocess.Popen | None = None

    @property
    def url(self) -> str:
        """Where a browser on this machine opens the recording."""
        return viewer_url("127.0.0.1" if self.host in ("0.0.0.0", "") else self.host, self.web_port, self.grpc_port)

    def start(self) -> "WebViewer":
        """Start the servers and wait until the viewer app answers; raises with the reason if not."""
        for name, port in (("--port", self.web_port), ("--grpc-port", self.grpc_port)):
            if not port_free(self.host, port):
                raise UsageError(f"{name} {port}: something already listens on {self.host}:{port}; pick another port")
        # BROWSER=/bin/true: rerun must not open a browser itself (serve() decides that).
        env = {**os.environ, "BROWSER": "/bin/true", "RERUN_ANALYTICS": "0"}
        self.process = subprocess.Popen(
            [
                rerun_executable(),
                "--web-viewer",
                "--bind",
                self.host,
                "--web-viewer-port",
                str(self.web_port),
                "--port",
                str(self.grpc_port),
                str(self.recording),
            ],
            env=env,
            start_new_session=True,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.PIPE,
        )
        probe = "127.0.0.1" if self.host in ("0.0.0.0", "") else self.host
        deadline = time.monotonic() + START_TIMEOUT_S
        while not (_listening(probe, self.web_port) and _listening(probe, self.grpc_port)):
            if self.process.poll() is not None:
                err = self.process.stderr.read().decode(errors="replace").strip()
                raise RuntimeError(f"rerun --web-viewer exited with code {self.process.returncode}: {err[-500:]}")
            if time.monotonic() > deadline:
                self.stop()
                raise TimeoutError(
                    f"rerun --web-viewer did not listen on ports {self.web_port} and "
                    f"{self.grpc_port} within {START_TIMEOUT_S:.0f} s"
                )
            time.sleep(0.2)
        return self

    def stop(self) -> None:
        """End the whole process group (the wrapper and the viewer binary)."""
        if self.process is None or self.process.poll() is not None:
            return
        for sig, wait_s in ((signal.SIGTERM, 5.0), (signal.SIGKILL, 5.0)):
            try:
                os.killpg(self.process.pid, sig)
            except ProcessLookupError:
                return
            try:
                self.process.wait(wait_s)
                return
            except subprocess.TimeoutExpired:
                continue

    def __enter__(self) -> "WebViewer":
        return self.start()

    def __exit__(self, *exc) -> None:
        self.stop()


def _interrupt(signum, frame):
    raise KeyboardInterrupt


def serve(
    target: str | Path,
    host: str = DEFAULT_HOST,
    port: int = DEFAULT_WEB_PORT,
    grpc_port: int = DEFAULT_GRPC_PORT,
    open_browser: bool = True,
) -> int:
    """Serve ``target``'s recording until Ctrl-C; print the URL and open it in a browser where there is one
    (never under CI). Returns the exit code."""
    viewer = WebViewer(target, host, port, grpc_port)
    signal.signal(signal.SIGTERM, _interrupt)  # a plain kill also ends the viewer's process group
    with viewer:
        print(f"serving {viewer.recording}\nopen {viewer.url}\n(Ctrl-C stops)", flush=True)
        if open_browser and not os.environ.get("CI"):
            try:
                webbrowser.get().open(viewer.url)
            except webbrowser.Error:
                pass  # no browser on this machine: the printed URL is the way in
        try:
            code = viewer.process.wait()
        except KeyboardInterrupt:
            print("stopped", flush=True)
            return 0
    return 0 if code == 0 else 1
