import json
import re

import pytest

from conftest import FIXTURE_NOTEBOOK, copy_fixture_runs, minimal_claim
from tvtrack.pipeline.report import (
    README_BEGIN,
    README_END,
    format_measured,
    update_readme,
    verdict_summary,
    write_report,
)
from tvtrack.pipeline.preflight import UsageError
from tvtrack.pipeline.runner import read_run


@pytest.fixture(scope="module")
def reproduce_dir(tmp_path_factory, fixture_runs):
    """``fixture_centroid`` (ok) and ``broken`` (failed): copies of the session's fixture runs (tests/conftest.py)."""
    return copy_fixture_runs(fixture_runs, tmp_path_factory.mktemp("reproduce"))


def _robust(verdict="reproduced"):
    return {
        "label": "robust",
        "where": [],
        "choices": [],
        "conditions": [],
        "seeds": [{"seed": s, "measured": 1.0, "verdict": verdict} for s in (1, 2, 3)],
        "note": "n",
    }


def _claim(cid, verdict, robustness, statement="A claim."):
    return {**minimal_claim(cid, verdict), "statement": statement, "robustness": robustness}


def _synthetic_run(root, name, claims, profile="paper", old_schema=False):
    """A run directory as the runner leaves it, with a hand-made results.json (new or pre-verdict-standard schema)."""
    run = root / name
    run.mkdir(parents=True)
    (run / "run.json").write_text(
        json.dumps(
            {
                "notebook": name,
                "profile": profile,
                "status": "ok",
                "runtime_s": 12.0,
                "finished_utc": "2026-11-24T10:00:00Z",
            }
        )
    )
    if old_schema:
        claims = [{k: v for k, v in c.items() if k not in ("rule", "robustness")} for c in claims]
    (run / "results.json").write_text(
        json.dumps(
            {
                "notebook": name,
                "citation": f"Author: {name}",
                "seed": 1,
                "runtime_s": 10.0,
                "git_commit": "abc",
                "claims": claims,
                "figures": [],
                "recording": None,
            }
        )
    )
    return run


DEPENDS = {
    "label": "depends",
    "where": ["reproduced when epoch = mid, designation_sd = 1.0"],
    "choices": [{"name": "epoch", "default": "first", "values": ["first", "mid"], "why": "unstated"}],
    "conditions": [{"choices": {"epoch": "mid"}, "measured": 4.0, "verdict": "reproduced"}],
    "seeds": [],
    "note": "",
}


@pytest.fixture
def synthetic_runs(tmp_path):
    root = tmp_path / "reproduce"
    _synthetic_run(
        root,
        "010_new",
        [
            _claim("C010-1", "reproduced", _robust()),
            _claim("C010-2", "not reproduced", DEPENDS, "The gain is 4."),
            _claim("C010-3", "not checkable", None),
        ],
    )
    _synthetic_run(root, "011_old", [_claim("C011-1", "partly", None)], old_schema=True)
    return root


def test_report_counts_claims_and_links_outputs(reproduce_dir, tmp_path):
    path = write_report(reproduce_dir, tmp_path / "REPRODUCTION.md", notebooks=["fixture_centroid", "broken", "absent"])
    text = path.read_text()
    assert (
        "**Claims: 1 reproduced · 0 partly · 0 not reproduced · 0 not checkable** (1 claims from 1 of 3 notebooks); "
        "of the checkable verdicts **0 robust · 0 limited · 0 unexplored · 0 depends · 0 unstable · 1 provisional**"
    ) in text
    # the fixture's design is far too small for a share: never robust, shown as provisional
    assert re.search(
        r"\| C900-1 \| [^|]+ \| \*\*reproduced\*\* \| provisional \| Reproduced \(too few configurations to label\): ",
        text,
    )
    assert "**Profile shown: paper**" in text
    assert "centroid_errors.png" in text and "recording.rrd" in text
    assert re.search(r"`python -m tvtrack view \S*fixture_centroid`", text)
    assert "**Run failed**" in text and "parameter 'n_trials' = 0" in text
    assert "## absent\n\nNot run yet" in text


