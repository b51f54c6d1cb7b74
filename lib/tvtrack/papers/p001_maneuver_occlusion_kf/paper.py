"""Paper 001 declared (:class:`tvtrack.paper.Paper`): its citation, parameters, register, claims, sizes,
measurements and recording, each from the module that holds it."""

from __future__ import annotations

from pathlib import Path
from typing import Any, Mapping

from ...paper import Measurement, Paper
from ...register import Register
from . import CITATION, recording
from .claims import CLAIMS, RULES
from .curves import measure_curves
from .params import RULES as PARAMETERS
from .params import check_cross
from .register import DEPENDS, GROUPS, build_register
from .sizes import Sizes
from .spherical import measure_spherical
from .study import measure_detection, measure_tradeoff

__all__ = ["PAPER", "register_for", "sizes"]

#: The register entries the notebook's parameters set the default of: ``{entry: parameter}``.
SET_BY_PARAMETERS = {
    "threshold": "threshold_method",
    "alpha": "alpha",
    "window_n": "window_n",
    "k_bound2": "k_bound2",
    "frame_rate_hz": "frame_rate_hz",
    "restart": "restart",
    "k_bound3": "k_bound3",
    "roc_delay_s": "roc_delay_s",
    "step_dv": "step_dv",
    "restart_accel_var": "restart_accel_var",
}


def register_for(p: Mapping[str, Any]) -> Register:
    """The register with the notebook's validated parameters as the defaults of the entries they set."""
    return build_register(**{entry: p[name] for entry, name in SET_BY_PARAMETERS.items()})


def sizes(p: Mapping[str, Any]) -> Sizes:
    """One full-size run's sizes (a dict) from the notebook's validated parameters; ``defaults`` is the register's
    default under them, ``train_seed`` the seed after the exploration's."""
    grids = dict(
        fixed2=p["fixed2_grid"],
        fixed3=p["fixed3_grid"],
        imm_q_ca=p["imm_q_ca_grid"],
        imm_p_stay=p["imm_p_stay_grid"],
        vdf_q_ca=p["vdf_q_ca_grid"],
        vdf_windows=p["vdf_windows"],
    )
    return dict(
        n_trials=p["n_trials"],
        n_fa_runs=p["n_fa_runs"],
        fa_duration_s=p["fa_duration_s"],
        sigma_eps=p["sigma_eps"],
        n_train=p["n_train"],
        n_tradeoff_trials=p["n_tradeoff_trials"],
        train_seed=p["seed"] + 1,
        kb3_grid=p["kb3_grid"],
        loss_grid_s=p["loss_grid_s"],
        n_fig4_trials=p["n_fig4_trials"],
        grids=grids,
        defaults=register_for(p).default(),
    )


PAPER = Paper(
    name="001_maneuver_occlusion_kf",
    citation=CITATION,
    home=Path(__file__).parent,
    rules=PARAMETERS,
    register=build_register(),
    depends=DEPENDS,
    claims=CLAIMS,
    claim_rules=RULES,
    Sizes=Sizes,
    build_sizes=sizes,
    measurements={
        "detection": Measurement(measure_detection, GROUPS["detection"]),
        "tradeoff": Measurement(measure_tradeoff, GROUPS["tradeoff"]),
        "curves": Measurement(measure_curves, GROUPS["curves"]),
        "spherical": Measurement(measure_spherical, GROUPS["spherical"]),
    },
    recording=recording,
    units={
        "fa_duration_s": "s",
        "frame_rate_hz": "Hz",
        "sigma_eps": "elements",
        "k_bound2": "frames",
        "k_bound3": "frames",
        "window_n": "frames",
        "restart_accel_var": "elements^2/frame^4",
        "kb3_grid": "frames",
        "loss_grid_s": "s",
        "fixed2_grid": "frames",
        "fixed3_grid": "frames",
        "vdf_windows": "frames",
        "gate_sigma": "standard deviations",
        "roc_delay_s": "s",
        "step_dv": "elements/frame",
        "crop_px": "px",
        "spot_sigma_px": "px",
    },
    consistency=check_cross,
)
