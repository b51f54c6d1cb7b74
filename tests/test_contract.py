"""The paper contract (:mod:`tvtrack.contract`): every package in ``lib/tvtrack/papers`` declares one
:class:`tvtrack.paper.Paper`, every paper runs at smoke size, and the checks see a package or a paper that does not
conform."""

from __future__ import annotations

import dataclasses
import importlib
import json
import subprocess
import sys
import types

import numpy as np
import pytest

from tvtrack import contract
from tvtrack.montecarlo import mean_ci
from tvtrack.paper import Measurement, Paper, Parameter
from tvtrack.parameters import Integer, Real
from tvtrack.register import Entry, Register
from tvtrack.verdicts import InBand

PACKAGES = contract.paper_packages()


def test_the_papers_folder_holds_the_five_papers():
    assert PACKAGES[:5] == [
        "p000_dissector_ekf",
        "p001_maneuver_occlusion_kf",
        "p002_unified_location_em",
        "p003_rotating_marker_tracker",
        "p004_laser_spot_prediction",
    ]


@pytest.mark.parametrize("name", PACKAGES)
def test_every_paper_package_conforms(name):
    package = importlib.import_module(f"tvtrack.papers.{name}")
    assert contract.check(package) == []
    # every name of the contract is read from the one declared Paper, and the citation is in the docstring too
    assert isinstance(package.PAPER, Paper) and package.PAPER.name == name[1:]
    for export, (_, attribute) in contract.EXPORTS.items():
        assert getattr(package, export) is getattr(package.PAPER, attribute), export
    assert set(package.RULES) <= set(package.CLAIMS)
    assert " ".join(package.CITATION.split()) in " ".join(package.__doc__.split())


#: Parameters replacing each paper's smoke profile in the run below: the smallest sizes its rules allow (or its
#: claims need), so that the run costs seconds.
SMALLEST = {
    "p000_dissector_ekf": dict(
        n_trials=30, duration_T=6.0, steady_window_T=2.0, acquire_by_T=3.0, substeps=2, dt_factor=2, dt_trials=20,
        dt_check_T=3.0, grid_trials=10, grid_points=51,
    ),
    "p001_maneuver_occlusion_kf": dict(
        n_trials=30, n_fa_runs=300, fa_duration_s=8.0, n_tradeoff_trials=10, n_train=5, kb3_grid=[20, 50, 100],
        n_fig4_trials=10, loss_grid_s=[6.0, 12.0], fixed2_grid=[2, 10], fixed3_grid=[3, 20], imm_q_ca_grid=[1e-3],
        vdf_q_ca_grid=[1e-5],
    ),
    "p002_unified_location_em": dict(crb_phases=1, em_iteration_cap=20),
    "p003_rotating_marker_tracker": dict(transient_s=0.2, fig1_duration_s=0.6, fig2_duration_s=0.8, loss_duration_s=0.4),
    "p004_laser_spot_prediction": dict(
        train_samples=200, n_mc_variance=1000, rbf_centres=10, mlp_hidden_units=2, floor_grid=[3, 10],
        window_grid=[4], lag_grid=[1],
    ),
}  # fmt: skip


@pytest.mark.parametrize("name", PACKAGES)
def test_every_paper_runs_at_smoke_size(name):
    paper = importlib.import_module(f"tvtrack.papers.{name}").PAPER
    assert contract.check_paper(paper, overrides=SMALLEST.get(name)) == []


def test_the_smallest_sizes_are_allowed_and_smaller_than_the_smoke_profile():
    for name, small in SMALLEST.items():
        paper = importlib.import_module(f"tvtrack.papers.{name}").PAPER
        smoke = paper.smoke_profile()
        paper.validate(smoke | small)
        assert set(small) <= set(paper.rules) and any(small[k] != smoke[k] for k in small), name


def test_viewer_keys_are_the_viewer_checks_expectation_fields():
    from tvtrack.pipeline.viewer import Expectation

    assert contract.VIEWER_KEYS == tuple(f.name for f in dataclasses.fields(Expectation))


def _toy_measure(config: dict, seed: int, sizes) -> dict:
    """A measurement of the fake paper: C999-1, the mean of ``sizes.n_trials`` draws around 0.5 px."""
    x = np.random.default_rng(seed).normal(0.5, 0.1, sizes.n_trials)
    return {"C999-1": mean_ci(x)}


@dataclasses.dataclass(frozen=True)
class _Sizes:
    n_trials: int = 10


@pytest.fixture(scope="module")
def fake_home(tmp_path_factory):
    """A repository tree with the fake paper's notebook (its parameters cell) and smoke profile."""
    root = tmp_path_factory.mktemp("fake_paper")
    home = root / "lib" / "tvtrack" / "papers" / "p999_fake"
    home.mkdir(parents=True)
    cell = (
        "seed = 1\nn_trials = 50  # runs; integer in [1, 100]\nnoise_px = 0.3  # px; real in [0, 2]\n"
        'output_dir = "."\nrerun_mode = "off"\n'
    )
    cells = [{"cell_type": "code", "metadata": {"tags": ["parameters"]}, "source": cell, "outputs": []}]
    (root / "notebooks").mkdir()
    (root / "notebooks" / "999_fake.ipynb").write_text(json.dumps({"cells": cells}))
    (root / "papermill_runs" / "profiles").mkdir(parents=True)
    (root / "papermill_runs" / "profiles" / "999_fake.smoke.toml").write_text("n_trials = 12\n")
    return home


