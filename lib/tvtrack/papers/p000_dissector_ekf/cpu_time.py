"""Time two compiled steps back to back, repeated, as a ratio with its interval (C000-4's CPU-time reading: register
entry "C000-4 cost measure" = "CPU time"; :func:`.study.cost_ratio` prepares the two variants and their samples)."""

from __future__ import annotations

import time

import numpy as np

from ...estimate import Estimate
from ...montecarlo import mean_ci

__all__ = ["paired_time_ratio"]


def paired_time_ratio(run_a, run_b, data, repeats: int) -> Estimate:
    """CPU time (``time.process_time``) of ``run_a(data)`` over ``run_b(data)``: the two timed back to back
    ``repeats`` times, their order alternating (so that a drift of the machine's load enters both); the ratio is the
    geometric mean of the paired ratios with the Student t interval of their logarithms, the spread of the timings
    on the machine that ran them (another machine may weigh an exp against an addition differently, which no
    interval of one machine covers). Both callables are run once on ``data[:1, :3]`` before the clock starts (a
    compiled step compiles there)."""

    def timed(run):
        t0 = time.process_time()
        run(data)
        return time.process_time() - t0

    run_a(data[:1, :3]), run_b(data[:1, :3])
    logs = []
    for i in range(repeats):
        if i % 2:  # the second first
            b = timed(run_b)
            a = timed(run_a)
        else:
            a = timed(run_a)
            b = timed(run_b)
        logs.append(np.log(a / b))
    e = mean_ci(logs)
    r = float(np.exp(e.value))
    return Estimate(
        r,
        r * e.stderr,
        float(np.exp(e.ci_low)),
        float(np.exp(e.ci_high)),
        e.n,
        e.confidence,
        f"geometric mean of {repeats} paired timings (Student t on their log ratios)",
    )
