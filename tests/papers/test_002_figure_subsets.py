"""Notebook 002 run with one figure set at a time (smoke scale).

The figure sets share state: the bias table and C002-15 read Fig 4's configurations, C002-10 needs
Figs 4-6, C002-11 and its headline conditions need Fig 5 and the extras, and Figs 1 and 2 share one
plan. A cell that reads another set's state crashed the headline sweeps (``figures = ["fig5"]``:
NameError ``rows``). These runs cover the sets that read shared state; fig1 (the same plan as fig2),
fig3, fig6 and fig7 touch only their own state and run in the full smoke profile. Each run costs
about 8 s of CPU, so four runs keep ``make test`` in budget.
"""

import pytest

from tvtrack.pipeline.runner import run_notebook
from tvtrack.results import load_results

NAME = "002_unified_location_em"


@pytest.mark.notebook
@pytest.mark.slow
@pytest.mark.parametrize("figure", ["fig5", "fig4", "extra", "fig2"])
def test_notebook_runs_with_one_figure_set(figure, tmp_path):
    outcome = run_notebook(NAME, tmp_path / figure, {"figures": [figure]}, profile="smoke")
    assert outcome.ok, f"figures = ['{figure}'] failed: {outcome.error}"
    claims = {c["id"]: c for c in load_results(tmp_path / figure / "results.json")["claims"]}
    assert len(claims) == 16
    checkable = {cid for cid, c in claims.items() if c["verdict"] != "not checkable"}
    expected = {"fig5": {"C002-11"}, "fig4": {"C002-15"}, "extra": {"C002-12"},
                "fig2": {"C002-1", "C002-2", "C002-3", "C002-4", "C002-5", "C002-6"}}[figure]
    assert checkable == expected
