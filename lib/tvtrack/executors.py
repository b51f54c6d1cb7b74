"""Executors for Monte Carlo work: a Dask scheduler address checked and connected with a deadline.

Used by :func:`tvtrack.explore.executor_for` (a notebook's ``scheduler`` parameter) and by the sweep
runner (``tvtrack sweep --executor dask``): one place that parses a scheduler address and connects to it
without hanging. ``distributed.Client`` can wait forever on a port where something that is not a Dask
scheduler listens (a web server, a silent socket), so the connection runs in a daemon thread joined with a
deadline.
"""

from __future__ import annotations

import re
import socket
import threading
from typing import Any

__all__ = ["SchedulerError", "parse_scheduler_address", "connect_dask"]

_ADDRESS = re.compile(
    r"^(?:(?P<scheme>[a-z]+)://)?(?P<host>\[[0-9a-fA-F:.]+\]|[^:/\s\[\]]+)"
    r"(?::(?P<port>[^/\s]*))?/?$"
)
_EXAMPLE = "e.g. tcp://127.0.0.1:8786"


class SchedulerError(ValueError):
    """A scheduler address that is malformed, unreachable or not a Dask scheduler (one-line message)."""


def parse_scheduler_address(address: str) -> tuple[str, int]:
    """``(host, port)`` of a Dask scheduler address such as ``tcp://127.0.0.1:8786`` or ``host:8786``.

    Raises
    ------
    SchedulerError
        The address has no port, a port that is not a number in [1, 65535], or another scheme than
        ``tcp``/``tls`` (one line naming the address).
    """
    match = _ADDRESS.match(address.strip())
    if not match:
        raise SchedulerError(f"scheduler address {address!r} is not HOST:PORT or tcp://HOST:PORT ({_EXAMPLE})")
    scheme, host, port = match.group("scheme"), match.group("host"), match.group("port")
    if scheme not in (None, "tcp", "tls"):
        raise SchedulerError(
            f"scheduler address {address!r}: scheme {scheme!r} is not supported; use tcp:// ({_EXAMPLE})"
        )
    if port is None or port == "":
        raise SchedulerError(
            f"scheduler address {address!r} has no port ({_EXAMPLE}; `dask scheduler` prints its address)"
        )
    if not port.isdigit() or not 1 <= int(port) <= 65535:
        raise SchedulerError(f"scheduler address {address!r}: port {port!r} is not a number in [1, 65535] ({_EXAMPLE})")
    return host.strip("[]"), int(port)


def connect_dask(address: str, timeout_s: float = 10.0, hint: str = "") -> Any:
    """A ``dask.distributed.Client`` of the scheduler at ``address``, connected within ``timeout_s`` seconds.

    Parameters
    ----------
    address : str
        ``host:port`` or ``tcp://host:port``.
    timeout_s : float
        Deadline in seconds for the TCP check and for the client's handshake each.
    hint : str
        Appended to every error message after ``"; "`` (e.g. how to start a scheduler).

    Raises
    ------
    SchedulerError
        One line naming the address: malformed (see :func:`parse_scheduler_address`), nothing listens
        there, or what listens does not answer as a Dask scheduler within the deadline.
    """
    host, port = parse_scheduler_address(address)
    tail = f"; {hint}" if hint else ""
    try:
        socket.create_connection((host, port), timeout=timeout_s).close()
    except OSError as exc:
        raise SchedulerError(f"cannot reach a Dask scheduler at {address!r}: {exc.strerror or exc}{tail}") from None
    url = address if "://" in address else f"tcp://{address}"
    outcome: dict = {}

    def connect():
        from distributed import Client

        try:
            outcome["client"] = Client(url, timeout=timeout_s)
        except BaseException as exc:  # noqa: BLE001 - e.g. MemoryError decoding an HTTP reply as a Dask frame
            outcome["error"] = exc

    thread = threading.Thread(target=connect, daemon=True, name="dask-connect")
    thread.start()
    thread.join(timeout_s)
    if "client" not in outcome:
        raise SchedulerError(
            f"no Dask scheduler answers at {address!r} within {timeout_s:g} s (something listens there, "
            f"but not a Dask scheduler){tail}"
        )
    return outcome["client"]
