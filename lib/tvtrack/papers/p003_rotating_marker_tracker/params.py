"""Parameter rules of notebook 003, written once (the parameters cell's comments repeat these ranges)."""

from __future__ import annotations

from ...parameters import Boolean, Integer, OneOf, Real, SchedulerAddress

__all__ = ["RULES", "check_consistency"]

RULES = {
    "seed": Integer(0, 2**62),
    "n_trials": Integer(2, 1000),
    "loss_trials": Integer(2, 1000),
    "replicates": Integer(3, 20),
    "max_replicates": Integer(3, 1000),
    "sizing_budget": Integer(-1, 100000),
    "max_subset": Integer(1, 3),
    "scheduler": SchedulerAddress(),
    "joint": Integer(0, 64),
    "screen_joint": Boolean(),
    "n_workers": Integer(1, 16),
    "rotation_hz": Real(0.0, 500.0, low_open=True),
    "transient_s": Real(0.0, 60.0),
    "fig1_duration_s": Real(0.0, 60.0, low_open=True),
    "fig2_duration_s": Real(0.0, 120.0, low_open=True),
    "loss_duration_s": Real(0.0, 60.0, low_open=True),
    "probe_sir": Real(0.0, 100.0, low_open=True),
    "probe_n_interferers": Integer(0, 12),
    "probe_kappa": Real(0.0, 1.0, low_open=True),
    "probe_marker": OneOf("rotating", "static"),
    "full_analysis": Boolean(),
    "record_seconds": Real(0.0, 20.0, low_open=True),
    "record_full_every": Integer(1, 1000),
}


def check_consistency(p: dict, lowest_fps: float) -> None:
    """Combinations the single-parameter rules cannot see; raises ``ValueError`` (the CLI's exit 2).

    Parameters
    ----------
    p : dict
        Validated parameters.
    lowest_fps : float
        The lowest frame rate the run uses (the register's ``fps`` values).
    """
    if p["rotation_hz"] >= lowest_fps / 2:
        raise ValueError(
            f"parameter 'rotation_hz' = {p['rotation_hz']} is at or above the frame-rate Nyquist "
            f"{lowest_fps / 2:g} Hz of the lowest frame rate run ({lowest_fps:g} frames/s)"
        )
    if p["max_replicates"] < p["replicates"]:
        raise ValueError(f"parameters 'max_replicates' = {p['max_replicates']} < 'replicates' = {p['replicates']}")
    if not p["transient_s"] < min(p["fig1_duration_s"], p["fig2_duration_s"]):
        raise ValueError(
            f"parameters 'transient_s' = {p['transient_s']}, 'fig1_duration_s' = {p['fig1_duration_s']}, "
            f"'fig2_duration_s' = {p['fig2_duration_s']}: the transient must be shorter than both runs"
        )
