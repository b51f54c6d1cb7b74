"""The benchmark table writer (benchmarks/figures.py): one row per figure, pass computed from the target's
direction, rows of figures not measured in a run kept, re-measured rows replaced."""

import importlib.util
import sys
from pathlib import Path

_spec = importlib.util.spec_from_file_location("bench_figures", Path(__file__).parents[1] / "benchmarks" / "figures.py")
figures = importlib.util.module_from_spec(_spec)
sys.modules["bench_figures"] = figures  # dataclasses resolve their module while it executes
_spec.loader.exec_module(figures)


def test_figures_pass_by_their_direction_and_merge_into_one_table(tmp_path):
    table = tmp_path / "table.md"
    floor = figures.Figure("001 speed-up", 412.0, 400, at_least=True, unit="x")
    ceiling = figures.Figure("runner overhead", 1.8, 1.5, at_least=False, unit="s")
    assert floor.passed and not ceiling.passed and ">= 400" in floor.row() and "<= 1.5 s" in ceiling.message()
    figures.write_table([floor, ceiling], table)
    figures.write_table([figures.Figure("runner overhead", 1.2, 1.5, at_least=False, unit="s")], table)
    rows = figures.read_table(table)
    assert set(rows) == {"001 speed-up", "runner overhead"}
    assert rows["runner overhead"] == "| runner overhead | 1.2 s | <= 1.5 s | yes |"
    assert rows["001 speed-up"] == "| 001 speed-up | 412 x | >= 400 x | yes |"
    assert table.read_text().count("| figure | value | target | pass |") == 1


def test_cpu_clock_counts_cpu_not_sleep():
    import time

    with figures.CpuClock() as c:
        time.sleep(0.5)
        t0 = time.process_time()
        while time.process_time() - t0 < 0.1:  # 0.1 s of CPU whatever the machine's speed (os.times ticks 10 ms)
            pass
    assert c.wall_s >= 0.5 and 0.05 < c.cpu_s < c.wall_s - 0.4  # the sleep is wall time, not CPU time


def test_a_note_states_the_conditions_in_the_value_cell(tmp_path):
    table = tmp_path / "table.md"
    note = figures.load_note()
    assert note.startswith("load ") or note == "load average unknown"
    fig = figures.Figure("001 speed-up", 412.0, 400, at_least=True, unit="x", note=note)
    figures.write_table([fig], table)
    assert figures.read_table(table)["001 speed-up"] == f"| 001 speed-up | 412 x ({note}) | >= 400 x | yes |"


def test_a_figure_without_a_target_is_reported_without_a_pass(tmp_path):
    table = tmp_path / "table.md"
    fig = figures.Figure("000 screening's saving", 1.07, None, at_least=True, note="16 joint configurations")
    assert fig.passed  # nothing to fail: a measured trade-off
    figures.write_table([fig], table)
    row = figures.read_table(table)["000 screening's saving"]
    assert row == "| 000 screening's saving | 1.07 (16 joint configurations) | reported, no target | - |"