def test_report_shows_labels_where_and_old_schema(synthetic_runs, tmp_path):
    text = write_report(synthetic_runs, tmp_path / "R.md", notebooks=["010_new", "011_old"]).read_text()
    assert ("**1 robust · 0 limited · 0 unexplored · 1 depends · 0 unstable** · 1 without a robustness record") in text
    assert (
        "By verdict: 1 reproduced (1 robust) · 1 partly (1 no record) · 1 not reproduced (1 depends) · 1 not checkable."
    ) in text
    # the flip named by the register's words, not the record's legacy "where" line with its code names
    assert (
        "| C010-2 | The gain is 4. | **not reproduced** | depends | Not reproduced: the measured value is 1.5 \\[1.2, "
        "1.8\\], against \\[0, 2\\] (the paper: 1). Under another reading of the paper's text it is reproduced: "
        "epoch = mid. |"
    ) in text
    assert "designation\\_sd" not in text
    assert "| C010-3 | A claim. | **not checkable** | — | Not checkable: nothing measurable. |" in text
    assert (
        "| C011-1 | A claim. | **partly** | — | Partly reproduced: the measured value is 1.5 \\[1.2, 1.8\\]. |" in text
    )


def test_verdict_summary_counts_labels_per_verdict():
    claims = [
        _claim("C1-1", "reproduced", _robust()),
        _claim("C1-2", "reproduced", DEPENDS),
        _claim("C1-3", "partly", {**DEPENDS, "label": "unstable"}),
    ]
    assert verdict_summary(claims) == (
        "2 reproduced (1 robust, 1 depends) · 1 partly (1 unstable) · 0 not reproduced · 0 not checkable"
    )


def test_an_undecided_claims_label_is_its_decided_parts_in_the_counts_and_the_table(tmp_path):
    """An undecided claim labelled by its decided parts is never plain "robust": the verdict counts and the
    per-notebook table say so, as its line on the first screen does."""
    claims = [_claim("C1-1", "undecided", _robust("undecided")), _claim("C1-2", "undecided", _robust("undecided"))]
    assert verdict_summary(claims[:1]).endswith("1 undecided (1 robust in its decided parts only) · 0 not checkable")
    assert "2 undecided (2 robust in their decided parts only)" in verdict_summary(claims)
    root = tmp_path / "runs"
    _synthetic_run(root, "010_new", claims[:1])
    text = write_report(root, tmp_path / "R.md", notebooks=["010_new"]).read_text()
    assert "| C1-1 | A claim. | **undecided** | robust in its decided parts only |" in text
    assert "| **undecided** | robust |" not in text


def test_a_claim_that_holds_in_part_with_a_part_undecided_is_labelled_by_its_decided_parts_everywhere(tmp_path):
    """Its line, the verdict counts, the per-notebook table, the first screen and the site all scope a robust label
    to the decided parts where one part is still undecided, as they do for an undecided claim."""
    from tvtrack.pipeline.report import _label_brackets, first_screen, first_screen_list
    from tvtrack.results import claims_table, label_verdict, results_summary

    parts = {n: {"verdict": v, "label": lab} for n, v, lab in [("a", "reproduced", "robust"),
             ("b", "not reproduced", "robust"), ("c", "undecided", "-")]}  # fmt: skip
    claim = _claim("C1-1", "partly", {**_robust("partly"), "parts": parts})
    assert (
        label_verdict(claim) == "undecided" and label_verdict(_claim("C1-2", "partly", _robust("partly"))) == "partly"
    )
    assert _label_brackets(claim).startswith(" (robust in its decided parts only")
    assert "1 partly (1 robust in its decided parts only)" in verdict_summary([claim])
    both = [claim, _claim("C1-2", "partly", _robust("partly"))]
    assert "2 partly (1 robust, 1 robust in its decided parts only)" in verdict_summary(both)
    assert "| **partly** | robust in its decided parts only |" in claims_table([claim])
    assert "1 of them (C1-1) with a part undecided, labelled by its decided parts only" in results_summary(both)
    rows = first_screen({"009_t": (None, {"claims": [{**claim, "verdict": "not reproduced"}]})})  # listed there
    assert "(not reproduced, robust in its decided parts only" in first_screen_list(rows)


