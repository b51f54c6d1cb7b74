"""The runner's own costs: papermill overhead per run, and what a 2-job sweep gains over 1 job.

Both are measured against a reference in the same run (issue 30): the runner's overhead as the
difference between a run of the fixture notebook through :func:`run_notebook` and a bare
``papermill.execute_notebook`` of an empty notebook on the same kernel; the sweep as the ratio of
1-job to 2-job wall time. Run with ``make bench`` (figures in benchmarks/results/table.md).
"""

import os
import shutil
import time

import nbformat

from tvtrack.pipeline.paths import REPO_ROOT
from tvtrack.pipeline.runner import KERNEL_ARGUMENTS, KERNEL_NAME, KERNEL_START_TIMEOUT_S, run_notebook
from tvtrack.pipeline.sweep import run_sweep

FIXTURE_NOTEBOOK = REPO_ROOT / "tests" / "fixtures" / "fixture_centroid.ipynb"
FIXTURE_SWEEP = REPO_ROOT / "tests" / "fixtures" / "fixture_sweep.toml"

# the fixture's cheapest run: its own work takes milliseconds, so the time is the overhead
TINY = {"n_trials": 1, "n_frames": 1, "rerun_mode": "off"}


def bare_papermill_s(tmp_path, rounds: int = 5) -> float:
    """Best wall time of a bare papermill run of an empty notebook (a parameters cell and ``pass``)."""
    import papermill as pm

    nb = nbformat.v4.new_notebook()
    params = nbformat.v4.new_code_cell("n = 1")
    params.metadata["tags"] = ["parameters"]
    nb.cells = [params, nbformat.v4.new_code_cell("pass")]
    nb.metadata["kernelspec"] = {"name": KERNEL_NAME, "display_name": KERNEL_NAME, "language": "python"}
    src = tmp_path / "empty.ipynb"
    nbformat.write(nb, src)
    best = float("inf")
    for i in range(rounds + 1):                                        # the first is a warm-up
        t0 = time.perf_counter()
        pm.execute_notebook(str(src), str(tmp_path / f"empty_out{i}.ipynb"), parameters={"n": 2},
                            kernel_name=KERNEL_NAME, progress_bar=False, log_output=False,
                            start_timeout=KERNEL_START_TIMEOUT_S, extra_arguments=KERNEL_ARGUMENTS)
        best = min(best, time.perf_counter() - t0) if i else best
    return best


def test_papermill_overhead_per_run(benchmark, tmp_path, figure):
    counter = iter(range(1000))

    def one_run():
        outcome = run_notebook(FIXTURE_NOTEBOOK, tmp_path / f"run{next(counter)}", TINY)
        assert outcome.ok
        return outcome

    outcome = benchmark.pedantic(one_run, rounds=5, iterations=1, warmup_rounds=1)
    bare = bare_papermill_s(tmp_path)
    overhead = benchmark.stats.stats.min - bare
    benchmark.extra_info.update(notebook_runtime_s=outcome.runtime_s, bare_papermill_s=bare, overhead_s=overhead)
    fig = figure("runner overhead per run over bare papermill", overhead, 1.5, at_least=False, unit="s")
    assert fig.passed, fig.message()


def test_sweep_speedup_two_jobs_over_one(benchmark, tmp_path, figure):
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
    fig = figure("sweep speed-up, 2 jobs over 1 (8 runs)", speedup, 1.3, at_least=True, unit="x")
    assert fig.passed, fig.message()
