"""Paper 003 declared (:class:`tvtrack.paper.Paper`): its citation, parameters, register, claims, sizes,
measurements and recording, each from the module that holds it."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path
from typing import Any, Mapping

from ...paper import Measurement, Paper
from ...parameters import OneOfList
from . import CITATION, recording
from .claims import CLAIMS, RULES, claim_rules
from .params import RULES as PARAMETERS
from .params import check_consistency
from .register import DEPENDS, REGISTER
from .scene import Scenario
from .study import I_CLAIMS, T_CLAIMS, Sizes, measure_interference, measure_tracking

__all__ = ["PAPER", "consistency", "rules_at", "sizes"]


def consistency(p: Mapping[str, Any]) -> None:
    """The constraints between parameters (:func:`.params.check_consistency`) at the lowest frame rate the run
    explores: every value of the register's ``fps`` where the run explores it, else its default."""
    fps = REGISTER["fps"]
    explored = "fps" in (p.get("register_entries") or REGISTER.names)
    check_consistency(p, lowest_fps=min(fps.values) if explored else fps.default)


def sizes(p: Mapping[str, Any]) -> Sizes:
    """The tracking study's sizes from the notebook's validated parameters (the interference study's differ in
    its ``trials``: ``loss_trials``)."""
    return Sizes(
        trials=p["n_trials"],
        fig1_s=p["fig1_duration_s"],
        fig2_s=p["fig2_duration_s"],
        transient_s=p["transient_s"],
        rotation_hz=p["rotation_hz"],
        horizon_s=p["loss_duration_s"],
    )


def rules_at(s: Sizes) -> dict:
    """The claim rules at the marker diameter of the scenario the sizes run."""
    return claim_rules(Scenario(rotation_hz=s.rotation_hz).diameter)


PAPER = Paper(
    name="003_rotating_marker_tracker",
    citation=CITATION,
    home=Path(__file__).parent,
    rules={**PARAMETERS, "register_entries": OneOfList(*REGISTER.names, min_len=0)},
    register=REGISTER,
    depends=DEPENDS,
    claims=CLAIMS,
    claim_rules=RULES,
    Sizes=Sizes,
    build_sizes=sizes,
    measurements={
        "tracking": Measurement(measure_tracking, T_CLAIMS),
        "interference": Measurement(
            measure_interference, I_CLAIMS, sizes=lambda p, s: replace(s, trials=p["loss_trials"])
        ),
    },
    recording=recording,
    units={
        "rotation_hz": "rev/s",
        "transient_s": "s",
        "fig1_duration_s": "s",
        "fig2_duration_s": "s",
        "loss_duration_s": "s",
        "record_seconds": "s",
    },
    consistency=consistency,
    rules_at=rules_at,
)
