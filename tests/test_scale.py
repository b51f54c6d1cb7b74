"""``reproduce --scheduler ADDRESS --max-replicates N``: the explorations on a Dask cluster give what they give on
this machine, the run records say where they ran and how many runs they used, bad inputs are one line, and the
``decide`` profile's caps are what the runs would need."""

import json
import shutil
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

from tvtrack.pipeline import reproduce as rep
from tvtrack.pipeline.paths import PROFILE_DIR
from tvtrack.pipeline.runner import find_notebook, read_run
from tvtrack.pipeline.scale import decide_plan, explorer_runs

NB = "003_rotating_marker_tracker"  # its smoke profile: one register entry, three replicates, about 10 s
# The cluster test's profile: 003's smoke profile with shorter runs (Fig. 1 and Fig. 2 runs of 0.4 s and 0.3 s,
# interference runs of 0.2 s, a 0.1 s transient): with the cap below, each of the two reproduces it compares ran in
# about 22 s against 52-76 s at the smoke lengths and a cap of 5, and both explorations are still sized to the cap.
SHORT = {"transient_s": 0.1, "fig1_duration_s": 0.4, "fig2_duration_s": 0.3, "loss_duration_s": 0.2}
PROFILE = "cluster"
VOLATILE = {"timing", "runtime_s", "cpu_s", "started_utc", "finished_utc", "versions", "git_commit", "parameters"}


def _stable(value):
    """``results.json`` without what a run may not repeat: clocks, versions and the parameters as injected."""
    if isinstance(value, dict):
        return {k: _stable(v) for k, v in value.items() if k not in VOLATILE and not k.endswith(("_wall_s", "_time_s"))}
    if isinstance(value, list):
        return [_stable(v) for v in value]
    return value


def _reproduce(tmp_path, monkeypatch, name, **kw):
    nb = tmp_path / "nbs" / f"{NB}.ipynb"
    if not nb.exists():
        assert not (PROFILE_DIR / f"{NB}.{PROFILE}.toml").exists()  # load_profile would read that one first
        nb.parent.mkdir()
        shutil.copy(find_notebook(NB), nb)
        values = {**_profile(f"{NB}.smoke.toml"), **SHORT}  # found beside the notebook (no such profile in PROFILE_DIR)
        (nb.parent / f"{NB}.{PROFILE}.toml").write_text("".join(f"{k} = {json.dumps(v)}\n" for k, v in values.items()))
    monkeypatch.setattr(rep, "list_notebooks", lambda: [nb])
    monkeypatch.setattr(rep, "usable_cores", lambda: 1)  # n_workers = 1 in the local run: one replicate at a time
    runs = tmp_path / name
    assert rep.reproduce(profile=PROFILE, jobs=1, runs_dir=runs, **kw) == 0
    return runs / f"reproduce-{PROFILE}" / NB


# The decide profile's raised cap at reduced size: the smoke profile's cap of 3 raised to 4. With the shorter runs
# both explorations (tracking and interference: all eleven claims) are sized to it, 21 explorer runs in each of the
# two reproduces compared (32 at 5: the same explorations sized, each to 5).
CAP = 4


def _sized_by_the_rule(data: dict) -> list[int]:
    """Each exploration's replicates, after checking the stopping rule: between 3 and the cap, and below the cap
    only where every part left undecided is projected to need more replicates than the cap."""
    sizes = []
    for c in data["claims"]:
        rob = c.get("robustness") or {}
        if not rob.get("design"):
            continue
        n = rob["design"]["replicates"]
        assert 3 <= n <= CAP and rob["design"]["max_replicates"] == CAP, (c["id"], n)
        for p in (rob.get("parts") or {}).values():
            r = p.get("runs_to_decide") or {}
            if p.get("verdict") == "undecided" and r.get("replicates"):
                assert r["replicates"] > CAP or n == CAP, (c["id"], r)
        sizes.append(n)
    return sizes


