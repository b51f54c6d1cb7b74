"""Benchmark figures: a figure is a ratio against a reference run in the same process or
work per CPU second, never an absolute wall time; :func:`write_table` merges them into one table,
``benchmarks/results/table.md`` (name, value, target, pass), which ``make bench`` writes and docs/benchmarks.md quotes.
"""

from __future__ import annotations

import os
import time
from dataclasses import dataclass
from pathlib import Path

TABLE = Path(__file__).parent / "results" / "table.md"
HEADER = ("| figure | value | target | pass |", "|---|---|---|---|")


@dataclass(frozen=True)
class Figure:
    """One benchmark figure: ``value`` against ``target`` (``at_least``: a floor, else a ceiling); a ``target`` of
    ``None`` is a figure the table reports without a pass or fail (a measured trade-off, not a promise)."""

    name: str
    value: float
    target: float | None
    at_least: bool
    unit: str = ""
    note: str = ""  # measuring conditions shown after the value (load average, engine)

    @property
    def passed(self) -> bool:
        if self.target is None:
            return True
        return self.value >= self.target if self.at_least else self.value <= self.target

    def row(self) -> str:
        unit = f" {self.unit}" if self.unit else ""
        note = f" ({self.note})" if self.note else ""
        if self.target is None:
            return f"| {self.name} | {self.value:.4g}{unit}{note} | reported, no target | - |"
        target = f"{'>=' if self.at_least else '<='} {self.target:.4g}{unit}"
        return f"| {self.name} | {self.value:.4g}{unit}{note} | {target} | {'yes' if self.passed else 'no'} |"

    def message(self) -> str:
        return f"{self.name}: {self.value:.4g} {self.unit} misses the target {self.row().split('|')[3].strip()}"


_FIGURES: dict[str, Figure] = {}


def record_figure(
    name: str, value: float, target: float | None, *, at_least: bool = True, unit: str = "", note: str = ""
) -> Figure:
    """Record a figure for the table and return it (assert ``fig.passed, fig.message()`` in the test);
    ``note`` states the measuring conditions (e.g. :func:`load_note`)."""
    fig = Figure(name, float(value), None if target is None else float(target), at_least, unit, note)
    _FIGURES[name] = fig
    return fig


def load_note() -> str:
    """The machine's load averages (1, 5, 15 min) as a note for a figure measured under that load."""
    try:
        one, five, fifteen = os.getloadavg()
    except OSError:
        return "load average unknown"
    return f"load {one:.2f}/{five:.2f}/{fifteen:.2f}, {os.cpu_count()} cores"


def cpu_seconds() -> float:
    """CPU seconds of this process (all threads) plus its waited-for child processes (sweep workers,
    notebook kernels and their own children)."""
    t = os.times()
    return t.user + t.system + t.children_user + t.children_system


class CpuClock:
    """``with CpuClock() as c: ...`` -> ``c.cpu_s`` (:func:`cpu_seconds` spent) and ``c.wall_s``."""

    def __enter__(self):
        self._cpu, self._wall = cpu_seconds(), time.perf_counter()
        return self

    def __exit__(self, *exc):
        self.cpu_s = cpu_seconds() - self._cpu
        self.wall_s = time.perf_counter() - self._wall
        return False


def read_table(path: Path = TABLE) -> dict[str, str]:
    """Rows of an existing table by figure name."""
    if not path.is_file():
        return {}
    rows = {}
    for line in path.read_text().splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) == 4 and line.startswith("| ") and cells[0] not in ("figure", "---"):
            rows[cells[0]] = line
    return rows


def write_table(figures, path: Path = TABLE) -> Path:
    """Merge ``figures`` into the table at ``path`` (sorted by name) and return the path."""
    rows = read_table(path)
    rows.update({f.name: f.row() for f in figures})
    path.parent.mkdir(parents=True, exist_ok=True)
    lines = [
        "Benchmark figures (`make bench`): ratios in one run or work per CPU second; rows not measured in the last",
        "run keep their previous value.",
        "",
        *HEADER,
        *(rows[k] for k in sorted(rows)),
    ]
    path.write_text("\n".join(lines) + "\n")
    return path