def test_readme_block_generated_with_the_first_screen_and_no_date(synthetic_runs, tmp_path):
    readme = tmp_path / "README.md"
    readme.write_text(f"intro\n{README_BEGIN}\nhand-written\n{README_END}\nrest\n")
    write_report(synthetic_runs, tmp_path / "R.md", notebooks=["010_new", "011_old"], readme=readme)
    text = readme.read_text()
    assert text.startswith("intro\n") and text.endswith(f"{README_END}\nrest\n") and "hand-written" not in text
    assert text.index(README_BEGIN) < text.index("Of 4 claims checked, 1 holds, 1 holds in part and 1 does not")
    assert "| 010\\_new | 3 | 1 | 0 | 1 | 0 | 1 | 1 robust, 1 depends |" in text  # one row per paper
    assert "**robust**: no explored reading" in text and "**undecided**: the interval straddles" in text  # glossary
    # the headline finding: one line with statement, verdict, label and its sentence
    assert (
        "- **010 C010-2** (not reproduced, depends: a reading) *The gain is 4.* Not reproduced: the measured value is 1.5 "
        "\\[1.2, 1.8\\], against \\[0, 2\\] (the paper: 1). Under another reading of the paper's text it is "
        "reproduced: epoch = mid."
    ) in text
    assert (
        "- **Hold** (label in brackets, the kind of change that flips it, and the claim's caveat where it has one): "
        "010: C010-1 (robust)." in text
    )  # a claim that holds: named, no sentence
    assert "- **010 C010-1**" not in text
    assert not re.search(r"20\d\d-\d\d-\d\d", text)  # no date: an unchanged result leaves git status clean
    before = readme.stat().st_mtime_ns
    write_report(synthetic_runs, tmp_path / "R.md", notebooks=["010_new", "011_old"], readme=readme)
    assert readme.read_text() == text and readme.stat().st_mtime_ns == before


def test_generated_text_is_escaped_in_markdown(tmp_path):
    root = tmp_path / "reproduce"
    claim = _claim(
        "C020-1",
        "not reproduced",
        {**DEPENDS, "conditions": [{"choices": {"reading": "v1 / sigma*2"}, "verdict": "reproduced"}]},
        "The error is sigma*2 * k_gain | <b>",
    )
    _synthetic_run(root, "020_esc", [claim])
    readme = tmp_path / "README.md"
    readme.write_text(f"{README_BEGIN}\n{README_END}\n")
    report = write_report(root, tmp_path / "R.md", notebooks=["020_esc"], readme=readme).read_text()
    for text in (report, readme.read_text()):
        assert "The error is sigma\\*2 \\* k\\_gain \\| \\<b\\>" in text
        assert "sigma*2" not in text.replace("sigma\\*2", "")
    assert "Under another reading of the paper's text it is reproduced: reading = v1 / sigma\\*2." in report


def test_first_screen_orders_failures_then_dependent_verdicts_and_reads_new_records(tmp_path):
    new_record = {
        "label": "unstable",
        "where": ["replicates split"],
        "conditions": [],
        "seeds": [],
        "coverage": "unstable over 3 replicates and 14 readings",
        "register": [{"name": "motion"}],
        "parts": {
            "gain": {"verdict": "reproduced", "label": "robust"},
            "bias": {"verdict": "partly", "label": "unstable"},
        },
    }
    root = tmp_path / "reproduce"
    _synthetic_run(
        root,
        "030_new",
        [
            _claim("C030-1", "reproduced", new_record),
            _claim("C030-2", "undecided", {**_robust(), "label": "unexplored"}),
            _claim("C030-3", "reproduced", _robust()),
            _claim("C030-10", "not reproduced", DEPENDS),
        ],
    )
    from tvtrack.pipeline.report import collect_runs, first_screen

    rows = first_screen(collect_runs(root, ["030_new"]))
    assert [(r["id"], r["verdict"], r["label"]) for r in rows] == [
        ("C030-10", "not reproduced", "depends"),
        ("C030-2", "undecided", "unexplored"),
        ("C030-1", "reproduced", "unstable"),
    ]
    text = write_report(root, tmp_path / "R.md", notebooks=["030_new"]).read_text()
    assert "covers: unstable over 3 replicates and 14 readings" in text
    assert "parts: gain reproduced, robust; bias partly, unstable" in text
    assert "1 undecided" in text and "1 unexplored" in text


