"""Parameter rules of notebook 001 (ranges written once; the parameters cell's comments state the same ranges,
every rule names a parameter of the notebook, which ``tests/papers/test_001_study.py`` checks)."""

from __future__ import annotations

from ...parameters import Integer, IntegerList, OneOf, Real, RealList, SchedulerAddress
from .scenario import THRESHOLD_READINGS

__all__ = ["RULES", "check_cross"]

RULES = {
    "n_trials": Integer(30, 100_000),
    "n_fa_runs": Integer(300, 1_000_000),
    "fa_duration_s": Real(8.0, 60.0),
    "n_tradeoff_trials": Integer(10, 100_000),
    "n_train": Integer(5, 10_000),
    "replicates": Integer(3, 20),
    "max_replicates": Integer(3, 1000),
    "sizing_budget": Integer(-1, 100000),
    "max_subset": Integer(1, 3),
    "scheduler": SchedulerAddress(),
    "joint_samples": Integer(0, 200),
    "frame_rate_hz": Real(5.0, 200.0),
    "sigma_eps": Real(0.0, 10.0, low_open=True),
    "k_bound2": Integer(3, 1000),
    "k_bound3": Integer(5, 1000),
    "window_n": Integer(2, 200),
    "alpha": Real(1e-6, 0.2),
    "threshold_method": OneOf(*THRESHOLD_READINGS),
    "restart": OneOf("A", "B", "C"),
    "restart_accel_var": Real(0.0, 1e8, low_open=True),
    "kb3_grid": IntegerList(5, 1000, min_len=3),
    "n_fig4_trials": Integer(10, 100_000),
    "loss_grid_s": RealList(5.6, 14.0, min_len=2),
    "fixed2_grid": IntegerList(2, 1000),
    "fixed3_grid": IntegerList(3, 1000),
    "imm_q_ca_grid": RealList(0.0, 1.0),
    "imm_p_stay_grid": RealList(0.5, 1.0, high_open=True),
    "vdf_q_ca_grid": RealList(0.0, 1.0),
    "vdf_windows": IntegerList(2, 100),
    "gate_sigma": Real(1.0, 10.0),
    "roc_delay_s": Real(0.1, 5.0),
    "step_dv": Real(0.0, 20.0, low_open=True),
    "record_every": Integer(1, 100),
    "crop_px": Integer(16, 256),
    "spot_sigma_px": Real(0.0, 10.0, low_open=True),
}


def check_cross(p: dict) -> None:
    """Constraints between parameters, checked before any work."""
    if p["max_replicates"] < p["replicates"]:
        raise ValueError(
            f"parameter 'max_replicates' = {p['max_replicates']}; it must be >= replicates = {p['replicates']}"
        )
    if 2 * p["window_n"] + 1 > 5.0 * p["frame_rate_hz"]:
        raise ValueError(
            f"parameter 'window_n' = {p['window_n']}: the detector's windows (2n + 1 frames) must fill "
            f"before the onset at 5 s ({5.0 * p['frame_rate_hz']:g} frames)"
        )
