"""Paper 002 declared (:class:`tvtrack.paper.Paper`): its citation, parameters, register, claims, sizes,
measurements and recording, each from the module that holds it."""

from __future__ import annotations

from pathlib import Path
from typing import Any, Mapping

from ...paper import Measurement, Paper
from ...verdicts import NotCheckable
from . import CITATION, recording
from .claims import CLAIMS, RULES
from .params import PARAMETERS
from .register import DEPENDS, REGISTER
from .study import Scale, measure_batch

__all__ = ["PAPER", "check_consistency", "sizes"]

#: The EM iteration cap at or above which no cap applies (the register's readings never exceed it).
NO_CAP = 5000


def check_consistency(p: Mapping[str, Any]) -> None:
    """Constraints between parameters; raises one ValueError naming the parameters."""
    if p["max_replicates"] < p["replicates"]:
        raise ValueError(f"max_replicates = {p['max_replicates']} must be >= replicates = {p['replicates']}")


def sizes(p: Mapping[str, Any]) -> Scale:
    """One replicate's sizes from the notebook's validated parameters (one worker where a scheduler runs the
    configurations; no iteration cap at or above :data:`NO_CAP`)."""
    return Scale(
        n_trials=p["n_trials"],
        n_iter_trials=p["n_iter_trials"],
        separations=tuple(p["separations_sigma"]),
        fig3_frames=tuple(p["fig3_frames"]),
        crb_phases=p["crb_phases"],
        n_bootstrap=p["n_bootstrap"],
        n_workers=1 if p["scheduler"] else p["n_workers"],
        max_iter=None if p["em_iteration_cap"] >= NO_CAP else p["em_iteration_cap"],
    )


PAPER = Paper(
    name="002_unified_location_em",
    citation=CITATION,
    home=Path(__file__).parent,
    rules=PARAMETERS,
    register=REGISTER,
    depends=DEPENDS,
    claims=CLAIMS,
    claim_rules=RULES,
    Sizes=Scale,
    build_sizes=sizes,
    measurements={
        "study": Measurement(
            measure_batch,
            tuple(cid for cid, r in RULES.items() if not isinstance(r, NotCheckable)),
            keyword="scale",
            batched=True,
        )
    },
    recording=recording,
    units={"separations_sigma": "sigma", "fig3_frames": "frames", "record_separation": "sigma"},
    consistency=check_consistency,
)