def test_report_has_the_forest_plot_and_the_robustness_picture(synthetic_runs, tmp_path):
    from PIL import Image

    from tvtrack.pipeline.report import collect_runs, forest_items
    from tvtrack.pipeline.figures import robustness_matrix

    text = write_report(synthetic_runs, tmp_path / "R.md", notebooks=["010_new", "011_old"]).read_text()
    assert "![forest plot" in text and "![robustness" in text
    for name in ("forest.png", "robustness.png"):
        assert Image.open(synthetic_runs / "figures" / name).size[0] > 300
    items = forest_items(collect_runs(synthetic_runs, ["010_new", "011_old"]))
    # C010-1 and C010-2 measured 1.5 [1.2, 1.8] against [0, 2] -> 0.75 [0.6, 0.9] on the band's scale
    assert [(i["name"], i["verdict"]) for i in items] == [
        ("010 C010-1", "reproduced"),
        ("010 C010-2", "not reproduced"),
    ]
    assert items[0]["value"] == pytest.approx(0.75) and (items[0]["low"], items[0]["high"]) == pytest.approx((0.6, 0.9))
    rows, entries, cells = robustness_matrix([_claim("C1-1", "not reproduced", DEPENDS)])
    assert (rows, entries, cells) == (["C1-1"], ["epoch"], [["reproduced"]])


def test_the_robustness_picture_reads_each_entry_varied_alone():
    """A cell is the verdict when its entry alone changes: a joint condition colours no column (every explorer
    condition carries its whole configuration, which once coloured every entry of the row), an undecided condition
    does not count as a flip, and an entry whose conditions all stay undecided reads undecided."""
    from tvtrack.pipeline.figures import robustness_matrix

    register = [{"name": n, "default": 0, "values": [0, 1]} for n in ("a", "b", "c", "d")]
    everything = {"a": 1, "b": 1, "c": 1, "d": 0}

    def cond(kind, changed, verdict):
        return {"kind": kind, "changed": changed, "config": everything, "verdict": verdict}

    conditions = [
        cond("single", {"a": 1}, "reproduced"),
        cond("single", {"b": 1}, "not reproduced"),
        cond("single", {"c": 1}, "undecided"),
        cond("joint", {"a": 1, "d": 1}, "not reproduced"),
        cond("combination", {"c": 1, "d": 1}, "partly"),
    ]
    record = {**_robust(), "register": register, "conditions": conditions}
    rows, entries, cells = robustness_matrix([_claim("C1-2", "reproduced", record)])
    assert rows == ["C1-2"] and entries == ["a", "b", "c", "d"]
    assert cells == [["reproduced", "not reproduced", "undecided", None]]


def test_readme_left_alone_without_complete_paper_runs(synthetic_runs, tmp_path, capsys):
    _synthetic_run(synthetic_runs, "012_smoke", [_claim("C012-1", "reproduced", _robust())], profile="smoke")
    readme = tmp_path / "README.md"
    original = f"{README_BEGIN}\nkept\n{README_END}\n"
    readme.write_text(original)
    write_report(synthetic_runs, tmp_path / "R.md", notebooks=["010_new", "012_smoke", "absent"], readme=readme)
    assert readme.read_text() == original
    assert "left as it is (no successful paper-profile run of 012_smoke, absent" in capsys.readouterr().out


def test_smoke_reproduce_writes_its_own_folder_and_leaves_paper_runs_alone(tmp_path, monkeypatch):
    import shutil

    from tvtrack.pipeline import reproduce as rep

    nb = tmp_path / "nbs" / "fixture_centroid.ipynb"
    nb.parent.mkdir()
    shutil.copy(FIXTURE_NOTEBOOK, nb)
    (nb.parent / "fixture_centroid.smoke.toml").write_text('n_trials = 10\nn_frames = 3\nrerun_mode = "off"\n')
    runs = tmp_path / "papermill_runs"
    paper = _synthetic_run(runs / "reproduce", "fixture_centroid", [_claim("C900-1", "reproduced", _robust())])
    before = {p.name: p.read_bytes() for p in paper.iterdir()}
    monkeypatch.setattr(rep, "list_notebooks", lambda: [nb])
    monkeypatch.setattr(rep, "REPORT_PATH", tmp_path / "REPRODUCTION.md")
    monkeypatch.setattr(rep, "README_PATH", tmp_path / "README.md")
    assert rep.reproduce(profile="smoke", jobs=1, runs_dir=runs) == 0
    assert {p.name: p.read_bytes() for p in paper.iterdir()} == before
    smoke = runs / "reproduce-smoke"
    assert read_run(smoke / "fixture_centroid")["profile"] == "smoke"
    assert "**Profile shown: smoke**" in (smoke / "REPRODUCTION.md").read_text()
    assert "not the paper-scale numbers" in (smoke / "REPRODUCTION.md").read_text()
    assert not (tmp_path / "REPRODUCTION.md").exists() and not (tmp_path / "README.md").exists()


