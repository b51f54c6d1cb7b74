"""Sweeps do what their file says: a seed list is a seed per run, two runs never share a
directory, every shipped sweep writes its summary, and a summary metric that no run writes, an unknown key
in a spec or a profile, is refused with one line before any run starts."""

import json
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import one_line_error as conftest_one_line_error, FIXTURE_NOTEBOOK
from tvtrack.pipeline.paths import SWEEP_DIR
from tvtrack.pipeline.preflight import UsageError
from tvtrack.pipeline.summary import check_metric_in, collect_summary, flatten_metrics
from tvtrack.pipeline.sweep import expand, load_spec

SHIPPED = sorted(SWEEP_DIR.glob("*.toml"))


def tvtrack(*args, timeout=60):
    return subprocess.run(
        [sys.executable, "-m", "tvtrack", *map(str, args)], capture_output=True, text=True, timeout=timeout
    )


def one_line_error(proc, *fragments, code=2):
    return conftest_one_line_error(proc, *fragments, status=(code,))


def spec(tmp_path, body, name="spec.toml"):
    path = tmp_path / name
    path.write_text(f'notebook = "{FIXTURE_NOTEBOOK}"\n{body}')
    return path


def nested(path: str, value: float) -> dict:
    """``{"a": {"b": {"value": v, "ci_low": ..., "ci_high": ...}}}`` for ``"a.b.value"``: a results tree with a
    number at the dotted path (and, for an Estimate, its interval)."""
    parts = path.split(".")
    leaf = {parts[-1]: value}
    if parts[-1] == "value":
        leaf.update(ci_low=value - 0.1, ci_high=value + 0.1, n=7, method="fake")
    tree = leaf
    for part in reversed(parts[:-1]):
        tree = {part: tree}
    return tree


def test_the_shipped_sweeps_are_found():
    assert len(SHIPPED) >= 10 and any(p.name == "004_horizon.toml" for p in SHIPPED)


@pytest.mark.parametrize("path", SHIPPED, ids=[p.stem for p in SHIPPED])
def test_every_shipped_sweep_expands_to_distinct_runs_and_writes_its_summary(tmp_path, path):
    """Each run its own directory; on fake results shaped like the notebook's (the metric at its dotted
    path), the summary step writes summary.csv with the metric's column and summary.png."""
    s = load_spec(path)
    runs = expand(s)
    ids = [r.run_id for r in runs]
    assert len(set(ids)) == len(ids) == len({json.dumps(r.parameters, sort_keys=True) for r in runs})
    x, y = s.summary["x"], s.summary["y"]
    for i, run in enumerate(runs):
        folder = tmp_path / "runs" / run.run_id
        folder.mkdir(parents=True)
        (folder / "run.json").write_text(json.dumps({"status": "ok", "runtime_s": 1.0}))
        metrics = {**nested(y, 10.0 + i), "a_list": [1, 2], "a_label": "text"}
        (folder / "results.json").write_text(json.dumps({"metrics": metrics, "claims": []}))
    csv_path, plot = collect_summary(tmp_path, runs, s.summary)
    assert plot is not None and plot.stat().st_size > 1000
    import csv

    rows = list(csv.DictReader(csv_path.open()))
    assert [float(r[y]) for r in rows] == [10.0 + i for i in range(len(runs))]
    assert [r[x] for r in rows] == [str(run.parameters[x]) for run in runs]


def test_a_seed_list_in_grid_gives_each_seed_its_own_run():
    runs = expand(load_spec(SWEEP_DIR / "004_horizon.toml"))
    assert [r.parameters["seed"] for r in runs] == [1, 2, 3]
    assert len({r.run_id for r in runs}) == 3


def test_a_seed_list_in_zip_and_the_fixed_seed_as_base_of_repeats(tmp_path):
    zipped = expand(load_spec(spec(tmp_path, "[zip]\nseed = [5, 9]\nspot_sigma_px = [1.0, 2.0]\n", "z.toml")))
    assert [(r.parameters["seed"], r.parameters["spot_sigma_px"]) for r in zipped] == [(5, 1.0), (9, 2.0)]
    repeated = expand(load_spec(spec(tmp_path, "repeats = 3\n[fixed]\nseed = 40\n", "r.toml")))
    assert [r.parameters["seed"] for r in repeated] == [40, 41, 42]


def test_a_seed_list_with_repeats_is_refused_saying_how_to_vary_seeds(tmp_path):
    both = spec(tmp_path, "repeats = 2\n[grid]\nseed = [1, 2, 3]\n", "both.toml")
    line = one_line_error(tvtrack("sweep", both, "-o", tmp_path / "s"), "both.toml", "repeats = 2", "seed = [...]")
    assert "repeats = 1" in line
    assert not (tmp_path / "s").exists()


def test_a_value_listed_twice_is_refused_two_runs_never_share_a_directory(tmp_path):
    twice = spec(tmp_path, "[grid]\nspot_sigma_px = [1.0, 2.0, 1.0]\n", "twice.toml")
    with pytest.raises(UsageError, match="same parameters"):
        expand(load_spec(twice))