@pytest.mark.determinism
def test_a_reproduce_on_a_local_cluster_gives_the_local_results(tmp_path, monkeypatch):
    """003's smoke profile with shorter runs (``SHORT``) and the decide profile's raised cap at reduced size (4), on
    this machine and on a LocalCluster of two worker processes: the same claims, verdicts, labels and numbers; the
    records say where each ran and how many explorer runs it used."""
    distributed = pytest.importorskip("distributed")
    local = _reproduce(tmp_path, monkeypatch, "local", max_replicates=CAP)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cl:
        remote = _reproduce(tmp_path, monkeypatch, "dask", max_replicates=CAP, scheduler=cl.scheduler_address)
    mine, theirs = (json.loads((d / "results.json").read_text()) for d in (local, remote))
    assert _stable(theirs) == _stable(mine)
    assert theirs["parameters"]["max_replicates"] == CAP and theirs["parameters"]["scheduler"] == cl.scheduler_address
    assert mine["parameters"]["scheduler"] == ""
    sizes = _sized_by_the_rule(mine)
    assert max(sizes) > 3  # the raised cap sized at least one exploration beyond the smoke profile's three
    here, there = read_run(local), read_run(remote)
    assert here["ran_on"] == {"where": "this machine", "workers": 1}
    assert there["ran_on"] == {"where": "dask", "scheduler": cl.scheduler_address, "workers": 2, "threads": 2}
    assert there["explorer_runs"] == here["explorer_runs"] == explorer_runs(local / "results.json")
    timing = [c["robustness"]["design"]["timing"] for c in mine["claims"] if c.get("robustness")]
    assert here["explorer_runs"] == sum(
        r["configurations"] for t in {json.dumps(t, sort_keys=True): t for t in timing}.values() for r in t.values()
    )
    assert here["explorer_runs"] >= 2 * max(sizes)  # two explorations (tracking and interference), sized


def _tvtrack(*args, timeout=60):
    return subprocess.run(
        [sys.executable, "-m", "tvtrack", *map(str, args)], capture_output=True, text=True, timeout=timeout
    )


def _one_line(proc, *fragments):
    assert proc.returncode == 2, (proc.returncode, proc.stderr)
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: ") and "Traceback" not in proc.stderr, proc.stderr
    for f in fragments:
        assert f in lines[0], (f, lines[0])


def test_bad_scheduler_or_cap_is_one_line_before_any_work(tmp_path):
    import socket

    with socket.socket() as s:  # a port where nothing listens
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    before = sorted(Path("papermill_runs").glob("reproduce*"))
    _one_line(_tvtrack("reproduce", "--scheduler", f"127.0.0.1:{port}"), "--scheduler", f"127.0.0.1:{port}")
    _one_line(_tvtrack("reproduce", "--scheduler", "localhost"), "--scheduler", "no port")
    # an empty address ran everything on this machine, as if no --scheduler had been given
    _one_line(_tvtrack("reproduce", "--scheduler", "", "--only", NB, "--profile", "smoke"), "--scheduler", "''")
    _one_line(_tvtrack("reproduce", "--max-replicates", "2"), "--max-replicates", ">= 3")
    _one_line(_tvtrack("reproduce", "--max-replicates", "many"), "--max-replicates", "'many'")
    _one_line(_tvtrack("reproduce", "--only", NB, "--max-replicates", "5000"), "--max-replicates 5000", NB, "1000")
    assert sorted(Path("papermill_runs").glob("reproduce*")) == before


def _profile(name):
    with (PROFILE_DIR / name).open("rb") as fh:
        return tomllib.load(fh)


def _validated_notebook(path: Path, validation: str) -> Path:
    import nbformat

    nb = nbformat.v4.new_notebook()
    params = nbformat.v4.new_code_cell("x = 1\noutput_dir = 'out'")
    params.metadata["tags"] = ["parameters"]
    nb.cells = [params, nbformat.v4.new_code_cell(validation)]
    nbformat.write(nb, path)
    return path