def test_update_readme_needs_markers(tmp_path):
    readme = tmp_path / "README.md"
    readme.write_text("no markers\n")
    with pytest.raises(ValueError, match="markers"):
        update_readme(readme, "x")


@pytest.mark.parametrize("failure", ["write", "ctrl-c"])
def test_a_readme_update_that_fails_midway_leaves_the_readme_as_it_was(tmp_path, monkeypatch, failure):
    # the README (and REPRODUCTION.md, a run's run.json) were rewritten in place: a full disk or a Ctrl-C between
    # the truncation and the write left an empty or cut file
    from tvtrack.pipeline import outputs

    readme = tmp_path / "README.md"
    readme.write_text(f"intro\n{README_BEGIN}\nold block\n{README_END}\noutro\n")
    readme.chmod(0o640)
    before = readme.read_bytes()
    if failure == "write":
        paragraph = "new block \udc80"  # cannot be encoded: the write fails after the file was opened
        expected = UnicodeEncodeError
    else:

        def stopped(*args):
            raise KeyboardInterrupt()

        monkeypatch.setattr(outputs.os, "replace", stopped)
        paragraph, expected = "new block", KeyboardInterrupt
    with pytest.raises(expected):
        update_readme(readme, paragraph)
    assert readme.read_bytes() == before and [p.name for p in tmp_path.iterdir()] == ["README.md"]
    monkeypatch.undo()
    update_readme(readme, "new block")
    assert readme.read_text() == f"intro\n{README_BEGIN}\nnew block\n{README_END}\noutro\n"
    assert readme.stat().st_mode & 0o777 == 0o640 and [p.name for p in tmp_path.iterdir()] == ["README.md"]


@pytest.mark.parametrize(
    "damage, fragment",
    [
        ("no markers\n", "(found 0 and 0)"),
        (f"{README_END}\n{README_BEGIN}\n", "(found 1 and 1, reversed)"),
        (f"{README_BEGIN}\n{README_BEGIN}\n{README_END}\n", "(found 2 and 1)"),
        (b"\xff\xfe not text", "not UTF-8 text"),
    ],
    ids=["no-markers", "reversed", "twice", "not-utf8"],
)
def test_a_readme_the_block_cannot_go_into_stops_report_and_reproduce_before_any_work(
    tmp_path, monkeypatch, capsys, damage, fragment
):
    # the README was read only at the very end: after an hour of paper-profile runs (and REPRODUCTION.md written),
    # a README without its markers gave a ValueError traceback
    from tvtrack.pipeline import cli, report
    from tvtrack.pipeline import reproduce as rep

    readme = tmp_path / "README.md"
    readme.write_bytes(damage if isinstance(damage, bytes) else damage.encode())
    for module in (report, rep):
        monkeypatch.setattr(module, "README_PATH", readme)
        monkeypatch.setattr(module, "REPORT_PATH", tmp_path / "REPRODUCTION.md")
    assert cli.main(["report"]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"error: {readme}: ") and fragment in err and err.count("\n") == 1, err
    with pytest.raises(UsageError, match=re.escape(fragment)):
        rep.reproduce(jobs=1, runs_dir=tmp_path / "runs")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["README.md"]


def test_report_without_notebooks_says_so(tmp_path):
    text = write_report(tmp_path, tmp_path / "R.md", notebooks=[]).read_text()
    assert "No notebooks in `notebooks/` yet" in text


def test_format_measured():
    assert format_measured({"value": 1.23456, "ci_low": 1.1, "ci_high": 1.3, "n": 5}) == "1.235 [1.1, 1.3]"
    assert format_measured({"a": 2, "b": {"value": 0.5, "ci_low": None, "ci_high": None}}) == "a: 2; b: 0.5"


