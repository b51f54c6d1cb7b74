"""The one scheduler-address parser and connector shared by the explorer and the sweep runner."""

import pytest

from tvtrack.executors import SchedulerError, parse_scheduler_address


@pytest.mark.parametrize(
    "address, expected",
    [
        ("127.0.0.1:8786", ("127.0.0.1", 8786)),
        ("tcp://host:1", ("host", 1)),
        ("tls://host:65535/", ("host", 65535)),
        ("tcp://[::1]:8786", ("::1", 8786)),
    ],
)
def test_addresses_parse_to_host_and_port(address, expected):
    assert parse_scheduler_address(address) == expected


@pytest.mark.parametrize(
    "address, words",
    [
        ("localhost", "has no port"),
        ("tcp://host:", "has no port"),
        ("tcp://host:0", "not a number in [1, 65535]"),
        ("tcp://host:70000", "not a number in [1, 65535]"),
        ("tcp://host:http", "'http'"),
        ("udp://host:1", "scheme 'udp'"),
        ("a b:1", "not HOST:PORT"),
    ],
)
def test_bad_addresses_are_one_line_value_errors_naming_the_address(address, words):
    with pytest.raises(SchedulerError, match=None) as info:
        parse_scheduler_address(address)
    message = str(info.value)
    assert isinstance(info.value, ValueError) and "\n" not in message
    assert repr(address) in message and words in message


def _state(pid: int) -> str:
    """A process's state letter from /proc ("Z" a zombie, "" gone)."""
    try:
        return open(f"/proc/{pid}/stat").read().rsplit(")", 1)[1].split()[0]
    except (FileNotFoundError, ProcessLookupError):
        return ""


def test_a_measurements_forked_workers_end_when_the_process_that_started_them_is_killed(tmp_path):
    """A kernel killed while its measurement's pool is open (Ctrl-C, then the kernel's grace period) leaves no
    worker behind: each forked worker notices its parent is gone and ends (before, they waited on their task queue
    for ever)."""
    import os
    import signal
    import subprocess
    import sys
    import time

    pids = tmp_path / "workers.txt"  # a file, not a pipe: an orphaned worker would hold a pipe open
    code = (
        "import os, sys\n"
        "from tvtrack.jobs import fork_pool\n"
        "pool = fork_pool(2)\n"
        "futures = [pool.submit(os.getpid) for _ in range(8)]\n"
        "workers = sorted({f.result() for f in futures} | set(pool._processes))\n"
        f"open({str(pids)!r}, 'w').write(' '.join(map(str, workers)))\n"
        "os.kill(os.getpid(), 9)\n"
    )
    with open(tmp_path / "stderr.txt", "w") as err:
        out = subprocess.run([sys.executable, "-c", code], stdout=subprocess.DEVNULL, stderr=err, timeout=60)
    assert out.returncode == -signal.SIGKILL, (tmp_path / "stderr.txt").read_text()
    workers = [int(p) for p in pids.read_text().split()]
    assert workers and os.getpid() not in workers
    deadline = time.monotonic() + 10.0
    while any(_state(p) not in ("", "Z") for p in workers) and time.monotonic() < deadline:
        time.sleep(0.2)
    assert [p for p in workers if _state(p) not in ("", "Z")] == []
