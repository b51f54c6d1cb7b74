"""pytest set-up of the benchmarks: the ``figure`` fixture (:func:`figures.record_figure`) and, at the end
of the session, the figures measured merged into ``benchmarks/results/table.md`` (:func:`figures.write_table`;
``TVTRACK_BENCH_TABLE`` names another file). See :mod:`figures` for what a figure is."""

import os
from pathlib import Path

import pytest
from figures import _FIGURES, TABLE, record_figure, write_table


@pytest.fixture
def figure():
    """:func:`figures.record_figure`, for a benchmark to state its figure."""
    return record_figure


def pytest_sessionfinish(session, exitstatus):
    if _FIGURES:
        write_table(_FIGURES.values(), Path(os.environ.get("TVTRACK_BENCH_TABLE", TABLE)))
