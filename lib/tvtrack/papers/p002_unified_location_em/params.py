"""Parameter rules of notebook 002 (the ranges written once; the parameters cell's comments repeat them)."""

from tvtrack.parameters import Boolean, Integer, OneOf, Real, RealList, IntegerList, SchedulerAddress

__all__ = ["PARAMETERS"]

PARAMETERS = {
    "n_trials": Integer(8, 100_000),
    "n_iter_trials": Integer(4, 100_000),
    "separations_sigma": RealList(0.0, 20.0, min_len=5),
    "fig3_frames": IntegerList(2, 200, min_len=3),
    "crb_phases": Integer(1, 4096),
    "n_bootstrap": Integer(2000, 20_000),
    "replicates": Integer(3, 50),
    "max_replicates": Integer(3, 1000),
    "sizing_budget": Integer(-1, 100000),
    "max_subset": Integer(1, 3),
    "scheduler": SchedulerAddress(),
    "joint_samples": Integer(0, 100),
    "screen_fraction": Real(0.0, 1.0, low_open=True),
    "one_at_a_time": Boolean(),
    "em_iteration_cap": Integer(10, 100_000),
    "n_workers": Integer(1, 16),
    "record_separation": Real(0.0, 20.0),
    "record_every": Integer(1, 50),
    "rerun_mode": OneOf("file", "off", "notebook"),
}
