"""Parameter rules of notebook 004 (ranges written once: the parameters cell's comments state the same ranges,
and ``tests/test_notebooks.py`` checks that they do)."""

from __future__ import annotations

from typing import Any, Mapping

from ...parameters import Integer, IntegerList, OneOfList, Real, RealList, SchedulerAddress
from .register import DEFAULT, NAMES

__all__ = ["RULES", "check_consistency"]

RULES = {
    "n_trials": Integer(3, 10),
    "max_replicates": Integer(3, 1000),
    "sizing_budget": Integer(-1, 100000),
    "max_subset": Integer(1, 3),
    "scheduler": SchedulerAddress(),
    "joint_samples": Integer(0, 64),
    "n_workers": Integer(1, 16),
    "explore_entries": OneOfList(*NAMES, min_len=0),
    "scintillation_sigma_ln": Real(0.0, 1.5),
    "n_paths": Integer(6, 15),
    "n_frames": Integer(200, 1000),
    "eval_start_frame": Integer(40, 99),
    "n_folds": Integer(2, 5),
    "floor_grid": IntegerList(3, 1000),
    "window_grid": IntegerList(2, 30),
    "lag_grid": IntegerList(1, 30),
    "fixed_floor": Integer(3, 1000),
    "fixed_window": Integer(4, 30),
    "horizons": IntegerList(1, 10),
    "mlp_hidden_units": Integer(2, 128),
    "rbf_centres": Integer(10, 1000),
    "train_samples": Integer(200, 100_000),
    "n_mc_variance": Integer(1000, 200_000),
    "record_every": Integer(1, 100),
    "budget_levels_dn": RealList(0.0, 64.0),
    "budget_gates": Integer(100, 20_000),
}


def check_consistency(p: Mapping[str, Any]) -> None:
    """Cross-parameter checks: one ``ValueError`` naming the parameters and what is allowed."""
    if p["max_replicates"] < p["n_trials"] or p["n_folds"] > p["n_paths"] // 2:
        raise ValueError(
            f"parameters: max_replicates = {p['max_replicates']} must be >= n_trials = {p['n_trials']}, "
            f"and n_folds = {p['n_folds']} <= n_paths // 2 = {p['n_paths'] // 2} (every fold needs >= 2 "
            "test paths)"
        )
    if p.get("scintillation_sigma_ln", DEFAULT["scintillation"]) != DEFAULT["scintillation"] and (
        p["explore_entries"] and "scintillation" not in p["explore_entries"]
    ):
        raise ValueError(
            f"parameter 'scintillation_sigma_ln' = {p['scintillation_sigma_ln']} moves the scintillation entry's "
            "default: 'scintillation' must then be in explore_entries (or explore_entries empty)"
        )