def test_the_preflight_checks_several_notebooks_in_one_process_and_names_a_broken_one(tmp_path):
    """Each override set gets its own answer, in order, per notebook; a validation cell that fails otherwise than with
    ValueError is a bug of that notebook, named."""
    from tvtrack.pipeline.preflight import NotebookBug, check_values_each

    check = "if x < 0:\n    raise ValueError(f'parameter x = {x}; it must be >= 0')"
    first = _validated_notebook(tmp_path / "first.ipynb", check)
    second = _validated_notebook(tmp_path / "second.ipynb", check.replace("x < 0", "x > 5").replace(">= 0", "<= 5"))
    broken = _validated_notebook(tmp_path / "broken.ipynb", "1 / 0")
    answers = check_values_each([(first, [{"x": 1}, {"x": -1}]), (second, [{"x": 6}])])
    assert answers == [[None, "parameter x = -1; it must be >= 0"], ["parameter x = 6; it must be <= 5"]]
    with pytest.raises(NotebookBug, match=r"validation cell of broken failed: ZeroDivisionError"):
        check_values_each([(first, [{"x": 1}]), (broken, [{}]), (second, [{"x": 1}])])


def test_the_decide_profile_caps_every_undecided_claims_projection():
    """Each notebook has a decide profile; where a claim or part is undecided its cap covers the replicates the docs'
    table projects for it (a row beyond every cap the notebook accepts says so), and the notebook's own validation
    accepts the profile."""
    from tvtrack.pipeline.preflight import check_values_each

    notebooks = sorted(Path("notebooks").glob("*.ipynb"))
    # every notebook's validation in one process (the preflight's own, as `reproduce --max-replicates` runs it)
    answers = check_values_each([(nb, [_profile(f"{nb.stem}.decide.toml")]) for nb in notebooks])
    assert answers == [[None]] * len(notebooks)
    table = (Path(__file__).parents[1] / "docs" / "scale.md").read_text()
    for nb in notebooks:
        values = _profile(f"{nb.stem}.decide.toml")
        for line in table.splitlines():
            cells = [c.strip() for c in line.strip("|").split("|")]
            if len(cells) > 3 and cells[0] == nb.stem[:3] and cells[2].isdigit():
                if "beyond the cap" in line:  # said so only where no cap the notebook accepts reaches it
                    assert int(cells[2]) > 1000 and "integer in [3, 1000]" in nb.read_text(), (nb.stem, cells)
                else:
                    assert values["max_replicates"] >= int(cells[2]), (nb.stem, cells)


def test_decide_plan_reads_the_projection_and_cost_of_each_undecided_part(tmp_path):
    design = {"timing": {"replicates": {"configurations": 3, "wall_s": 9.0, "cpu_s": 24.0}}, "replicates": 10}
    parts = {
        "a": {"verdict": "undecided", "runs_to_decide": {"replicates": 320, "now": 10, "runs": 25528}},
        "b": {"verdict": "reproduced", "runs_to_decide": None},
    }
    claim = {"id": "C900-6", "robustness": {"design": design, "parts": parts}}
    (tmp_path / "900_x").mkdir()
    (tmp_path / "900_x" / "results.json").write_text(json.dumps({"claims": [claim]}))
    (row,) = decide_plan(tmp_path)
    assert (row["claim"], row["part"], row["now"], row["replicates"], row["runs"]) == ("C900-6", "a", 10, 320, 25528)
    assert row["cpu_s_per_replicate"] == 8.0
    assert row["core_hours"] == pytest.approx(310 * 8.0 / 3600)


def _measure_batch(configs, seeds, claims=None):
    """A batched measurement: the mean of draws from each seed, shifted where ``a`` is 2 (one undecided claim at
    the default, sized by the explorer, and one that flips)."""
    from tvtrack.montecarlo import mean_ci
    import numpy as np

    out = []
    for cfg, seed in zip(configs, seeds):
        x = np.random.default_rng(seed).normal(0.45 + (cfg["a"] == 2), 1.0, 300)
        out.append({"X": mean_ci(x)})
    return out


