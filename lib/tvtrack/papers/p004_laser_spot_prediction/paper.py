"""Paper 004 declared (:class:`tvtrack.paper.Paper`): its citation, parameters, register, claims, sizes,
measurements and recording, each from the module that holds it."""

from __future__ import annotations

from pathlib import Path
from typing import Any, Mapping

from ...paper import Measurement, Paper
from . import CITATION, recording
from .claims import CLAIMS, RULES
from .params import RULES as PARAMETERS
from .params import check_consistency
from .register import DEPENDS, build
from .sizes import StudySize
from .study import measure_batch

__all__ = ["PAPER", "sizes"]

#: The claim true by construction: the notebook records the recursion's first estimate, nothing is explored.
BY_CONSTRUCTION = "C004-7"


def sizes(p: Mapping[str, Any]) -> StudySize:
    """One run's sizes from the notebook's validated parameters."""
    return StudySize(
        p["n_paths"],
        p["n_frames"],
        p["eval_start_frame"],
        p["n_folds"],
        tuple(p["floor_grid"]),
        tuple(p["window_grid"]),
        p["fixed_floor"],
        p["fixed_window"],
        p["mlp_hidden_units"],
        p["rbf_centres"],
        p["train_samples"],
        p["n_mc_variance"],
        lag_grid=tuple(p["lag_grid"]),
    )


PAPER = Paper(
    name="004_laser_spot_prediction",
    citation=CITATION,
    home=Path(__file__).parent,
    rules=PARAMETERS,
    register=build(),
    depends=DEPENDS,
    claims=CLAIMS,
    claim_rules=RULES,
    Sizes=StudySize,
    build_sizes=sizes,
    measurements={
        "study": Measurement(
            measure_batch, tuple(cid for cid in RULES if cid != BY_CONSTRUCTION), keyword="size", batched=True
        )
    },
    recording=recording,
    units={
        "scintillation_sigma_ln": "ln(irradiance)",
        "n_frames": "frames",
        "eval_start_frame": "frames",
        "floor_grid": "samples",
        "window_grid": "samples",
        "lag_grid": "samples",
        "fixed_floor": "samples",
        "fixed_window": "samples",
        "horizons": "frames",
        "budget_levels_dn": "DN",
    },
    consistency=check_consistency,
)
