"""The paper contract (:mod:`tvtrack.contract`): every package in ``lib/tvtrack/papers`` exports the same names
with the same meaning, and the check sees a package that does not."""

from __future__ import annotations

import dataclasses
import importlib
import subprocess
import sys
import types

import pytest

from tvtrack import contract
from tvtrack.parameters import Integer
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
    # every claim with a rule has a statement, and the citation is in the package docstring too
    assert set(package.RULES) <= set(package.CLAIMS)
    assert " ".join(package.CITATION.split()) in " ".join(package.__doc__.split())


def test_viewer_keys_are_the_viewer_checks_expectation_fields():
    from tvtrack.pipeline.viewer import Expectation

    assert contract.VIEWER_KEYS == tuple(f.name for f in dataclasses.fields(Expectation))


def _fake(**overrides) -> types.ModuleType:
    """A conforming package ``tvtrack.papers.p999_fake`` (built in memory), with ``overrides`` replacing names."""
    recording = types.ModuleType("tvtrack.papers.p999_fake.recording")
    recording.VIEWER_EXPECTATIONS = {"image": False}

    @dataclasses.dataclass
    class Sizes:
        n_trials: int = 10

    names = {
        "CITATION": "A. Author, A title, A journal, 1999",
        "REGISTER": Register([Entry("noise", "model", "Gaussian", ("Gaussian", "Laplace"), "not stated")]),
        "DEPENDS": {"C999-1": ["noise"]},
        "RULES": {"C999-1": InBand("RMS error", high=1.0, unit="px")},
        "PARAMETERS": {"n_trials": Integer(1, 100)},
        "CLAIMS": {"C999-1": {"statement": "The error is below 1 px.", "paper_value": "< 1 px"}},
        "Sizes": Sizes,
        "recording": recording,
    } | overrides
    module = types.ModuleType("tvtrack.papers.p999_fake", "A fake paper.")
    for k, v in names.items():
        if v is not None:
            setattr(module, k, v)
    return module


def test_a_conforming_fake_passes():
    assert contract.check(_fake()) == []


@pytest.mark.parametrize(
    "override, expected",
    [
        ({"CITATION": None}, "CITATION"),
        ({"CITATION": ""}, "CITATION must be a non-empty string"),
        ({"REGISTER": {"noise": "Gaussian"}}, "REGISTER must be a tvtrack.register.Register"),
        ({"DEPENDS": {"C999-1": ["motion"]}}, "names entries not in REGISTER: ['motion']"),
        ({"DEPENDS": {"C999-2": ["noise"]}}, "DEPENDS: 'C999-2' is not a claim"),
        ({"RULES": {"C999-1": "reproduced"}}, "not a tvtrack.verdicts.Rule"),
        ({"RULES": {"C999-3": InBand("x", high=1.0)}}, "RULES: 'C999-3' is not a claim"),
        ({"PARAMETERS": {"n_trials": (1, 100)}}, "not a tvtrack.parameters.ParamRule"),
        ({"PARAMETERS": {"workers": Integer(1, 16)}}, "name the number of worker processes n_workers"),
        ({"CLAIMS": {"C999-1": ("The error is below 1 px.", "< 1 px")}}, "exactly 'statement' and 'paper_value'"),
        ({"CLAIMS": {"C998-1": {"statement": "s", "paper_value": "v"}}}, "does not start with 'C999-'"),
        ({"Sizes": {"n_trials": 10}}, "Sizes must be a class"),
        ({"recording": None}, "recording"),
    ],
)
def test_the_check_names_what_a_package_gets_wrong(override, expected):
    problems = contract.check(_fake(**override))
    assert problems and any(expected in p for p in problems), problems


def test_the_check_sees_unknown_viewer_expectations():
    fake = _fake()
    fake.recording.VIEWER_EXPECTATIONS = {"overlay": ("gate",)}  # a typo of "overlays"
    assert any("unknown keys ['overlay']" in p for p in contract.check(fake))


def test_a_lazy_export_imports_only_its_own_module():
    code = (
        "import sys, tvtrack.papers.p000_dissector_ekf as p; "
        "before = 'tvtrack.papers.p000_dissector_ekf.study' in sys.modules; "
        "p.CITATION; p.PARAMETERS; "
        "print(before, 'tvtrack.papers.p000_dissector_ekf.params' in sys.modules, "
        "'tvtrack.papers.p000_dissector_ekf.study' in sys.modules, {'CITATION', 'REGISTER', 'Sizes'} <= set(dir(p)))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.split()
    assert out == ["False", "True", "False", "True"]


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
