"""The runner's own costs: papermill overhead per run, and what a 2-job sweep gains over 1 job.

Run with ``make bench`` (pytest-benchmark; results in benchmarks/results/benchmarks.json).
"""

import os
import shutil
import time

from tvtrack.pipeline.paths import REPO_ROOT
from tvtrack.pipeline.runner import run_notebook
from tvtrack.pipeline.sweep import run_sweep

FIXTURE_NOTEBOOK = REPO_ROOT / "tests" / "fixtures" / "fixture_centroid.ipynb"
FIXTURE_SWEEP = REPO_ROOT / "tests" / "fixtures" / "fixture_sweep.toml"

# the fixture's cheapest run: its own work takes milliseconds, so the time is the overhead
TINY = {"n_trials": 1, "n_frames": 1, "rerun_mode": "off"}


def test_papermill_overhead_per_run(benchmark, tmp_path):
    counter = iter(range(1000))

    def one_run():
        outcome = run_notebook(FIXTURE_NOTEBOOK, tmp_path / f"run{next(counter)}", TINY)
        assert outcome.ok
        return outcome

    outcome = benchmark.pedantic(one_run, rounds=5, iterations=1, warmup_rounds=1)
    benchmark.extra_info["notebook_runtime_s"] = outcome.runtime_s


def test_sweep_speedup_two_jobs_over_one(benchmark, tmp_path):
    timings = {}

    def sweep(jobs):
        out = tmp_path / f"jobs{jobs}"
        shutil.rmtree(out, ignore_errors=True)
        t0 = time.perf_counter()
        s = run_sweep(FIXTURE_SWEEP, jobs=jobs, output=out, progress=False)
        timings[jobs] = time.perf_counter() - t0
        assert s.n_ok == 8

    sweep(1)
    benchmark.pedantic(sweep, args=(2,), rounds=1, iterations=1)
    speedup = timings[1] / timings[2]
    benchmark.extra_info.update(one_job_s=timings[1], two_jobs_s=timings[2], speedup=speedup,
                                cpus=os.cpu_count())
    print(f"\n8-run sweep: 1 job {timings[1]:.1f} s, 2 jobs {timings[2]:.1f} s, speed-up x{speedup:.2f}")
    # on 2 free cores the pool should give most of the ideal x2
    assert speedup > 1.3, f"2 jobs gave only x{speedup:.2f} over 1 job"
