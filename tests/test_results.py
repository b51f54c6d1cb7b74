import json

import numpy as np
import pytest

from tvtrack.montecarlo import Estimate
from tvtrack.results import Claim, Results, judge_interval, load_results


def make(tmp_path):
    return Results(notebook="999_test", citation="A. Author 2000", parameters={"seed": 5, "output_dir": str(tmp_path)})


def test_results_json_round_trip(tmp_path):
    r = make(tmp_path)
    r.metric("rms", Estimate(1.0, 0.1, 0.8, 1.2, 30))
    r.metric("array", np.arange(3))
    r.metric("nan", float("nan"))
    r.claim(id="C999-1", statement="s", paper_value="1", acceptance="a", measured=np.float64(1.5),
            verdict="partly", note="n")
    data = load_results(r.write())
    assert data["notebook"] == "999_test" and data["seed"] == 5
    assert data["metrics"]["rms"]["ci_high"] == 1.2
    assert data["metrics"]["array"] == [0, 1, 2]
    assert data["metrics"]["nan"] is None
    assert data["claims"][0]["measured"] == 1.5
    assert "numpy" in data["versions"] and data["runtime_s"] >= 0
    json.loads((tmp_path / "results.json").read_text())  # strict JSON (no NaN)


def test_claims_are_validated(tmp_path):
    r = make(tmp_path)
    with pytest.raises(ValueError, match="verdict 'ok'"):
        r.claim(id="C999-1", statement="s", paper_value="", acceptance="", measured=1, verdict="ok")
    with pytest.raises(ValueError, match="claim id"):
        Claim(id="claim1", statement="s", paper_value="", acceptance="", measured=1, verdict="partly")
    r.claim(id="C999-2", statement="s", paper_value="", acceptance="", measured=1, verdict="partly")
    with pytest.raises(ValueError, match="recorded twice"):
        r.claim(id="C999-2", statement="s", paper_value="", acceptance="", measured=1, verdict="partly")


def test_load_results_rejects_bad_files(tmp_path):
    p = tmp_path / "results.json"
    p.write_text(json.dumps({"notebook": "x"}))
    with pytest.raises(ValueError, match="lacks"):
        load_results(p)


@pytest.mark.parametrize("ci, expected", [((0.5, 0.9), "reproduced"), ((0.9, 1.1), "partly"),
                                          ((1.2, 1.5), "not reproduced")])
def test_judge_interval(ci, expected):
    assert judge_interval(Estimate(sum(ci) / 2, 0.1, *ci, 10), high=1.0) == expected


def test_figure_is_saved_and_listed(tmp_path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    r = make(tmp_path)
    fig, ax = plt.subplots()
    ax.plot([0, 1])
    r.save_figure(fig, "fig1", "caption")
    assert (tmp_path / "fig1.png").stat().st_size > 0
    assert r.figures == [{"file": "fig1.png", "caption": "caption"}]
    with pytest.raises(ValueError, match="figure name"):
        r.save_figure(fig, "../evil", "c")