def test_ctrl_c_during_reproduce_keeps_earlier_runs_and_leaves_no_temporaries(tmp_path):
    import os
    import shutil
    import signal
    import subprocess
    import sys
    import time

    nb = tmp_path / "nbs" / "fixture_centroid.ipynb"
    nb.parent.mkdir()
    shutil.copy(FIXTURE_NOTEBOOK, nb)
    (nb.parent / "fixture_centroid.smoke.toml").write_text('n_trials = 20000\nn_frames = 20\nrerun_mode = "off"\n')
    runs = tmp_path / "papermill_runs"
    earlier = _synthetic_run(
        runs / "reproduce-smoke", "fixture_centroid", [_claim("C900-1", "reproduced", _robust())], profile="smoke"
    )
    before = {p.name: p.read_bytes() for p in earlier.iterdir()}
    script = (
        f"import sys; from pathlib import Path; import tvtrack.pipeline.reproduce as r\n"
        f"r.list_notebooks = lambda: [Path({str(nb)!r})]\n"
        f"from tvtrack.pipeline import cli\n"
        f"cli._cmd_reproduce = lambda a: r.reproduce(profile='smoke', jobs=1, runs_dir=Path({str(runs)!r}))\n"
        f"sys.exit(cli.main(['reproduce']))\n"
    )
    proc = subprocess.Popen(
        [sys.executable, "-c", script],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        start_new_session=True,
    )
    folder = runs / "reproduce-smoke"
    deadline = time.time() + 120
    while time.time() < deadline and not list(folder.glob(".tmp-*")):
        time.sleep(0.1)
    time.sleep(2.0)
    os.killpg(proc.pid, signal.SIGINT)
    stdout, stderr = proc.communicate(timeout=30)
    assert proc.returncode == 130, stderr
    lines = [line for line in (stdout + stderr).splitlines() if line.strip() and "\r" not in line]
    assert lines[-1].startswith("interrupted: reproduce") and "kept" in lines[-1], stdout + stderr
    assert not list(folder.glob(".tmp-*")) and not list(folder.glob(".new-*"))
    assert {p.name: p.read_bytes() for p in earlier.iterdir()} == before


# --- the report a reader understands in a minute ------------------------------------------------------


@pytest.fixture
def explored_runs(tmp_path):
    """Two runs whose claims carry the explorer's record (share, flips, runs to decide, register phrases)."""
    from record_fixtures import CLAIMS

    root = tmp_path / "reproduce"
    _synthetic_run(root, "001_explored", CLAIMS[:3] + CLAIMS[4:])
    _synthetic_run(root, "002_smoke", CLAIMS[3:4], profile="smoke")
    return root


def _sentence_cells(text: str) -> dict[str, str]:
    """``{claim id: its sentence}`` from the per-notebook tables (the last cell), unescaped."""
    cells = {}
    for m in re.finditer(r"^\| (C\d{3}-\w+) \| .* \| ([^|]*(?:\\\|[^|]*)*) \|$", text, re.M):
        cells[m.group(1)] = m.group(2).replace("\\", "")
    return cells


def test_each_claim_in_one_plain_sentence_with_units_and_no_register_keys(explored_runs, tmp_path):
    from record_fixtures import CLAIMS, REGISTER_KEYS

    text = write_report(explored_runs, tmp_path / "R.md", notebooks=["001_explored", "002_smoke"]).read_text()
    cells = _sentence_cells(text)
    assert set(cells) == {c["id"] for c in CLAIMS}
    assert all("…" not in s and s.endswith(".") for s in cells.values()), cells
    for key in REGISTER_KEYS:  # phrases only: no register key, plain or escaped, anywhere in the report
        assert key not in text and key.replace("_", "\\_") not in text, key
    # the reading that flips C001-3 is named before the world it does not extend to (which is behind the click)
    assert cells["C001-3"] == (
        "Not reproduced: per-test false-alarm rate / alpha is 351.6 [350, 353.1] x alpha, against [0, 2] "
        "x alpha (set here to check the paper's \"rho <= 0.5\"). Under another reading of the paper's text it is reproduced: sigma read as the SD of the raw "
        "velocity increments."
    )
    assert (
        "flipped by: sigma read as the SD of the raw velocity increments (a reading of the paper's text); a target"
        in text
    )
    assert "About 7 independent replicates are projected to decide it." in cells["C004-3b"]
    # every measured value carries its unit or says what it is a ratio of
    for c in CLAIMS:
        if c["verdict"] == "not checkable":
            continue
        rules = c["rule"].get("parts", {"claim": c["rule"]}).values()
        shown = [r["unit"] for r in rules if r["unit"] in cells[c["id"]]]
        named = [r["quantity"] for r in rules if r["unit"].startswith("ratio of") and r["quantity"] in cells[c["id"]]]
        assert shown or named, (c["id"], cells[c["id"]])  # a unit, or a dimensionless ratio said by its quantity
    # deterministic numbers show no interval; the 9-point vector is summarised by its ends and trend
    assert not re.search(r"\[([-\d.e+]+), \1\]", text.replace("\\", ""))
    assert "falls from 216300 px to 0.178 px over 9 points" in text and "7839" not in text


