"""Wall-clock limits that a loaded machine does not break (`make test` passes under load).

A test that bounds a wall time (a refusal before any work, a Ctrl-C that stops promptly, a viewer check) states
the limit for an idle machine; :func:`wall_budget` stretches it by the machine's load, the runnable processes per
core over the last minute (at least 1), so the test still fails on a hang or a wait of the wrong order.
"""

from __future__ import annotations

import os


def load_factor() -> float:
    """Runnable processes per usable core over the last minute, at least 1."""
    try:
        cores = len(os.sched_getaffinity(0))
    except AttributeError:  # pragma: no cover - not Linux
        cores = os.cpu_count() or 1
    return max(1.0, os.getloadavg()[0] / max(cores, 1))


def wall_budget(idle_s: float) -> float:
    """``idle_s`` (the limit on an idle machine), stretched by :func:`load_factor`."""
    return idle_s * load_factor()
