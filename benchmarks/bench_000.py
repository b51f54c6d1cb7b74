"""Speed targets of notebook 000 (issue 5): both filter variants on 1000 trials x 600 steps in under 1 s
on one core; the Figs. 2-3 sweeps at the paper profile in under 3 minutes on 2 cores."""

import time
from pathlib import Path

import numpy as np
import pytest

from tvtrack.papers.p000_dissector_ekf.model import (background_intensity, DissectorScan, draw_noises, GaussMarkovMessage, simulate)
from tvtrack.papers.p000_dissector_ekf.ekf import run_variant1, run_variant2, variant1_filter, variant2_filter

MSG = GaussMarkovMessage(0.1, 0.15)


@pytest.fixture(scope="module")
def data():
    scan = DissectorScan(background_intensity(20.0, 1.0, 0.05), 0.5, time_offset=-0.025)
    _, y = simulate(scan, MSG, draw_noises(np.random.default_rng(0), 1000, 600))
    return scan, y


def test_both_variants_1000_trials_600_steps(benchmark, data):
    scan, y = data
    f1, f2 = variant1_filter(scan, MSG), variant2_filter(scan, MSG)

    def both():
        run_variant1(f1, y)
        run_variant2(f2, y)
    benchmark.pedantic(both, rounds=3, iterations=1)
    assert benchmark.stats.stats.min < 1.0, f"both variants took {benchmark.stats.stats.min:.2f} s (target < 1 s)"


@pytest.mark.parametrize("spec", ["000_fig2_psi", "000_fig3_contrast"])
def test_figure_sweeps_at_paper_profile(benchmark, spec, tmp_path):
    from tvtrack.pipeline.paths import SWEEP_DIR
    from tvtrack.pipeline.sweep import run_sweep

    t0 = time.perf_counter()
    summary = benchmark.pedantic(lambda: run_sweep(Path(SWEEP_DIR) / f"{spec}.toml", jobs=2,
                                                   output=tmp_path / spec, progress=False),
                                 rounds=1, iterations=1)
    elapsed = time.perf_counter() - t0
    del summary
    assert elapsed < 180.0, f"sweep {spec} took {elapsed:.0f} s (target < 180 s on 2 cores)"