def _paper(home, **overrides) -> Paper:
    """A conforming fake paper ``999_fake``, with ``overrides`` replacing its fields."""
    recording = types.ModuleType("tvtrack.papers.p999_fake.recording")
    recording.VIEWER_EXPECTATIONS = {"image": False}
    fields = dict(
        name="999_fake",
        citation="A. Author, A title, A journal, 1999",
        home=home,
        rules={"n_trials": Integer(1, 100), "noise_px": Real(0.0, 2.0)},
        register=Register([Entry("noise", "model", "Gaussian", ("Gaussian", "Laplace"), "not stated")]),
        depends={"C999-1": ["noise"]},
        claims={"C999-1": {"statement": "The error is below 1 px.", "paper_value": "< 1 px"}},
        claim_rules={"C999-1": InBand("RMS error", high=1.0, unit="px")},
        Sizes=_Sizes,
        build_sizes=lambda p: _Sizes(n_trials=p["n_trials"]),
        measurements={"error": Measurement(_toy_measure, ("C999-1",))},
        recording=recording,
        units={"noise_px": "px"},
    )
    return Paper(**(fields | overrides))


def _fake(home, **overrides) -> types.ModuleType:
    """A package ``tvtrack.papers.p999_fake`` (built in memory) declaring the fake paper."""
    module = types.ModuleType("tvtrack.papers.p999_fake", "A fake paper.")
    module.PAPER = _paper(home, **overrides)
    return module


def test_a_conforming_fake_passes(fake_home):
    assert contract.check(_fake(fake_home)) == []
    assert contract.check_paper(_paper(fake_home)) == []


@pytest.mark.parametrize(
    "override, expected",
    [
        ({"citation": ""}, "CITATION must be a non-empty string"),
        ({"register": {"noise": "Gaussian"}}, "REGISTER must be a tvtrack.register.Register"),
        ({"depends": {"C999-1": ["motion"]}}, "names entries not in REGISTER: ['motion']"),
        ({"depends": {"C999-2": ["noise"]}}, "DEPENDS: 'C999-2' is not a claim"),
        ({"claim_rules": {"C999-1": "reproduced"}}, "not a tvtrack.verdicts.Rule"),
        ({"rules": {"n_trials": (1, 100)}}, "not a tvtrack.parameters.ParamRule"),
        ({"rules": {"n_trials": Integer(1, 100), "workers": Integer(1, 16)}}, "name the number of worker processes"),
        ({"claims": {"C999-1": ("The error is below 1 px.", "< 1 px")}}, "exactly 'statement' and 'paper_value'"),
        ({"Sizes": {"n_trials": 10}}, "Sizes must be a class"),
        ({"recording": None}, "recording must be the package's recording module"),
        ({"units": {"noise_px": "px", "noise": "px"}}, "units: 'noise' is not a parameter"),
        ({"name": "998_fake"}, "PAPER.name is '998_fake', not the notebook's name '999_fake'"),
        ({"measurements": {}}, "measurements must name at least one measurement function"),
    ],
)
def test_the_check_names_what_a_package_gets_wrong(fake_home, override, expected):
    problems = contract.check(_fake(fake_home, **override))
    assert problems and any(expected in p for p in problems), problems


def test_the_check_names_a_package_without_a_paper():
    module = types.ModuleType("tvtrack.papers.p999_fake", "A fake paper.")
    assert contract.check(module) == [
        "tvtrack.papers.p999_fake: PAPER (a tvtrack.paper.Paper in paper.py) is missing or fails: "
        "AttributeError(\"module 'tvtrack.papers.p999_fake' has no attribute 'PAPER'\")"
    ]
    module.PAPER = {"name": "999_fake"}
    assert contract.check(module) == ["tvtrack.papers.p999_fake: PAPER is a dict, not a tvtrack.paper.Paper"]


def test_the_check_sees_unknown_viewer_expectations(fake_home):
    fake = _fake(fake_home)
    fake.PAPER.recording.VIEWER_EXPECTATIONS = {"overlay": ("gate",)}  # a typo of "overlays"
    assert any("unknown keys ['overlay']" in p for p in contract.check(fake))


def _no_claim(config: dict, seed: int, sizes) -> dict:
    return {}


def _words(config: dict, seed: int, sizes) -> dict:
    return {"C999-1": "about half a pixel"}


def _raises(config: dict, seed: int, sizes) -> dict:
    raise ValueError(f"{sizes.n_trials} trials: too few")


