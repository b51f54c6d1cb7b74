"""Paper 000 declared (:class:`tvtrack.paper.Paper`): its citation, parameters, register, claims, sizes,
measurements and recording, each from the module that holds it."""

from __future__ import annotations

from pathlib import Path
from typing import Any, Mapping

from ...paper import Measurement, Paper
from . import CITATION, recording
from .claims import CLAIMS, RULES, claim_rules
from .params import RULES as PARAMETERS
from .params import check_consistency
from .register import DEPENDS, REGISTER
from .sizes import Sizes
from .study import measure, measure_cost

__all__ = ["PAPER", "sizes"]

#: The claims :func:`.study.measure` measures (C000-4 is the cost study's, C000-10 is not checkable).
MEASURED = ("C000-1", "C000-2", "C000-3", "C000-5", "C000-6", "C000-7", "C000-8", "C000-9")


def sizes(p: Mapping[str, Any]) -> Sizes:
    """One full-size run's sizes from the notebook's validated parameters (the discretisation check's points: the
    ``dt_check_psi`` values at contrast 0.5, then the ``dt_check_contrasts`` at psi_A 20)."""
    return Sizes(
        n_trials=p["n_trials"],
        duration_T=p["duration_T"],
        window_T=p["steady_window_T"],
        dt=p["dt"],
        substeps=p["substeps"],
        psi_grid=tuple(p["psi_grid"]),
        contrast_grid=tuple(p["contrast_grid"]),
        dt_points=tuple((psi, 0.5) for psi in p["dt_check_psi"]) + tuple((20.0, c) for c in p["dt_check_contrasts"]),
        dt_factor=p["dt_factor"],
        dt_trials=p["dt_trials"],
        dt_duration_T=p["dt_check_T"],
        grid_trials=p["grid_trials"],
        grid_points=p["grid_points"],
        lock_factor=p["lock_factor"],
        acquire_by_T=p["acquire_by_T"],
    )


PAPER = Paper(
    name="000_dissector_ekf",
    citation=CITATION,
    home=Path(__file__).parent,
    rules=PARAMETERS,
    register=REGISTER,
    depends=DEPENDS,
    claims=CLAIMS,
    claim_rules=RULES,
    Sizes=Sizes,
    build_sizes=sizes,
    measurements={
        "accuracy": Measurement(measure, MEASURED),
        "cost": Measurement(measure_cost, ("C000-4",), keyword="n_trials", sizes=lambda p, s: p["n_trials"]),
    },
    recording=recording,
    units={
        "duration_T": "T",
        "steady_window_T": "T",
        "dt": "T",
        "dt_check_T": "T",
        "pulse_durations": "T",
        "betas": "1/T",
        "acquire_by_T": "T",
        "offsets": "T",
    },
    consistency=check_consistency,
    rules_at=claim_rules,
)
