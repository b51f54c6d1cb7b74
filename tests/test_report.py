import json
import re

import pytest

from conftest import FIXTURE_NOTEBOOK
from tvtrack.pipeline.report import (README_BEGIN, README_END, format_measured, update_readme, verdict_summary,
                                     write_report)
from tvtrack.pipeline.runner import run_notebook


@pytest.fixture(scope="module")
def reproduce_dir(tmp_path_factory):
    root = tmp_path_factory.mktemp("reproduce")
    assert run_notebook(FIXTURE_NOTEBOOK, root / "fixture_centroid", {"n_trials": 10, "n_frames": 3}).ok
    assert not run_notebook(FIXTURE_NOTEBOOK, root / "broken", {"n_trials": 0}).ok
    return root


def _robust(verdict="reproduced"):
    return {"label": "robust", "where": [], "choices": [], "conditions": [],
            "seeds": [{"seed": s, "measured": 1.0, "verdict": verdict} for s in (1, 2, 3)], "note": "n"}


def _claim(cid, verdict, robustness, statement="A claim."):
    return {"id": cid, "statement": statement, "paper_value": "1", "rule": {"kind": "in_band", "text": "in [0, 2]"},
            "acceptance": "in [0, 2]", "measured": {"value": 1.5, "ci_low": 1.2, "ci_high": 1.8, "n": 50},
            "verdict": verdict, "note": "", "robustness": robustness}


def _synthetic_run(root, name, claims, profile="paper", old_schema=False):
    """A run directory as the runner leaves it, with a hand-made results.json (new or pre-verdict-standard schema)."""
    run = root / name
    run.mkdir(parents=True)
    (run / "run.json").write_text(json.dumps({"notebook": name, "profile": profile, "status": "ok", "runtime_s": 12.0,
                                              "finished_utc": "2026-11-24T10:00:00Z"}))
    if old_schema:
        claims = [{k: v for k, v in c.items() if k not in ("rule", "robustness")} for c in claims]
    (run / "results.json").write_text(json.dumps({"notebook": name, "citation": f"Author: {name}", "seed": 1,
                                                  "runtime_s": 10.0, "git_commit": "abc", "claims": claims,
                                                  "figures": [], "recording": None}))
    return run


DEPENDS = {"label": "depends", "where": ["reproduced when epoch = mid, designation_sd = 1.0"],
           "choices": [{"name": "epoch", "default": "first", "values": ["first", "mid"], "why": "unstated"}],
           "conditions": [{"choices": {"epoch": "mid"}, "measured": 4.0, "verdict": "reproduced"}],
           "seeds": [], "note": ""}


@pytest.fixture
def synthetic_runs(tmp_path):
    root = tmp_path / "reproduce"
    _synthetic_run(root, "010_new", [_claim("C010-1", "reproduced", _robust()),
                                     _claim("C010-2", "not reproduced", DEPENDS, "The gain is 4."),
                                     _claim("C010-3", "not checkable", None)])
    _synthetic_run(root, "011_old", [_claim("C011-1", "partly", None)], old_schema=True)
    return root


def test_report_counts_claims_and_links_outputs(reproduce_dir, tmp_path):
    path = write_report(reproduce_dir, tmp_path / "REPRODUCTION.md", notebooks=["fixture_centroid", "broken", "absent"])
    text = path.read_text()
    assert ("**Claims: 1 reproduced · 0 partly · 0 not reproduced · 0 not checkable** (1 claims, 3 notebooks); "
            "of the checkable verdicts **0 robust · 1 unexplored · 0 depends · 0 unstable**") in text
    # the fixture varies nothing of a simulated world: it cannot be called robust
    assert "| C900-1 | **reproduced** | unexplored |" in text
    assert "centroid_errors.png" in text and "recording.rrd" in text
    assert re.search(r"`python -m tvtrack view \S*fixture_centroid`", text)
    assert "**Run failed**" in text and "parameter 'n_trials' = 0" in text
    assert "## absent\n\nNot run yet" in text


def test_report_shows_labels_where_and_old_schema(synthetic_runs, tmp_path):
    text = write_report(synthetic_runs, tmp_path / "R.md", notebooks=["010_new", "011_old"]).read_text()
    assert ("**1 robust · 0 unexplored · 1 depends · 0 unstable** · 1 without a robustness record") in text
    assert ("By verdict: 1 reproduced (1 robust) · 1 partly (1 no record) · 1 not reproduced (1 depends) · "
            "1 not checkable.") in text
    assert "| C010-2 | **not reproduced** | depends | reproduced when epoch = mid, designation_sd = 1.0 |" in text
    assert "| C010-3 | **not checkable** | — |  |" in text
    assert "| C011-1 | **partly** | — |  |" in text


def test_verdict_summary_counts_labels_per_verdict():
    claims = [_claim("C1-1", "reproduced", _robust()), _claim("C1-2", "reproduced", DEPENDS),
              _claim("C1-3", "partly", {**DEPENDS, "label": "unstable"})]
    assert verdict_summary(claims) == ("2 reproduced (1 robust, 1 depends) · 1 partly (1 unstable) · "
                                       "0 not reproduced · 0 not checkable")


def test_readme_paragraph_generated_with_dependence(synthetic_runs, tmp_path):
    readme = tmp_path / "README.md"
    readme.write_text(f"intro\n{README_BEGIN}\nhand-written\n{README_END}\nrest\n")
    write_report(synthetic_runs, tmp_path / "R.md", notebooks=["010_new", "011_old"], readme=readme)
    text = readme.read_text()
    assert text.startswith("intro\n") and text.endswith(f"{README_END}\nrest\n") and "hand-written" not in text
    assert "4 claims, **1 reproduced · 1 partly · 1 not reproduced · 1 not checkable**" in text
    assert "1 are robust" in text and "1 depend on a reading" in text and "1 have no robustness record" in text
    # the headline finding carries where it flips
    assert ("**010 C010-2**: The gain is 4. Measured 1.5 [1.2, 1.8] (in [0, 2]); "
            "depends: reproduced when epoch = mid, designation_sd = 1.0.") in text


def test_readme_left_alone_without_complete_paper_runs(synthetic_runs, tmp_path, capsys):
    _synthetic_run(synthetic_runs, "012_smoke", [_claim("C012-1", "reproduced", _robust())], profile="smoke")
    readme = tmp_path / "README.md"
    original = f"{README_BEGIN}\nkept\n{README_END}\n"
    readme.write_text(original)
    write_report(synthetic_runs, tmp_path / "R.md", notebooks=["010_new", "012_smoke", "absent"], readme=readme)
    assert readme.read_text() == original
    assert "left as it is (no successful paper-profile run of 012_smoke, absent" in capsys.readouterr().out


def test_update_readme_needs_markers(tmp_path):
    readme = tmp_path / "README.md"
    readme.write_text("no markers\n")
    with pytest.raises(ValueError, match="markers"):
        update_readme(readme, "x")


def test_report_without_notebooks_says_so(tmp_path):
    text = write_report(tmp_path, tmp_path / "R.md", notebooks=[]).read_text()
    assert "No notebooks in `notebooks/` yet" in text


def test_format_measured():
    assert format_measured({"value": 1.23456, "ci_low": 1.1, "ci_high": 1.3, "n": 5}) == "1.235 [1.1, 1.3]"
    assert format_measured({"a": 2, "b": {"value": 0.5, "ci_low": None, "ci_high": None}}) == "a: 2; b: 0.5"
