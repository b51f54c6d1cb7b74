import json

import numpy as np
import pytest

from tvtrack.montecarlo import Estimate
from tvtrack.results import Claim, Results, load_results
from tvtrack.register import Entry
from tvtrack.labels import Condition, Robustness
from tvtrack.verdicts import InBand, NotCheckable

SEEDS = Robustness(note="no unstated choice: a test fixture", seeds={1: 1.5, 2: 1.4, 3: 1.6})


def make(tmp_path):
    return Results(notebook="999_test", citation="A. Author 2000", parameters={"seed": 5, "output_dir": str(tmp_path)})


def test_results_json_round_trip(tmp_path):
    r = make(tmp_path)
    r.metric("rms", Estimate(1.0, 0.1, 0.8, 1.2, 30))
    r.metric("array", np.arange(3))
    r.metric("nan", float("nan"))
    r.claim(
        id="C999-1",
        statement="s",
        paper_value="1",
        rule=InBand("x", 1.0, 2.0),
        measured=np.float64(1.5),
        note="n",
        robustness=SEEDS,
    )
    data = load_results(r.write())
    assert data["notebook"] == "999_test" and data["seed"] == 5
    assert data["metrics"]["rms"]["ci_high"] == 1.2
    assert data["metrics"]["array"] == [0, 1, 2]
    assert data["metrics"]["nan"] is None
    claim = data["claims"][0]
    assert claim["measured"] == 1.5 and claim["verdict"] == "reproduced"
    assert claim["acceptance"] == claim["rule"]["text"] and claim["rule"]["kind"] == "in_band"
    assert claim["robustness"]["label"] == "unexplored" and [s["seed"] for s in claim["robustness"]["replicates"]] == [
        1,
        2,
        3,
    ]
    assert "numpy" in data["versions"] and data["runtime_s"] >= 0
    json.loads((tmp_path / "results.json").read_text())  # strict JSON (no NaN)


def test_the_rule_decides_and_claims_are_validated(tmp_path):
    r = make(tmp_path)
    c = r.claim(
        id="C999-1",
        statement="s",
        paper_value="1-2",
        rule=InBand("x", 1.0, 2.0),
        measured=Estimate(2.5, 0.1, 2.3, 2.7, 10),
        robustness=SEEDS,
    )
    assert c.verdict == "not reproduced" and "wholly above" in c.decision
    with pytest.raises(TypeError):  # a verdict cannot be typed
        r.claim(
            id="C999-2",
            statement="s",
            paper_value="",
            rule=InBand("x", 1.0, 2.0),
            measured=1,
            verdict="reproduced",
            robustness=SEEDS,
        )
    with pytest.raises(TypeError, match="Rule"):
        r.claim(id="C999-2", statement="s", paper_value="", rule="x in [1, 2]", measured=1, robustness=SEEDS)
    with pytest.raises(ValueError, match="robustness record"):
        r.claim(id="C999-2", statement="s", paper_value="", rule=InBand("x", 1.0, 2.0), measured=1)
    with pytest.raises(ValueError, match="at least 3 seeds"):
        r.claim(
            id="C999-2",
            statement="s",
            paper_value="",
            rule=InBand("x", 1.0, 2.0),
            measured=1,
            robustness=Robustness(note="n", seeds={1: 1.0}),
        )
    with pytest.raises(ValueError, match="unknown choices"):
        r.claim(
            id="C999-2",
            statement="s",
            paper_value="",
            rule=InBand("x", 1.0, 2.0),
            measured=1,
            robustness=Robustness([Entry("a", "reading", 1, (1, 2), "w")], [Condition({"b": 2}, 1.0)], SEEDS.seeds),
        )
    nc = r.claim(id="C999-3", statement="s", paper_value="", rule=NotCheckable("true by construction"), measured=None)
    assert nc.verdict == "not checkable" and nc.robustness is None
    with pytest.raises(ValueError, match="claim id"):
        r.claim(id="claim1", statement="s", paper_value="", rule=NotCheckable("r"), measured=None)
    with pytest.raises(ValueError, match="recorded twice"):
        r.claim(id="C999-3", statement="s", paper_value="", rule=NotCheckable("r"), measured=None)
    with pytest.raises(ValueError, match="rule's text"):
        Claim(
            id="C999-4",
            statement="s",
            paper_value="",
            rule={"kind": "in_band", "text": "a"},
            acceptance="b",
            measured=1,
            verdict="not checkable",
        )


def test_load_results_rejects_bad_files(tmp_path):
    p = tmp_path / "results.json"
    p.write_text(json.dumps({"notebook": "x"}))
    with pytest.raises(ValueError, match="lacks"):
        load_results(p)


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


def test_results_record_the_kernels_cpu_seconds(tmp_path):
    """``cpu_s``: CPU time spent since the Results was made (the benchmark table's per-notebook CPU figure)."""
    import time

    r = make(tmp_path)
    t = time.process_time()
    while time.process_time() - t < 0.35:
        pass
    time.sleep(0.3)  # wall, not CPU
    data = r.to_dict()
    # cpu_s comes from os.times (10 ms ticks): a stated 0.02 s below the 0.35 s spun
    assert 0.33 <= data["cpu_s"] < data["runtime_s"] - 0.25