def test_a_smoke_design_is_never_shown_as_robust(explored_runs, tmp_path):
    text = write_report(explored_runs, tmp_path / "R.md", notebooks=["002_smoke"]).read_text()
    row = next(line for line in text.splitlines() if line.startswith("| C001-5 |"))
    assert "| provisional |" in row and "robust" not in row and "too few configurations to label" in row
    assert "**Profile shown: smoke**" in text and "its labels are provisional" in text
    assert (
        "of the checkable verdicts comes from a design too small to label (a smoke-size run): none of them is called robust"
        in text
    )


def test_the_report_opens_with_the_paragraph_the_glossary_and_the_papers(explored_runs, tmp_path):
    text = write_report(explored_runs, tmp_path / "R.md", notebooks=["001_explored", "002_smoke"]).read_text()
    head = "\n".join(text.splitlines()[:18])
    assert "\nOf 5 claims checked, 2 hold, 0 hold in part and 1 does not; the runs could not decide 1" in head
    assert (
        (
            "\n\nWhat the verdicts turn on: a reading of the paper's text (alone or with other readings) flips 1 claim; "
            "a world beyond the paper (alone or with other worlds) flips 1 claim.\n\n"
        )
        in head
    )  # a paragraph of its own, after the counts  # a flip counts where it changes the whole claim's verdict, not only a part's; C001-7's named flip
    # moves only a part, but its record has a condition (sigma read from the raw increments) whose whole verdict
    # differs, so it is never said to stay under every change explored
    assert "Labels (how sure, and why): **robust**: no explored reading" in head and "**provisional**:" in head
    assert "\n\nWhat counts as a flip: a change (another reading, setting or world) flips a verdict only when" in head
    assert "it decides the other way; an interval across a band edge, or fewer runs, leaves it undecided. " in head
    # the register, which the claims' sentences name, is defined on the first screen
    assert "The changes tried are each notebook's register: its list of what the paper left open" in head
    assert "| 001\\_explored | 4 | 1 | 0 | 1 | 1 | 1 | 1 limited, 1 unexplored, 1 depends |" in head
    assert (
        "- **001 C001-3** (not reproduced, depends: a reading; a world too)" in text
        and "- **001 C004-3b** (undecided, unexplored)" in text
    )


def test_each_paper_opens_with_what_it_claims_what_holds_what_does_not_and_why_then_its_limitations(
    explored_runs, tmp_path
):
    text = write_report(explored_runs, tmp_path / "R.md", notebooks=["001_explored"]).read_text()
    section = text[text.index("## 001_explored") :]
    paragraph = section.split("\n\n")[2]
    assert paragraph == (
        "The paper makes 4 claims checked here; 3 can be measured. 1 claim holds (C001-7). It does not hold that neighbouring velocity samples correlate by \\<= 0.5, negligibly; the pair distributions may be "
        "multiplied (C001-3): per-test false-alarm rate / alpha is 351.6 \\[350, 353.1\\] x alpha, against "
        "\\[0, 2\\] x alpha (set here to check the paper's \"rho \\<= 0.5\"); it holds under a reading of the paper's text: sigma read as the SD of the raw velocity "
        "increments. The runs could not decide C004-3b."
    )
    limits = section.split("\n\n")[3]
    assert limits.startswith("**Limitations.** C001-6 is not checkable: the recording of the real aircraft is not ")
    assert "More runs than these would be needed to decide C004-3b." in limits
    smoke = write_report(explored_runs, tmp_path / "S.md", notebooks=["002_smoke"]).read_text()
    assert "These are smoke-size runs: no verdict is labelled, and none is called robust." in smoke


