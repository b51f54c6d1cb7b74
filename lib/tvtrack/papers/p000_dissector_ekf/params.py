"""The parameter rules of paper 000's notebook (ranges written once; the parameters cell's comments repeat them and
``tests/papers/test_000_validation.py`` checks that bad values are refused)."""

from __future__ import annotations

from typing import Any, Mapping

from ...parameters import Integer, Real, RealList, SchedulerAddress

__all__ = ["RULES", "check_consistency"]

RULES = {
    "n_trials": Integer(30, 20_000),
    "duration_T": Real(5.0, 200.0),
    "steady_window_T": Real(1.0, 100.0),
    "dt": Real(0.01, 0.1),
    "substeps": Integer(2, 50),
    "psi_grid": RealList(0.5, 1000.0),
    "contrast_grid": RealList(0.0, 0.99),
    "dt_check_psi": RealList(0.5, 1000.0),
    "dt_check_contrasts": RealList(0.0, 0.99),
    "dt_factor": Integer(2, 40),
    "dt_trials": Integer(20, 5000),
    "dt_check_T": Real(3.0, 200.0),
    "grid_trials": Integer(10, 5000),
    "grid_points": Integer(51, 4001),
    "grid_psi": RealList(0.5, 1000.0),
    "grid_contrasts": RealList(0.0, 0.99),
    "pulse_durations": RealList(0.1, 1.0),
    "betas": RealList(0.1, 1000.0),
    "lock_factor": Real(2.0, 50.0),
    "acquire_by_T": Real(1.0, 30.0),
    "offsets": RealList(-1.0, 1.0),
    "replicates": Integer(3, 20),
    "max_replicates": Integer(3, 1000),
    "sizing_budget": Integer(-1, 100000),
    "max_subset": Integer(1, 3),
    "scheduler": SchedulerAddress(),
    "joint": Integer(0, 200),
    "screen_trials": Integer(0, 20_000),
    "record_scans": Integer(1, 1000),
}


def check_consistency(p: Mapping[str, Any]) -> None:
    """Constraints between parameters; raises one ValueError naming the parameters."""
    if p["steady_window_T"] >= p["duration_T"] or p["acquire_by_T"] >= p["duration_T"] - p["steady_window_T"]:
        raise ValueError(
            f"parameters 'steady_window_T' = {p['steady_window_T']}, 'acquire_by_T' = {p['acquire_by_T']}: "
            f"need acquire_by_T < duration_T - steady_window_T < duration_T = {p['duration_T']}"
        )
    if not {0.0, 0.5, 0.9} <= set(p["contrast_grid"]) or len(p["psi_grid"]) < 2:
        raise ValueError(
            f"parameters 'contrast_grid' = {p['contrast_grid']} must hold 0, 0.5 and 0.9 and 'psi_grid' = "
            f"{p['psi_grid']} at least two values (trend claims C000-5, -6, -7, -9)"
        )
    off = list(p["offsets"])
    if off != sorted(off) or min(off) >= 0 or max(off) <= 0:
        raise ValueError(
            f"parameter 'offsets' = {off} must be ascending with offsets on both sides of 0 (the acquisition figure "
            f"states the pull-in range on each side)"
        )
    if p["screen_trials"] > p["n_trials"]:
        raise ValueError(f"parameter 'screen_trials' = {p['screen_trials']} must be at most n_trials = {p['n_trials']}")
    if max(p["betas"]) * p["dt"] >= 1.0:
        raise ValueError(
            f"parameter 'betas' = {p['betas']}: each beta_0 dt must be < 1 (dt = {p['dt']}; the Euler step of X2)"
        )
    if p["max_replicates"] < p["replicates"]:
        raise ValueError(
            f"parameter 'max_replicates' = {p['max_replicates']} must be >= replicates = {p['replicates']}"
        )