def test_a_summary_metric_the_notebook_does_not_write_is_refused_before_any_run(tmp_path):
    wrong = spec(tmp_path, '[grid]\nspot_sigma_px = [1.0]\n[summary]\nx = "spot_sigma_px"\ny = "centroid_rms.value"\n')
    line = one_line_error(tvtrack("sweep", wrong, "-o", tmp_path / "s"), "'centroid_rms.value'", "[summary] y")
    assert "'centroid_rms_px'" in line and "invalid_fraction" in line  # the metrics there are
    assert not (tmp_path / "s").exists()


def test_a_nested_path_the_finished_runs_do_not_hold_is_named_with_the_paths_they_do(tmp_path):
    results = tmp_path / "results.json"
    results.write_text(json.dumps({"metrics": nested("detection.median_s.value", 1.0)}))
    check_metric_in(results, "detection.median_s.value")
    check_metric_in(results, "detection.median_s.ci_high")
    with pytest.raises(UsageError) as info:
        check_metric_in(results, "detection.median.value")
    assert "'detection.median.value'" in str(info.value) and "'detection.median_s.value'" in str(info.value)


def test_nested_metrics_flatten_by_their_dotted_path():
    flat = flatten_metrics({"a": 1, "b": {"c": {"value": 2.5, "ci_low": 2.0, "method": "x"}, "d": [1]}, "e": None})
    assert flat == {"a": 1, "b.c.value": 2.5, "b.c.ci_low": 2.0, "e": None}


def test_unknown_keys_of_a_spec_and_its_summary_are_refused_with_a_suggestion(tmp_path):
    one_line_error(tvtrack("sweep", spec(tmp_path, "gird = 1\n", "g.toml")), "g.toml", "'gird'", "'grid'")
    typo = spec(
        tmp_path,
        '[grid]\nspot_sigma_px = [1.0]\n[summary]\nx = "spot_sigma_px"\ny = "centroid_rms_px.value"\nylable = "a"\n',
        "s.toml",
    )
    one_line_error(tvtrack("sweep", typo), "s.toml", "[summary]", "'ylable'", "'ylabel'")


def test_an_unknown_key_in_a_profile_is_refused_with_a_suggestion(tmp_path):
    nb = tmp_path / "fixture_centroid.ipynb"
    shutil.copy(FIXTURE_NOTEBOOK, nb)
    (tmp_path / "fixture_centroid.tiny.toml").write_text("n_trails = 3\nn_frames = 2\n")
    line = one_line_error(
        tvtrack("run", nb, "--profile", "tiny", "-o", tmp_path / "r"), "fixture_centroid.tiny.toml", "'n_trails'"
    )
    assert "did you mean 'n_trials'" in line
    assert not (tmp_path / "r").exists()
    one_line_error(tvtrack("edit", nb, "--profile", "tiny"), "'n_trails'", "'n_trials'")


def test_every_shipped_profile_names_only_parameters_of_its_notebook():
    from tvtrack.pipeline.paths import PROFILE_DIR
    from tvtrack.pipeline.runner import find_notebook, load_profile

    profiles = sorted(PROFILE_DIR.glob("*.toml"))
    assert profiles
    for path in profiles:
        stem, profile = path.name.split(".")[:2]
        # raises on an unknown key; a profile may be empty (a decide profile that needs no cap raised)
        assert isinstance(load_profile(find_notebook(stem), profile), dict)


def test_ids_of_a_spec_are_stable_and_distinct_across_the_fixture(tmp_path):
    body = "repeats = 2\n[grid]\nspot_sigma_px = [1.0, 2.0]\n[zip]\nn_frames = [3, 4]\nread_noise_e = [1.0, 2.0]\n"
    runs = expand(load_spec(spec(tmp_path, body)))
    assert len(runs) == 8 and len({r.run_id for r in runs}) == 8
    assert Path(FIXTURE_NOTEBOOK).is_file()


def test_metric_names_written_through_an_f_string_match_any_value_of_their_fields(tmp_path):
    from tvtrack.pipeline.summary import check_metric, notebook_metric_names

    nb = tmp_path / "m.ipynb"
    cells = [
        {"cell_type": "code", "metadata": {"tags": ["parameters"]}, "source": "seed = 1\n", "outputs": []},
        {"cell_type": "code", "metadata": {}, "source": 'results.metric(f"gain/d{d:g}/ratio", r)\n', "outputs": []},
        {"cell_type": "code", "metadata": {}, "source": "results.metric('rms_px', e)\n", "outputs": []},
    ]
    nb.write_text(json.dumps({"cells": cells, "metadata": {}, "nbformat": 4, "nbformat_minor": 5}))
    assert notebook_metric_names(nb) == ["gain/d{...}/ratio", "rms_px"]
    for good in ("gain/d0.5/ratio", "gain/d2/ratio.value", "rms_px", "rms_px.ci_high"):
        check_metric(nb, good)
    for bad in ("gain/ratio", "rms", "rms_px_total"):
        with pytest.raises(UsageError, match="its metrics: gain/d{...}/ratio, rms_px"):
            check_metric(nb, bad)
    # a name computed at run time cannot be read from the source: nothing is refused
    cells.append({"cell_type": "code", "metadata": {}, "source": "results.metric(name, v)\n", "outputs": []})
    nb.write_text(json.dumps({"cells": cells, "metadata": {}, "nbformat": 4, "nbformat_minor": 5}))
    assert notebook_metric_names(nb) is None
    check_metric(nb, "anything.at.all")