def test_a_smoke_run_is_never_robust_even_where_its_record_says_robust(tmp_path):
    """A smoke design small enough that every combination fits is not flagged provisional by the explorer; at the
    smoke profile it is still never called robust: not in the paragraph, the counts, the table or the sentence."""
    import copy

    from record_fixtures import SMOKE

    claim = copy.deepcopy(SMOKE)
    claim["robustness"]["provisional"] = False  # what the smoke site showed as "labels: 6 robust"
    root = tmp_path / "reproduce-smoke"
    _synthetic_run(root, "003_smoke", [claim], profile="smoke")
    readme = tmp_path / "README.md"
    readme.write_text(f"{README_BEGIN}\n{README_END}\n")
    text = write_report(root, tmp_path / "R.md", notebooks=["003_smoke"], readme=readme).read_text()
    assert "1 robust" not in text and "| robust |" not in text and "(1 robust)" not in text
    assert "1 of the checkable verdicts comes from a design too small to label" in text
    assert "| 003\\_smoke | 1 | 1 | 0 | 0 | 0 | 0 | 1 provisional |" in text
    assert "| C001-5 | " in text and "| provisional | Reproduced (too few configurations to label): " in text


def test_the_first_screen_names_the_claims_that_hold_hold_in_part_or_give_nothing_to_measure():
    import copy

    from record_fixtures import DEPENDS, NOT_CHECKABLE, SMOKE
    from tvtrack.pipeline.report import holding_lines

    part = copy.deepcopy(DEPENDS) | {"id": "C001-4", "verdict": "partly"}
    held = copy.deepcopy(DEPENDS) | {"id": "C001-7", "verdict": "reproduced"}
    runs = {
        "001_maneuver": (None, {"claims": [DEPENDS, part, held, NOT_CHECKABLE]}),
        "003_marker": (None, {"claims": [SMOKE | {"id": "C003-1"}]}),
        "004_laser": (None, None),
    }
    assert holding_lines(runs) == [
        "- **Hold** (label in brackets, the kind of change that flips it, and the claim's caveat where it has one): 001: "
        "C001-7 (depends: a reading; a world too); 003: C003-1 (provisional).",
        "- **Hold in part** (label in brackets, the kind of change that flips it, and which parts hold): 001: C001-4 "
        "(depends: a reading; a world too).",
        "- **Not checkable**: 001: C001-6.",  # a reader asks which claims give nothing to measure, too
    ]
    assert holding_lines({"001_maneuver": (None, {"claims": [DEPENDS]})}) == []  # nothing holds: no line


def test_the_forest_plot_opens_a_rule_chosen_by_a_reading():
    """A claim judged by a rule that a reading chooses is drawn with the chosen rule's band and parts (once left
    out, the forest plot missing every claim of that kind)."""
    from tvtrack.pipeline.figures import forest_items

    part = {"kind": "in_band", "text": "in [0, 2]", "low": 0.0, "high": 2.0}
    other = {"kind": "in_band", "text": "in [10, 20]", "low": 10.0, "high": 20.0}
    rule = {
        "kind": "by_reading",
        "entry": "criterion",
        "default": {"kind": "all_of", "parts": {"x": part, "y": part}},
        "rules": {"other": other},
    }
    est = {"value": 1.5, "ci_low": 1.2, "ci_high": 1.8, "n": 50}
    tagged = {**minimal_claim("C9-1"), "rule": rule, "measured": {"reading": "usual", "measured": {"x": est, "y": est}}}
    chosen = {**minimal_claim("C9-2"), "rule": rule, "measured": {"reading": "other", "measured": {**est, "value": 15}}}
    items = forest_items({"009_x": (None, {"claims": [tagged, chosen]})})
    assert [i["name"] for i in items] == ["009 C9-1 x", "009 C9-1 y", "009 C9-2"]
    assert items[0]["band"] == (0.0, 2.0) and items[0]["value"] == pytest.approx(0.75)
    assert items[2]["band"] == (10.0, 20.0) and items[2]["value"] == pytest.approx(0.5)


def test_a_paper_profile_with_one_provisional_claim_keeps_every_labels_count():
    """At the paper profile a claim explored over too few configurations is provisional; the summary counts it
    beside the other labels (once, its presence replaced the whole sentence of how sure the verdicts are)."""
    from tvtrack.paragraphs import results_summary

    def claim(cid, label, provisional=False):
        return {**minimal_claim(cid), "robustness": {"label": label, "provisional": provisional, "parts": {}}}

    text = results_summary([claim("C1-1", "robust"), claim("C1-2", "unexplored", True), claim("C1-3", "depends")])
    assert "Of the 3 checkable verdicts, 1 survives every reading of the paper, 1 turns on a reading" in text
    assert "1 comes from a design too small to label (provisional: never called robust)" in text