class _OneAtATime:
    """An executor without a worker count (as a Dask client): each task runs at ``submit``; the calls are kept."""

    def __init__(self):
        self.calls = []

    def submit(self, fn, *args, **kw):
        from concurrent.futures import Future

        self.calls.append(args)
        f = Future()
        f.set_result(fn(*args, **kw))
        return f


def test_a_batched_measurement_on_an_executor_gives_the_in_process_exploration():
    """Before, ``batched=True`` ignored the executor: every configuration ran in the notebook's process."""
    from tvtrack.explore import explore
    from tvtrack.register import Entry, Register
    from tvtrack.verdicts import InBand

    reg = Register([Entry("a", "regime", 0, (0, 1, 2), "test regime a")])
    kw = dict(seed=13, replicates=3, max_replicates=20, joint=2, batched=True)
    here = explore(_measure_batch, reg, {"X": InBand("mean", -0.5, 0.5)}, **kw)
    pool = _OneAtATime()
    there = explore(_measure_batch, reg, {"X": InBand("mean", -0.5, 0.5)}, executor=pool, **kw)
    every = len(there.runs) + sum(len(r.sized) for r in there.runs)  # the conditions' sizing replicates too
    assert len(pool.calls) == every > 3 and all(len(cfgs) == 1 for cfgs, _ in pool.calls)
    assert [(r.config, r.seed, r.stage) for r in there.runs] == [(r.config, r.seed, r.stage) for r in here.runs]
    assert [r.outputs["X"] for r in there.runs] == [r.outputs["X"] for r in here.runs]
    assert there.settings["replicates"] == here.settings["replicates"] > 3  # sized past the minimum
    assert there.record("X")["parts"] == here.record("X")["parts"]


def test_a_notebooks_scheduler_parameter_is_an_address_with_a_port_or_empty(tmp_path):
    from tvtrack.parameters import SchedulerAddress, validate_parameters

    rules = {"scheduler": SchedulerAddress()}
    base = {"seed": 1, "n_trials": 1, "output_dir": str(tmp_path), "rerun_mode": "off"}
    for ok in ("", " tcp://10.0.0.5:8786 ", "node7:8786"):
        assert validate_parameters({**base, "scheduler": ok}, rules)["scheduler"] == ok.strip()
    for bad in ("localhost", "tcp://host:99999", "http://host:8786", 8786):
        with pytest.raises(ValueError, match="'scheduler'.*tcp://HOST:PORT"):
            validate_parameters({**base, "scheduler": bad}, rules)


def test_each_notebook_gets_a_worker_per_usable_core_and_its_share_of_the_blas_threads(tmp_path, monkeypatch):
    """Side by side, each kernel keeps its share of the BLAS threads (cores // jobs), but a notebook with an
    ``n_workers`` parameter gets a worker per usable core: the one left running when the others end uses them all."""
    seen = {}

    def fake_run(notebooks, profile, folder, jobs, threads, setups):
        seen.update(
            jobs=jobs, threads=threads, workers={nb.stem: p.get("n_workers") for nb, (p, _) in zip(notebooks, setups)}
        )
        return []

    monkeypatch.setattr(rep, "usable_cores", lambda: 4)
    monkeypatch.setattr(rep, "_run_notebooks", fake_run)
    monkeypatch.setattr(rep, "write_report", lambda *a, **k: tmp_path / "REPRODUCTION.md")
    names = ["000_dissector_ekf", "004_laser_spot_prediction"]
    assert rep.reproduce(profile="smoke", jobs=2, runs_dir=tmp_path, only=names) == 0
    # 000 has no n_workers parameter (its filters run in the kernel)
    assert seen == {"jobs": 2, "threads": 2, "workers": {"004_laser_spot_prediction": 4, "000_dissector_ekf": None}}
