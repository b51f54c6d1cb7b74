"""Where each notebook's exploration spends its time, and what the screened joint design saves.

Read from the last paper-profile ``make reproduce`` (each claim's ``robustness.design.timing`` in
``papermill_runs/reproduce/<notebook>/results.json``, written by :func:`tvtrack.explore.explore`: configurations
and wall seconds per stage -- replicates, sizing, one at a time, joint screened / confirmed at full size, pinned,
combinations). Per notebook, as figures in the table ``make bench`` writes:

- **configurations per CPU second** of its explorations (all stages together; wall seconds where a run predates
  the CPU clock), against its pro-rata share of the budget: the budget (15 minutes on 2 cores, 1,800 core-seconds)
  split between the notebooks in proportion to the CPU seconds each spent, so every notebook passes exactly when
  the five together fit (one notebook may take more than a fifth when the others take less);
- (the CPU seconds of ``make reproduce``, the notebooks' ``cpu_s`` summed against the budget's 1,800 core-seconds,
  are ``bench_runner``'s rows; the last measured run, 2026-11-28: 1,463 CPU s -- 002 638, 003 435, 004 206,
  001 124, 000 61 -- in 13 min 05 s wall on 2 idle cores; a stage's CPU seconds include an executor's worker
  processes, :func:`tvtrack.explore.cpu_seconds`);
- **the screening's saving**: the full-size cost of the joint design (its configurations at the replicates'
  full-size cost per configuration) over what the screened design cost (screening plus the confirmations
  at full size); at least 1 where a notebook screens (a screen that costs more than it saves fails). No notebook
  screens by default, so ``bench_000.py`` measures it both ways in one run, reported without a target;
- every stage's configurations and seconds, in the row's note.

And **the smoke profile's seconds**: each notebook run at its smoke profile here (the edit loop's Run All), against
the 30 s its profile file promises on an idle 2-core machine, scaled by the load it ran under (load average over
cores, at least 1).
Skipped when there is no reproduce.
"""

import json
import os

import pytest
from figures import load_note

from tvtrack.pipeline.paths import reproduce_dir
from tvtrack.pipeline.runner import list_notebooks, run_notebook

SMOKE_TARGET_S = 30.0
#: `make reproduce`'s budget: 15 minutes on 2 cores, in core-seconds.
BUDGET_CORE_S = 15 * 60 * 2


def _designs(results: dict) -> list[dict]:
    """The distinct exploration designs of one notebook (claims of one exploration share one design)."""
    seen, out = set(), []
    for c in results.get("claims", []):
        design = (c.get("robustness") or {}).get("design")
        if not design or "timing" not in design:
            continue
        key = json.dumps(design, sort_keys=True, default=str)
        if key not in seen:
            seen.add(key)
            out.append(design)
    return out


def _stages(designs: list[dict]) -> dict[str, list]:
    """Per stage: [configurations, CPU seconds] (wall seconds for a run that predates the CPU clock)."""
    total: dict[str, list] = {}
    for d in designs:
        for stage, row in d["timing"].items():
            t = total.setdefault(stage, [0, 0.0])
            t[0] += row["configurations"]
            t[1] += row.get("cpu_s", row["wall_s"])
    return total


def _results(name: str) -> dict | None:
    path = reproduce_dir() / name / "results.json"
    return json.loads(path.read_text()) if path.exists() else None


def _notebook_cpu() -> dict[str, float]:
    """Each notebook's CPU seconds in its last paper-profile run (``cpu_s`` of its results.json)."""
    out = {}
    for nb in list_notebooks():
        r = _results(nb.stem)
        if r is not None and r.get("cpu_s"):
            out[nb.stem] = float(r["cpu_s"])
    return out


@pytest.mark.parametrize("name", [nb.stem for nb in list_notebooks()])
def test_exploration_configurations_per_second_and_screening_saving(benchmark, name, figure):
    results = _results(name)
    if results is None or not _designs(results):
        pytest.skip(f"no paper-profile reproduce with exploration timings for {name}")
    stages = benchmark.pedantic(lambda: _stages(_designs(results)), rounds=1, iterations=1)
    n = sum(v[0] for v in stages.values())
    secs = sum(v[1] for v in stages.values())
    note = "; ".join(f"{k}: {v[0]} in {v[1]:.0f} s" for k, v in stages.items())
    # target: its pro-rata share of the budget (the budget split by the CPU each notebook spent)
    cpu = _notebook_cpu()
    share = BUDGET_CORE_S * cpu[name] / sum(cpu.values()) if name in cpu else BUDGET_CORE_S / len(list_notebooks())
    target = n / (secs * share / cpu[name]) if name in cpu else n / share
    fig = figure(f"{name} exploration, configurations per CPU s", n / secs, target, at_least=True, note=note)
    assert fig.passed, fig.message()
    screened = [k for k in stages if k.endswith(", screened")]
    if screened and stages.get("replicates", [0])[0]:
        per_full = stages["replicates"][1] / stages["replicates"][0]  # one full-size configuration
        full_cost = sum(stages[k][0] for k in screened) * per_full
        spent = sum(
            stages[k][1] + stages.get(k.replace("screened", "confirmed at full size"), [0, 0.0])[1] for k in screened
        )
        saving = figure(
            f"{name} screening's saving (full-size cost / screened cost)", full_cost / spent, 1.0, at_least=True
        )
        assert saving.passed, saving.message()


@pytest.mark.parametrize("name", [nb.stem for nb in list_notebooks()])
def test_smoke_profile_seconds(benchmark, name, tmp_path, figure):
    outcome = benchmark.pedantic(lambda: run_notebook(name, tmp_path / name, profile="smoke"), rounds=1, iterations=1)
    assert outcome.ok, outcome.error
    # the promise is for an idle machine: the target grows with the load the run met (cores already busy)
    busy = max(1.0, os.getloadavg()[0] / (os.cpu_count() or 1))
    fig = figure(
        f"{name} smoke profile, wall s",
        outcome.runtime_s,
        SMOKE_TARGET_S * busy,
        at_least=False,
        unit="s",
        note=load_note(),
    )
    assert fig.passed, fig.message()
