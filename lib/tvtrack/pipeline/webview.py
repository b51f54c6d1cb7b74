"""``python -m tvtrack view RUN``: a run's recording in the Rerun web viewer, served from this machine.

``rerun --web-viewer`` (from the pinned rerun-sdk) serves the viewer's wasm app on one port and the
recording over gRPC on another; the browser opens ``http://HOST:WEB/?url=rerun+http://HOST:GRPC/proxy``.
Both listen on loopback unless told otherwise. Facts measured on this project's machines
(``shared/notes/web-viewer-in-browser.md``): if a port is taken, ``rerun`` silently defers to whatever
listens there, so both ports are checked free first and the child is checked alive; ``rerun`` is a
Python wrapper around the real binary, so it runs in its own process group and the whole group is ended.

Fixed default ports (:data:`DEFAULT_WEB_PORT`, :data:`DEFAULT_GRPC_PORT`, Rerun's own defaults) make
the URL predictable, so the static site can link to it: run the command, then follow the link.

Before anything starts (:func:`preflight`), each of these is one line ``error: ...`` and exit status 2: a
port outside [1, 65535], a host that does not resolve or is no address of this machine, a port where
something listens, a recording that ``rerun rrd verify`` does not read. Ctrl-C, SIGTERM and SIGHUP (the
terminal closed) all stop the viewer's process group, so its ports are free again.
"""

from __future__ import annotations

import contextlib
import errno
import os
import re
import signal
import socket
import subprocess
import time
import webbrowser
from pathlib import Path
from urllib.parse import quote

from .preflight import UsageError
from .viewer.environment import rerun_executable, verify_rrd

__all__ = [
    "DEFAULT_HOST",
    "DEFAULT_WEB_PORT",
    "DEFAULT_GRPC_PORT",
    "find_recording",
    "viewer_url",
    "port_free",
    "preflight",
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
    return _bind_problem(host, port, "--port") is None


def _family(host: str) -> int:
    return socket.AF_INET6 if ":" in host else socket.AF_INET


def _bind_problem(host: str, port: int, option: str) -> str | None:
    """Why ``port`` on ``host`` cannot be bound now, in one line, or ``None``."""
    with socket.socket(_family(host), socket.SOCK_STREAM) as s:
        try:
            s.bind((host, port))
        except OSError as exc:
            if exc.errno == errno.EADDRINUSE:
                return f"{option} {port}: something already listens on {host}:{port}; pick another port"
            if exc.errno == errno.EADDRNOTAVAIL:
                return f"--host {host}: not an address of this machine (127.0.0.1 for this machine only)"
            if exc.errno == errno.EACCES:
                return f"{option} {port}: binding it needs privileges (ports below 1024); pick a port above 1023"
            return f"{option} {port}: cannot listen on {host}:{port}: {exc.strerror or exc}"
    return None


def preflight(recording: Path, host: str, web_port: int, grpc_port: int) -> None:
    """The checks made before the viewer starts, each a one-line :class:`UsageError`: ports in range and
    distinct, a host that resolves to an address of this machine, both ports free, a readable recording."""
    for option, port in (("--port", web_port), ("--grpc-port", grpc_port)):
        if isinstance(port, bool) or not isinstance(port, int) or not 1 <= port <= 65535:
            raise UsageError(f"{option} {port}: a port is a number in [1, 65535]")
    if web_port == grpc_port:
        raise UsageError(f"--port and --grpc-port are both {web_port}; the viewer needs two ports")
    try:
        socket.getaddrinfo(host, None, proto=socket.IPPROTO_TCP)
    except (socket.gaierror, UnicodeError) as exc:
        reason = getattr(exc, "strerror", None) or str(exc)
        raise UsageError(f"--host {host!r} does not resolve ({reason}); 127.0.0.1 serves this machine only") from None
    for option, port in (("--port", web_port), ("--grpc-port", grpc_port)):
        problem = _bind_problem(host, port, option)
        if problem:
            raise UsageError(problem)
    try:
        verify_rrd(recording)
    except (ValueError, OSError, subprocess.SubprocessError) as exc:
        raise UsageError(f"{recording} is not a readable Rerun recording: {_verify_reason(str(exc))}") from None


_ANSI = re.compile(r"\x1b\[[0-9;]*m")
_LOG_LINE = re.compile(r"^\d{4}-\d\d-\d\dT")


def _verify_reason(report: str) -> str:
    """The line of ``rerun rrd verify``'s report that says what is wrong (colours and log lines dropped)."""
    text = _ANSI.sub("", report).split("failed (exit", 1)[-1].split("): ", 1)[-1]
    lines = [ln.strip() for ln in text.splitlines() if ln.strip() and not _LOG_LINE.match(ln.strip())]
    lines = [ln for ln in lines if not ln.startswith("Error: Verification failed")] or lines or ["no details"]
    reason = lines[0].rsplit(" -- skipping: ", 1)[-1]
    return " ".join(reason.split())[:240]


def _listening(host: str, port: int) -> bool:
    with socket.socket(_family(host), socket.SOCK_STREAM) as s:
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
        preflight(self.recording, self.host, self.web_port, self.grpc_port)
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
        try:
            self._wait_until_listening()
        except BaseException:  # a signal while it starts, too: no server left holding the ports
            self.stop()
            raise
        return self

    def _wait_until_listening(self) -> None:
        probe = "127.0.0.1" if self.host in ("0.0.0.0", "") else ("::1" if self.host == "::" else self.host)
        deadline = time.monotonic() + START_TIMEOUT_S
        while not (_listening(probe, self.web_port) and _listening(probe, self.grpc_port)):
            if self.process.poll() is not None:
                err = self.process.stderr.read().decode(errors="replace").strip()
                raise RuntimeError(f"rerun --web-viewer exited with code {self.process.returncode}: {err[-500:]}")
            if time.monotonic() > deadline:
                raise TimeoutError(
                    f"rerun --web-viewer did not listen on ports {self.web_port} and "
                    f"{self.grpc_port} within {START_TIMEOUT_S:.0f} s"
                )
            time.sleep(0.2)

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
    # a plain kill, and the terminal closing (SIGHUP), also end the viewer's process group and free its ports
    for signum in (signal.SIGTERM, signal.SIGHUP):
        signal.signal(signum, _interrupt)
    with viewer:
        try:  # a signal may come while the URL is still being printed: it stops the viewer the same way
            print(f"serving {viewer.recording}\nopen {viewer.url}\n(Ctrl-C stops)", flush=True)
            if open_browser and not os.environ.get("CI"):
                try:
                    webbrowser.get().open(viewer.url)
                except webbrowser.Error:
                    pass  # no browser on this machine: the printed URL is the way in
            code = viewer.process.wait()
        except KeyboardInterrupt:
            with contextlib.suppress(OSError):  # the terminal may be gone (SIGHUP)
                print("stopped", flush=True)
            return 0
    return 0 if code == 0 else 1