@pytest.mark.parametrize(
    "override, expected",
    [
        (
            {"measurements": {"error": Measurement(_no_claim, ("C999-1",))}},
            "999_fake: measurement 'error': claim C999-1 is missing",
        ),
        (
            {"claim_rules": {"C999-1": InBand("RMS error", high=1.0), "C999-3": InBand("x", high=1.0)}},
            "999_fake: RULES: 'C999-3' is not a claim in CLAIMS",
        ),
        (
            {"rules": {"n_trials": Integer(20, 100), "noise_px": Real(0.0, 2.0)}},
            "999_fake: smoke parameters: parameter 'n_trials' = 12 is out of range; it must be an integer in [20, 100]",
        ),
        (
            {"measurements": {"error": Measurement(_toy_measure, ("C999-1", "C999-2"))}},
            "999_fake: measurement 'error' measures 'C999-2', not a claim in CLAIMS",
        ),
        (
            {"measurements": {"error": Measurement(_words, ("C999-1",))}},
            "999_fake: measurement 'error': claim C999-1 is not what its rule reads",
        ),
        (
            {"measurements": {"error": Measurement(_raises, ("C999-1",))}},
            "999_fake: measurement 'error' fails at smoke size: ValueError: 12 trials: too few",
        ),
    ],
)
def test_a_broken_paper_fails_its_run_with_one_clear_line(fake_home, override, expected):
    problems = contract.check_paper(_paper(fake_home, **override))
    assert len(problems) == 1 and problems[0].startswith(expected), problems


def _at_most_forty(p: dict) -> None:
    if p["n_trials"] > 40:
        raise ValueError(f"parameter n_trials = {p['n_trials']}: at most 40 in the fake paper")


def test_a_paper_derives_its_declarations_validation_sizes_and_rules(fake_home):
    paper = _paper(fake_home, consistency=_at_most_forty)
    declared = paper.parameters()
    assert declared["noise_px"] == Parameter(Real(0.0, 2.0), "px", paper=0.3, smoke=0.3)
    assert declared["n_trials"] == Parameter(Integer(1, 100), "", paper=50, smoke=12)
    assert declared["seed"].paper == 1 and "output_dir" in declared  # the common rules too
    assert paper.paper_profile()["n_trials"] == 50 and paper.smoke_profile()["n_trials"] == 12
    params = paper.validate(paper.smoke_profile())
    assert params["n_trials"] == 12 and paper.sizes(params) == _Sizes(n_trials=12)
    with pytest.raises(ValueError, match="n_trials = 50: at most 40"):
        paper.validate(paper.paper_profile())
    with pytest.raises(ValueError, match="parameter 'noise_px' = 3.0 is out of range"):
        paper.validate(paper.smoke_profile() | {"noise_px": 3.0})
    assert paper.rule("C999-1") is paper.claim_rules["C999-1"]
    with pytest.raises(KeyError, match="no rule for claim 'C999-2'"):
        paper.rule("C999-2")
    at = _paper(fake_home, rules_at=lambda s: {"C999-1": InBand("RMS error", high=s.n_trials / 10)})
    assert at.rule("C999-1", _Sizes(n_trials=20)).high == 2.0 and at.rule("C999-1").high == 1.0


def test_importing_a_package_imports_none_of_its_modules_until_a_name_is_read():
    code = (
        "import sys, tvtrack.papers.p000_dissector_ekf as p; "
        "before = 'tvtrack.papers.p000_dissector_ekf.study' in sys.modules; "
        "p.CITATION; cited = 'tvtrack.papers.p000_dissector_ekf.paper' in sys.modules; p.PARAMETERS; "
        "print(before, cited, 'tvtrack.papers.p000_dissector_ekf.paper' in sys.modules, "
        "{'PAPER', 'CITATION', 'REGISTER', 'Sizes'} <= set(dir(p)))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.split()
    assert out == ["False", "False", "True", "True"]


@pytest.mark.parametrize("name", PACKAGES)
def test_viewer_expectations_make_an_expectation(name):
    from tvtrack.pipeline.viewer import Expectation

    recording = importlib.import_module(f"tvtrack.papers.{name}.recording")
    expected = dataclasses.replace(Expectation(), **recording.VIEWER_EXPECTATIONS)
    assert {k: getattr(expected, k) for k in recording.VIEWER_EXPECTATIONS} == recording.VIEWER_EXPECTATIONS


def test_the_project_has_a_licence_and_cites_every_paper():
    import yaml

    root = contract.PAPERS_DIR.parents[2]
    assert "Permission is hereby granted" in (root / "LICENSE").read_text()
    cff = yaml.safe_load((root / "CITATION.cff").read_text())
    assert cff["cff-version"] == "1.2.0" and cff["license"] == "MIT"
    titles = [" ".join(r["title"].lower().split()) for r in cff["references"]]
    for name in PACKAGES:
        citation = " ".join(importlib.import_module(f"tvtrack.papers.{name}").CITATION.lower().split())
        assert any(t in citation for t in titles), f"{name}: its paper is not among CITATION.cff's references"
